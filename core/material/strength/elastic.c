/* Linear-elastic deviatoric response, tau_dev = 2 G dev(ln U) (Hencky strain):
 * no flow law, so no plastic state and no return mapping. */
#include "scene/keys.h"
#include "material/strength/strength.h"

static const struct tlsph_key keys[] = {TLSPH_KEY_MODEL_TYPE};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/materials/*/strength", "elastic", keys);

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    (void)m;
    return tlsph_keys_unknown(obj, &table, pointer, err);
}

const struct tlsph_strength_model tlsph_strength_elastic = {
    .name = "elastic",
    .module = "strength:elastic",
    .keys = &table,
    .parse = parse,
    .flow = 0,
};
