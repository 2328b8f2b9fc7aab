/* The table of strength models (strength.h): the elastic model, then the
 * flow laws. */
#include <string.h>

#include "material/strength/strength.h"

/* One row per flow law, in the order of the scene's lists of accepted names:
 * ROW(name) stands for the descriptor tlsph_strength_<name>, whose .name is
 * "name" and whose flow is not NULL. */
#define FLOW_LAWS(ROW) ROW(linear_hardening) ROW(johnson_cook) ROW(swift) ROW(voce)

#define DECLARE(id) extern const struct tlsph_strength_model tlsph_strength_##id;
FLOW_LAWS(DECLARE)

#define ENTRY(id) &tlsph_strength_##id,
static const struct tlsph_strength_model *const models[] = {&tlsph_strength_elastic,
                                                            FLOW_LAWS(ENTRY)};

const struct tlsph_strength_model *tlsph_strength_find(const char *name)
{
    for (size_t i = 0; i < sizeof models / sizeof *models; i++)
        if (strcmp(models[i]->name, name) == 0)
            return models[i];
    return NULL;
}

/* ", linear_hardening, johnson_cook, ..." */
#define LISTED(id) ", " #id
const char *tlsph_strength_names(void) { return "elastic" FLOW_LAWS(LISTED); }
const char *tlsph_strength_plastic_names(void) { return FLOW_LAWS(LISTED) + 2; }
