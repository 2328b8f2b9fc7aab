/* The table of equations of state (eos.h). */
#include <string.h>

#include "material/eos/eos.h"

/* One row per model, in the order of the scene's list of accepted names:
 * ROW(name) stands for the descriptor tlsph_eos_<name>, whose .name is "name". */
#define EOS_MODELS(ROW) ROW(linear) ROW(mie_gruneisen)

#define DECLARE(id) extern const struct tlsph_eos_model tlsph_eos_##id;
EOS_MODELS(DECLARE)

#define ENTRY(id) &tlsph_eos_##id,
static const struct tlsph_eos_model *const models[] = {EOS_MODELS(ENTRY)};

const struct tlsph_eos_model *tlsph_eos_find(const char *name)
{
    for (size_t i = 0; i < sizeof models / sizeof *models; i++)
        if (strcmp(models[i]->name, name) == 0)
            return models[i];
    return NULL;
}

/* ", linear, mie_gruneisen" without its first separator */
#define LISTED(id) ", " #id
const char *tlsph_eos_names(void) { return EOS_MODELS(LISTED) + 2; }
