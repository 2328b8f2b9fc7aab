/* Linear isotropic hardening: sigma_y = sigma_0 + H eps_p.
 * Parameters: yield_stress sigma_0 (Pa), hardening_modulus H (Pa, >= 0; 0 is
 * perfect plasticity). */
#include "material/strength/parse_util.h"
#include "material/strength/strength.h"

enum { SIGMA0, H };

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    static const char *const keys[] = {"type", "yield_stress", "hardening_modulus", NULL};
    int bad = jc_unknown_keys(obj, keys, pointer, err) != 0;
    double s0 = 0, h = 0;
    bad |= strength_stress(obj, "yield_stress", 1, 0, m, pointer, &s0, err) < 0;
    bad |= strength_stress(obj, "hardening_modulus", 1, 1, m, pointer, &h, err) < 0;
    m->strength_params[SIGMA0] = s0;
    m->strength_params[H] = h;
    return bad ? -1 : 0;
}

static void flow(const struct tlsph_material *m, double eps_p, double rate, double T,
                 struct tlsph_flow *out)
{
    (void)rate;
    (void)T;
    out->stress = m->strength_params[SIGMA0] + m->strength_params[H] * eps_p;
    out->d_strain = m->strength_params[H];
    out->d_rate = 0.0;
    out->d_temperature = 0.0;
}

const struct tlsph_strength_model tlsph_strength_linear_hardening = {
    .name = "linear_hardening",
    .module = "strength:linear_hardening",
    .parse = parse,
    .flow = flow,
};
