/* Linear EOS in the logarithmic volume strain: p = -K ln(J) / J.
 *
 * Together with the elastic deviatoric response 2G dev(ln V)/J this is the
 * isotropic Hencky hyperelastic material (Kirchhoff stress tau = K ln J I +
 * 2G dev ln V), so small strains give Hooke's law with bulk modulus K and large
 * elastic deformations stay energy-conserving.  No parameters beyond E and nu. */
#include <math.h>

#include "scene/json_check.h"
#include "material/eos/eos.h"

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    static const char *const keys[] = {"type", NULL};
    (void)m;
    return jc_unknown_keys(obj, keys, pointer, err) ? -1 : 0;
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
    .parse = parse,
    .pressure = pressure,
};
