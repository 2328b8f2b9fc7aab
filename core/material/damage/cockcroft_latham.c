/* Cockcroft-Latham criterion (paper 000 eqs. 41-42): damage initiates when the
 * plastic work of the largest principal tensile stress,
 *   W = int <sigma_1> d eps_p,   <s> = max(s, 0),
 * reaches the critical value W_cr; D_init = W / W_cr.
 * Parameter: critical_work W_cr (J/m^3 = Pa; Table 3 gives it in MPa).
 * The integral is taken with the end-of-step stress (backward rule), the same
 * point in the step where the return mapping satisfies the yield condition. */
#include <math.h>

#include "scene/json_check.h"
#include "material/damage/damage.h"

enum { WCR };

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    static const char *const keys[] = {"type", "critical_work", "evolution", NULL};
    int bad = jc_unknown_keys(obj, keys, pointer, err) != 0;
    bad |= jc_number(obj, "critical_work", 1, ((struct jc_range){0.0, 1e12, JC_OPEN, JC_CLOSED}),
                     "J/m^3 (= Pa)", pointer, &m->damage.params[WCR], err) < 0;
    return bad ? -1 : 0;
}

static double initiation(const struct tlsph_material *m, const struct tlsph_damage_step *s)
{
    return fmax(s->sigma1, 0.0) * s->deps_p / m->damage.params[WCR];
}

const struct tlsph_damage_model tlsph_damage_cockcroft_latham = {
    .name = "cockcroft_latham",
    .module = "damage:cockcroft_latham",
    .needs_sigma1 = 1,
    .parse = parse,
    .initiation = initiation,
};
