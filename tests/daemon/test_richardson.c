/* Unit tests of server/richardson.c against hand-worked sequences.
 *
 * References (each worked by hand in the comment of its test):
 *  - f(h) = 1 + 0.5 h^2 at h = 0.1, 0.2, 0.4: order 2, limit 1 exactly;
 *  - f(h) = 2 - 3 h^1.5 at h = 1, 2, 4: order 1.5 (not an integer), limit 2;
 *  - the three-grid formulas of Celik et al. (J. Fluids Eng. 130, 2008):
 *    p = ln(e32/e21)/ln r, f_ext = f1 + (f1 - f2)/(r^p - 1),
 *    GCI_fine = Fs |f1 - f_ext| / |f1| with Fs = 1.25 (Roache 1998);
 *  - oscillatory (e32/e21 < 0), divergent (|e32| <= |e21|), orders outside
 *    [0.5, 6], and four resolutions whose two triplets disagree (Roache's
 *    GCI ratio check).
 * Also the convergence process's own arithmetic (server/convergence*.c): the
 * threshold crossing, the ladder it builds (bodies refined together) and the
 * cost fit of a result whose runs carry cost records.
 * Tolerances: 1e-12 relative (the arithmetic is exact up to round-off). */
#include <check.h>
#include <math.h>

#include "convergence.h"
#include "richardson.h"
#include "support/check_main.h"

#define CLOSE(a, b) ck_assert_msg(fabs((a) - (b)) <= 1e-12 * fmax(1.0, fabs(b)), \
                                  "%s = %.17g, expected %.17g", #a, (double)(a), (double)(b))

START_TEST(second_order)
{
    /* f = 1.005, 1.02, 1.08: e21 = 0.015, e32 = 0.06, ratio 4 = 2^2 -> p = 2;
     * f_ext = 1.005 - 0.015/3 = 1; errors 0.005, 0.02, 0.08;
     * GCI_fine = 1.25 * 0.005 / 1.005 */
    const double h[] = {0.1, 0.2, 0.4}, f[] = {1.005, 1.02, 1.08};
    struct trich_estimate e;
    ck_assert_int_eq(trich_estimate(h, f, 3, &e), TRICH_CONVERGING);
    CLOSE(e.ratio, 2.0);
    CLOSE(e.order, 2.0);
    CLOSE(e.extrapolated, 1.0);
    CLOSE(e.safety_factor, 1.25);
    CLOSE(e.error[0], 0.005);
    CLOSE(e.error[1], 0.02);
    CLOSE(e.error[2], 0.08);
    CLOSE(e.relative[1], 0.02);
    CLOSE(e.gci[0], 1.25 * 0.005 / 1.005);
    ck_assert(isnan(e.asymptotic_ratio)); /* three resolutions: no independent check */
    /* target GCI 0.0015625 = 0.00625 / 4 at order 2: half the spacing */
    CLOSE(trich_spacing_for(&e, h, 0.0015625), 0.05);
}
END_TEST

START_TEST(fractional_order)
{
    /* f = 2 - 3 h^1.5: -1, 2 - 6 sqrt 2, -22; e32/e21 = 2^1.5 -> p = 1.5;
     * f_ext = -1 + (6 sqrt 2 - 3) / (2 sqrt 2 - 1) = -1 + 3 = 2 */
    const double h[] = {1, 2, 4}, f[] = {-1.0, 2.0 - 6.0 * sqrt(2.0), -22.0};
    struct trich_estimate e;
    ck_assert_int_eq(trich_estimate(h, f, 3, &e), TRICH_CONVERGING);
    CLOSE(e.order, 1.5);
    CLOSE(e.extrapolated, 2.0);
    CLOSE(e.error[0], 3.0);
    CLOSE(e.gci[0], 1.25 * 3.0 / 1.0);
}
END_TEST

