/* Surface-conforming particles ("placement": "conforming", core/scene/conforming.c)
 * and the Hertz impact of an elastic sphere on a rigid flat (the `wall`).
 *
 * Volumes: every particle of a shell gets the shell's volume / count, so the
 * volumes sum to the body's volume, 4/3 pi R^3 (pi R^2 per metre in 2-D,
 * pi R^2 L for a cylinder), to round-off: tolerance 1e-12 relative.  A quarter
 * sphere (the sphere minus the half-spaces x < c_x and y < c_y) keeps exactly a
 * quarter of every shell.
 *
 * Hertz theory (Johnson, Contact Mechanics, ch. 4 and 11.4): a sphere of radius
 * R, mass m, speed v on a flat, the quasi-static elastic impact,
 *   1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2   (rigid flat: E2 -> infinity),
 *   1/R* = 1/R1 + 1/R2 (flat: R* = R),  1/m* = 1/m1 + 1/m2 (flat: m* = m),
 *   delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5)      (maximum approach),
 *   F_max = 4/3 E* sqrt(R*) delta_max^(3/2)               (peak force),
 *   t_c = 2.94 delta_max / v = 2.87 (m*^2 / (R* E*^2 v))^(1/5)   (duration).
 * Steel, E = 200 GPa, nu = 0.3, rho = 7850 kg/m^3, R = 10 mm.
 *
 * What resolution Hertz needs: the contact radius a = sqrt(R* delta_max) is
 * 0.43 mm at 1 m/s (it grows as v^(2/5)); a particle held by the wall acts
 * like a flat punch of radius about one spacing h (measured stiffness
 * 2 E* x 0.98 h at h = 1 mm), so the contact is Hertzian only once a > h.
 * Measured (docs/contact.md, "Hertz impact"): the errors shrink as a / h
 * grows, with the spacing or with the speed.  The tests:
 *  - at 20 m/s, h = 1 mm (a / h = 1.4): contact time and peak force against
 *    Hertz within the tolerances below, set from the measured convergence;
 *  - at 1 m/s, h = 2 mm: the conforming sphere is closer to Hertz than the
 *    lattice sphere in both contact time and peak force. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact/contact.h"
#include "support/scene_builder.h"
#include "support/check_main.h"

#define RADIUS  0.01 /* m */
#define DENSITY 7850.0
#define YOUNG   2.0e11
#define POISSON 0.3

static const double pi = 3.14159265358979323846;

static double sum_volumes(const struct tlsph_model *m)
{
    double v = 0.0;
    for (size_t i = 0; i < m->p.n; i++)
        v += m->p.vol0[i];
    return v;
}

static struct tlsph_model *body_model(int dim, const char *body)
{
    char json[2048];
    snprintf(json, sizeof json,
             "{\"dimension\":%d,\"time\":{\"end\":1e-6},"
             "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2e11,"
             "\"poisson_ratio\":0.3}},\"bodies\":[%s]}",
             dim, body);
    return build_model(json);
}

