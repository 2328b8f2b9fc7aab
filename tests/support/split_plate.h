/* The free plate of the split tests (tests/engine/test_split.c) and the
 * split benches (bench/split_balance.c): its scene and the helpers both use. */
#ifndef TLSPH_TEST_SPLIT_PLATE_H
#define TLSPH_TEST_SPLIT_PLATE_H

#include "run/model.h"

/* A free plate of 10 x 8 x 3 particles (spacing 1 mm, body 0) with a violent
 * initial velocity, every pair force on (hourglass, viscosity), beside a free
 * block (body 1), no contact: the scene's text after its "time" block (the
 * caller writes "{\"dimension\":3,\"time\":{...}," before it). */
#define SPLIT_PLATE_AFTER_TIME                                                                    \
    "\"contact\":{\"enabled\":false},"                                                            \
    "\"discretization\":{\"hourglass\":{\"enabled\":true,\"coefficient\":1.0},"                   \
    "\"viscosity\":{\"enabled\":true,\"linear\":1.0,\"quadratic\":1.0}},"                         \
    "\"materials\":{\"m\":{\"density\":7800,\"youngs_modulus\":2e11,\"poisson_ratio\":0.3}},"     \
    "\"bodies\":[{\"name\":\"plate\",\"material\":\"m\",\"spacing\":0.001,"                       \
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.010,0.008,0.003]}},"                       \
    "\"initial_velocity\":[\"20*sin(500*x)+5\",\"30*cos(700*y*x*100)\",\"-10*x*y*1e5\"]},"        \
    "{\"name\":\"block\",\"material\":\"m\",\"spacing\":0.001,"                                   \
    "\"geometry\":{\"box\":{\"min\":[0.02,0,0],\"max\":[0.024,0.004,0.003]}},"                    \
    "\"initial_velocity\":[\"-3\",\"40*y*100\",\"0\"]}]}"

/* The reference coordinate along axis of body 0's particle nearest v (m). */
double split_plate_lattice(const struct tlsph_model *m, int axis, double v);

/* dt^2/8 sum_i |f_i|^2 / m_i (J): the part of velocity Verlet's kinetic
 * energy at whole steps that no force's work books (both half kicks of a
 * step of dt: KE(n+1) - KE(n) = dt/2 (f(n) + f(n+1)).v(n+1/2) + this term of
 * f(n+1) minus that of f(n)). */
double split_plate_verlet_term(const struct tlsph_model *m, double dt);

#endif
