/* Cockcroft-Latham criterion (paper 000 eqs. 41-42): damage initiates when the
 * plastic work of the largest principal tensile stress,
 *   W = int <sigma_1> d eps_p,   <s> = max(s, 0),
 * reaches the critical value W_cr; D_init = W / W_cr.
 * Parameter: critical_work W_cr (J/m^3 = Pa; Table 3 gives it in MPa).
 * The integral is taken with the end-of-step stress (backward rule), the same
 * point in the step where the return mapping satisfies the yield condition. */
#include <math.h>

#include "scene/keys.h"
#include "material/damage/damage.h"

enum { WCR };

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    {.name = "critical_work", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 1e12, JC_OPEN, JC_CLOSED}, .unit = "J/m^3", .said = "J/m^3 (= Pa)",
     .offset = TLSPH_PARAM(WCR),
     .description = "critical plastic work of the largest principal tensile stress W_cr"},
    {.name = "evolution", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_CALLER,
     .table = &tlsph_damage_evolution_keys, .description = "damage evolution (eq. 45)"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/materials/*/damage", "cockcroft_latham", keys);
/* clang-format on */

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    const struct tlsph_key_target to = {.base = m->damage.params, .terms = &m->damage.terms};
    return tlsph_keys_read(obj, &table, pointer, &to, err);
}

static double initiation(const struct tlsph_material *m, const struct tlsph_damage_step *s)
{
    return fmax(s->sigma1, 0.0) * s->deps_p / m->damage.params[WCR];
}

const struct tlsph_damage_model tlsph_damage_cockcroft_latham = {
    .name = "cockcroft_latham",
    .module = "damage:cockcroft_latham",
    .keys = &table,
    .needs_sigma1 = 1,
    .parse = parse,
    .initiation = initiation,
};