START_TEST(conforming_volumes_sum_to_the_body)
{
    /* 3-D sphere, placement absent: a plain sphere is conforming by default */
    struct tlsph_model *m =
        body_model(3, "{\"name\":\"ball\",\"material\":\"steel\",\"spacing\":0.001,"
                      "\"geometry\":{\"sphere\":{\"center\":[0.1,0.2,0.3],\"radius\":0.01}}}");
    ck_assert_int_eq(m->scene.bodies[0].placement, TLSPH_PLACEMENT_CONFORMING);
    const double V = 4.0 / 3.0 * pi * RADIUS * RADIUS * RADIUS;
    double rmax = 0.0, mass = 0.0;
    for (size_t i = 0; i < m->p.n; i++) {
        const double *X = m->p.X + 3 * i;
        rmax = fmax(rmax, hypot(hypot(X[0] - 0.1, X[1] - 0.2), X[2] - 0.3));
        mass += m->p.mass[i];
    }
    const size_t full = m->p.n;
    fprintf(stderr,
            "sphere R = 10 mm, h = 1 mm: %zu particles (V/h^3 = %.1f), volume %.15g of %.15g\n",
            full, V / 1e-9, sum_volumes(m), V);
    ck_assert_msg(fabs(sum_volumes(m) / V - 1.0) < 1e-12, "volumes %.17g, sphere %.17g",
                  sum_volumes(m), V);
    ck_assert_msg(fabs(mass / (DENSITY * V) - 1.0) < 1e-12, "mass %.17g", mass);
    /* the outer shell half a shell inside the surface: 10 shells of 1 mm */
    ck_assert_msg(fabs(rmax - 0.0095) < 1e-12 * RADIUS, "outer shell at %.17g m", rmax);
    /* about one particle per h^3 */
    ck_assert(fabs((double)full / (V / 1e-9) - 1.0) < 0.03);
    tlsph_model_free(m);

    /* quarter: the sphere minus x < 0.1 and y < 0.2 keeps a quarter of every shell */
    m = body_model(3, "{\"name\":\"q\",\"material\":\"steel\",\"spacing\":0.001,"
                      "\"placement\":\"conforming\",\"geometry\":{\"difference\":["
                      "{\"sphere\":{\"center\":[0.1,0.2,0.3],\"radius\":0.01}},"
                      "{\"box\":{\"min\":[0,0,0],\"max\":[0.1,1,1]}},"
                      "{\"box\":{\"min\":[0,0,0],\"max\":[1,0.2,1]}}]}}");
    ck_assert_uint_eq(4 * m->p.n, full);
    ck_assert_msg(fabs(sum_volumes(m) / (V / 4.0) - 1.0) < 1e-12, "quarter volumes %.17g",
                  sum_volumes(m));
    tlsph_model_free(m);

    /* 2-D disc R = 5 mm, h = 0.5 mm: area pi R^2 per metre */
    m = body_model(2, "{\"name\":\"disc\",\"material\":\"steel\",\"spacing\":0.0005,"
                      "\"placement\":\"conforming\","
                      "\"geometry\":{\"sphere\":{\"center\":[0,0,0],\"radius\":0.005}}}");
    const double A = pi * 0.005 * 0.005;
    fprintf(stderr, "disc R = 5 mm, h = 0.5 mm: %zu particles (A/h^2 = %.1f)\n", m->p.n,
            A / 2.5e-7);
    ck_assert_msg(fabs(sum_volumes(m) / A - 1.0) < 1e-12, "areas %.17g, disc %.17g", sum_volumes(m),
                  A);
    ck_assert(fabs((double)m->p.n / (A / 2.5e-7) - 1.0) < 0.05);
    tlsph_model_free(m);

    /* 3-D cylinder R = 5 mm, L = 20 mm, oblique axis: pi R^2 L; the outer ring
     * at R - h/2 from the axis */
    m = body_model(3, "{\"name\":\"bar\",\"material\":\"steel\",\"spacing\":0.001,"
                      "\"placement\":\"conforming\",\"geometry\":{\"cylinder\":{"
                      "\"base\":[0.01,0,0],\"axis\":[2,2,1],\"radius\":0.005,\"length\":0.02}}}");
    const double Vc = pi * 0.005 * 0.005 * 0.02;
    double rho_max = 0.0;
    for (size_t i = 0; i < m->p.n; i++) {
        const double d[3] = {m->p.X[3 * i] - 0.01, m->p.X[3 * i + 1], m->p.X[3 * i + 2]};
        const double s_ax = (2.0 * d[0] + 2.0 * d[1] + d[2]) / 3.0;
        rho_max =
            fmax(rho_max, sqrt(fmax(0.0, d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - s_ax * s_ax)));
    }
    fprintf(stderr, "cylinder R = 5 mm, L = 20 mm, h = 1 mm: %zu particles (V/h^3 = %.1f)\n",
            m->p.n, Vc / 1e-9);
    ck_assert_msg(fabs(sum_volumes(m) / Vc - 1.0) < 1e-12, "volumes %.17g, cylinder %.17g",
                  sum_volumes(m), Vc);
    ck_assert_msg(fabs(rho_max - 0.0045) < 1e-12, "outer ring %.17g m from the axis", rho_max);
    tlsph_model_free(m);

    /* the lattice stays reachable, every particle h^3 */
    m = body_model(3, "{\"name\":\"ball\",\"material\":\"steel\",\"spacing\":0.001,"
                      "\"placement\":\"lattice\","
                      "\"geometry\":{\"sphere\":{\"center\":[0,0,0],\"radius\":0.01}}}");
    ck_assert_int_eq(m->scene.bodies[0].placement, TLSPH_PLACEMENT_LATTICE);
    for (size_t i = 0; i < m->p.n; i++)
        ck_assert(m->p.vol0[i] == 0.001 * 0.001 * 0.001);
    tlsph_model_free(m);
}
END_TEST

