/* Swift power-law hardening: sigma_y = K (eps_0 + eps_p)^n.
 * Parameters: strength_coefficient K (Pa), reference_strain eps_0 (> 0, so the
 * initial yield stress K eps_0^n is finite and positive), hardening_exponent n. */
#include <math.h>

#include "material/strength/parse_util.h"
#include "material/strength/strength.h"

enum { K, EPS0, N };

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    static const char *const keys[] = {"type", "strength_coefficient", "reference_strain",
                                       "hardening_exponent", NULL};
    int bad = jc_unknown_keys(obj, keys, pointer, err) != 0;
    double k = 0, e0 = 0, n = 0;
    bad |= jc_number(obj, "strength_coefficient", 1, JC_POSITIVE, "Pa", pointer, &k, err) < 0;
    bad |= jc_number(obj, "reference_strain", 1,
                     ((struct jc_range){0.0, 10.0, JC_OPEN, JC_CLOSED}), DIMENSIONLESS, pointer, &e0,
                     err) < 0;
    bad |= jc_number(obj, "hardening_exponent", 1,
                     ((struct jc_range){0.0, 5.0, JC_OPEN, JC_CLOSED}), DIMENSIONLESS, pointer, &n,
                     err) < 0;
    if (!bad && m->youngs_modulus > 0.0 && k * pow(e0, n) >= m->youngs_modulus) {
        char p[TLSPH_POINTER_MAX];
        tlsph_pointer_join(p, sizeof p, pointer, "strength_coefficient");
        tlsph_errors_add(err, p,
                         "initial yield stress K eps_0^n = %g Pa must be below the Young's "
                         "modulus %g Pa",
                         k * pow(e0, n), m->youngs_modulus);
        bad = 1;
    }
    m->strength_params[K] = k;
    m->strength_params[EPS0] = e0;
    m->strength_params[N] = n;
    return bad ? -1 : 0;
}

static void flow(const struct tlsph_material *m, double eps_p, double rate, double T,
                 struct tlsph_flow *out)
{
    (void)rate;
    (void)T;
    const double k = m->strength_params[K], n = m->strength_params[N];
    const double base = m->strength_params[EPS0] + eps_p;
    const double s = k * pow(base, n);
    out->stress = s;
    out->d_strain = n * s / base;
    out->d_rate = 0.0;
    out->d_temperature = 0.0;
}

const struct tlsph_strength_model tlsph_strength_swift = {
    .name = "swift",
    .module = "strength:swift",
    .parse = parse,
    .flow = flow,
};
