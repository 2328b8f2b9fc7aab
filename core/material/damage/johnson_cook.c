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

#include "material/damage/johnson_cook_keys.h"

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    JC_FAILURE_KEYS_D123,
    JC_FAILURE_KEYS_RATE,
    JC_FAILURE_KEYS_THERMAL,
    {.name = "evolution", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_CALLER,
     .table = &tlsph_damage_evolution_keys, .description = "damage evolution (eq. 45)"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/materials/*/damage", "johnson_cook", keys);
/* clang-format on */

int tlsph_damage_jc_read(const json_t *obj, const struct tlsph_key_table *tab,
                         struct tlsph_material *m, const char *pointer, struct tlsph_errors *err)
{
    double *q = m->damage.params;
    const struct tlsph_key_target to = {.base = q, .terms = &m->damage.terms};
    int bad = tlsph_keys_read(obj, tab, pointer, &to, err) != 0;
    /* eps_f must be positive at every triaxiality: D1 + D2 exp(D3 s) > 0 for all s
     * with D1, D2 >= 0 (their ranges) holds unless both are 0. */
    if (!bad && q[JC_D1] == 0.0 && q[JC_D2] == 0.0) {
        tlsph_key_error(err, pointer, "d2",
                        "d1 = %g and d2 = %g give a failure strain d1 + d2 exp(d3 sigma*) that "
                        "is not positive at every triaxiality: need d1 >= 0, d2 >= 0, not both 0",
                        q[JC_D1], q[JC_D2]);
        bad = 1;
    }
    if (json_object_get(obj, "d5")) {
        if (q[JC_TREF] > 0.0 && q[JC_TMELT] > 0.0 && q[JC_TMELT] <= q[JC_TREF]) {
            tlsph_key_error(err, pointer, "melting_temperature",
                            "'melting_temperature' = %g K must exceed 'reference_temperature' "
                            "= %g K",
                            q[JC_TMELT], q[JC_TREF]);
            bad = 1;
        }
        if (!m->thermal.enabled) {
            tlsph_key_error(err, pointer, "d5",
                            "the thermal term 'd5' needs a temperature: add a \"thermal\" "
                            "block to the material");
            bad = 1;
        }
    }
    return bad ? -1 : 0;
}

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    return tlsph_damage_jc_read(obj, &table, m, pointer, err);
}

static double failure_strain(const struct tlsph_material *m, const struct tlsph_damage_step *s)
{
    const double *q = m->damage.params;
    double ef = q[JC_D1] + q[JC_D2] * exp(q[JC_D3] * s->triaxiality);
    if (m->damage.terms & TLSPH_FLOW_RATE)
        ef *= pow(1.0 + s->rate / q[JC_EPSDOT0], q[JC_D4]);
    if (m->damage.terms & TLSPH_FLOW_THERMAL)
        ef *= 1.0 + q[JC_D5] * tlsph_damage_jc_homologous(q, s->T);
    return ef;
}

static double initiation(const struct tlsph_material *m, const struct tlsph_damage_step *s)
{
    return s->deps_p / failure_strain(m, s);
}

const struct tlsph_damage_model tlsph_damage_johnson_cook = {
    .name = "johnson_cook",
    .module = "damage:johnson_cook",
    .keys = &table,
    .parse = parse,
    .initiation = initiation,
};
