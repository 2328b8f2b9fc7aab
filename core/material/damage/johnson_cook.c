/* Johnson-Cook failure criterion (paper 000 eqs. 43-44), in the form of Dey et
 * al. (2006) that the paper's Table 3 parameters belong to:
 *
 *   D_init = sum d eps_p / eps_f,
 *   eps_f  = (D1 + D2 exp(D3 sigma*)) (1 + epsdot*)^D4 (1 + D5 T*),
 *
 * sigma* the stress triaxiality sigma_m / sigma_eq (from the current effective
 * stress), epsdot* = epsdot_p / epsdot_0 and T* = (T - T_ref)/(T_melt - T_ref).
 * Under uniaxial tension (sigma* = 1/3) and no rate or thermal term,
 * eps_f = D1 + D2 exp(D3/3).
 *
 * The rate term is on only when the scene gives d4 (with reference_strain_rate),
 * the thermal term only when it gives d5 (with reference_temperature and
 * melting_temperature, and a "thermal" block on the material).  The paper runs
 * its case study without either ("no strain rate effect is considered"). */
#include <math.h>

#include "scene/json_check.h"
#include "material/damage/damage.h"

enum { D1, D2, D3, D4, EPSDOT0, D5, TREF, TMELT };

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    static const char *const keys[] = {"type", "d1", "d2", "d3", "d4", "reference_strain_rate",
                                       "d5", "reference_temperature", "melting_temperature",
                                       "evolution", NULL};
    double *q = m->damage.params;
    const struct jc_range any = {-1e3, 1e3, JC_CLOSED, JC_CLOSED};
    int bad = jc_unknown_keys(obj, keys, pointer, err) != 0;
    bad |= jc_number(obj, "d1", 1, any, "(dimensionless strain)", pointer, &q[D1], err) < 0;
    bad |= jc_number(obj, "d2", 1, any, "(dimensionless strain)", pointer, &q[D2], err) < 0;
    bad |= jc_number(obj, "d3", 1, any, "(dimensionless)", pointer, &q[D3], err) < 0;
    /* eps_f must be positive at every triaxiality: D1 >= 0 and D1 + D2 exp(D3 s) > 0
     * for all s holds iff D1 > 0 with D2 >= 0, or D1 >= 0 with D2 > 0. */
    if (!bad && (q[D1] < 0.0 || q[D2] < 0.0 || (q[D1] == 0.0 && q[D2] == 0.0))) {
        char p[TLSPH_POINTER_MAX];
        tlsph_pointer_join(p, sizeof p, pointer, q[D1] < 0.0 ? "d1" : "d2");
        tlsph_errors_add(err, p,
                         "d1 = %g and d2 = %g give a failure strain d1 + d2 exp(d3 sigma*) that "
                         "is not positive at every triaxiality: need d1 >= 0, d2 >= 0, not both 0",
                         q[D1], q[D2]);
        bad = 1;
    }
    if (json_object_get(obj, "d4")) {
        bad |= jc_number(obj, "d4", 1, ((struct jc_range){-10.0, 10.0, JC_CLOSED, JC_CLOSED}),
                         "(dimensionless)", pointer, &q[D4], err) < 0;
        bad |= jc_number(obj, "reference_strain_rate", 1, JC_POSITIVE, "1/s", pointer,
                         &q[EPSDOT0], err) < 0;
        m->damage.terms |= TLSPH_FLOW_RATE;
    } else {
        bad |= jc_misplaced(obj, "reference_strain_rate", "d4", pointer, err);
    }
    if (json_object_get(obj, "d5")) {
        bad |= jc_number(obj, "d5", 1, ((struct jc_range){-1.0, 1e3, JC_OPEN, JC_CLOSED}),
                         "(dimensionless)", pointer, &q[D5], err) < 0;
        bad |= jc_number(obj, "reference_temperature", 1, JC_POSITIVE, "K", pointer, &q[TREF],
                         err) < 0;
        bad |= jc_number(obj, "melting_temperature", 1, JC_POSITIVE, "K", pointer, &q[TMELT],
                         err) < 0;
        if (q[TREF] > 0.0 && q[TMELT] > 0.0 && q[TMELT] <= q[TREF]) {
            char p[TLSPH_POINTER_MAX];
            tlsph_pointer_join(p, sizeof p, pointer, "melting_temperature");
            tlsph_errors_add(err, p, "'melting_temperature' = %g K must exceed "
                             "'reference_temperature' = %g K", q[TMELT], q[TREF]);
            bad = 1;
        }
        if (!m->thermal.enabled) {
            char p[TLSPH_POINTER_MAX];
            tlsph_pointer_join(p, sizeof p, pointer, "d5");
            tlsph_errors_add(err, p, "the thermal term 'd5' needs a temperature: add a "
                             "\"thermal\" block to the material");
            bad = 1;
        }
        m->damage.terms |= TLSPH_FLOW_THERMAL;
    } else {
        bad |= jc_misplaced(obj, "reference_temperature", "d5", pointer, err);
        bad |= jc_misplaced(obj, "melting_temperature", "d5", pointer, err);
    }
    return bad ? -1 : 0;
}

static double failure_strain(const struct tlsph_material *m, const struct tlsph_damage_step *s)
{
    const double *q = m->damage.params;
    double ef = q[D1] + q[D2] * exp(q[D3] * s->triaxiality);
    if (m->damage.terms & TLSPH_FLOW_RATE)
        ef *= pow(1.0 + s->rate / q[EPSDOT0], q[D4]);
    if (m->damage.terms & TLSPH_FLOW_THERMAL) {
        /* same convention as the JC flow law: no effect below T_ref; at and above
         * T_melt the homologous temperature stays 1 */
        const double Ts = fmin(fmax((s->T - q[TREF]) / (q[TMELT] - q[TREF]), 0.0), 1.0);
        ef *= 1.0 + q[D5] * Ts;
    }
    return ef;
}

static double initiation(const struct tlsph_material *m, const struct tlsph_damage_step *s)
{
    return s->deps_p / failure_strain(m, s);
}

const struct tlsph_damage_model tlsph_damage_johnson_cook = {
    .name = "johnson_cook",
    .module = "damage:johnson_cook",
    .needs_sigma1 = 0,
    .parse = parse,
    .initiation = initiation,
};
