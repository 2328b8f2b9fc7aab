/* GTN parameters (paper 000 §5.4; Table 3 gives f0, f_c, f_F and k_w for the
 * Weldox steels).  The paper states neither q1, q2 nor nucleation parameters:
 * q1 = 1.5, q2 = 1 are Tvergaard's values (Int. J. Fract. 17, 1981), the usual
 * choice; nucleation is off unless the scene asks for it. */
#include <math.h>

#include "scene/keys.h"
#include "material/damage/damage.h"
#include "material/damage/gtn.h"

#define NUMBER TLSPH_KEY_NUMBER
#define REQUIRED TLSPH_KEY_REQUIRED
#define DEFAULT TLSPH_KEY_DEFAULT

/* clang-format off */
static const struct tlsph_key nucleation_keys[] = {
    {.name = "amplitude", .kind = NUMBER, .flags = REQUIRED, .range = {0.0, 1.0, JC_OPEN, JC_OPEN},
     .unit = "1", .said = "(void volume fraction F_N)", .offset = TLSPH_PARAM(GTN_FN),
     .description = "nucleated void volume fraction F_N"},
    {.name = "mean_strain", .kind = NUMBER, .flags = REQUIRED,
     .range = {0.0, 10.0, JC_CLOSED, JC_CLOSED}, .unit = "1",
     .said = "(matrix plastic strain eps_N)", .offset = TLSPH_PARAM(GTN_EN),
     .description = "mean matrix plastic strain of nucleation eps_N"},
    {.name = "deviation", .kind = NUMBER, .flags = REQUIRED,
     .range = {0.0, 10.0, JC_OPEN, JC_CLOSED}, .unit = "1",
     .said = "(standard deviation s_N of the matrix plastic strain)",
     .offset = TLSPH_PARAM(GTN_SN), .description = "standard deviation s_N"},
};
static const struct tlsph_key_table nucleation_table =
    TLSPH_KEY_TABLE("/materials/*/damage/nucleation", "gtn", nucleation_keys);

static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    {.name = "q1", .kind = NUMBER, .flags = DEFAULT, .range = {0.0, 10.0, JC_OPEN, JC_CLOSED},
     .unit = "1", .def = 1.5, .offset = TLSPH_PARAM(GTN_Q1),
     .description = "Tvergaard factor q1"},
    {.name = "q2", .kind = NUMBER, .flags = DEFAULT, .range = {0.0, 10.0, JC_OPEN, JC_CLOSED},
     .unit = "1", .def = 1.0, .offset = TLSPH_PARAM(GTN_Q2),
     .description = "Tvergaard factor q2"},
    {.name = "initial_void_fraction", .kind = NUMBER, .flags = REQUIRED,
     .range = {0.0, 1.0, JC_CLOSED, JC_OPEN}, .unit = "1", .said = "(void volume fraction f0)",
     .offset = TLSPH_PARAM(GTN_F0),
     .description = "initial void volume fraction f0, below critical_void_fraction"},
    {.name = "critical_void_fraction", .kind = NUMBER, .flags = REQUIRED,
     .range = {0.0, 1.0, JC_OPEN, JC_OPEN}, .unit = "1", .said = "(void volume fraction f_c)",
     .offset = TLSPH_PARAM(GTN_FC),
     .description = "void fraction f_c where coalescence starts (eq. 47), below "
                    "failure_void_fraction and 1/q1"},
    {.name = "failure_void_fraction", .kind = NUMBER, .flags = REQUIRED,
     .range = {0.0, 1.0, JC_OPEN, JC_OPEN}, .unit = "1", .said = "(void volume fraction f_F)",
     .offset = TLSPH_PARAM(GTN_FF),
     .description = "void fraction f_F where f* = 1/q1, D = 1: failure"},
    {.name = "shear_coefficient", .kind = NUMBER, .flags = DEFAULT,
     .range = {0.0, 100.0, JC_CLOSED, JC_CLOSED}, .unit = "1", .said = "(k_w, dimensionless)",
     .def = 0.0, .offset = TLSPH_PARAM(GTN_KW),
     .description = "Nahshon-Hutchinson shear growth coefficient k_w (eqs. 51-52); 0 = off"},
    {.name = "nucleation", .kind = TLSPH_KEY_OBJECT, .table = &nucleation_table,
     .description = "Chu-Needleman strain-controlled nucleation (eq. 50); absent = off"},
    {.name = "evolution", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_REFUSED,
     .description = "refused: the damage of gtn comes from the void fraction"},
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/materials/*/damage", "gtn", keys);
/* clang-format on */

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    double *g = m->damage.params;
    const struct tlsph_key_target to = {.base = g, .terms = &m->damage.terms};
    int bad = tlsph_keys_read(obj, &table, pointer, &to, err) != 0;
    if (!bad && !(g[GTN_F0] < g[GTN_FC])) {
        tlsph_key_error(err, pointer, "initial_void_fraction",
                        "initial void fraction %g must be below the critical void fraction %g",
                        g[GTN_F0], g[GTN_FC]);
        bad = 1;
    }
    if (!bad && !(g[GTN_FC] < g[GTN_FF])) {
        tlsph_key_error(err, pointer, "failure_void_fraction",
                        "failure void fraction %g must exceed the critical void fraction %g",
                        g[GTN_FF], g[GTN_FC]);
        bad = 1;
    }
    /* eq. 47 accelerates f* from f_c to 1/q1: needs f_c < 1/q1 */
    if (!bad && !(g[GTN_FC] < 1.0 / g[GTN_Q1])) {
        tlsph_key_error(err, pointer, "critical_void_fraction",
                        "critical void fraction %g must be below 1/q1 = %g (where f* ends, "
                        "eq. 47)",
                        g[GTN_FC], 1.0 / g[GTN_Q1]);
        bad = 1;
    }
    if (tlsph_damage_refuse_evolution(obj, pointer,
                                      "gtn: its damage is D = q1 f* from the void fraction "
                                      "(eq. 48)",
                                      err) != 0)
        bad = 1;
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
    .keys = &table,
    .porous = 1,
    .fields = TLSPH_DAMAGE_FIELD_VOID_FRACTION,
    .parse = parse,
    .point_update = tlsph_gtn_point_update,
    .point_init = tlsph_gtn_point_init,
    .modules = modules,
};
