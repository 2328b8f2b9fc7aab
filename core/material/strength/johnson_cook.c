/* Johnson-Cook flow stress (paper 000 eq. 38 without damage; paper 003 eq. 56):
 *
 *   sigma_y = (A + B eps_p^n) (1 + C ln(epsdot_p / epsdot_0)) (1 - T*^m),
 *   T* = (T - T_ref) / (T_melt - T_ref).
 *
 * The rate term is on only when the scene gives rate_coefficient C, the thermal
 * term only when it gives thermal_exponent m (with reference_temperature and
 * melting_temperature, and a "thermal" block on the material so that a
 * temperature exists).  Conventions at the ends of the ranges, as in Abaqus and
 * LS-DYNA: no rate effect below epsdot_0 (the logarithm would soften the
 * material without bound as the rate goes to 0), no thermal softening below
 * T_ref, and no strength at or above T_melt.  These are parts of the law, not
 * clamps on the numerics: the return mapping sees their exact derivatives. */
#include <math.h>

#include "material/strength/parse_util.h"
#include "material/strength/strength.h"

enum { A, B, N, C, EPSDOT0, M, TREF, TMELT };

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    static const char *const keys[] = {"type",
                                       "yield_stress",
                                       "hardening_coefficient",
                                       "hardening_exponent",
                                       "rate_coefficient",
                                       "reference_strain_rate",
                                       "thermal_exponent",
                                       "reference_temperature",
                                       "melting_temperature",
                                       NULL};
    double *q = m->strength_params;
    int bad = jc_unknown_keys(obj, keys, pointer, err) != 0;
    bad |= strength_stress(obj, "yield_stress", 1, 0, m, pointer, &q[A], err) < 0;
    bad |= strength_stress(obj, "hardening_coefficient", 1, 1, m, pointer, &q[B], err) < 0;
    bad |= jc_number(obj, "hardening_exponent", 1, ((struct jc_range){0.0, 5.0, JC_OPEN, JC_CLOSED}),
                     DIMENSIONLESS, pointer, &q[N], err) < 0;

    m->strength_terms = 0;
    q[EPSDOT0] = 1.0;
    int r = jc_number(obj, "rate_coefficient", 0, ((struct jc_range){0.0, 1.0, JC_OPEN, JC_CLOSED}),
                      DIMENSIONLESS, pointer, &q[C], err);
    bad |= r < 0;
    if (r == 0) {
        m->strength_terms |= TLSPH_FLOW_RATE;
        bad |= jc_number(obj, "reference_strain_rate", 0,
                         ((struct jc_range){0.0, 1e12, JC_OPEN, JC_CLOSED}), "1/s", pointer,
                         &q[EPSDOT0], err) < 0;
    } else if (r == 1) {
        bad |= jc_misplaced(obj, "reference_strain_rate", "rate_coefficient", pointer, err);
    }

    r = jc_number(obj, "thermal_exponent", 0, ((struct jc_range){0.0, 10.0, JC_OPEN, JC_CLOSED}),
                  DIMENSIONLESS, pointer, &q[M], err);
    bad |= r < 0;
    if (r == 0) {
        m->strength_terms |= TLSPH_FLOW_THERMAL;
        const struct jc_range kelvin = {0.0, 1e5, JC_OPEN, JC_CLOSED};
        int tb = jc_number(obj, "reference_temperature", 1, kelvin, "K", pointer, &q[TREF], err) < 0;
        tb |= jc_number(obj, "melting_temperature", 1, kelvin, "K", pointer, &q[TMELT], err) < 0;
        char p[TLSPH_POINTER_MAX];
        if (!tb && q[TMELT] <= q[TREF]) {
            tlsph_pointer_join(p, sizeof p, pointer, "melting_temperature");
            tlsph_errors_add(err, p,
                             "'melting_temperature' = %g K must be above 'reference_temperature' "
                             "= %g K",
                             q[TMELT], q[TREF]);
            tb = 1;
        }
        if (!m->thermal.enabled) {
            tlsph_pointer_join(p, sizeof p, pointer, "thermal_exponent");
            tlsph_errors_add(err, p,
                             "thermal softening needs a temperature: add a \"thermal\" block "
                             "(specific_heat, initial_temperature) to material '%s'",
                             m->name);
            tb = 1;
        } else if (!tb && m->thermal.initial_temperature >= q[TMELT]) {
            tlsph_pointer_join(p, sizeof p, pointer, "melting_temperature");
            tlsph_errors_add(err, p,
                             "the material starts molten: initial temperature %g K is not below "
                             "'melting_temperature' = %g K",
                             m->thermal.initial_temperature, q[TMELT]);
            tb = 1;
        }
        bad |= tb;
    } else if (r == 1) {
        bad |= jc_misplaced(obj, "reference_temperature", "thermal_exponent", pointer, err);
        bad |= jc_misplaced(obj, "melting_temperature", "thermal_exponent", pointer, err);
    }
    return bad ? -1 : 0;
}

static void flow(const struct tlsph_material *m, double eps_p, double rate, double T,
                 struct tlsph_flow *out)
{
    const double *q = m->strength_params;
    const double n = q[N];
    const double hard = eps_p > 0.0 ? q[B] * pow(eps_p, n) : 0.0; /* one pow: the hot call */
    const double g = q[A] + hard;
    /* dg/deps = B n eps^(n-1) = n hard / eps: unbounded at eps = 0 when n < 1 */
    const double dg = eps_p > 0.0 ? n * hard / eps_p
                                  : (n < 1.0 ? INFINITY : (n == 1.0 ? q[B] : 0.0));

    double fr = 1.0, dfr = 0.0;
    if ((m->strength_terms & TLSPH_FLOW_RATE) && rate > q[EPSDOT0]) {
        fr = 1.0 + q[C] * log(rate / q[EPSDOT0]);
        dfr = q[C] / rate;
    }

    double ft = 1.0, dft = 0.0;
    if (m->strength_terms & TLSPH_FLOW_THERMAL) {
        const double span = q[TMELT] - q[TREF];
        const double ts = (T - q[TREF]) / span;
        if (ts >= 1.0) {
            ft = 0.0;
        } else if (ts > 0.0) {
            const double p = pow(ts, q[M]);
            ft = 1.0 - p;
            dft = -q[M] * p / ts / span;
        }
    }

    out->stress = g * fr * ft;
    out->d_strain = ft > 0.0 ? dg * fr * ft : 0.0; /* molten: no hardening, no inf*0 */
    out->d_rate = g * dfr * ft;
    out->d_temperature = g * fr * dft;
}

const struct tlsph_strength_model tlsph_strength_johnson_cook = {
    .name = "johnson_cook",
    .module = "strength:johnson_cook",
    .parse = parse,
    .flow = flow,
};
