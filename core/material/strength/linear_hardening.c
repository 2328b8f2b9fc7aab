/* Linear isotropic hardening: sigma_y = sigma_0 + H eps_p.
 * Parameters: yield_stress sigma_0 (Pa), hardening_modulus H (Pa, >= 0; 0 is
 * perfect plasticity). */
#include "material/strength/parse_util.h"
#include "material/strength/strength.h"

enum { SIGMA0, H };

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    STRENGTH_STRESS("yield_stress", JC_OPEN, SIGMA0, "initial yield stress sigma_0"),
    STRENGTH_STRESS("hardening_modulus", JC_CLOSED, H,
                    "hardening modulus H; 0 = perfect plasticity"),
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/materials/*/strength", "linear_hardening", keys);
/* clang-format on */

static void flow(const struct tlsph_material *m, double eps_p, double rate, double T,
                 struct tlsph_flow *out)
{
    (void)rate;
    (void)T;
    const double s0 = m->strength_params[SIGMA0], h = m->strength_params[H];
    /* no rate and no temperature term: d_rate = d_temperature = 0 */
    *out = (struct tlsph_flow){.stress = s0 + h * eps_p, .d_strain = h};
}

const struct tlsph_strength_model tlsph_strength_linear_hardening = {
    .name = "linear_hardening",
    .module = "strength:linear_hardening",
    .keys = &table,
    .parse = tlsph_strength_parse,
    .flow = flow,
};