/* Unequal particle volumes keep the pair forces equal and opposite: a
 * conforming sphere (2 mm, 532 particles) with a shearing, spinning initial
 * velocity and no boundary condition keeps its momentum over 200 steps to
 * round-off, 1e-12 of sum m |v| (measured in the log). */
START_TEST(conforming_sphere_conserves_momentum)
{
    struct tlsph_model *m =
        body_model(3, "{\"name\":\"ball\",\"material\":\"steel\",\"spacing\":0.002,"
                      "\"geometry\":{\"sphere\":{\"center\":[0,0,0],\"radius\":0.01}},"
                      "\"initial_velocity\":[\"300*y + 2\",\"-500*z\",\"400*x*x/0.01\"]}");
    double p0[3], p1[3];
    tlsph_model_momentum(m, p0);
    const double scale = momentum_scale(m);
    struct tlsph_diagnostic d;
    for (int k = 0; k < 200; k++) {
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &d) == 0, "step %ld: %s", m->step, d.message);
    }
    tlsph_model_momentum(m, p1);
    double worst = 0.0;
    for (int c = 0; c < 3; c++)
        worst = fmax(worst, fabs(p1[c] - p0[c]) / scale);
    fprintf(stderr, "conforming sphere, 200 steps: momentum change %.2e of sum m|v|\n", worst);
    ck_assert_msg(worst < 1e-12, "momentum changed by %.3g of sum m|v|", worst);
    tlsph_model_free(m);
}
END_TEST

struct impact {
    double duration; /* s: first step the wall pushes to the first it no longer does */
    double peak;     /* N */
    double rebound;  /* the sphere's upward speed when the contact ends / v */
    size_t particles;
    long steps;
};

/* The full sphere (no symmetry planes: the symmetry condition does not mirror
 * the kernel, which moved the conforming quarter's contact time by 6 % at
 * 1 mm) falling at v onto the wall z = 0, its lowest particle 1e-3 h above it. */
