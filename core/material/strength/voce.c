/* Voce saturation hardening: sigma_y = sigma_s - (sigma_s - sigma_0) exp(-b eps_p).
 * Parameters: yield_stress sigma_0 (Pa), saturation_stress sigma_s (Pa, >=
 * sigma_0), saturation_rate b (1). */
#include <math.h>

#include "material/strength/parse_util.h"
#include "material/strength/strength.h"

enum { SIGMA0, SIGMAS, B };

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    static const char *const keys[] = {"type", "yield_stress", "saturation_stress",
                                       "saturation_rate", NULL};
    int bad = jc_unknown_keys(obj, keys, pointer, err) != 0;
    double s0 = 0, ss = 0, b = 0;
    bad |= strength_stress(obj, "yield_stress", 1, 0, m, pointer, &s0, err) < 0;
    bad |= strength_stress(obj, "saturation_stress", 1, 0, m, pointer, &ss, err) < 0;
    bad |= jc_number(obj, "saturation_rate", 1, ((struct jc_range){0.0, 1e4, JC_OPEN, JC_CLOSED}),
                     DIMENSIONLESS, pointer, &b, err) < 0;
    if (!bad && ss < s0) {
        char p[TLSPH_POINTER_MAX];
        tlsph_pointer_join(p, sizeof p, pointer, "saturation_stress");
        tlsph_errors_add(err, p,
                         "'saturation_stress' = %g Pa must not be below 'yield_stress' = %g Pa "
                         "(softening laws are not supported)",
                         ss, s0);
        bad = 1;
    }
    m->strength_params[SIGMA0] = s0;
    m->strength_params[SIGMAS] = ss;
    m->strength_params[B] = b;
    return bad ? -1 : 0;
}

static void flow(const struct tlsph_material *m, double eps_p, double rate, double T,
                 struct tlsph_flow *out)
{
    (void)rate;
    (void)T;
    const double s0 = m->strength_params[SIGMA0], ss = m->strength_params[SIGMAS];
    const double b = m->strength_params[B];
    const double decay = (ss - s0) * exp(-b * eps_p);
    out->stress = ss - decay;
    out->d_strain = b * decay;
    out->d_rate = 0.0;
    out->d_temperature = 0.0;
}

const struct tlsph_strength_model tlsph_strength_voce = {
    .name = "voce",
    .module = "strength:voce",
    .parse = parse,
    .flow = flow,
};
