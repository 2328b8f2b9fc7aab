/* The table of strength models (strength.h): the elastic model, then the
 * flow laws. */
#include "material/strength/strength.h"
#include "util/name_list.h"

/* One row per flow law, in the order of the scene's lists of accepted names:
 * ROW(name) stands for the descriptor tlsph_strength_<name>, whose .name is
 * "name" and whose flow is not NULL. */
#define FLOW_LAWS(ROW) ROW(linear_hardening) ROW(johnson_cook) ROW(swift) ROW(voce)

#define DECLARE(id) extern const struct tlsph_strength_model tlsph_strength_##id;
FLOW_LAWS(DECLARE)

#define ENTRY(id) &tlsph_strength_##id,
static const struct tlsph_strength_model *const models[] = {&tlsph_strength_elastic,
                                                            FLOW_LAWS(ENTRY)};

/* "elastic, linear_hardening, johnson_cook, ...": the rows of models[] */
const char *tlsph_strength_names(void) { return "elastic" FLOW_LAWS(TLSPH_LISTED); }
const char *tlsph_strength_plastic_names(void) { return FLOW_LAWS(TLSPH_LISTED) + 2; }

const struct tlsph_strength_model *tlsph_strength_find(const char *name)
{
    const int k = tlsph_name_list_index(tlsph_strength_names(), name);
    return k < 0 ? NULL : models[k];
}
