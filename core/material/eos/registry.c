#include <string.h>

#include "material/eos/eos.h"

static const struct tlsph_eos_model *const models[] = {
    &tlsph_eos_linear,
    &tlsph_eos_mie_gruneisen,
};

const struct tlsph_eos_model *tlsph_eos_find(const char *name)
{
    for (size_t i = 0; i < sizeof models / sizeof *models; i++)
        if (strcmp(models[i]->name, name) == 0)
            return models[i];
    return NULL;
}

const char *tlsph_eos_names(void)
{
    return "linear, mie_gruneisen";
}