START_TEST(flags)
{
    const double h[] = {0.1, 0.2, 0.4, 0.8};
    struct trich_estimate e;
    /* oscillatory: e21 = +0.1, e32 = -0.15 */
    const double osc[] = {1.0, 1.1, 0.95};
    ck_assert_int_eq(trich_estimate(h, osc, 3, &e), TRICH_OSCILLATORY);
    ck_assert(isnan(e.order) && isnan(e.extrapolated) && isnan(e.error[0]) && isnan(e.gci[0]));
    /* Stern et al.: half the range of the three values, (1.1 - 0.95) / 2, over |f1| = 1 */
    CLOSE(e.oscillation, 0.075);
    CLOSE(e.oscillation_relative, 0.075);
    /* divergent: the change halves as the spacing doubles (e32/e21 = 0.5) */
    const double div[] = {1.0, 1.1, 1.15};
    ck_assert_int_eq(trich_estimate(h, div, 3, &e), TRICH_DIVERGENT);
    ck_assert(isnan(e.extrapolated) && isnan(e.oscillation)); /* only when it oscillates */
    /* order ln(1.1)/ln 2 = 0.1375 < 0.5: reported, no estimate */
    const double slow[] = {1.0, 1.1, 1.21};
    ck_assert_int_eq(trich_estimate(h, slow, 3, &e), TRICH_NON_ASYMPTOTIC);
    CLOSE(e.order, log(1.1) / log(2.0));
    ck_assert(isnan(e.extrapolated) && isnan(e.gci[0]));
    /* order log2(999) = 9.96 > 6 */
    const double fast[] = {1.0, 1.001, 2.0};
    ck_assert_int_eq(trich_estimate(h, fast, 3, &e), TRICH_NON_ASYMPTOTIC);
    /* equal values: no visible error */
    const double same[] = {3.0, 3.0, 3.0};
    ck_assert_int_eq(trich_estimate(h, same, 3, &e), TRICH_UNCHANGED);
    CLOSE(e.extrapolated, 3.0);
    CLOSE(e.error[2], 0.0);
    /* two values, or a missing middle value: the order cannot be observed */
    ck_assert_int_eq(trich_estimate(h, same, 2, &e), TRICH_TOO_FEW);
    const double hole[] = {1.0, NAN, 1.2, 1.3};
    ck_assert_int_eq(trich_estimate(h, hole, 4, &e), TRICH_TOO_FEW);
}
END_TEST

START_TEST(finest_missing)
{
    /* the finest run has not finished: the three next ones (the sequence of
     * second_order) give the estimate, indexed like the input */
    const double h[] = {0.05, 0.1, 0.2, 0.4}, f[] = {NAN, 1.005, 1.02, 1.08};
    struct trich_estimate e;
    ck_assert_int_eq(trich_estimate(h, f, 4, &e), TRICH_CONVERGING);
    ck_assert_uint_eq(e.first, 1);
    CLOSE(e.order, 2.0);
    CLOSE(e.extrapolated, 1.0);
    ck_assert(isnan(e.error[0]));
    CLOSE(e.error[1], 0.005);
    CLOSE(e.error[3], 0.08);
    CLOSE(trich_spacing_for(&e, h, 0.0015625), 0.05);
}
END_TEST

START_TEST(four_resolutions)
{
    const double h[] = {0.1, 0.2, 0.4, 0.8};
    struct trich_estimate e;
    /* f = 1 + h^2: both triplets have p = 2; ratio = (f1/f2)(3/3) = 1.01/1.04 */
    const double quad[] = {1.01, 1.04, 1.16, 1.64};
    ck_assert_int_eq(trich_estimate(h, quad, 4, &e), TRICH_CONVERGING);
    CLOSE(e.order, 2.0);
    CLOSE(e.order_coarse, 2.0);
    CLOSE(e.asymptotic_ratio, 1.01 / 1.04);
    CLOSE(e.extrapolated, 1.0);
    CLOSE(e.error[3], 0.64);
    /* f = 1 + h^2 + 5 h^4 = 1.0105, 1.048, 1.288, 3.688: e21 = 0.0375, e32 = 0.24,
     * e43 = 2.4; p12 = log2 6.4, p23 = log2 10; ratio = (1.0105/1.048)(5.4/9) = 0.5785:
     * the coarse triplet is not in the asymptotic range */
    const double quart[] = {1.0105, 1.048, 1.288, 3.688};
    ck_assert_int_eq(trich_estimate(h, quart, 4, &e), TRICH_NON_ASYMPTOTIC);
    CLOSE(e.order, log(6.4) / log(2.0));
    CLOSE(e.order_coarse, log(10.0) / log(2.0));
    CLOSE(e.asymptotic_ratio, 1.0105 / 1.048 * 5.4 / 9.0);
    ck_assert(isnan(e.extrapolated));
}
END_TEST

