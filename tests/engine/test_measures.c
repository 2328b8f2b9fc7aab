/* Gauges and sections (core/io/measures.c): the time series a tensile test
 * reports (paper 000 §6).
 *
 * References and tolerances:
 *  1. Section means are exact volume-weighted means: a stress field linear in z
 *     averaged over a slab symmetric about z0 gives its value at z0, and a
 *     uniform stress rotated out of its principal axes gives its largest
 *     eigenvalue and n.sigma.n; both to 1e-12 relative.  Particles are chosen
 *     by reference position within thickness/2 of the plane.
 *  2. The gauge's default length is the distance of the two groups' reference
 *     centroids (for one end layer each of a bar of length L: L - h, exact) and
 *     its axis points from the first group to the second.
 *  3. Physics: an elastic bar (E = 200 GPa, nu = 0.3) pulled slowly at both ends
 *     is in uniaxial stress, so engineering stress = E x engineering strain;
 *     after a smooth ramp 20 times the wave transit time the ratio is 1 within
 *     3 % (the SPH bar's stiffness error at 4 x 4 particles across plus the
 *     residual elastic waves; measured 1.014).  The middle section's mean
 *     normal stress and largest principal stress equal the engineering stress
 *     within the same 3 % (uniaxial, small strain: the area change is 6e-4;
 *     measured equal to 1e-4).
 *  4. A probe reads the centre of mass of the particles it picked: two free
 *     bodies of different density moving at different uniform velocities
 *     (no force acts: F = I) give the mass-weighted mean displacement
 *     (m_a v_a + m_b v_b) t / (m_a + m_b) and velocity, exact up to the
 *     round-off of the drift (1e-9 relative); a probe on one body reads that
 *     body's v t.
 *  5. An extent reads the outer edges of hand-placed particles: radius = the
 *     largest distance of a centre from the axis line + h/2, over the lowest
 *     layer (centres strictly within h/2 of the lowest centre) or over all;
 *     lower/upper = the extreme axial coordinates from the axis point -/+ h/2;
 *     the answers computed by hand below, to 1e-12 m (round-off). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bc/boundary.h"
#include "io/fields.h"
#include "io/measures.h"
#include "support/scene_builder.h"
#include "support/check_main.h"

static const char *bar_scene =
    "{\"dimension\":3,\"parameters\":{\"v0\":0.1,\"tau\":2e-5},"
    "\"time\":{\"end\":1.2e-4,\"cfl\":0.3},"
    "\"discretization\":{\"hourglass\":{\"enabled\":true}},"
    "\"output\":{\"gauges\":[{\"name\":\"bar\",\"between\":[\"left\",\"right\"],"
    "\"area\":4e-6}],"
    "\"sections\":[{\"name\":\"middle\",\"point\":[0.01,0,0],\"normal\":[2,0,0],"
    "\"thickness\":0.00075}]},"
    "\"materials\":{\"steel\":{\"density\":7800,\"youngs_modulus\":2e11,\"poisson_ratio\":0.3}},"
    "\"bodies\":[{\"name\":\"bar\",\"material\":\"steel\",\"spacing\":0.0005,"
    "\"geometry\":{\"box\":{\"min\":[0,-0.001,-0.001],\"max\":[0.02,0.001,0.001]}}}],"
    "\"boundary_conditions\":["
    "{\"type\":\"velocity\",\"name\":\"left\",\"select\":{\"box\":{\"min\":[-1,-1,-1],"
    "\"max\":[0.0005,1,1]}},\"velocity\":[\"-v0*(1-exp(-t/tau))\",null,null]},"
    "{\"type\":\"velocity\",\"name\":\"right\",\"select\":{\"box\":{\"min\":[0.0195,-1,-1],"
    "\"max\":[1,1,1]}},\"velocity\":[\"v0*(1-exp(-t/tau))\",null,null]}]}";

START_TEST(section_means_are_exact)
{
    struct tlsph_model *m = build_model(bar_scene);
    ck_assert_uint_eq(m->scene.nsections, 1);
    /* the plane x = 0.01 lies between the layers at 0.00975 and 0.01025 */
    ck_assert_uint_eq(m->measures.section_count[0], 2 * 4 * 4);
    ck_assert_double_eq(m->scene.sections[0].normal[0], 1.0); /* normalised */
    double v[TLSPH_SECTION_NVALUES];

    /* sigma_xx = a + b (x - 0.01): the mean over the symmetric slab is a */
    const double a = 3e8, b = 7e10;
    for (size_t i = 0; i < m->p.n; i++) {
        double *s = m->p.sigma + 6 * i;
        for (int c = 0; c < 6; c++)
            s[c] = 0.0;
        s[0] = a + b * (m->p.X[3 * i] - 0.01);
    }
    tlsph_section_values(m, 0, v);
    ck_assert_msg(fabs(v[TLSPH_SECTION_NORMAL] - a) <= 1e-12 * a, "normal %.17g", v[1]);
    ck_assert_msg(fabs(v[TLSPH_SECTION_MAX_PRINCIPAL] - a) <= 1e-12 * a, "s1 %.17g", v[0]);

    /* principal stresses (5, 2, -1) x 1e8 rotated by 30 degrees about z */
    const double c = cos(M_PI / 6), s_ = sin(M_PI / 6), p1 = 5e8, p2 = 2e8, p3 = -1e8;
    const double sxx = c * c * p1 + s_ * s_ * p2, syy = s_ * s_ * p1 + c * c * p2,
                 sxy = c * s_ * (p1 - p2);
    for (size_t i = 0; i < m->p.n; i++) {
        double *s = m->p.sigma + 6 * i;
        s[0] = sxx; s[1] = sxy; s[2] = 0.0; s[3] = syy; s[4] = 0.0; s[5] = p3;
    }
    tlsph_section_values(m, 0, v);
    ck_assert_msg(fabs(v[TLSPH_SECTION_MAX_PRINCIPAL] - p1) <= 1e-12 * p1, "s1 %.17g", v[0]);
    ck_assert_msg(fabs(v[TLSPH_SECTION_NORMAL] - sxx) <= 1e-12 * p1, "normal %.17g", v[1]);
    ck_assert_double_eq(v[TLSPH_SECTION_PLASTIC], 0.0); /* elastic: no plasticity module */
    ck_assert_uint_eq(tlsph_family_width(&tlsph_series_families[TLSPH_FAMILY_SECTIONS], m),
                      2); /* so no such column either */
    tlsph_model_free(m);
}
END_TEST

