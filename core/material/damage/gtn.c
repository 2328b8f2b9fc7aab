/* GTN parameters (paper 000 §5.4; Table 3 gives f0, f_c, f_F and k_w for the
 * Weldox steels).  The paper states neither q1, q2 nor nucleation parameters:
 * q1 = 1.5, q2 = 1 are Tvergaard's values (Int. J. Fract. 17, 1981), the usual
 * choice; nucleation is off unless the scene asks for it. */
#include <math.h>

#include "scene/json_check.h"
#include "material/damage/damage.h"
#include "material/damage/gtn.h"

static void add(struct tlsph_errors *err, const char *pointer, const char *key, const char *why,
                double a, double b)
{
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, pointer, key);
    tlsph_errors_add(err, p, why, a, b);
}

static int parse_nucleation(const json_t *obj, double *g, const char *pointer,
                            struct tlsph_errors *err)
{
    static const char *const keys[] = {"amplitude", "mean_strain", "deviation", NULL};
    const json_t *n = jc_object(obj, "nucleation", 0, pointer, err);
    if (!n)
        return json_object_get(obj, "nucleation") ? -1 : 0;
    char P[TLSPH_POINTER_MAX];
    tlsph_pointer_join(P, sizeof P, pointer, "nucleation");
    int bad = jc_unknown_keys(n, keys, P, err) != 0;
    const struct jc_range fraction = {0.0, 1.0, JC_OPEN, JC_OPEN};
    bad |= jc_number(n, "amplitude", 1, fraction, "(void volume fraction F_N)", P, &g[GTN_FN],
                     err) < 0;
    bad |= jc_number(n, "mean_strain", 1, JC_BETWEEN(0.0, 10.0),
                     "(matrix plastic strain eps_N)", P, &g[GTN_EN], err) < 0;
    bad |= jc_number(n, "deviation", 1, ((struct jc_range){0.0, 10.0, JC_OPEN, JC_CLOSED}),
                     "(standard deviation s_N of the matrix plastic strain)", P, &g[GTN_SN],
                     err) < 0;
    return bad ? -1 : 0;
}

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    static const char *const keys[] = {"type", "q1", "q2", "initial_void_fraction",
                                       "critical_void_fraction", "failure_void_fraction",
                                       "shear_coefficient", "nucleation", "evolution", NULL};
    double *g = m->damage.params;
    g[GTN_Q1] = 1.5;
    g[GTN_Q2] = 1.0;
    int bad = jc_unknown_keys(obj, keys, pointer, err) != 0;
    const struct jc_range factor = {0.0, 10.0, JC_OPEN, JC_CLOSED};
    const struct jc_range fraction = {0.0, 1.0, JC_OPEN, JC_OPEN};
    bad |= jc_number(obj, "q1", 0, factor, "(dimensionless)", pointer, &g[GTN_Q1], err) < 0;
    bad |= jc_number(obj, "q2", 0, factor, "(dimensionless)", pointer, &g[GTN_Q2], err) < 0;
    bad |= jc_number(obj, "initial_void_fraction", 1, ((struct jc_range){0.0, 1.0, JC_CLOSED,
                                                                         JC_OPEN}),
                     "(void volume fraction f0)", pointer, &g[GTN_F0], err) < 0;
    bad |= jc_number(obj, "critical_void_fraction", 1, fraction, "(void volume fraction f_c)",
                     pointer, &g[GTN_FC], err) < 0;
    bad |= jc_number(obj, "failure_void_fraction", 1, fraction, "(void volume fraction f_F)",
                     pointer, &g[GTN_FF], err) < 0;
    bad |= jc_number(obj, "shear_coefficient", 0, JC_BETWEEN(0.0, 100.0),
                     "(k_w, dimensionless)", pointer, &g[GTN_KW], err) < 0;
    bad |= parse_nucleation(obj, g, pointer, err) != 0;
    if (!bad && !(g[GTN_F0] < g[GTN_FC])) {
        add(err, pointer, "initial_void_fraction",
            "initial void fraction %g must be below the critical void fraction %g", g[GTN_F0],
            g[GTN_FC]);
        bad = 1;
    }
    if (!bad && !(g[GTN_FC] < g[GTN_FF])) {
        add(err, pointer, "failure_void_fraction",
            "failure void fraction %g must exceed the critical void fraction %g", g[GTN_FF],
            g[GTN_FC]);
        bad = 1;
    }
    /* eq. 47 accelerates f* from f_c to 1/q1: needs f_c < 1/q1 */
    if (!bad && !(g[GTN_FC] < 1.0 / g[GTN_Q1])) {
        add(err, pointer, "critical_void_fraction",
            "critical void fraction %g must be below 1/q1 = %g (where f* ends, eq. 47)",
            g[GTN_FC], 1.0 / g[GTN_Q1]);
        bad = 1;
    }
    if (json_object_get(obj, "evolution")) {
        char p[TLSPH_POINTER_MAX];
        tlsph_pointer_join(p, sizeof p, pointer, "evolution");
        tlsph_errors_add(err, p, "'evolution' does not apply to gtn: its damage is D = q1 f* "
                                 "from the void fraction (eq. 48)");
        bad = 1;
    }
    return bad ? -1 : 0;
}

/* The optional mechanisms the parameters switch on. */
static int modules(const struct tlsph_material *m, const char *out[TLSPH_DAMAGE_MAX_MODULES])
{
    const double *g = m->damage.params;
    int n = 0;
    if (g[GTN_FN] > 0.0)
        out[n++] = "damage:gtn_nucleation";
    if (g[GTN_KW] > 0.0)
        out[n++] = "damage:gtn_shear";
    return n;
}

const struct tlsph_damage_model tlsph_damage_gtn = {
    .name = "gtn",
    .module = "damage:gtn",
    .needs_sigma1 = 0,
    .porous = 1,
    .fields = TLSPH_DAMAGE_FIELD_VOID_FRACTION,
    .parse = parse,
    .initiation = NULL,
    .point_update = tlsph_gtn_point_update,
    .point_init = tlsph_gtn_point_init,
    .modules = modules,
};
