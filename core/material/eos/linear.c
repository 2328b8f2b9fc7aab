/* Linear EOS in the logarithmic volume strain: p = -K ln(J) / J.
 *
 * Together with the elastic deviatoric response 2G dev(ln V)/J this is the
 * isotropic Hencky hyperelastic material (Kirchhoff stress tau = K ln J I +
 * 2G dev ln V), so small strains give Hooke's law with bulk modulus K and large
 * elastic deformations stay energy-conserving.  No parameters beyond E and nu. */
#include <math.h>

#include "scene/keys.h"
#include "material/eos/eos.h"

static const struct tlsph_key keys[] = {TLSPH_KEY_MODEL_TYPE};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/materials/*/eos", "linear", keys);

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    (void)m;
    return tlsph_keys_unknown(obj, &table, pointer, err);
}

static void pressure(const struct tlsph_material *m, double J, double e, double *p, double *K_t)
{
    (void)e;
    const double lnJ = log(J);
    *p = -m->bulk_modulus * lnJ / J;
    /* -J dp/dJ = K (1 - ln J) / J */
    *K_t = m->bulk_modulus * (1.0 - lnJ) / J;
}

const struct tlsph_eos_model tlsph_eos_linear = {
    .name = "linear",
    .module = "eos:linear",
    .keys = &table,
    .parse = parse,
    .pressure = pressure,
};