START_TEST(gauge_length_and_axis)
{
    struct tlsph_model *m = build_model(bar_scene);
    ck_assert_uint_eq(m->scene.ngauges, 1);
    /* end layers at x = 0.00025 and 0.01975 */
    ck_assert_msg(fabs(m->measures.gauge_length[0] - 0.0195) <= 1e-15, "L0 %.17g",
                  m->measures.gauge_length[0]);
    ck_assert_msg(fabs(m->measures.gauge_axis[0][0] - 1.0) <= 1e-15, "axis");
    tlsph_model_free(m);
}
END_TEST

START_TEST(elastic_bar_follows_hooke)
{
    struct tlsph_model *m = build_model(bar_scene);
    run_until(m, m->scene.end_time);
    double g[2], v[TLSPH_SECTION_NVALUES];
    tlsph_boundary_displacements(m); /* as the run loop does before sampling series */
    tlsph_gauge_values(m, 0, g);
    tlsph_section_values(m, 0, v);
    const double E = 2e11, hooke = g[0] / (E * g[1]);
    printf("strain %.3e, stress %.4g Pa: stress / (E strain) = %.4f; section normal / eng. "
           "stress = %.4f, sigma_1 / eng. stress = %.4f\n",
           g[1], g[0], hooke, v[TLSPH_SECTION_NORMAL] / g[0],
           v[TLSPH_SECTION_MAX_PRINCIPAL] / g[0]);
    fflush(stdout);
    ck_assert_msg(g[1] > 5e-4, "the bar was not stretched: strain %g", g[1]);
    ck_assert_msg(fabs(hooke - 1.0) <= 0.03, "stress / (E strain) = %g", hooke);
    ck_assert_msg(fabs(v[TLSPH_SECTION_NORMAL] / g[0] - 1.0) <= 0.03, "section normal");
    ck_assert_msg(fabs(v[TLSPH_SECTION_MAX_PRINCIPAL] / g[0] - 1.0) <= 0.03, "section s1");
    tlsph_model_free(m);
}
END_TEST