START_TEST(power_fit)
{
    struct trich_power_fit fit;
    const double h[] = {1.0, 0.5, 0.25};
    /* exact: y = 3 h^-3 */
    const double y[] = {3.0, 24.0, 192.0};
    ck_assert_int_eq(trich_fit_power(h, y, 3, &fit), 0);
    CLOSE(fit.q, 3.0);
    CLOSE(fit.c, 3.0);
    ck_assert(fit.rms_log_residual < 1e-12);
    CLOSE(trich_power_eval(&fit, 0.125), 1536.0);
    /* y = h^-2 times 1.1, 1/1.1, 1.1: the pattern (+d, -d, +d), d = ln 1.1, is
     * orthogonal to the centred ln h, so q stays 2; the intercept takes its mean
     * d/3 and the residuals are d (2/3, -4/3, 2/3): RMS d sqrt(8/9) */
    const double d = log(1.1);
    const double noisy[] = {1.1, 4.0 / 1.1, 16.0 * 1.1};
    ck_assert_int_eq(trich_fit_power(h, noisy, 3, &fit), 0);
    CLOSE(fit.q, 2.0);
    CLOSE(fit.c, exp(d / 3.0));
    CLOSE(fit.rms_log_residual, d * sqrt(8.0 / 9.0));
    /* fewer than two usable points */
    const double bad[] = {1.0, -1.0, NAN};
    ck_assert_int_eq(trich_fit_power(h, bad, 3, &fit), -1);
}
END_TEST

START_TEST(crossing)
{
    /* 0.8 -> 0.4 between t = 1 and 2 crosses 0.5 at 1 + 0.3/0.4 = 1.75 */
    const double t[] = {0, 1, 2, 3}, v[] = {1.0, 0.8, 0.4, 0.2};
    CLOSE(tconv_crossing_time(t, v, 4, 0.5, "falling"), 1.75);
    CLOSE(tconv_crossing_time(t, v, 4, 0.5, "either"), 1.75);
    CLOSE(tconv_crossing_time(t, v, 4, 0.5, NULL), 1.75);
    ck_assert(isnan(tconv_crossing_time(t, v, 4, 0.5, "rising")));
    ck_assert(isnan(tconv_crossing_time(t, v, 4, 2.0, "either")));
}
END_TEST

START_TEST(ladder_study)
{
    /* two bodies at 2 and 1 mm: the ladder names the first; the second keeps
     * half the first's spacing */
    json_t *in = json_loads(
        "{\"base\": {\"bodies\": [{\"spacing\": 0.002}, {\"spacing\": 0.001}]},"
        " \"ladder\": {\"spacing\": 0.004, \"ratio\": 2, \"count\": 3},"
        " \"outputs\": [{\"name\": \"t\", \"series\": \"kinetic_energy\","
        "  \"reduce\": \"time_of_threshold\", \"threshold\": 1e-3},"
        "  {\"name\": \"k\", \"series\": \"kinetic_energy\", \"reduce\": \"max\"}]}",
        0, NULL);
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    json_t *st = tconv_study(in, &err);
    ck_assert_ptr_nonnull(st);
    ck_assert_int_eq((int)err.count, 0);
    json_t *p = json_object_get(json_object_get(st, "sweep"), "parameters");
    ck_assert_uint_eq(json_array_size(p), 2);
    json_t *v1 = json_object_get(json_array_get(p, 1), "values");
    ck_assert_str_eq(json_string_value(json_object_get(json_array_get(p, 1), "pointer")),
                     "/bodies/1/spacing");
    CLOSE(json_real_value(json_array_get(v1, 0)), 0.002);
    CLOSE(json_real_value(json_array_get(v1, 2)), 0.0005);
    /* the study's own outputs: only those a summary can reduce */
    ck_assert_uint_eq(json_array_size(json_object_get(st, "outputs")), 1);
    ck_assert(tconv_is_convergence(st));
    json_decref(st);
    /* refused: a ratio that is not constant, naming the field */
    json_object_set_new(in, "ladder", json_loads("{\"spacings\": [0.004, 0.002, 0.0015]}", 0, NULL));
    ck_assert_ptr_null(tconv_study(in, &err));
    ck_assert_uint_eq(err.count, 1);
    ck_assert_str_eq(err.items[0].pointer, "/ladder/spacings");
    tlsph_errors_free(&err);
    json_decref(in);
}
END_TEST

