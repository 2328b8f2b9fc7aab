/* The fused kinematics + stress pass (tlsph_constitutive_with_kinematics,
 * one parallel region per body) against its reference, the separate passes
 * tlsph_kinematics then tlsph_constitutive: every field they write and every
 * number they record must be the same bit for bit (tolerance 0: the fused
 * pass splits each body's range among the threads as the separate loops do
 * and sums in the same order).  Run with 2 threads on a Taylor bar of 5 334
 * particles, above TLSPH_PARALLEL_MIN_ITEMS, so the regions really run in
 * parallel; three evaluations under a velocity gradient that makes the
 * copper flow, so the plastic history and the heating take part.  And which
 * treatments may fuse: intact and virtual links, not damage-aware (its
 * gather reads the neighbours' damage, which the update writes). */
#include <check.h>
#include <math.h>
#include <string.h>

#include "material/constitutive.h"
#include "sph/kinematics.h"
#include "util/parallel.h"
#include "support/scene_builder.h"
#include "support/check_main.h"

/* x = X + a smooth displacement, v = a compressive velocity gradient (1/s)
 * with some shear: the same for both models at every evaluation k */
static void move(struct tlsph_model *m, int k)
{
    const double s = 2e-3 * (k + 1), rate = 2e4;
    for (size_t i = 0; i < m->p.n; i++) {
        const double *X = m->p.X + 3 * i;
        double *x = m->p.x + 3 * i, *v = m->p.v + 3 * i;
        x[0] = X[0] * (1.0 + 0.5 * s) + 1e-5 * sin(700.0 * X[2]);
        x[1] = X[1] * (1.0 + 0.5 * s) + 1e-5 * cos(900.0 * X[0]);
        x[2] = X[2] * (1.0 - s);
        v[0] = 0.5 * rate * X[0] + 0.1 * rate * X[2];
        v[1] = 0.5 * rate * X[1];
        v[2] = -rate * X[2];
    }
}

static void same_array(const double *a, const double *b, size_t n, const char *what)
{
    if (!a || !b) {
        ck_assert_msg(a == b, "%s: present in one model only", what);
        return;
    }
    ck_assert_msg(memcmp(a, b, n * sizeof *a) == 0, "%s differs", what);
}

START_TEST(fused_pass_matches_separate_passes)
{
#ifdef _OPENMP
    omp_set_num_threads(2); /* util/parallel.h includes omp.h */
#endif
    struct tlsph_model *ref = build_example("taylor-bar", 0.0006);
    struct tlsph_model *fus = build_example("taylor-bar", 0.0006);
    ck_assert_uint_ge(ref->p.n, TLSPH_PARALLEL_MIN_ITEMS);
    ck_assert(tlsph_kinematics_fusable(fus));
    const double dt = 2e-9;
    for (int k = 0; k < 3; k++) {
        move(ref, k);
        move(fus, k);
        tlsph_kinematics(ref, dt);
        tlsph_constitutive(ref, dt);
        tlsph_constitutive_with_kinematics(fus, dt);
    }
    const size_t n = ref->p.n;
    ck_assert_msg(ref->plastic_point_steps > 0, "the test must make the copper flow");
    same_array(ref->p.F, fus->p.F, 9 * n, "F");
    same_array(ref->p.Fdot, fus->p.Fdot, 9 * n, "Fdot");
    same_array(ref->p.sigma, fus->p.sigma, 6 * n, "sigma");
    same_array(ref->p.P_tilde, fus->p.P_tilde, 9 * n, "P_tilde");
    same_array(ref->p.e, fus->p.e, n, "e");
    same_array(ref->p.eps_p, fus->p.eps_p, n, "eps_p");
    same_array(ref->p.T, fus->p.T, n, "T");
    same_array(ref->p.hg_scale, fus->p.hg_scale, n, "hg_scale");
    ck_assert(memcmp(&ref->energy.plastic_work, &fus->energy.plastic_work, sizeof(double)) == 0);
    ck_assert(memcmp(&ref->dt_cfl, &fus->dt_cfl, sizeof(double)) == 0);
    ck_assert(memcmp(&ref->max_wave_speed, &fus->max_wave_speed, sizeof(double)) == 0);
    ck_assert(memcmp(&ref->min_detF, &fus->min_detF, sizeof(double)) == 0);
    ck_assert_int_eq(ref->plastic_point_steps, fus->plastic_point_steps);
    ck_assert_int_eq(ref->return_iterations, fus->return_iterations);
    tlsph_model_free(ref);
    tlsph_model_free(fus);
}
END_TEST

START_TEST(which_treatments_fuse)
{
    struct tlsph_model *links = build_example("projectile-beam-links", 0);
    struct tlsph_model *aware = build_example("weldox-notched-r2", 0);
    ck_assert(tlsph_kinematics_fusable(links));
    ck_assert(!tlsph_kinematics_fusable(aware));
    tlsph_model_free(links);
    tlsph_model_free(aware);
}
END_TEST

TLSPH_CHECK_MAIN("fused_phases", 120, fused_pass_matches_separate_passes, which_treatments_fuse)
