/* Longitudinal wave speed of a slender 3-D bar: a free-free steel bar of
 * 100 x 4 x 4 mm vibrating in its first longitudinal mode has period
 * T = 2 L / c with c = sqrt(E/rho) (1-D bar theory; the Rayleigh-Love lateral
 * inertia correction is ~nu^2 pi^2 r^2 / (2 L^2) ~ 1e-4 here).  The period is
 * measured from successive zero crossings of the mean axial velocity of the
 * left quarter of the bar.  Tolerance: 3 %. */
#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "support/scene_builder.h"
#include "support/check_main.h"

static const char *bar =
    "{\"dimension\":3,\"time\":{\"end\":1.0,\"cfl\":0.3},"
    "\"parameters\":{\"L\":0.1,\"v0\":1.0},"
    "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2.1e11,\"poisson_ratio\":0.3}},"
    "\"bodies\":[{\"name\":\"bar\",\"material\":\"steel\",\"spacing\":0.001,"
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.1,0.004,0.004]}},"
    "\"initial_velocity\":[\"v0*cos(3.141592653589793*x/L)\",\"0\",\"0\"]}]}";

static double left_velocity(const struct tlsph_model *m)
{
    double s = 0.0, w = 0.0;
    for (size_t i = 0; i < m->p.n; i++)
        if (m->p.X[3 * i] < 0.025) {
            s += m->p.mass[i] * m->p.v[3 * i];
            w += m->p.mass[i];
        }
    return s / w;
}

START_TEST(bar_wave_speed)
{
    struct tlsph_model *m = build_model(bar);
    const double L = 0.1, c = sqrt(2.1e11 / 7850.0), T = 2.0 * L / c;
    double prev_v = left_velocity(m), prev_t = 0.0;
    double crossings[8];
    int nc = 0;
    struct tlsph_diagnostic d;
    while (m->t < 2.6 * T && nc < 8) {
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &d) == 0, "%s", d.message);
        const double v = left_velocity(m);
        if ((prev_v > 0) != (v > 0))
            crossings[nc++] = prev_t + (m->t - prev_t) * prev_v / (prev_v - v);
        prev_v = v;
        prev_t = m->t;
    }
    ck_assert_int_ge(nc, 4);
    /* crossings are half a period apart; average over the ones observed */
    const double T_measured = 2.0 * (crossings[nc - 1] - crossings[0]) / (nc - 1);
    const double c_measured = 2.0 * L / T_measured;
    fprintf(stderr, "bar wave speed: %.1f m/s measured, %.1f m/s = sqrt(E/rho), error %.3f %%\n",
            c_measured, c, 100.0 * (c_measured - c) / c);
    ck_assert_msg(fabs(c_measured - c) < 0.03 * c, "wave speed %.1f vs %.1f", c_measured, c);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("wave", 300, bar_wave_speed)
