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

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    STRENGTH_STRESS("yield_stress", JC_OPEN, A, "initial yield stress A"),
    STRENGTH_STRESS("hardening_coefficient", JC_CLOSED, B, "hardening coefficient B"),
    STRENGTH_POSITIVE("hardening_exponent", 5.0, N, "hardening exponent n"),
    {.name = "rate_coefficient", .kind = TLSPH_KEY_NUMBER, .range = {0.0, 1.0, JC_OPEN, JC_CLOSED},
     .unit = "1", .term = TLSPH_FLOW_RATE, .offset = TLSPH_PARAM(C),
     .description = "strain-rate coefficient C; absent = no rate term"},
    {.name = "reference_strain_rate", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,
     .range = {0.0, 1e12, JC_OPEN, JC_CLOSED}, .unit = "1/s", .def = 1.0,
     .with = "rate_coefficient", .offset = TLSPH_PARAM(EPSDOT0),
     .description = "reference plastic strain rate epsdot_0; no rate effect below it"},
    {.name = "thermal_exponent", .kind = TLSPH_KEY_NUMBER, .range = {0.0, 10.0, JC_OPEN, JC_CLOSED},
     .unit = "1", .term = TLSPH_FLOW_THERMAL, .offset = TLSPH_PARAM(M),
     .description = "thermal-softening exponent m; absent = no thermal softening; needs the "
                    "material's thermal block"},
    {.name = "reference_temperature", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 1e5, JC_OPEN, JC_CLOSED}, .unit = "K", .with = "thermal_exponent",
     .offset = TLSPH_PARAM(TREF),
     .description = "reference temperature T_ref; no softening below it"},
    {.name = "melting_temperature", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 1e5, JC_OPEN, JC_CLOSED}, .unit = "K", .with = "thermal_exponent",
     .offset = TLSPH_PARAM(TMELT),
     .description = "melting temperature T_melt, above T_ref and the initial temperature; "
                    "no strength at and above it"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/materials/*/strength", "johnson_cook", keys);
/* clang-format on */

/* The thermal term compares its temperatures with each other and with the
 * material's thermal block. */
static int check_thermal(const struct tlsph_material *m, const char *pointer,
                         struct tlsph_errors *err)
{
    const double *q = m->strength_params;
    int bad = !(q[TREF] > 0.0 && q[TMELT] > 0.0); /* not both read */
    int reported = 0;
    if (!bad && q[TMELT] <= q[TREF]) {
        tlsph_key_error(err, pointer, "melting_temperature",
                        "'melting_temperature' = %g K must be above 'reference_temperature' "
                        "= %g K",
                        q[TMELT], q[TREF]);
        bad = reported = 1;
    }
    if (!m->thermal.enabled) {
        tlsph_key_error(err, pointer, "thermal_exponent",
                        "thermal softening needs a temperature: add a \"thermal\" block "
                        "(specific_heat, initial_temperature) to material '%s'",
                        m->name);
        reported = 1;
    } else if (!bad && m->thermal.initial_temperature >= q[TMELT]) {
        tlsph_key_error(err, pointer, "melting_temperature",
                        "the material starts molten: initial temperature %g K is not below "
                        "'melting_temperature' = %g K",
                        m->thermal.initial_temperature, q[TMELT]);
        reported = 1;
    }
    return reported ? -1 : 0;
}

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    const struct tlsph_key_target to = strength_target(m);
    int bad = tlsph_keys_read(obj, &table, pointer, &to, err) != 0;
    if (json_object_get(obj, "thermal_exponent"))
        bad |= check_thermal(m, pointer, err) != 0;
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
    .keys = &table,
    .parse = parse,
    .flow = flow,
};
