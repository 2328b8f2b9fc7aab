/* Voce saturation hardening: sigma_y = sigma_s - (sigma_s - sigma_0) exp(-b eps_p).
 * Parameters: yield_stress sigma_0 (Pa), saturation_stress sigma_s (Pa, >=
 * sigma_0), saturation_rate b (1). */
#include <math.h>

#include "material/strength/parse_util.h"
#include "material/strength/strength.h"

enum { SIGMA0, SIGMAS, B };

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    STRENGTH_STRESS("yield_stress", JC_OPEN, SIGMA0, "initial yield stress sigma_0"),
    STRENGTH_STRESS("saturation_stress", JC_OPEN, SIGMAS,
                    "saturation stress sigma_s, not below yield_stress"),
    STRENGTH_POSITIVE("saturation_rate", 1e4, B, "saturation rate b"),
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/materials/*/strength", "voce", keys);
/* clang-format on */

static int check(const struct tlsph_material *m, const char *pointer, struct tlsph_errors *err)
{
    const double *q = m->strength_params;
    if (q[SIGMAS] >= q[SIGMA0])
        return 0;
    tlsph_key_error(err, pointer, "saturation_stress",
                    "'saturation_stress' = %g Pa must not be below 'yield_stress' = %g Pa "
                    "(softening laws are not supported)",
                    q[SIGMAS], q[SIGMA0]);
    return -1;
}

static void flow(const struct tlsph_material *m, double eps_p, double rate, double T,
                 struct tlsph_flow *out)
{
    (void)rate;
    (void)T;
    const double s0 = m->strength_params[SIGMA0], ss = m->strength_params[SIGMAS];
    const double b = m->strength_params[B];
    const double decay = (ss - s0) * exp(-b * eps_p);
    /* no rate and no temperature term: d_rate = d_temperature = 0 */
    *out = (struct tlsph_flow){.stress = ss - decay, .d_strain = b * decay};
}

const struct tlsph_strength_model tlsph_strength_voce = {
    .name = "voce",
    .module = "strength:voce",
    .keys = &table,
    .parse = tlsph_strength_parse,
    .check = check,
    .flow = flow,
};
