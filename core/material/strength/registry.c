#include <string.h>

#include "material/strength/strength.h"

static const struct tlsph_strength_model *const models[] = {
    &tlsph_strength_elastic,     &tlsph_strength_linear_hardening, &tlsph_strength_johnson_cook,
    &tlsph_strength_swift,       &tlsph_strength_voce,
};

const struct tlsph_strength_model *tlsph_strength_find(const char *name)
{
    for (size_t i = 0; i < sizeof models / sizeof *models; i++)
        if (strcmp(models[i]->name, name) == 0)
            return models[i];
    return NULL;
}

const char *tlsph_strength_names(void)
{
    return "elastic, linear_hardening, johnson_cook, swift, voce";
}

const char *tlsph_strength_plastic_names(void)
{
    return "linear_hardening, johnson_cook, swift, voce";
}
