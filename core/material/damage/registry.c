#include <string.h>

#include "material/damage/damage.h"

static const struct tlsph_damage_model *const models[] = {
    &tlsph_damage_cockcroft_latham,
    &tlsph_damage_johnson_cook,
    &tlsph_damage_gtn,
};

const struct tlsph_damage_model *tlsph_damage_find(const char *name)
{
    for (size_t i = 0; i < sizeof models / sizeof *models; i++)
        if (strcmp(models[i]->name, name) == 0)
            return models[i];
    return NULL;
}

const char *tlsph_damage_names(void) { return "cockcroft_latham, johnson_cook, gtn"; }
