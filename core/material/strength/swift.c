/* Swift power-law hardening: sigma_y = K (eps_0 + eps_p)^n.
 * Parameters: strength_coefficient K (Pa), reference_strain eps_0 (> 0, so the
 * initial yield stress K eps_0^n is finite and positive), hardening_exponent n. */
#include <math.h>

#include "material/strength/parse_util.h"
#include "material/strength/strength.h"

enum { K, EPS0, N };

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    {.name = "strength_coefficient", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "Pa", .offset = TLSPH_PARAM(K),
     .description = "strength coefficient K; the initial yield stress K eps_0^n must be below "
                    "the Young's modulus"},
    STRENGTH_POSITIVE("reference_strain", 10.0, EPS0, "reference (pre-)strain eps_0"),
    STRENGTH_POSITIVE("hardening_exponent", 5.0, N, "hardening exponent n"),
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/materials/*/strength", "swift", keys);
/* clang-format on */

static int check(const struct tlsph_material *m, const char *pointer, struct tlsph_errors *err)
{
    const double *q = m->strength_params, yield = q[K] * pow(q[EPS0], q[N]);
    if (m->youngs_modulus <= 0.0 || yield < m->youngs_modulus) /* E = 0: invalid, reported */
        return 0;
    tlsph_key_error(err, pointer, "strength_coefficient",
                    "initial yield stress K eps_0^n = %g Pa must be below the Young's modulus "
                    "%g Pa",
                    yield, m->youngs_modulus);
    return -1;
}

static void flow(const struct tlsph_material *m, double eps_p, double rate, double T,
                 struct tlsph_flow *out)
{
    (void)rate;
    (void)T;
    const double k = m->strength_params[K], n = m->strength_params[N];
    const double base = m->strength_params[EPS0] + eps_p;
    const double s = k * pow(base, n);
    /* no rate and no temperature term: d_rate = d_temperature = 0 */
    *out = (struct tlsph_flow){.stress = s, .d_strain = n * s / base};
}

const struct tlsph_strength_model tlsph_strength_swift = {
    .name = "swift",
    .module = "strength:swift",
    .keys = &table,
    .parse = tlsph_strength_parse,
    .check = check,
    .flow = flow,
};
