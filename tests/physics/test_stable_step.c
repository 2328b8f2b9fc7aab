/* The stable-step estimate (core/material/step_estimate.h) against the stable
 * step measured on the discretisation itself (tests/support/stable_step.h: the
 * leapfrog limit 2 / omega_max of the engine's force evaluation linearised by
 * finite differences, with the damping of artificial viscosity).
 *
 * References and bounds (measured values in docs/performance.md, "the stable
 * step"):
 *  1. Safe: on an elastic block, a plastic Taylor bar's flowing foot and a
 *     block crushed with the largest viscosity, the estimate dt_cfl (before the
 *     CFL factor) is below the measured limit: dt_crit / dt_cfl >= 1 (measured
 *     1.07, 1.19 at this 1.6 mm bar, 1.2-1.4 at 0.8 mm, and 1.16).
 *  1b. The measured limit is the edge: the elastic block stepped at a fixed
 *     0.97 dt_crit runs 400 steps, at 1.03 dt_crit it does not (measured: 0.99
 *     runs, 1.01 is non-finite by step 50).
 *  2. Not wasteful: dt_crit / dt_cfl <= 2 (the "elastic" estimate's 1.6-1.7 on
 *     the flowing foot is what the "tangent" one removes; on the foot the
 *     tangent estimate is at least 15 % above the elastic one).
 *  3. Viscosity in the step (issue 18): the block crushed at 40 m/s with
 *     linear = quadratic = 10 (tests/hard/viscosity_max.json) runs to its end at
 *     the default cfl (the scene names none; 0.6 since 2026-11-26), checked every
 *     step, with the energy balance within 1 % of the energy scale at its end
 *     (measured 0.012 % at cfl 0.6); with the "elastic" estimate it stopped on
 *     `speed` after 10 steps at cfl 0.3. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "run/integrate.h"
#include "support/check_main.h"
#include "support/scene_builder.h"
#include "support/stable_step.h"

static double measured_ratio(struct tlsph_model *m, int damped)
{
    struct stable_step_measure s;
    ck_assert_int_eq(stable_step_measure(m, 60, &s), 0);
    ck_assert_msg(s.spread < 0.01, "power iteration did not settle: %g", s.spread);
    const double crit = damped ? s.dt_crit_damped : s.dt_crit;
    printf("dt_cfl %.4g s, dt_crit %.4g s, damped %.4g s (xi %.3g): ratio %.3f\n", m->dt_cfl,
           s.dt_crit, s.dt_crit_damped, s.xi, crit / m->dt_cfl);
    return crit / m->dt_cfl;
}

/* A 4 mm steel cube at 0.5 mm (512 particles) stretched at 20 m/s across; step > 0:
 * stepped at that fixed step for steps steps, with the energy contract at 1. */
static struct tlsph_model *elastic_block(double step, int steps)
{
    char time[256];
    if (step > 0.0)
        snprintf(time, sizeof time,
                 "\"time\":{\"end\":%.17g,\"step\":%.17g},\"output\":{\"frames\":1},"
                 "\"stability\":{\"energy_tolerance\":1.0}",
                 step * steps, step);
    else
        snprintf(time, sizeof time, "\"time\":{\"end\":1e-5}");
    char json[1024];
    snprintf(json, sizeof json,
             "{\"dimension\":3,%s,"
             "\"materials\":{\"s\":{\"density\":7800,\"youngs_modulus\":2e11,"
             "\"poisson_ratio\":0.3}},"
             "\"bodies\":[{\"name\":\"b\",\"material\":\"s\",\"spacing\":0.0005,"
             "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.004,0.004,0.004]}},"
             "\"initial_velocity\":[\"20*(x - 0.002)/0.004\",0,0]}]}",
             time);
    return build_model(json);
}

START_TEST(elastic_block_measured)
{
    struct tlsph_model *m = elastic_block(0.0, 0);
    run_until(m, 5e-7);
    const double r = measured_ratio(m, 0);
    ck_assert_msg(r >= 1.0 && r <= 2.0, "dt_crit / dt_cfl = %g", r);
    tlsph_model_free(m);
}
END_TEST

/* The edge itself: the elastic block stepped at a fixed step just under and just
 * over the measured limit.  Near the limit the synchronous kinetic energy
 * misstates the highest modes' energy by 1 / (1 - (omega dt / 2)^2), so the
 * energy contract is relaxed to 1 (with 0.05 it stops from 0.9 dt_crit on);
 * measured: 0.99 dt_crit runs, 1.01 goes non-finite by step 50. */