static struct impact drop(const char *placement, double h, double v, int on_block)
{
    /* the lowest particle: conforming, the bottom ring of the outer shell
     * (conforming.c); lattice, the lowest lattice level inside the sphere */
    double low;
    if (strcmp(placement, "conforming") == 0) {
        const double N = round(RADIUS / h), t = RADIUS / N, r = RADIUS - 0.5 * t;
        low = r * cos(pi / (2.0 * fmax(1.0, round(pi * r / h))));
    } else {
        const int n = (int)(2.0 * RADIUS / h) + 1;
        double best = INFINITY;
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                const double a = -RADIUS + (i + 0.5) * h, b = -RADIUS + (j + 0.5) * h;
                best = fmin(best, a * a + b * b);
            }
        low = 0.0;
        for (int k = 0; k < n; k++) {
            const double z = -RADIUS + (k + 0.5) * h;
            if (best + z * z <= RADIUS * RADIUS) {
                low = -z;
                break;
            }
        }
    }
    /* the flat: the wall z = 0, or a steel block 12 x 12 x 6 mm whose top layer
     * lies at -h/2 and whose bottom layer is held (the half-space), touched by
     * the penalty law's default line form once the particles' surfaces meet */
    char flat[1024];
    if (on_block)
        snprintf(
            flat, sizeof flat,
            ",{\"name\":\"block\",\"material\":\"steel\",\"spacing\":%.17g,"
            "\"geometry\":{\"box\":{\"min\":[-0.006,-0.006,-0.006],\"max\":[0.006,0.006,0]}}}],"
            "\"contact\":{\"law\":{\"type\":\"penalty\"}},"
            "\"boundary_conditions\":[{\"type\":\"velocity\",\"name\":\"base\","
            "\"velocity\":[0,0,0],\"select\":{\"body\":\"block\","
            "\"expression\":\"z < %.17g\"}}]}",
            h, -0.006 + 0.75 * h);
    else
        snprintf(flat, sizeof flat,
                 "],\"boundary_conditions\":[{\"type\":\"wall\",\"name\":\"floor\","
                 "\"point\":[0,0,0],\"normal\":[0,0,1]}]}");
    char json[3072];
    snprintf(json, sizeof json,
             "{\"dimension\":3,\"time\":{\"end\":%g,\"cfl\":0.3},"
             "\"materials\":{\"steel\":{\"density\":%.17g,\"youngs_modulus\":%.17g,"
             "\"poisson_ratio\":%.17g}},"
             "\"bodies\":[{\"name\":\"ball\",\"material\":\"steel\",\"spacing\":%.17g,"
             "\"placement\":\"%s\",\"geometry\":{\"sphere\":{\"center\":[0,0,%.17g],"
             "\"radius\":%.17g}},\"initial_velocity\":[0,0,%.17g]}%s",
             on_block ? 2e-4 : 1e-4, DENSITY, YOUNG, POISSON, h, placement,
             low + (on_block ? 0.5 * h : 0.0) + 1e-3 * h, RADIUS, -v, flat);
    struct tlsph_model *m = build_model(json);
    struct impact r = {.duration = 0.0, .peak = 0.0, .particles = m->p.n};
    double start = -1.0;
    struct tlsph_diagnostic d;
    while (m->t < m->scene.end_time) {
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &d) == 0, "step %ld: %s", m->step, d.message);
        double Fc[3];
        if (on_block)
            tlsph_contact_body_force(m, 0, Fc);
        const double F = on_block ? Fc[2] : m->groups[0].reaction[2];
        if (F > 0.0 && start < 0.0)
            start = m->t;
        if (start >= 0.0 && !(F > 0.0)) {
            r.duration = m->t - start;
            double p = 0.0, mass = 0.0;
            for (size_t i = m->body_begin[0]; i < m->body_end[0]; i++) {
                p += m->p.mass[i] * m->p.v[3 * i + 2];
                mass += m->p.mass[i];
            }
            r.rebound = p / (mass * v);
            break;
        }
        r.peak = fmax(r.peak, F);
    }
    r.steps = m->step;
    ck_assert_msg(start >= 0.0 && r.duration > 0.0, "the contact did not end within %g s",
                  m->scene.end_time);
    tlsph_model_free(m);
    return r;
}

/* Hertz on a rigid flat (or, on_block, a held steel half-space): duration (s)
 * and peak force (N) at speed v. */
static void hertz(double v, int on_block, double *duration, double *peak)
{
    const double Es = YOUNG / (1.0 - POISSON * POISSON) / (on_block ? 2.0 : 1.0);
    const double mass = DENSITY * 4.0 / 3.0 * pi * RADIUS * RADIUS * RADIUS;
    const double dmax = pow(15.0 * mass * v * v / (16.0 * Es * sqrt(RADIUS)), 0.4);
    *peak = 4.0 / 3.0 * Es * sqrt(RADIUS) * pow(dmax, 1.5);
    *duration = 2.94 * dmax / v;
}

/* 20 m/s, h = 1 mm: a = 1.41 mm.  Measured (docs/contact.md): contact time
 * -39.0 / -9.1 / -6.9 % at h = 2 / 1 / 0.5 mm, peak force +45.0 / +5.2 / +8.7 %:
 * from 1 mm on the error stays within 7-9 % (at 20 m/s the strains reach 10 %,
 * where Hertz's small-strain theory is itself approximate).  The tolerances,
 * 15 % on the duration and 10 % on the peak, hold the 1 and 0.5 mm results and
 * fail the 2 mm ones. */
