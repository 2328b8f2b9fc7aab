/* Rankine criterion on the particle (the particle form of paper 001 eq. 40):
 * the particle fails outright (D from 0 to 1, no eq. 45 evolution) once its
 * largest principal stretch exceeds 1 by the threshold,
 *   D_init = max over the history of (lambda_max - 1) / stretch,
 * lambda_max^2 the largest eigenvalue of C = F^T F.  lambda_max - 1 is the
 * largest stretch (r - r0)/r0 of any short fibre at the point, so it is the
 * virtual links' eq. 40 measure maximised over the directions: the criterion
 * that fits a brittle (elastic) material with the particle-damage treatments
 * (damage_aware, pseudo_spring), for comparing them with the links
 * (docs/virtual-links.md, Kalthoff-Winkler).  It reads the strain, not plastic
 * flow, so it runs every step (state_based).  Parameter: stretch (1). */
#include <math.h>

#include "scene/keys.h"
#include "material/damage/damage.h"

enum { STRETCH };

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    {.name = "stretch", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 10.0, JC_OPEN, JC_CLOSED}, .unit = "1",
     .offset = TLSPH_PARAM(STRETCH),
     .description = "largest principal stretch minus 1 at which the particle fails "
                    "(paper 001 eq. 40's link threshold; its Kalthoff-Winkler: 0.0044)"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/materials/*/damage", "rankine", keys);
/* clang-format on */

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    const struct tlsph_key_target to = {.base = m->damage.params, .terms = &m->damage.terms};
    m->damage.evolution_factor = INFINITY; /* sudden: fails at D_init = 1 */
    return tlsph_keys_read(obj, &table, pointer, &to, err);
}

/* state_based: the value of D_init this step (the caller keeps the maximum) */
static double initiation(const struct tlsph_material *m, const struct tlsph_damage_step *s)
{
    return fmax(s->stretch1, 0.0) / m->damage.params[STRETCH];
}

const struct tlsph_damage_model tlsph_damage_rankine = {
    .name = "rankine",
    .module = "damage:rankine",
    .keys = &table,
    .sudden = 1,
    .state_based = 1,
    .parse = parse,
    .initiation = initiation,
};