static int steps_survived(double dt, int steps)
{
    struct tlsph_model *m = elastic_block(dt, steps);
    struct tlsph_diagnostic d;
    int s = 0;
    while (s < steps) {
        tlsph_model_step(m);
        if (tlsph_model_check(m, &d) != 0)
            break;
        s++;
    }
    tlsph_model_free(m);
    return s;
}

START_TEST(edge_of_stability)
{
    struct tlsph_model *m = elastic_block(0.0, 0);
    struct stable_step_measure s;
    ck_assert_int_eq(stable_step_measure(m, 60, &s), 0);
    tlsph_model_free(m);
    const int below = steps_survived(0.97 * s.dt_crit, 400);
    const int above = steps_survived(1.03 * s.dt_crit, 400);
    printf("dt_crit %.4g s: 0.97 x ran %d of 400 steps, 1.03 x %d\n", s.dt_crit, below, above);
    ck_assert_int_eq(below, 400);
    ck_assert_int_lt(above, 400);
}
END_TEST

/* The FE Taylor bar (examples/taylor-bar-linear-hardening.json) at 1.6 mm,
 * 12 us after impact: the foot flows. */
static struct tlsph_model *taylor(const char *estimate)
{
    json_t *root = load_example("taylor-bar-linear-hardening");
    json_object_set_new(json_array_get(json_object_get(root, "bodies"), 0), "spacing",
                        json_real(0.0016));
    json_object_set_new(json_object_get(root, "time"), "step_estimate", json_string(estimate));
    struct tlsph_model *m = build_model_json(root);
    run_until(m, 1.2e-5);
    ck_assert(m->plastic_point_steps > 0);
    return m;
}

START_TEST(plastic_foot)
{
    struct tlsph_model *m = taylor("tangent");
    const double r = measured_ratio(m, 0);
    ck_assert_msg(r >= 1.0 && r <= 2.0, "dt_crit / dt_cfl = %g", r);
    /* the same state under the elastic estimate: re-evaluate with it */
    const double dt_tangent = m->dt_cfl;
    m->scene.step_estimate = 0;
    tlsph_evaluate(m, m->dt);
    const double dt_elastic = m->dt_cfl;
    printf("foot: tangent %.4g s, elastic %.4g s: %.3f\n", dt_tangent, dt_elastic,
           dt_tangent / dt_elastic);
    ck_assert_msg(dt_tangent >= 1.15 * dt_elastic, "tangent %g, elastic %g", dt_tangent,
                  dt_elastic);
    tlsph_model_free(m);
}
END_TEST

static json_t *crushed_block(void)
{
    const char *top = getenv("top_srcdir");
    char path[4096];
    snprintf(path, sizeof path, "%s/tests/hard/viscosity_max.json", top ? top : ".");
    json_error_t jerr;
    json_t *root = json_load_file(path, 0, &jerr);
    ck_assert_msg(root != NULL, "cannot read %s: %s", path, jerr.text);
    return root;
}

START_TEST(viscous_block_measured)
{
    struct tlsph_model *m = build_model_json(crushed_block());
    run_until(m, 5e-6);
    const double r = measured_ratio(m, 1);
    ck_assert_msg(r >= 1.0 && r <= 2.0, "dt_crit_damped / dt_cfl = %g", r);
    tlsph_model_free(m);
}
END_TEST

START_TEST(viscous_block_runs_at_default_cfl)
{
    json_t *root = crushed_block();
    ck_assert(json_object_get(json_object_get(root, "time"), "cfl") == NULL);
    struct tlsph_model *m = build_model_json(root);
    ck_assert(m->scene.cfl == TLSPH_DEFAULT_CFL);
    run_until(m, m->scene.end_time); /* fails the test if a check stops it */
    const double balance = fabs(tlsph_energy_balance(&m->energy)) / m->energy.scale;
    printf("crushed block: %ld steps, balance %.4g of the scale\n", m->step, balance);
    ck_assert_msg(balance < 0.01, "balance %g", balance);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("stable_step", 300, elastic_block_measured, edge_of_stability, plastic_foot,
                 viscous_block_measured, viscous_block_runs_at_default_cfl)
