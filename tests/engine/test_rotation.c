/* Objectivity.
 * 1. A rigid rotation (90 degrees and 37 degrees about a skew axis, plus a
 *    translation) produces no stress and no force: reference 0; tolerance
 *    1e-9 E for stress (round-off of the polar decomposition is ~1e-15 E) and
 *    1e-9 E * spacing^2 for forces.
 * 2. A rotation superposed on a stretch rotates the stress: sigma(R U) = R
 *    sigma(U) R^T, to 1e-9 relative. */
#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "material/constitutive.h"
#include "sph/forces.h"
#include "sph/kinematics.h"
#include "util/mat3.h"
#include "support/scene_builder.h"
#include "support/check_main.h"

static const char *block =
    "{\"dimension\":3,\"time\":{\"end\":1e-6},"
    "\"discretization\":{\"hourglass\":{\"enabled\":true},\"viscosity\":{\"enabled\":true}},"
    "\"materials\":{\"m\":{\"density\":7800,\"youngs_modulus\":2e11,\"poisson_ratio\":0.3}},"
    "\"bodies\":[{\"name\":\"b\",\"material\":\"m\",\"spacing\":0.001,"
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.006,0.005,0.004]}}}]}";

static void rotation(double angle, const double axis[3], double *R)
{
    const double n = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    const double a = axis[0] / n, b = axis[1] / n, c = axis[2] / n;
    const double C = cos(angle), S = sin(angle), T = 1 - C;
    const double M[9] = {C + a * a * T,     a * b * T - c * S, a * c * T + b * S,
                         b * a * T + c * S, C + b * b * T,     b * c * T - a * S,
                         c * a * T - b * S, c * b * T + a * S, C + c * c * T};
    for (int k = 0; k < 9; k++)
        R[k] = M[k];
}

static void deform(struct tlsph_model *m, const double *A)
{
    for (size_t i = 0; i < m->p.n; i++)
        for (int r = 0; r < 3; r++) {
            m->p.x[3 * i + r] = 0.01 * r;
            for (int c = 0; c < 3; c++)
                m->p.x[3 * i + r] += A[3 * r + c] * m->p.X[3 * i + c];
        }
    tlsph_kinematics(m, 0.0);
    tlsph_constitutive(m, 0.0);
    tlsph_forces(m);
}

START_TEST(rigid_rotation_is_stress_free)
{
    struct tlsph_model *m = build_model(block);
    const double axes[2][3] = {{0, 0, 1}, {1, 2, -0.5}};
    const double angles[2] = {M_PI / 2, 37.0 * M_PI / 180.0};
    const double E = 2e11, ds = 0.001;
    for (int t = 0; t < 2; t++) {
        double R[9];
        rotation(angles[t], axes[t], R);
        deform(m, R);
        double smax = 0, fmax_ = 0;
        for (size_t i = 0; i < m->p.n; i++) {
            for (int k = 0; k < 6; k++)
                smax = fmax(smax, fabs(m->p.sigma[6 * i + k]));
            for (int k = 0; k < 3; k++)
                fmax_ = fmax(fmax_, fabs(m->p.f[3 * i + k]));
        }
        ck_assert_msg(smax < 1e-9 * E, "rotation %d: max |sigma| = %.3g Pa", t, smax);
        ck_assert_msg(fmax_ < 1e-9 * E * ds * ds, "rotation %d: max |f| = %.3g N", t, fmax_);
    }
    tlsph_model_free(m);
}
END_TEST

START_TEST(rotated_stretch_rotates_stress)
{
    struct tlsph_model *m = build_model(block);
    const double U[9] = {1.01, 0.004, 0, 0.004, 0.995, 0.002, 0, 0.002, 1.003};
    deform(m, U);
    size_t n = m->p.n;
    double *s0 = malloc(6 * n * sizeof *s0);
    ck_assert(s0);
    for (size_t k = 0; k < 6 * n; k++)
        s0[k] = m->p.sigma[k];
    double R[9], RU[9];
    const double axis[3] = {0.3, -1, 0.4};
    rotation(1.1, axis, R);
    mat3_mul(R, U, RU);
    deform(m, RU);
    double worst = 0, scale = 0;
    for (size_t i = 0; i < n; i++) {
        double S[9], T[9], RS[9];
        sym6_to_mat3(s0 + 6 * i, S);
        mat3_mul(R, S, RS);
        mat3_mul_bt(RS, R, T);
        double t6[6];
        mat3_to_sym6(T, t6);
        for (int k = 0; k < 6; k++) {
            worst = fmax(worst, fabs(t6[k] - m->p.sigma[6 * i + k]));
            scale = fmax(scale, fabs(t6[k]));
        }
    }
    ck_assert(scale > 1e8);
    ck_assert_msg(worst <= 1e-9 * scale, "sigma(RU) - R sigma(U) R^T = %.3g (scale %.3g)", worst,
                  scale);
    free(s0);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("rotation", 0, rigid_rotation_is_stress_free, rotated_stretch_rotates_stress)
