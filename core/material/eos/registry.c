/* The table of equations of state (eos.h). */
#include "material/eos/eos.h"
#include "util/name_list.h"

/* One row per model, in the order of the scene's list of accepted names:
 * ROW(name) stands for the descriptor tlsph_eos_<name>, whose .name is "name". */
#define EOS_MODELS(ROW) ROW(linear) ROW(mie_gruneisen)

#define DECLARE(id) extern const struct tlsph_eos_model tlsph_eos_##id;
EOS_MODELS(DECLARE)

#define ENTRY(id) &tlsph_eos_##id,
static const struct tlsph_eos_model *const models[] = {EOS_MODELS(ENTRY)};

/* "linear, mie_gruneisen": the rows of models[] */
const char *tlsph_eos_names(void) { return EOS_MODELS(TLSPH_LISTED) + 2; }

const struct tlsph_eos_model *tlsph_eos_find(const char *name)
{
    const int k = tlsph_name_list_index(tlsph_eos_names(), name);
    return k < 0 ? NULL : models[k];
}
