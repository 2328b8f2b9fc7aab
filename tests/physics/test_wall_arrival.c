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
#include <string.h>

#include "bc/kind.h"
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

/* The wall's reaction series (core/io/fields.c, "walls"): the cube of 10^3
 * particles lands on the wall and the wall stops its first layer, then holds
 * the body while it rebounds elastically.  The wall is the only external
 * force, so its impulse over the run, sum of reaction x step, is the change of
 * the body's momentum (impulse balance; the pair forces cancel to round-off):
 * tolerance 1e-10 of the initial momentum.  Its torque about the wall's point
 * q = 0: the stops act along the normal z, symmetrically under the cube's
 * mirror planes x = y = 5 mm, so the angular impulse is (c - q) x impulse with
 * c the cube's centre: tolerance 1e-8 of |c| |impulse| (the mirror symmetry
 * holds to the round-off of the pair sums). */
START_TEST(wall_reaction_is_the_momentum_it_gives)
{
    struct tlsph_model *m = cube_above_wall(10);
    ck_assert(strcmp(m->scene.bcs[0].kind->name, "wall") == 0);
    double p0[3], p1[3], impulse[3] = {0, 0, 0}, angular[3] = {0, 0, 0};
    tlsph_model_momentum(m, p0);
    struct tlsph_diagnostic d;
    double peak = 0.0;
    while (m->t < m->scene.end_time * (1.0 - 1e-12)) {
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &d) == 0, "step %ld: %s", m->step, d.message);
        const struct tlsph_group *g = &m->groups[0];
        for (int c = 0; c < 3; c++) {
            impulse[c] += g->reaction[c] * m->dt;
            angular[c] += g->torque[c] * m->dt;
        }
        peak = fmax(peak, g->reaction[2]);
    }
    tlsph_model_momentum(m, p1);
    const double scale = fabs(p0[2]);
    const double centre[3] = {0.005, 0.005, 0.005};
    const double expect[3] = {centre[1] * impulse[2] - centre[2] * impulse[1],
                              centre[2] * impulse[0] - centre[0] * impulse[2],
                              centre[0] * impulse[1] - centre[1] * impulse[0]};
    fprintf(stderr,
            "wall impulse (%.3e, %.3e, %.6e) N s, momentum change (%.3e, %.3e, %.6e), peak "
            "reaction %.3e N; angular impulse (%.6e, %.6e, %.3e), (c - q) x impulse (%.6e, "
            "%.6e, %.3e)\n",
            impulse[0], impulse[1], impulse[2], p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2], peak,
            angular[0], angular[1], angular[2], expect[0], expect[1], expect[2]);
    ck_assert(impulse[2] > 0.1 * scale); /* the wall did push */
    for (int c = 0; c < 3; c++) {
        ck_assert_msg(fabs(impulse[c] - (p1[c] - p0[c])) < 1e-10 * scale,
                      "component %d: wall impulse %.15g, momentum change %.15g", c, impulse[c],
                      p1[c] - p0[c]);
        ck_assert_msg(fabs(angular[c] - expect[c]) < 1e-8 * 0.005 * sqrt(3.0) * impulse[2],
                      "torque component %d: %.15g N m s, expected %.15g", c, angular[c],
                      expect[c]);
    }
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("wall_arrival", 300, single_particle_loses_all_its_energy_to_the_wall,
                 cube_books_its_first_layer_as_wall_loss, wall_reaction_is_the_momentum_it_gives)
