/* Energy conservation of an undamped vibrating body: a free-free steel bar
 * (40 x 4 x 4 mm) started in its first longitudinal mode, v_x = v0 cos(pi x/L),
 * with hourglass control on and no artificial viscosity.
 * Reference: kinetic + internal energy at t = 0 (no dissipation, no external
 * work).  Tolerance: drift < 0.5 % of the initial energy at every
 * step over 5 oscillation periods T = 2L/sqrt(E/rho). */
#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "support/scene_builder.h"
#include "support/check_main.h"

static const char *bar =
    "{\"dimension\":3,\"time\":{\"end\":1.0,\"cfl\":0.3},"
    "\"parameters\":{\"L\":0.04,\"v0\":1.0},"
    "\"discretization\":{\"hourglass\":{\"enabled\":true,\"coefficient\":1.0},"
    "\"viscosity\":{\"enabled\":false}},"
    "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2.1e11,\"poisson_ratio\":0.3}},"
    "\"bodies\":[{\"name\":\"bar\",\"material\":\"steel\",\"spacing\":0.001,"
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.04,0.004,0.004]}},"
    "\"initial_velocity\":[\"v0*cos(3.141592653589793*x/L)\",\"0\",\"0\"]}]}";

START_TEST(vibrating_bar_conserves_energy)
{
    struct tlsph_model *m = build_model(bar);
    const double c = sqrt(2.1e11 / 7850.0), T = 2.0 * 0.04 / c;
    const double E0 = m->energy.kinetic + m->energy.internal;
    ck_assert(E0 > 0.0);
    double worst = 0.0, max_internal = 0.0;
    struct tlsph_diagnostic d;
    while (m->t < 5.0 * T) {
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &d) == 0, "%s", d.message);
        const double E = m->energy.kinetic + m->energy.internal;
        worst = fmax(worst, fabs(E - E0) / E0);
        max_internal = fmax(max_internal, m->energy.internal);
    }
    fprintf(stderr, "energy drift over 5 periods: %.4f %% (%ld steps, hourglass work %.3g J, E0 %.3g J)\n",
            100.0 * worst, m->step, m->energy.hourglass, E0);
    /* the energy really did move between kinetic and internal */
    ck_assert(max_internal > 0.8 * E0);
    ck_assert_msg(worst < 0.005, "energy drift %.4f %% exceeds 0.5 %%", 100.0 * worst);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("energy", 300, vibrating_bar_conserves_energy)
