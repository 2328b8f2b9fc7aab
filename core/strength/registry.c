#include <string.h>

#include "strength.h"

static const struct tlsph_strength_model *const models[] = {
    &tlsph_strength_elastic,
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
    return "elastic";
}
