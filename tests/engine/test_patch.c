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

START_TEST(patch_3d)
{
    struct tlsph_model *m = build_model(block3d);
    ck_assert_uint_eq(m->p.n, 8 * 6 * 5);
    ck_assert_uint_eq(m->deficient_supports, 0);
    check_patch(m);
    tlsph_model_free(m);
}
END_TEST

START_TEST(patch_2d)
{
    struct tlsph_model *m = build_model(plate2d);
    ck_assert_uint_eq(m->p.n, 9 * 7);
    check_patch(m);
    tlsph_model_free(m);
}
END_TEST

/* Brute-force eq. 31 on a deformed block: f_i = sum_j V_i V_j (P~_i + P~_j) grad W_ij. */
START_TEST(forces_match_brute_force)
{
    check_stress_forces(block3d, 3);
}
END_TEST

TLSPH_CHECK_MAIN("patch", 0, patch_3d, patch_2d, forces_match_brute_force)
