/* The table of damage models (damage.h). */
#include <string.h>

#include "material/damage/damage.h"

/* One row per model, in the order of the scene's list of accepted names:
 * ROW(name) stands for the descriptor tlsph_damage_<name>, whose .name is "name". */
#define DAMAGE_MODELS(ROW) ROW(cockcroft_latham) ROW(johnson_cook) ROW(gtn)

#define DECLARE(id) extern const struct tlsph_damage_model tlsph_damage_##id;
DAMAGE_MODELS(DECLARE)

#define ENTRY(id) &tlsph_damage_##id,
static const struct tlsph_damage_model *const models[] = {DAMAGE_MODELS(ENTRY)};

const struct tlsph_damage_model *tlsph_damage_find(const char *name)
{
    for (size_t i = 0; i < sizeof models / sizeof *models; i++)
        if (strcmp(models[i]->name, name) == 0)
            return models[i];
    return NULL;
}

/* ", cockcroft_latham, johnson_cook, gtn" without its first separator */
#define LISTED(id) ", " #id
const char *tlsph_damage_names(void) { return DAMAGE_MODELS(LISTED) + 2; }
