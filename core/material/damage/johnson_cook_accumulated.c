/* Accumulated Johnson-Cook damage with a critical value (paper 003 eq. 62,
 * after Simkins and Li 2006):
 *
 *   D = sum d eps_p / eps_f,
 *   eps_f = (D1 + D2 exp(D3 sigma_m/sigma_M)) (1 + D4 ln(epsdot_p/epsdot_0)) (1 + D5 T*),
 *
 * and the particle fails (D = 1 in the engine's sense: no stress) when the sum
 * reaches the critical value D_c.  Before that the stress is not degraded at
 * all: paper 003's Johnson-Cook material (eqs. 56-61) has no damage in its flow
 * law; D only decides where the crack grows.  The paper tests D_c on fibres of
 * three particles through the plate (§3, eq. 20); the engine has no fibres, so
 * the test is per particle.
 *
 * What differs from paper 000's criterion (johnson_cook.c, docs/damage.md):
 * the rate factor is the original Johnson-Cook 1 + D4 ln epsdot* (paper 000:
 * the Dey form (1 + epsdot*)^D4), taken as 1 below epsdot_0 as in the JC flow
 * law; failure is sudden at D_c instead of D_init reaching 1 and then
 * eq. 45's evolution with the (1 - D) coupling.  sigma_M is the flow stress;
 * during plastic flow the effective von Mises stress equals it, so the
 * triaxiality is the same sigma_m / sigma_eq the other criteria read.
 *
 * In the engine's two variables: D_init = (sum d eps_p / eps_f) / D_c, so the
 * output field damage_initiation reaches 1 at failure, and the damage D jumps
 * from 0 to 1 there (evolution factor infinite, damage.h). */
#include <math.h>

#include "material/damage/johnson_cook_keys.h"

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    JC_FAILURE_KEYS_D123,
    JC_FAILURE_KEYS_RATE,
    JC_FAILURE_KEYS_THERMAL,
    {.name = "critical_damage", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 1e3, JC_OPEN, JC_CLOSED}, .unit = "1", .offset = TLSPH_PARAM(JC_DC),
     .description = "critical accumulated damage D_c: the particle fails when "
                    "sum d eps_p / eps_f reaches it (paper 003: 0.1)"},
    {.name = "evolution", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_REFUSED,
     .description = "refused: the accumulated damage fails the particle at critical_damage, "
                    "with no evolution law"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/materials/*/damage", "johnson_cook_accumulated", keys);
/* clang-format on */

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    int bad = tlsph_damage_jc_read(obj, &table, m, pointer, err) != 0;
    if (tlsph_damage_refuse_evolution(
            obj, pointer, "johnson_cook_accumulated: the particle fails at critical_damage",
            err) != 0)
        bad = 1;
    /* D jumps from 0 to 1 when D_init = D / D_c reaches 1 (tlsph_damage_evolution) */
    m->damage.evolution_factor = INFINITY;
    return bad ? -1 : 0;
}

static double initiation(const struct tlsph_material *m, const struct tlsph_damage_step *s)
{
    const double *q = m->damage.params;
    double ef = q[JC_D1] + q[JC_D2] * exp(q[JC_D3] * s->triaxiality);
    if ((m->damage.terms & TLSPH_FLOW_RATE) && s->rate > q[JC_EPSDOT0])
        ef *= 1.0 + q[JC_D4] * log(s->rate / q[JC_EPSDOT0]);
    if (m->damage.terms & TLSPH_FLOW_THERMAL)
        ef *= 1.0 + q[JC_D5] * tlsph_damage_jc_homologous(q, s->T);
    /* With D4 < 0 the rate factor reaches 0 at epsdot* = exp(1/|D4|) (e^67 for
     * the paper's -0.015): no strain left, the particle fails in this step. */
    if (!(ef > 0.0))
        return 1.0 + s->deps_p;
    return s->deps_p / (ef * q[JC_DC]);
}

const struct tlsph_damage_model tlsph_damage_johnson_cook_accumulated = {
    .name = "johnson_cook_accumulated",
    .module = "damage:johnson_cook_accumulated",
    .keys = &table,
    .parse = parse,
    .initiation = initiation,
    .sudden = 1,
};
