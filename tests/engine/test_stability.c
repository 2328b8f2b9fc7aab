/* The run-time guards of issue 13 (docs/engine.md, "Stability contract"):
 *  - time that stops: a step that is not positive, that leaves t + dt == t, or
 *    that would make the run pass TLSPH_MAX_STEPS stops the run with a
 *    "time_step" diagnostic naming the particles that limit the step; time.max_steps
 *    lifts the projection (the run is bounded by it);
 *  - the frame schedule: a step that would pass two frame times ends at the
 *    next one; a step no longer than the frame interval is left alone
 *    (bit-identical results for every run whose steps are shorter);
 *  - an energy balance that fails names the particles whose energy changed
 *    most, the one given an extra kick first;
 *  - the writer refuses a frame holding a value that is not finite in its stored
 *    type (a stress of 1e39 Pa is finite in the model but Inf in float32) and
 *    leaves the file as it was.
 * References: the definitions in core/run/stability.c, core/run/integrate.c and
 * core/io/output/output.h; exact comparisons except where stated. */
#include <check.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/output/output.h"
#include "run/integrate.h"
#include "scene/limits.h"
#include "support/check_main.h"
#include "support/scene_builder.h"

/* a steel cube of 4 x 4 x 4 particles at rest, 1 ms */
#define CUBE(TIME)                                                                                 \
    "{\"dimension\":3,\"time\":" TIME ","                                                          \
    "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2.1e11,\"poisson_ratio\":0.3}}" \
    ","                                                                                            \
    "\"bodies\":[{\"name\":\"cube\",\"material\":\"steel\",\"spacing\":0.001,"                     \
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.004,0.004,0.004]}}}]}"

START_TEST(time_that_stops)
{
    struct tlsph_model *m = build_model(CUBE("{\"end\":1e-3}"));
    struct tlsph_diagnostic d;
    ck_assert_int_eq(tlsph_time_check(m, &d), 0);

    const double dt_cfl = m->dt_cfl;
    m->dt_cfl = 0.0; /* no step at all */
    ck_assert_int_eq(tlsph_time_check(m, &d), -1);
    ck_assert_str_eq(d.quantity, "time_step");
    ck_assert(d.value == 0.0);
    ck_assert_uint_eq(d.nids, 16); /* every particle limits a zero step: the first 16 */

    /* a step that advances, but the run would take 2e8 steps */
    m->dt_cfl = 1e-3 / (2.0 * (double)TLSPH_MAX_STEPS) / m->scene.cfl;
    ck_assert_int_eq(tlsph_time_check(m, &d), -1);
    ck_assert_msg(fabs(d.limit - 1e-3 / (double)TLSPH_MAX_STEPS) <= 1e-15 * d.limit, "limit %g",
                  d.limit); /* the step that would just do: round-off */
    ck_assert_msg(strstr(d.message, "time_step") && strstr(d.message, "(limiting the step)"), "%s",
                  d.message);

    m->dt_cfl = dt_cfl;
    ck_assert_int_eq(tlsph_time_check(m, &d), 0);
    tlsph_model_free(m);

    /* with max_steps the run is bounded: no projection, but time must still move */
    m = build_model(CUBE("{\"end\":1e-3,\"max_steps\":10}"));
    m->dt_cfl = 1e-3 / (2.0 * (double)TLSPH_MAX_STEPS) / m->scene.cfl;
    ck_assert_int_eq(tlsph_time_check(m, &d), 0);
    m->t = 5e-4;
    m->dt_cfl = 1e-25; /* t + dt == t */
    ck_assert_int_eq(tlsph_time_check(m, &d), -1);
    ck_assert_str_eq(d.quantity, "time_step");
    ck_assert(d.limit == nextafter(5e-4, 1.0) - 5e-4);
    m->dt_cfl = -1.0;
    ck_assert_int_eq(tlsph_time_check(m, &d), -1);
    tlsph_model_free(m);
}
END_TEST

