/* The table of damage models (damage.h). */
#include "material/damage/damage.h"
#include "util/name_list.h"

/* One row per model, in the order of the scene's list of accepted names:
 * ROW(name) stands for the descriptor tlsph_damage_<name>, whose .name is "name". */
#define DAMAGE_MODELS(ROW)                                                                         \
    ROW(cockcroft_latham) ROW(johnson_cook) ROW(gtn) ROW(gurson) ROW(gtn_aravas) ROW(sm_gurson)   \
        ROW(m_gurson) ROW(johnson_cook_accumulated) ROW(rankine)

#define DECLARE(id) extern const struct tlsph_damage_model tlsph_damage_##id;
DAMAGE_MODELS(DECLARE)

#define ENTRY(id) &tlsph_damage_##id,
static const struct tlsph_damage_model *const models[] = {DAMAGE_MODELS(ENTRY)};

/* "cockcroft_latham, johnson_cook, gtn, ...": the rows of models[] */
const char *tlsph_damage_names(void) { return DAMAGE_MODELS(TLSPH_LISTED) + 2; }

const struct tlsph_damage_model *tlsph_damage_find(const char *name)
{
    const int k = tlsph_name_list_index(tlsph_damage_names(), name);
    return k < 0 ? NULL : models[k];
}
