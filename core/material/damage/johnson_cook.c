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

#include "scene/keys.h"
#include "material/damage/damage.h"

enum { D1, D2, D3, D4, EPSDOT0, D5, TREF, TMELT };

#define NUMBER TLSPH_KEY_NUMBER
#define REQUIRED TLSPH_KEY_REQUIRED

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    {.name = "d1", .kind = NUMBER, .flags = REQUIRED, .range = {0.0, 1e3, JC_CLOSED, JC_CLOSED},
     .unit = "1", .said = "(dimensionless strain)", .offset = TLSPH_PARAM(D1),
     .description = "failure-strain constant D1"},
    {.name = "d2", .kind = NUMBER, .flags = REQUIRED, .range = {0.0, 1e3, JC_CLOSED, JC_CLOSED},
     .unit = "1", .said = "(dimensionless strain)", .offset = TLSPH_PARAM(D2),
     .description = "failure-strain coefficient D2; d1 and d2 not both 0"},
    {.name = "d3", .kind = NUMBER, .flags = REQUIRED, .range = {-1e3, 1e3, JC_CLOSED, JC_CLOSED},
     .unit = "1", .offset = TLSPH_PARAM(D3), .description = "triaxiality exponent D3"},
    {.name = "d4", .kind = NUMBER, .range = {-10.0, 10.0, JC_CLOSED, JC_CLOSED}, .unit = "1",
     .term = TLSPH_FLOW_RATE, .offset = TLSPH_PARAM(D4),
     .description = "strain-rate coefficient D4; absent = no rate term"},
    {.name = "reference_strain_rate", .kind = NUMBER, .flags = REQUIRED,
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "1/s", .with = "d4",
     .offset = TLSPH_PARAM(EPSDOT0), .description = "reference plastic strain rate epsdot_0"},
    {.name = "d5", .kind = NUMBER, .range = {-1.0, 1e3, JC_OPEN, JC_CLOSED}, .unit = "1",
     .term = TLSPH_FLOW_THERMAL, .offset = TLSPH_PARAM(D5),
     .description = "thermal coefficient D5; absent = no thermal term; needs the material's "
                    "thermal block"},
    {.name = "reference_temperature", .kind = NUMBER, .flags = REQUIRED,
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "K", .with = "d5",
     .offset = TLSPH_PARAM(TREF), .description = "reference temperature T_ref of T*"},
    {.name = "melting_temperature", .kind = NUMBER, .flags = REQUIRED,
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "K", .with = "d5",
     .offset = TLSPH_PARAM(TMELT), .description = "melting temperature T_melt of T*, above T_ref"},
    {.name = "evolution", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_CALLER,
     .table = &tlsph_damage_evolution_keys, .description = "damage evolution (eq. 45)"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/materials/*/damage", "johnson_cook", keys);
/* clang-format on */

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    double *q = m->damage.params;
    const struct tlsph_key_target to = {.base = q, .terms = &m->damage.terms};
    int bad = tlsph_keys_read(obj, &table, pointer, &to, err) != 0;
    /* eps_f must be positive at every triaxiality: D1 + D2 exp(D3 s) > 0 for all s
     * with D1, D2 >= 0 (their ranges) holds unless both are 0. */
    if (!bad && q[D1] == 0.0 && q[D2] == 0.0) {
        tlsph_key_error(err, pointer, "d2",
                        "d1 = %g and d2 = %g give a failure strain d1 + d2 exp(d3 sigma*) that "
                        "is not positive at every triaxiality: need d1 >= 0, d2 >= 0, not both 0",
                        q[D1], q[D2]);
        bad = 1;
    }
    if (json_object_get(obj, "d5")) {
        if (q[TREF] > 0.0 && q[TMELT] > 0.0 && q[TMELT] <= q[TREF]) {
            tlsph_key_error(err, pointer, "melting_temperature",
                            "'melting_temperature' = %g K must exceed 'reference_temperature' "
                            "= %g K",
                            q[TMELT], q[TREF]);
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
    .keys = &table,
    .parse = parse,
    .initiation = initiation,
};
