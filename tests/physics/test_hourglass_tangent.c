/* The "tangent" hourglass stiffness (discretization.hourglass.stiffness):
 * where particles flow plastically the Ganzenmueller spring uses the
 * elasto-plastic tangent E H / (E + H) instead of E (core/material/constitutive.c,
 * core/sph/forces.c).
 *
 * References and tolerances:
 *  1. Where nothing yields it is the elastic spring exactly: a plastic bar
 *     loaded below yield moves bit for bit as with "elastic" stiffness.
 *  2. The pair's modulus is the mean of both particles', symmetric in i and j,
 *     so the forces stay antisymmetric: linear momentum of a plastic bar torn
 *     apart stays at its initial value to 1e-12 of sum m|v| (test_momentum.c's
 *     bound), and the energy balance (hourglass energy is the work done against
 *     the spring, whatever its modulus) closes within 1e-3 of E0 as in
 *     test_failure.c.
 *  3. It does what it is for: in the flowing particles the scale is the
 *     tangent ratio (linear hardening H = 5e8 Pa, E = 2e11 Pa: 2.49e-3, to
 *     1e-12), and the work absorbed by the springs falls (measured: below a
 *     tenth of the elastic spring's).
 *  4. It is the default (measured more accurate on the Taylor bars,
 *     docs/performance.md): a plastic scene that names no stiffness gets the
 *     scale array, an elastic one does not (its spring is Young's modulus by
 *     construction, bit for bit as before the default changed). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "support/scene_builder.h"
#include "support/check_main.h"

static char *bar(const char *stiffness, double v_scale)
{
    static char text[4096];
    snprintf(text, sizeof text,
             "{\"dimension\":3,\"time\":{\"end\":1.0,\"max_steps\":100000,\"cfl\":0.3},"
             "\"discretization\":{\"hourglass\":{\"enabled\":true,\"coefficient\":1.0,"
             "\"stiffness\":\"%s\"}},"
             "\"materials\":{\"steel\":{\"density\":7800,\"youngs_modulus\":2e11,"
             "\"poisson_ratio\":0.3,"
             "\"strength\":{\"type\":\"linear_hardening\",\"yield_stress\":3e8,"
             "\"hardening_modulus\":5e8}}},"
             "\"bodies\":[{\"name\":\"bar\",\"material\":\"steel\",\"spacing\":0.0005,"
             "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.012,0.003,0.003]}},"
             "\"initial_velocity\":[\"%g*(x - 0.006)\",\"3\",\"-2 + %g*y\"]}]}",
             stiffness, 5e4 * v_scale, 1000 * v_scale);
    return text;
}

START_TEST(elastic_regions_are_unchanged)
{
    /* ends at +-0.3 m/s: stress ~ rho c v = 12 MPa, far below yield */
    struct tlsph_model *a = build_model(bar("elastic", 1e-3));
    struct tlsph_model *b = build_model(bar("tangent", 1e-3));
    ck_assert_ptr_null(a->p.hg_scale);
    ck_assert_ptr_nonnull(b->p.hg_scale);
    for (int s = 0; s < 300; s++) {
        tlsph_model_step(a);
        tlsph_model_step(b);
    }
    ck_assert_int_eq(b->plastic_point_steps, 0);
    ck_assert(memcmp(a->p.x, b->p.x, 3 * a->p.n * sizeof(double)) == 0);
    ck_assert(memcmp(a->p.v, b->p.v, 3 * a->p.n * sizeof(double)) == 0);
    tlsph_model_free(a);
    tlsph_model_free(b);
}
END_TEST

static double tear(const char *stiffness, int check_scale)
{
    struct tlsph_model *m = build_model(bar(stiffness, 1.0));
    double p0[3];
    tlsph_model_momentum(m, p0);
    const double scale = momentum_scale(m);
    double worst_p = 0.0, worst_e = 0.0;
    struct tlsph_diagnostic d;
    for (int s = 1; s <= 1500; s++) {
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &d) == 0, "unstable: %s", d.message);
        worst_e = fmax(worst_e, fabs(tlsph_energy_balance(&m->energy)) / m->energy.initial);
        if (s % 100 == 0) {
            double p[3];
            tlsph_model_momentum(m, p);
            for (int c = 0; c < 3; c++)
                worst_p = fmax(worst_p, fabs(p[c] - p0[c]) / scale);
        }
    }
    size_t flowing = 0;
    if (check_scale) {
        const double ratio = 5e8 / (2e11 + 5e8);
        for (size_t i = 0; i < m->p.n; i++) {
            const double sc = m->p.hg_scale[i];
            ck_assert_msg(sc == 1.0 || fabs(sc - ratio) <= 1e-12 * ratio, "scale %.17g", sc);
            flowing += sc < 1.0;
        }
        ck_assert_msg(flowing > m->p.n / 10, "only %zu particles flowing", flowing);
    }
    const double hg = m->energy.hourglass;
    printf("%s: hourglass work %.4g J (plastic %.4g J), %zu flowing with the tangent scale; "
           "momentum drift %.2e of sum m|v|; energy balance %.2e of E0\n",
           stiffness, hg, m->energy.plastic_work, flowing, worst_p, worst_e);
    fflush(stdout);
    ck_assert_msg(worst_p <= 1e-12, "momentum drifted by %g", worst_p);
    ck_assert_msg(worst_e <= 1e-3, "energy balance off by %g of E0", worst_e);
    tlsph_model_free(m);
    return hg;
}

START_TEST(plastic_tearing_conserves_and_relaxes_the_spring)
{
    const double elastic = tear("elastic", 0);
    const double tangent = tear("tangent", 1);
    ck_assert_msg(tangent < 0.1 * elastic, "hourglass work %g vs %g with the elastic spring",
                  tangent, elastic);
}
END_TEST

/* The bar of bar() without a stiffness key, plastic or elastic. */
static struct tlsph_model *default_bar(int plastic)
{
    static char text[2048];
    snprintf(text, sizeof text,
             "{\"dimension\":3,\"time\":{\"end\":1e-5},"
             "\"discretization\":{\"hourglass\":{\"enabled\":true}},"
             "\"materials\":{\"steel\":{\"density\":7800,\"youngs_modulus\":2e11,"
             "\"poisson_ratio\":0.3%s}},"
             "\"bodies\":[{\"name\":\"bar\",\"material\":\"steel\",\"spacing\":0.0005,"
             "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.012,0.003,0.003]}}}]}",
             plastic ? ",\"strength\":{\"type\":\"linear_hardening\",\"yield_stress\":3e8,"
                       "\"hardening_modulus\":5e8}"
                     : "");
    return build_model(text);
}

START_TEST(tangent_is_the_default_for_plastic_materials)
{
    struct tlsph_model *plastic = default_bar(1), *elastic = default_bar(0);
    ck_assert_int_eq(plastic->scene.hourglass_tangent, 1);
    ck_assert_ptr_nonnull(plastic->p.hg_scale);
    ck_assert_ptr_null(elastic->p.hg_scale);
    tlsph_model_free(plastic);
    tlsph_model_free(elastic);
}
END_TEST

TLSPH_CHECK_MAIN("hourglass_tangent", 600, elastic_regions_are_unchanged,
                 plastic_tearing_conserves_and_relaxes_the_spring,
                 tangent_is_the_default_for_plastic_materials)