static const char *two_bodies_scene =
    "{\"dimension\":2,\"time\":{\"end\":2e-5,\"cfl\":0.3},"
    "\"contact\":{\"enabled\":false},"
    "\"output\":{\"probes\":[{\"name\":\"both\",\"select\":{\"box\":{\"min\":[-1,-1,0],"
    "\"max\":[1,1,0]}}},{\"name\":\"light\",\"select\":{\"body\":\"light\"}}]},"
    "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2.1e11,"
    "\"poisson_ratio\":0.3},\"alu\":{\"density\":2700,\"youngs_modulus\":7e10,"
    "\"poisson_ratio\":0.33}},"
    "\"bodies\":[{\"name\":\"heavy\",\"material\":\"steel\",\"spacing\":0.001,"
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.01,0.006,0]}},"
    "\"initial_velocity\":[2,0,0]},"
    "{\"name\":\"light\",\"material\":\"alu\",\"spacing\":0.001,"
    "\"geometry\":{\"box\":{\"min\":[0.05,0,0],\"max\":[0.058,0.004,0]}},"
    "\"initial_velocity\":[0,-3,0]}]}";

START_TEST(probe_reads_the_centre_of_mass)
{
    struct tlsph_model *m = build_model(two_bodies_scene);
    ck_assert_uint_eq(m->scene.nprobes, 2);
    double ma = 0.0, mb = 0.0;
    for (size_t i = 0; i < m->p.n; i++)
        *(m->p.body[i] == 0 ? &ma : &mb) += m->p.mass[i];
    ck_assert_uint_eq(m->measures.probe_count[0], m->p.n);
    ck_assert_msg(fabs(m->measures.probe_mass[0] - (ma + mb)) <= 1e-12 * (ma + mb), "mass");
    run_until(m, m->scene.end_time);
    const double t = m->t, va[3] = {2, 0, 0}, vb[3] = {0, -3, 0};
    double both[6], light[6];
    tlsph_probe_values(m, 0, both);
    tlsph_probe_values(m, 1, light);
    for (int d = 0; d < 3; d++) {
        const double v = (ma * va[d] + mb * vb[d]) / (ma + mb);
        ck_assert_msg(fabs(both[d] - v * t) <= 1e-9 * 3.0 * t, "both u[%d] %.17g, want %.17g", d,
                      both[d], v * t);
        ck_assert_msg(fabs(both[3 + d] - v) <= 1e-9 * 3.0, "both v[%d] %.17g", d, both[3 + d]);
        ck_assert_msg(fabs(light[d] - vb[d] * t) <= 1e-9 * 3.0 * t, "light u[%d] %.17g", d,
                      light[d]);
        ck_assert_msg(fabs(light[3 + d] - vb[d]) <= 1e-9 * 3.0, "light v[%d]", d);
    }
    ck_assert_uint_eq(tlsph_family_width(&tlsph_series_families[TLSPH_FAMILY_PROBES], m), 6);
    tlsph_model_free(m);
}
END_TEST

/* A cube of 4 x 4 x 4 particles, spacing 1 mm (centres at 0.5 .. 3.5 mm); the
 * extents' axis is z through (2, 2, 10) mm, given with length 2. */