START_TEST(conforming_sphere_on_a_wall_is_hertzian_when_resolved)
{
    const double v = 20.0;
    double tc, Fmax;
    hertz(v, 0, &tc, &Fmax);
    const struct impact c = drop("conforming", 0.001, v, 0);
    fprintf(stderr,
            "20 m/s, h = 1 mm, %zu particles, %ld steps: contact %.4g us (Hertz %.4g, %+.1f %%), "
            "peak %.5g N (Hertz %.5g, %+.1f %%)\n",
            c.particles, c.steps, c.duration * 1e6, tc * 1e6, 100.0 * (c.duration / tc - 1.0),
            c.peak, Fmax, 100.0 * (c.peak / Fmax - 1.0));
    ck_assert_msg(fabs(c.duration / tc - 1.0) < 0.15, "contact time %.4g us, Hertz %.4g us",
                  c.duration * 1e6, tc * 1e6);
    ck_assert_msg(fabs(c.peak / Fmax - 1.0) < 0.10, "peak force %.5g N, Hertz %.5g N", c.peak,
                  Fmax);
}
END_TEST

/* The conforming and the lattice sphere at 1 m/s, h = 2 mm, on the wall or
 * the block: the conforming one closer to Hertz in both the contact time and
 * the peak force.  Returns the conforming sphere's impact. */
static struct impact closer_than_the_lattice(int on_block)
{
    double tc, Fmax;
    hertz(1.0, on_block, &tc, &Fmax);
    const struct impact c = drop("conforming", 0.002, 1.0, on_block);
    const struct impact l = drop("lattice", 0.002, 1.0, on_block);
    fprintf(stderr,
            "%s, 1 m/s, h = 2 mm: Hertz %.4g us, %.5g N; conforming (%zu particles) %.4g us "
            "(%+.1f %%), %.5g N (%+.1f %%), rebound %.4f v; lattice (%zu) %.4g us (%+.1f %%), "
            "%.5g N (%+.1f %%)\n",
            on_block ? "block" : "wall", tc * 1e6, Fmax, c.particles, c.duration * 1e6,
            100.0 * (c.duration / tc - 1.0), c.peak, 100.0 * (c.peak / Fmax - 1.0), c.rebound,
            l.particles, l.duration * 1e6, 100.0 * (l.duration / tc - 1.0), l.peak,
            100.0 * (l.peak / Fmax - 1.0));
    ck_assert(fabs(c.duration / tc - 1.0) < fabs(l.duration / tc - 1.0));
    ck_assert(fabs(c.peak / Fmax - 1.0) < fabs(l.peak / Fmax - 1.0));
    return c;
}

/* 1 m/s, h = 2 mm (a = 0.43 mm, a fifth of a spacing): neither placement
 * resolves the contact, but the conforming sphere touches at a point where
 * the lattice puts a flat patch.  Measured: contact time -67 % vs -79 %, peak
 * force +164 % vs +345 % (at 1 mm: -48 % vs -74 %, +66 % vs +240 %). */
START_TEST(conforming_sphere_is_closer_to_hertz_than_the_lattice)
{
    closer_than_the_lattice(0);
}
END_TEST

/* The elastic half-space: the sphere on a steel block (E* = E / (2 (1 - nu^2)),
 * m* = m, held bottom), body-body contact with the penalty law's line form,
 * 1 m/s, h = 2 mm.  Measured (docs/contact.md): conforming -55.1 % on the
 * contact time and +90.7 % on the peak force, lattice -75.7 % and +274 %
 * (1 mm: -30.7 / +23.8 % against -70.3 / +191 %; 0.5 mm: +0.4 / -14.9 %).  The
 * conforming sphere is closer to Hertz in both, and the contact gives it back
 * its speed: rebound 1 within 2 % (measured 0.9974; the line form is elastic,
 * the energy stays in the bodies). */
START_TEST(conforming_sphere_on_an_elastic_block)
{
    const struct impact c = closer_than_the_lattice(1);
    ck_assert_msg(fabs(c.rebound - 1.0) < 0.02, "rebound %.4f v", c.rebound);
}
END_TEST

TLSPH_CHECK_MAIN("hertz", 600, conforming_volumes_sum_to_the_body,
                 conforming_sphere_conserves_momentum,
                 conforming_sphere_on_a_wall_is_hertzian_when_resolved,
                 conforming_sphere_is_closer_to_hertz_than_the_lattice,
                 conforming_sphere_on_an_elastic_block)
