/* 2-D plane-strain strip pulled apart: 40 x 10 mm steel strip, both ends
 * pulled along x with v = +-vmax (1 - exp(-t/tau)), lateral edges free.
 * In the gauge section (middle half) the state is uniaxial stress in plane
 * strain: sigma_yy = 0, eps_zz = 0, so sigma_xx = E/(1-nu^2) eps_xx.
 * Measured: mean sigma_xx of the gauge particles against the gauge strain
 * from the mean x positions of two particle bands at x = L/4 and 3L/4.
 * Reference: E/(1-nu^2).  Tolerance: 1 %. */
#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "support/scene_builder.h"
#include "support/check_main.h"

static const char *strip =
    "{\"dimension\":2,\"time\":{\"end\":4e-4,\"cfl\":0.3},"
    "\"parameters\":{\"vmax\":0.1,\"tau\":1e-4},"
    "\"discretization\":{\"viscosity\":{\"enabled\":true,\"linear\":1.0,\"quadratic\":0.0}},"
    "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2.1e11,\"poisson_ratio\":0.3}},"
    "\"bodies\":[{\"name\":\"strip\",\"material\":\"steel\",\"spacing\":0.001,"
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.04,0.01,0]}}}],"
    "\"boundary_conditions\":["
    "{\"type\":\"velocity\",\"name\":\"left\",\"select\":{\"box\":{\"min\":[-1,-1,-1],\"max\":[0.001,1,1]}},"
    "\"velocity\":[\"-vmax*(1-exp(-t/tau))\",null,null]},"
    "{\"type\":\"velocity\",\"name\":\"right\",\"select\":{\"box\":{\"min\":[0.039,-1,-1],\"max\":[1,1,1]}},"
    "\"velocity\":[\"vmax*(1-exp(-t/tau))\",null,null]}]}";

START_TEST(plane_strain_modulus)
{
    struct tlsph_model *m = build_model(strip);
    const double E = 2.1e11, nu = 0.3, ref = E / (1 - nu * nu);
    const double Xa = 0.0105, Xb = 0.0295; /* lattice columns near L/4 and 3L/4 */
    const double L0 = band_mean_x(m, Xb) - band_mean_x(m, Xa);
    run_until(m, 4e-4);
    const double eps = (band_mean_x(m, Xb) - band_mean_x(m, Xa)) / L0 - 1.0;
    double sxx = 0, syy = 0;
    int n = 0;
    for (size_t i = 0; i < m->p.n; i++)
        if (m->p.X[3 * i] > Xa && m->p.X[3 * i] < Xb) {
            sxx += m->p.sigma[6 * i];
            syy += m->p.sigma[6 * i + 3];
            n++;
        }
    sxx /= n;
    syy /= n;
    const double slope = sxx / eps;
    fprintf(stderr, "strip: eps %.4g, sigma_xx %.4g Pa, sigma_yy %.3g Pa, slope %.5g vs E/(1-nu^2) "
                    "%.5g (%.3f %%)\n", eps, sxx, syy, slope, ref, 100 * (slope - ref) / ref);
    ck_assert(eps > 5e-4);
    ck_assert_msg(fabs(slope - ref) < 0.01 * ref, "slope %.5g vs %.5g", slope, ref);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("strip", 300, plane_strain_modulus)
