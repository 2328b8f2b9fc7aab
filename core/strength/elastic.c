/* Linear-elastic deviatoric response: tau_dev = 2 G eps_dev (Hencky strain). */
#include "../scene/json_check.h"
#include "strength.h"

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    static const char *const keys[] = {"type", NULL};
    (void)m;
    return jc_unknown_keys(obj, keys, pointer, err) ? -1 : 0;
}

static void deviatoric(const struct tlsph_material *m, const double eps_dev[6], double tau_dev[6])
{
    const double g2 = 2.0 * m->shear_modulus;
    for (int k = 0; k < 6; k++)
        tau_dev[k] = g2 * eps_dev[k];
}

const struct tlsph_strength_model tlsph_strength_elastic = {
    .name = "elastic",
    .parse = parse,
    .deviatoric = deviatoric,
};
