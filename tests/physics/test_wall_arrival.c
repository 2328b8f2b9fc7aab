/* Energy booked by a wall when a body arrives at it: an elastic steel cube
 * (E = 210 GPa, nu = 0.3, rho = 7850 kg/m^3, spacing 1 mm) moving at 10 m/s
 * towards a rigid frictionless wall, its lowest layer starting half a spacing
 * above it; 100 us (the layer arrives at 50 us).  The wall stops an arriving
 * particle inelastically and books the kinetic energy this removes as its
 * (negative) work W.
 *
 * Reference: energy conservation, kinetic + internal + hourglass + viscous - W
 * = initial kinetic energy KE0, at every step.
 *  - 1 particle (no neighbour, no force): the stop removes all of its kinetic
 *    energy, so W = -KE0 exactly and the balance is round-off: tolerance 1e-12
 *    of KE0.
 *  - 10 x 10 x 10 particles: the arriving layer carries 1/10 of KE0, and its
 *    neighbours push on it while it stops, so W = -0.1 KE0 to within the work
 *    of those forces over one step: |W / KE0 + 0.1| < 0.01 (measured 0.003).
 *    Balance: 0.5 % of KE0 (measured 0.16 %; the stability contract's limit,
 *    5 % of the energy scale, is ten times looser).
 * Before the fix the wall left the drift velocity of the arriving step
 * unbooked: 0.69 of the layer's energy, and both runs stopped on
 * energy_balance at contact. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "support/scene_builder.h"
#include "support/check_main.h"

/* side: the cube's edge in spacings (1 or 10) */
static struct tlsph_model *cube_above_wall(int side)
{
    char json[1024];
    const double edge = 0.001 * side;
    snprintf(json, sizeof json,
             "{\"dimension\":3,\"time\":{\"end\":1e-4,\"cfl\":0.3},"
             "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2.1e11,"
             "\"poisson_ratio\":0.3}},"
             "\"bodies\":[{\"name\":\"cube\",\"material\":\"steel\",\"spacing\":0.001,"
             "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[%.17g,%.17g,%.17g]}},"
             "\"initial_velocity\":[0,0,-10]}],"
             "\"boundary_conditions\":[{\"type\":\"wall\",\"name\":\"floor\","
             "\"point\":[0,0,0],\"normal\":[0,0,1]}]}",
             edge, edge, edge);
    return build_model(json);
}

/* Runs the cube to its end, checking the stability contract and the balance
 * (relative to KE0) every step; returns the worst balance and sets *wall to
 * W / KE0 at the end. */
static double run_and_balance(struct tlsph_model *m, double *wall)
{
    const double ke0 = m->energy.kinetic;
    ck_assert(ke0 > 0.0);
    struct tlsph_diagnostic d;
    double worst = 0.0;
    while (m->t < m->scene.end_time * (1.0 - 1e-12)) {
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &d) == 0, "step %ld: %s", m->step, d.message);
        worst = fmax(worst, fabs(tlsph_energy_balance(&m->energy)) / ke0);
    }
    *wall = m->energy.external_work / ke0;
    return worst;
}

START_TEST(single_particle_loses_all_its_energy_to_the_wall)
{
    struct tlsph_model *m = cube_above_wall(1);
    ck_assert_uint_eq(m->p.n, 1);
    double wall;
    const double worst = run_and_balance(m, &wall);
    fprintf(stderr, "1 particle, %ld steps: wall work %.15f KE0, worst balance %.2e KE0\n", m->step,
            wall, worst);
    /* on the wall to round-off of the drift that ended there */
    ck_assert_msg(fabs(m->p.v[2]) < 1e-9 && fabs(m->p.x[2]) < 1e-15,
                  "not at rest on the wall: z %.3g m, v_z %.3g m/s", m->p.x[2], m->p.v[2]);
    ck_assert_msg(fabs(wall + 1.0) < 1e-12, "wall work %.15f of KE0, expected -1", wall);
    ck_assert_msg(worst < 1e-12, "energy balance %.3g of KE0", worst);
    tlsph_model_free(m);
}
END_TEST

START_TEST(cube_books_its_first_layer_as_wall_loss)
{
    struct tlsph_model *m = cube_above_wall(10);
    ck_assert_uint_eq(m->p.n, 1000);
    double wall;
    const double worst = run_and_balance(m, &wall);
    fprintf(stderr, "10^3 particles, %ld steps: wall work %.4f KE0, worst balance %.2e KE0\n",
            m->step, wall, worst);
    ck_assert_msg(fabs(wall + 0.1) < 0.01, "wall work %.4f of KE0, expected -0.1", wall);
    ck_assert_msg(worst < 0.005, "energy balance %.3g of KE0", worst);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("wall_arrival", 300, single_particle_loses_all_its_energy_to_the_wall,
                 cube_books_its_first_layer_as_wall_loss)