START_TEST(result_costs)
{
    /* three successful runs whose result files are missing, with cost records
     * wall = 2 h^-3 (h = 4, 2, 1 mm), particles N = 1e-4 h^-2 and peak memory
     * 1e6 + 1e3 N: the fits give q = 3 and 2 and memory (1e6, 1e3) exactly;
     * no output value (the file is missing), hence no estimate */
    json_t *stored = json_loads(
        "{\"sweep\": {\"parameters\": [{\"pointer\": \"/bodies/0/spacing\","
        "  \"values\": [0.004, 0.002, 0.001]}]},"
        " \"convergence\": {\"ladder\": {\"pointers\": [\"/bodies/0/spacing\"], \"ratio\": 2},"
        "  \"outputs\": [{\"name\": \"k\", \"series\": \"kinetic_energy\", \"reduce\": \"max\"}]}}",
        0, NULL);
    const double h[] = {0.004, 0.002, 0.001};
    json_t *params[3], *cost[3];
    struct tstudy_row rows[3];
    for (int i = 0; i < 3; i++) {
        params[i] = json_pack("{s:f}", "/bodies/0/spacing", h[i]);
        cost[i] = json_pack("{s:f,s:f,s:f,s:f}", "particles", 1e-4 / (h[i] * h[i]), "steps", 100.0 / h[i],
                            "wall_seconds", 2.0 / (h[i] * h[i] * h[i]), "peak_memory_bytes",
                            1e6 + 1e3 * 1e-4 / (h[i] * h[i]));
        rows[i] = (struct tstudy_row){i, "x", "successful", params[i], "/nonexistent.h5", cost[i]};
    }
    json_t *res = tconv_result(stored, rows, 3);
    ck_assert_ptr_nonnull(res);
    json_t *cm = json_object_get(res, "cost_model");
    CLOSE(json_real_value(json_object_get(json_object_get(cm, "wall_seconds"), "q")), 3.0);
    CLOSE(json_real_value(json_object_get(json_object_get(cm, "particles"), "q")), 2.0);
    json_t *mem = json_object_get(cm, "peak_memory_bytes");
    ck_assert(fabs(json_real_value(json_object_get(mem, "fixed")) - 1e6) < 1e-6);
    CLOSE(json_real_value(json_object_get(mem, "per_particle")), 1e3);
    json_t *o = json_array_get(json_object_get(res, "outputs"), 0);
    ck_assert_str_eq(json_string_value(json_object_get(o, "status")), "too_few");
    ck_assert(json_is_null(json_array_get(json_object_get(o, "values"), 0)));
    ck_assert_uint_eq(json_array_size(json_object_get(o, "missing")), 3);
    ck_assert(json_is_true(json_object_get(res, "complete")));
    /* runs finest first */
    CLOSE(json_real_value(json_object_get(json_array_get(json_object_get(res, "runs"), 0), "spacing")),
          0.001);
    json_decref(res);
    for (int i = 0; i < 3; i++) {
        json_decref(params[i]);
        json_decref(cost[i]);
    }
    json_decref(stored);
}
END_TEST

TLSPH_CHECK_MAIN("richardson", 0, second_order, fractional_order, flags, finest_missing,
                  four_resolutions, power_fit, crossing, ladder_study, result_costs)