START_TEST(frame_schedule)
{
    struct tlsph_model *m = build_model(CUBE("{\"end\":1e-3}"));
    const double step = m->scene.cfl * m->dt_cfl;
    ck_assert(step > 0.0);
    ck_assert(tlsph_next_dt(m) == step); /* no schedule: the CFL step */

    /* steps no longer than the frame interval are never touched */
    m->frame_interval = step;
    m->next_frame_time = 0.3 * step;
    ck_assert(tlsph_next_dt(m) == step);
    m->frame_interval = 0.7 * step; /* passes one frame time only */
    m->t = 0.0;
    m->next_frame_time = 0.5 * step;
    ck_assert(tlsph_next_dt(m) == step);

    /* a step that would pass the frame time after next ends at the next one */
    m->frame_interval = 0.25 * step;
    m->t = 1.0 * step;
    m->next_frame_time = 1.1 * step;
    ck_assert(tlsph_next_dt(m) == 1.1 * step - 1.0 * step);
    /* and a step cut short is no stalled time: the projection counts stable steps */
    m->next_frame_time = (1.0 + 1e-11) * step;
    struct tlsph_diagnostic d;
    ck_assert_int_eq(tlsph_time_check(m, &d), 0);
    tlsph_model_free(m);
}
END_TEST

START_TEST(energy_balance_names_particles)
{
    struct tlsph_model *m = build_model(CUBE("{\"end\":1e-3}"));
    for (int s = 0; s < 5; s++)
        tlsph_model_step(m);
    struct tlsph_diagnostic d;
    ck_assert_int_eq(tlsph_model_check(m, &d), 0);
    /* energy from nowhere: particle 37 moves, the balance books 1 J it never got */
    const size_t k = 37;
    m->p.v[3 * k] = 1.0;
    m->energy.kinetic += 1.0;
    m->energy.scale += 1.0;
    ck_assert_int_eq(tlsph_model_check(m, &d), -1);
    ck_assert_str_eq(d.quantity, "energy_balance");
    ck_assert_uint_ge(d.nids, 1);
    ck_assert_int_eq(d.ids[0], m->p.id[k]);
    ck_assert_msg(strstr(d.message, "(largest energy change)"), "%s", d.message);
    tlsph_model_free(m);
}
END_TEST

/* Frames in DIR/result.h5 (the length of the frames' step dataset). */
static hsize_t frames_in(const char *dir)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/result.h5", dir);
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    ck_assert(f >= 0);
    hid_t ds = H5Dopen2(f, "/particles/solid/position/step", H5P_DEFAULT);
    hid_t sp = H5Dget_space(ds);
    hsize_t n = 0;
    H5Sget_simple_extent_dims(sp, &n, NULL);
    H5Sclose(sp);
    H5Dclose(ds);
    H5Fclose(f);
    return n;
}

START_TEST(writer_refuses_non_finite)
{
    struct tlsph_model *m = build_model(CUBE("{\"end\":1e-3}"));
    char dir[] = "/tmp/test_stability.XXXXXX";
    ck_assert(mkdtemp(dir) != NULL);
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tlsph_output *out = tlsph_output_open(dir, m, &err);
    ck_assert(out != NULL);
    ck_assert_int_eq(tlsph_output_frame(out, m), 0);
    ck_assert_int_eq(tlsph_output_series(out, m), 0);

    const size_t k = 21;
    m->p.sigma[6 * k + 3] = 1e39; /* finite here, beyond float32 in the file */
    ck_assert_int_eq(tlsph_output_frame(out, m), TLSPH_OUTPUT_REFUSED);
    const struct tlsph_output_refusal *r = tlsph_output_refusal(out);
    ck_assert_str_eq(r->dataset, "/particles/solid/stress/value");
    ck_assert_uint_eq(r->nids, 1);
    ck_assert_int_eq(r->ids[0], m->p.id[k]);
    ck_assert(isinf(r->value));

    m->p.sigma[6 * k + 3] = 0.0;
    m->energy.kinetic = NAN; /* a series sample */
    m->step = 1;
    ck_assert_int_eq(tlsph_output_series(out, m), TLSPH_OUTPUT_REFUSED);
    ck_assert_str_eq(tlsph_output_refusal(out)->dataset, "/observables/kinetic_energy/value");

    struct tlsph_cost cost = {0};
    ck_assert_int_eq(tlsph_output_close(out, m, &cost, "unstable", NULL), 0);
    ck_assert_int_eq((int)frames_in(dir), 1); /* the refused frame left no trace */
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(cmd), 0);
    tlsph_errors_free(&err);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("stability", 120, time_that_stops, frame_schedule, energy_balance_names_particles,
                 writer_refuses_non_finite)
