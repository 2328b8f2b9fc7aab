/* Patch test: an affine displacement x = A X + b of a 3-D block (and a 2-D
 * plane-strain plate) gives F = A exactly at every particle, boundary and
 * corner particles included, because the corrected gradient reproduces linear
 * fields (paper 000 eqs. 16-17, 26).  An affine velocity field v = B X gives
 * Fdot = B the same way.  Reference: the imposed A and B.
 * Tolerance: 1e-10 relative (round-off of the sums is ~1e-14).
 *
 * Also checks the pair-force loop against a brute-force evaluation of eq. 31
 * (all pairs found by an O(n^2) search, kernel evaluated directly). */
#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "sph/forces.h"
#include "sph/kernel.h"
#include "sph/kinematics.h"
#include "material/constitutive.h"
#include "support/scene_builder.h"
#include "support/check_main.h"

static const char *block3d =
    "{\"dimension\":3,\"time\":{\"end\":1e-6},"
    "\"discretization\":{\"kernel\":\"cubic_spline\",\"support_factor\":2.4},"
    "\"materials\":{\"m\":{\"density\":2700,\"youngs_modulus\":7e10,\"poisson_ratio\":0.33}},"
    "\"bodies\":[{\"name\":\"b\",\"material\":\"m\",\"spacing\":0.001,"
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.008,0.006,0.005]}}}]}";

static const char *plate2d =
    "{\"dimension\":2,\"time\":{\"end\":1e-6},"
    "\"materials\":{\"m\":{\"density\":2700,\"youngs_modulus\":7e10,\"poisson_ratio\":0.33}},"
    "\"bodies\":[{\"name\":\"b\",\"material\":\"m\",\"spacing\":0.001,"
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.009,0.007,0]}}}]}";

static void check_affine(struct tlsph_model *m, const double A[9], const double B[9])
{
    const double b[3] = {0.3e-3, -0.2e-3, 0.1e-3};
    for (size_t i = 0; i < m->p.n; i++) {
        const double *X = m->p.X + 3 * i;
        for (int r = 0; r < 3; r++) {
            m->p.x[3 * i + r] = (m->dim == 2 && r == 2) ? 0.0 : b[r];
            m->p.v[3 * i + r] = 0.0;
            for (int c = 0; c < 3; c++) {
                m->p.x[3 * i + r] += A[3 * r + c] * X[c];
                m->p.v[3 * i + r] += B[3 * r + c] * X[c];
            }
        }
    }
    tlsph_kinematics(m, 0.0);
    double worst = 0.0, worstd = 0.0;
    for (size_t i = 0; i < m->p.n; i++)
        for (int k = 0; k < 9; k++) {
            worst = fmax(worst, fabs(m->p.F[9 * i + k] - A[k]));
            worstd = fmax(worstd, fabs(m->p.Fdot[9 * i + k] - B[k]));
        }
    ck_assert_msg(worst < 1e-10, "max |F - A| = %.3g", worst);
    ck_assert_msg(worstd < 1e-10 * 100.0, "max |Fdot - B| = %.3g (|B| ~ 100/s)", worstd);
}

START_TEST(patch_3d)
{
    struct tlsph_model *m = build_model(block3d);
    ck_assert_uint_eq(m->p.n, 8 * 6 * 5);
    ck_assert_uint_eq(m->deficient_supports, 0);
    const double A[9] = {1.02, 0.03, -0.01, 0.015, 0.97, 0.02, -0.02, 0.01, 1.05};
    const double B[9] = {10, -30, 5, 20, 40, -15, 7, 3, -60};
    check_affine(m, A, B);
    tlsph_model_free(m);
}
END_TEST

START_TEST(patch_2d)
{
    struct tlsph_model *m = build_model(plate2d);
    ck_assert_uint_eq(m->p.n, 9 * 7);
    const double A[9] = {1.03, -0.02, 0, 0.01, 0.96, 0, 0, 0, 1};
    const double B[9] = {15, -8, 0, 4, 25, 0, 0, 0, 0};
    check_affine(m, A, B);
    tlsph_model_free(m);
}
END_TEST

/* Every pair inside the kernel's support, at full weight. */
static double within_support(const struct tlsph_model *m, size_t i, size_t j, double r,
                             void *ctx)
{
    (void)ctx;
    return r < m->p.h[i] + m->p.h[j] ? 1.0 : 0.0;
}

/* Brute-force eq. 31 on a deformed block: f_i = sum_j V_i V_j (P~_i + P~_j) grad W_ij. */
START_TEST(forces_match_brute_force)
{
    struct tlsph_model *m = build_model(block3d);
    m->scene.hourglass = 0;
    m->scene.viscosity = 0;
    srand(3);
    check_forces_match_brute_force(m, within_support, NULL);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("patch", 0, patch_3d, patch_2d, forces_match_brute_force)
