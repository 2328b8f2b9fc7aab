/* Linear-elastic deviatoric response, tau_dev = 2 G dev(ln U) (Hencky strain):
 * no flow law, so no plastic state and no return mapping. */
#include "scene/json_check.h"
#include "material/strength/strength.h"

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    static const char *const keys[] = {"type", NULL};
    (void)m;
    return jc_unknown_keys(obj, keys, pointer, err) ? -1 : 0;
}

const struct tlsph_strength_model tlsph_strength_elastic = {
    .name = "elastic",
    .module = "strength:elastic",
    .parse = parse,
    .flow = 0,
};