static const char *cube_scene =
    "{\"dimension\":3,\"time\":{\"end\":1e-6},"
    "\"output\":{\"extents\":[{\"name\":\"foot\",\"select\":{\"body\":\"cube\"},"
    "\"point\":[0.002,0.002,0.01],\"axis\":[0,0,2],\"radius_over\":\"lowest_layer\"},"
    "{\"name\":\"all\",\"select\":{\"body\":\"cube\"},"
    "\"point\":[0.002,0.002,0.01],\"axis\":[0,0,2]}]},"
    "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2.1e11,"
    "\"poisson_ratio\":0.3}},"
    "\"bodies\":[{\"name\":\"cube\",\"material\":\"steel\",\"spacing\":0.001,"
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.004,0.004,0.004]}}}]}";

/* The particle whose reference centre is (i, j, k) + 0.5 mm. */
static size_t cube_particle(const struct tlsph_model *m, int i, int j, int k)
{
    for (size_t a = 0; a < m->p.n; a++) {
        const double *X = m->p.X + 3 * a;
        if (fabs(X[0] - (i + 0.5) * 1e-3) < 1e-9 && fabs(X[1] - (j + 0.5) * 1e-3) < 1e-9 &&
            fabs(X[2] - (k + 0.5) * 1e-3) < 1e-9)
            return a;
    }
    ck_abort_msg("no particle at (%d, %d, %d)", i, j, k);
    return 0;
}

static void place(struct tlsph_model *m, size_t a, double x, double y, double z)
{
    m->p.x[3 * a] = x;
    m->p.x[3 * a + 1] = y;
    m->p.x[3 * a + 2] = z;
}

START_TEST(extent_reads_the_outer_edges)
{
    struct tlsph_model *m = build_model(cube_scene);
    ck_assert_uint_eq(m->scene.nextents, 2);
    ck_assert_uint_eq(m->measures.extent_count[0], 64);
    /* hand placed (mm): the lowest centre at z = 0.4 (so the lowest layer is
     * z < 0.9: the whole bottom layer at 0.5 stays in it); in it, one centre 4
     * from the axis at z = 0.85; above it, one at z = 0.95 (just out of the
     * layer) 4.8 from the axis and one at z = 2 5.5 from it; the highest
     * centre at z = 4.2 on the axis.  The other centres stay at their
     * reference positions, at most sqrt(2) 1.5 = 2.12 from the axis. */
    place(m, cube_particle(m, 0, 0, 0), 0.002 + 0.003, 0.002, 0.0004);
    place(m, cube_particle(m, 1, 0, 0), 0.002, 0.002 - 0.004, 0.00085);
    place(m, cube_particle(m, 2, 2, 1), 0.002 + 0.0048 * 0.6, 0.002 + 0.0048 * 0.8, 0.00095);
    place(m, cube_particle(m, 3, 3, 2), 0.002 - 0.0055, 0.002, 0.002);
    place(m, cube_particle(m, 1, 1, 3), 0.002, 0.002, 0.0042);
    double foot[TLSPH_EXTENT_NVALUES], all[TLSPH_EXTENT_NVALUES];
    tlsph_extent_values(m, 0, foot);
    tlsph_extent_values(m, 1, all);
    /* axial coordinates from the point at z = 10 mm: lowest centre 0.4 - 10,
     * highest 4.2 - 10; edges -/+ 0.5 */
    const double want_foot[] = {4.5e-3, 9e-3, -10.1e-3, -5.3e-3, 4.8e-3};
    const double want_all[] = {6e-3, 12e-3, -10.1e-3, -5.3e-3, 4.8e-3};
    for (int c = 0; c < TLSPH_EXTENT_NVALUES; c++) {
        ck_assert_msg(fabs(foot[c] - want_foot[c]) <= 1e-12, "foot value %d: %.15g, want %.15g",
                      c, foot[c], want_foot[c]);
        ck_assert_msg(fabs(all[c] - want_all[c]) <= 1e-12, "all value %d: %.15g, want %.15g", c,
                      all[c], want_all[c]);
    }
    ck_assert_uint_eq(tlsph_family_width(&tlsph_series_families[TLSPH_FAMILY_EXTENTS], m),
                      TLSPH_EXTENT_NVALUES);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("measures", 300, section_means_are_exact, gauge_length_and_axis,
                 elastic_bar_follows_hooke, probe_reads_the_centre_of_mass,
                 extent_reads_the_outer_edges)
