/* Linear momentum of a free body (no boundary condition) is conserved to
 * round-off over 1000 steps with every pair force on (stress, hourglass,
 * viscosity), under a violent, non-symmetric initial velocity field.
 * Reference: total momentum at t = 0 (pair forces are antisymmetric, eq. 31).
 * Tolerance: 1e-12 of sum_i m_i |v_i| (accumulated round-off of 1000 steps). */
#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "support/scene_builder.h"
#include "support/check_main.h"

static const char *scene =
    "{\"dimension\":3,\"time\":{\"end\":1.0,\"max_steps\":1000},"
    "\"discretization\":{\"hourglass\":{\"enabled\":true,\"coefficient\":1.0},"
    "\"viscosity\":{\"enabled\":true,\"linear\":1.0,\"quadratic\":1.0}},"
    "\"materials\":{\"m\":{\"density\":7800,\"youngs_modulus\":2e11,\"poisson_ratio\":0.3,"
    "\"eos\":{\"type\":\"mie_gruneisen\",\"c0\":4570,\"s\":1.49,\"gamma0\":1.9}}},"
    "\"bodies\":[{\"name\":\"b\",\"material\":\"m\",\"spacing\":0.001,"
    "\"geometry\":{\"difference\":[{\"box\":{\"min\":[0,0,0],\"max\":[0.012,0.008,0.006]}},"
    "{\"sphere\":{\"center\":[0.006,0.004,0.003],\"radius\":0.002}}]},"
    "\"initial_velocity\":[\"20*sin(500*x)+5\",\"30*cos(700*y*x*100)\",\"-10*x*y*1e5\"]}]}";

START_TEST(free_body_momentum)
{
    struct tlsph_model *m = build_model(scene);
    check_momentum_kept(m, 1000);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("momentum", 120, free_body_momentum)
