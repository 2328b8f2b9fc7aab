/* Scene parser, validator and geometry (core/scene/).
 *
 * - Good scenes parse, defaults and derived elastic constants are right
 *   (G = E/(2(1+nu)), K = E/(3(1-2nu)), c = sqrt((K + 4G/3)/rho0); exact to 1e-12 rel.).
 * - Lattice counts: boxes exactly; curved shapes within the discretisation error
 *   of the analytic volume.  For a shape of size ~10-20 spacings the number of
 *   simple-cubic points differs from V/h^dim by a surface term of order
 *   (surface area / h^2) x O(1) cancelling fluctuations; measured errors are below
 *   1 %, we allow 3 %.
 * - Boolean geometry (union without double counting, difference), the notched bar
 *   (root radius kept, points just outside it removed).  The lattice walk, which
 *   tests each point only against the objects whose box meets its row, gives
 *   exactly the points, in order, of tlsph_geometry_contains over every lattice
 *   point of the bounding box (nested unions and differences of 300 objects,
 *   many surfaces passing through lattice points).
 * - Expressions: initial velocity of x, velocity BC of t, selector conditions.
 * - Errors: exact JSON pointers for representative bad inputs, all errors
 *   collected, scene zeroed on failure, file errors. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bc/kind.h"
#include "material/damage/damage.h"
#include "material/eos/eos.h"
#include "material/strength/strength.h"
#include "scene/parse_internal.h" /* tlsph_lattice_range */
#include "scene/scene.h"
#include "support/check_main.h"

#define BASE_HEAD                                                                            \
    "{\"dimension\": 3, \"time\": {\"end\": 1e-4},"                                          \
    "\"materials\": {\"steel\": {\"density\": 7850, \"youngs_modulus\": 2.1e11, "            \
    "\"poisson_ratio\": 0.3}},"

static int parse(const char *text, struct tlsph_scene *s, struct tlsph_errors *e)
{
    tlsph_errors_init(e);
    return tlsph_scene_parse(text, strlen(text), s, e);
}

static void dump(const struct tlsph_errors *e)
{
    for (size_t i = 0; i < e->count; i++)
        fprintf(stderr, "  %s: %s\n", e->items[i].pointer, e->items[i].message);
}

static int has_pointer(const struct tlsph_errors *e, const char *p)
{
    for (size_t i = 0; i < e->count; i++)
        if (strcmp(e->items[i].pointer, p) == 0)
            return 1;
    return 0;
}

static int is_zero(const struct tlsph_scene *s)
{
    static const struct tlsph_scene zero;
    return memcmp(s, &zero, sizeof zero) == 0;
}

/* Parses a one-body scene with the given body JSON (and dimension) and returns its lattice. */
static size_t body_count(int dim, const char *body, double **pts)
{
    char text[4096];
    snprintf(text, sizeof text,
             "{\"dimension\": %d, \"time\": {\"end\": 1e-4},"
             "\"materials\": {\"m\": {\"density\": 1000, \"youngs_modulus\": 1e9, "
             "\"poisson_ratio\": 0.25}}, \"bodies\": [%s]}",
             dim, body);
    struct tlsph_scene s;
    struct tlsph_errors e;
    int rc = parse(text, &s, &e);
    if (rc != 0)
        dump(&e);
    ck_assert_int_eq(rc, 0);
    double *x = NULL;
    size_t n = 0;
    ck_assert_int_eq(tlsph_body_lattice(&s, 0, s.max_particles, &x, &n, &e), 0);
    if (pts)
        *pts = x;
    else
        free(x);
    tlsph_scene_free(&s);
    tlsph_errors_free(&e);
    return n;
}

static void assert_near_count(size_t n, double exact, double rel)
{
    const double err = fabs((double)n - exact) / exact;
    if (err > rel)
        fprintf(stderr, "count %zu vs analytic %.1f (rel. error %.4f)\n", n, exact, err);
    ck_assert(err <= rel);
}

/* ------------------------------------------------------------------ good scenes */

START_TEST(test_defaults_and_derived)
{
    const char *text = BASE_HEAD
        "\"bodies\": [{\"name\": \"bar\", \"material\": \"steel\", \"spacing\": 0.001,"
        "\"geometry\": {\"box\": {\"min\": [0,0,0], \"max\": [0.01,0.004,0.003]}}}]}";
    struct tlsph_scene s;
    struct tlsph_errors e;
    ck_assert_int_eq(parse(text, &s, &e), 0);
    ck_assert_uint_eq(e.count, 0);
    ck_assert_str_eq(s.name, "scene");
    ck_assert_int_eq(s.dimension, 3);
    ck_assert(s.cfl == 0.6 && s.fixed_dt == 0.0 && s.max_steps == 0);
    ck_assert(s.kernel == TLSPH_KERNEL_WENDLAND_C2 && s.support_factor == 2.01);
    ck_assert(s.hourglass == 1 && s.hourglass_coefficient == 1.0 && s.hourglass_tangent == 1);
    ck_assert(s.viscosity == 0 && s.viscosity_linear == 1.0 && s.viscosity_quadratic == 0.0);
    ck_assert(s.check_every == 10 && s.energy_tolerance == 0.05 && s.speed_limit_factor == 1.0);
    ck_assert(s.max_particles == 2000000 && s.frames == 20 && s.series_every == 10);
    ck_assert_uint_eq(s.nmaterials, 1);
    const struct tlsph_material *m = &s.materials[0];
    const double G = 2.1e11 / 2.6, K = 2.1e11 / (3 * 0.4);
    ck_assert(fabs(m->shear_modulus - G) <= 1e-12 * G);
    ck_assert(fabs(m->bulk_modulus - K) <= 1e-12 * K);
    const double c = sqrt((K + 4 * G / 3) / 7850);
    ck_assert(fabs(m->wave_speed - c) <= 1e-12 * c);
    ck_assert(m->eos != NULL && m->strength != NULL);
    ck_assert_int_eq(s.bodies[0].material, 0);
    /* default origin = min corner of the bounds */
    ck_assert(s.bodies[0].origin[0] == 0 && s.bodies[0].origin[1] == 0);
    ck_assert_ptr_nonnull(s.json_text);
    json_error_t je;
    json_t *round = json_loads(s.json_text, 0, &je);
    ck_assert_ptr_nonnull(round);
    json_decref(round);
    tlsph_scene_free(&s);
    ck_assert(is_zero(&s));
    tlsph_scene_free(&s); /* safe on a zeroed scene */
    tlsph_errors_free(&e);
}
END_TEST

START_TEST(test_full_scene)
{
    const char *text =
        "{\"name\": \"full\", \"dimension\": 3, \"parameters\": {\"vmax\": 5, \"tau\": 1e-5},"
        "\"time\": {\"end\": 1e-4, \"cfl\": 0.25, \"step\": 1e-8, \"max_steps\": 7},"
        "\"discretization\": {\"kernel\": \"cubic_spline\", \"support_factor\": 2.4,"
        "  \"hourglass\": {\"enabled\": false, \"coefficient\": 2},"
        "  \"viscosity\": {\"enabled\": true, \"linear\": 0.5, \"quadratic\": 0.25}},"
        "\"stability\": {\"check_every\": 3, \"energy_tolerance\": 0.2, \"speed_limit\": 0.5},"
        "\"limits\": {\"max_particles\": 5000}, \"output\": {\"frames\": 4, \"series_every\": 2},"
        "\"materials\": {\"al\": {\"density\": 2700, \"youngs_modulus\": 7e10, \"poisson_ratio\": 0.33,"
        "  \"eos\": {\"type\": \"mie_gruneisen\", \"c0\": 5000, \"s\": 1.4}}},"
        "\"bodies\": [{\"name\": \"b\", \"material\": \"al\", \"spacing\": 0.001,"
        "  \"geometry\": {\"box\": {\"min\": [0,0,0], \"max\": [0.01,0.004,0.003]}},"
        "  \"initial_velocity\": [\"vmax*sin(pi*x/0.01)\", 0, \"-2\"]}],"
        "\"boundary_conditions\": ["
        "  {\"type\": \"fixed\", \"select\": {\"body\": \"b\", \"box\": {\"min\": [-1,-1,-1], \"max\": [0.001,1,1]}}},"
        "  {\"type\": \"velocity\", \"name\": \"pull\", \"select\": {\"expression\": \"x > 0.009 && y >= 0\"},"
        "   \"velocity\": [\"vmax*(1-exp(-t/tau))\", null, 1.5]},"
        "  {\"type\": \"wall\", \"point\": [0,0,0], \"normal\": [0,0,2]},"
        "  {\"type\": \"symmetry\", \"point\": [0,0,0], \"normal\": [0,3,4]},"
        "  {\"type\": \"body_force\", \"acceleration\": [0,0,-9.81]}]}";
    struct tlsph_scene s;
    struct tlsph_errors e;
    int rc = parse(text, &s, &e);
    dump(&e);
    ck_assert_int_eq(rc, 0);
    ck_assert_str_eq(s.name, "full");
    ck_assert(s.cfl == 0.25 && s.fixed_dt == 1e-8 && s.max_steps == 7);
    ck_assert(s.kernel == TLSPH_KERNEL_CUBIC_SPLINE && s.support_factor == 2.4);
    ck_assert(s.hourglass == 0 && s.hourglass_coefficient == 2.0);
    ck_assert(s.viscosity == 1 && s.viscosity_linear == 0.5 && s.viscosity_quadratic == 0.25);
    ck_assert(s.check_every == 3 && s.energy_tolerance == 0.2 && s.speed_limit_factor == 0.5);
    ck_assert(s.max_particles == 5000 && s.frames == 4 && s.series_every == 2);
    ck_assert_uint_eq(s.nparams, 2);
    ck_assert_str_eq(s.materials[0].eos->name, "mie_gruneisen");
    ck_assert(s.materials[0].eos_params[0] == 5000);

    /* initial velocity: vmax*sin(pi*x/0.01) at x = 0.005 is vmax = 5 */
    struct tlsph_body *b = &s.bodies[0];
    const double X[3] = {0.005, 0, 0};
    ck_assert(fabs(tlsph_expr_eval(&b->initial_velocity[0], X) - 5.0) < 1e-12);
    ck_assert(tlsph_expr_eval(&b->initial_velocity[2], X) == -2.0);
    ck_assert(b->initial_velocity[1].evaluator != NULL && b->initial_velocity[1].constant);

    ck_assert_uint_eq(s.nbcs, 5);
    ck_assert_str_eq(s.bcs[0].name, "bc0");
    ck_assert(strcmp(s.bcs[0].kind->name, "fixed") == 0 && s.bcs[0].select.body == 0);
    ck_assert(s.bcs[0].select.has_box && s.bcs[0].select.box_max[0] == 0.001);
    ck_assert(s.bcs[0].select.expression.evaluator == NULL);

    struct tlsph_bc *v = &s.bcs[1];
    ck_assert_str_eq(v->name, "pull");
    ck_assert(v->velocity_set[0] && !v->velocity_set[1] && v->velocity_set[2]);
    ck_assert(v->velocity[1].evaluator == NULL);
    const double t = 1e-5;
    ck_assert(fabs(tlsph_expr_eval(&v->velocity[0], &t) - 5.0 * (1 - exp(-1.0))) < 1e-12);
    ck_assert(tlsph_expr_eval(&v->velocity[2], &t) == 1.5);
    const double in[3] = {0.0095, 0.001, 0}, out1[3] = {0.0085, 0.001, 0},
                 out2[3] = {0.0095, -0.001, 0}, edge[3] = {0.0095, 0.0, 0};
    ck_assert(tlsph_expr_eval(&v->select.expression, in) == 1.0);
    ck_assert(tlsph_expr_eval(&v->select.expression, out1) == 0.0);
    ck_assert(tlsph_expr_eval(&v->select.expression, out2) == 0.0);
    ck_assert(tlsph_expr_eval(&v->select.expression, edge) == 1.0); /* >= is inclusive */

    ck_assert(strcmp(s.bcs[2].kind->name, "wall") == 0 && s.bcs[2].normal[2] == 1.0);
    ck_assert_str_eq(s.bcs[3].kind->name, "symmetry");
    ck_assert(fabs(s.bcs[3].normal[1] - 0.6) < 1e-15 && fabs(s.bcs[3].normal[2] - 0.8) < 1e-15);
    ck_assert(s.bcs[3].select.body == -1 && !s.bcs[3].select.has_box &&
              s.bcs[3].select.expression.evaluator == NULL);
    ck_assert(strcmp(s.bcs[4].kind->name, "body_force") == 0 && s.bcs[4].acceleration[2] == -9.81);
    ck_assert(s.bcs[4].select.body == -1);
    tlsph_scene_free(&s);
    tlsph_errors_free(&e);
}
END_TEST

START_TEST(test_conditions)
{
    const char *text = BASE_HEAD
        "\"bodies\": [{\"name\": \"bar\", \"material\": \"steel\", \"spacing\": 0.001,"
        "\"geometry\": {\"box\": {\"min\": [0,0,0], \"max\": [0.01,0.004,0.003]}}}],"
        "\"boundary_conditions\": ["
        "{\"type\": \"fixed\", \"select\": {\"expression\": \"x < 1 || (y <= 2 && z > 3)\"}},"
        "{\"type\": \"fixed\", \"select\": {\"expression\": \"x*x + y*y <= 1\"}}]}";
    struct tlsph_scene s;
    struct tlsph_errors e;
    ck_assert_int_eq(parse(text, &s, &e), 0);
    struct tlsph_expr *c = &s.bcs[0].select.expression, *d = &s.bcs[1].select.expression;
    const double p1[3] = {0.5, 9, 0}, p2[3] = {5, 2, 4}, p3[3] = {5, 2, 3}, p4[3] = {1, 3, 9};
    ck_assert(tlsph_expr_eval(c, p1) == 1.0);
    ck_assert(tlsph_expr_eval(c, p2) == 1.0);
    ck_assert(tlsph_expr_eval(c, p3) == 0.0); /* z > 3 is strict */
    ck_assert(tlsph_expr_eval(c, p4) == 0.0); /* x < 1 is strict */
    const double q1[3] = {0.6, 0.8, 0}, q2[3] = {0.8, 0.8, 0};
    ck_assert(tlsph_expr_eval(d, q1) == 1.0);
    ck_assert(tlsph_expr_eval(d, q2) == 0.0);
    tlsph_scene_free(&s);
    tlsph_errors_free(&e);
}
END_TEST

/* ------------------------------------------------------------------ geometry */

START_TEST(test_box_exact)
{
    double *x;
    size_t n = body_count(3,
                          "{\"name\": \"b\", \"material\": \"m\", \"spacing\": 0.001,"
                          "\"geometry\": {\"box\": {\"min\": [0,0,0], \"max\": [0.01,0.004,0.003]}}}",
                          &x);
    ck_assert_uint_eq(n, 120); /* 10 x 4 x 3 */
    /* x fastest, then y, then z; points at (i + 1/2) h */
    ck_assert(fabs(x[0] - 0.0005) < 1e-15 && fabs(x[1] - 0.0005) < 1e-15);
    ck_assert(fabs(x[3] - 0.0015) < 1e-15 && fabs(x[4] - 0.0005) < 1e-15);
    ck_assert(fabs(x[3 * 10 + 1] - 0.0015) < 1e-15);
    ck_assert(fabs(x[3 * 40 + 2] - 0.0015) < 1e-15);
    ck_assert(fabs(x[3 * 119] - 0.0095) < 1e-15 && fabs(x[3 * 119 + 2] - 0.0025) < 1e-15);
    free(x);
    /* 2-D: 10 x 4 points in the plane z = 0 */
    n = body_count(2,
                   "{\"name\": \"b\", \"material\": \"m\", \"spacing\": 0.001,"
                   "\"geometry\": {\"box\": {\"min\": [0,0,7], \"max\": [0.01,0.004,7]}}}",
                   &x);
    ck_assert_uint_eq(n, 40);
    for (size_t i = 0; i < n; i++)
        ck_assert(x[3 * i + 2] == 0.0);
    free(x);
}
END_TEST

START_TEST(test_curved_counts)
{
    /* cylinder R = 5 mm, L = 20 mm, h = 0.5 mm, tilted axis: V/h^3 = 12566.4 */
    size_t n = body_count(3,
                          "{\"name\": \"c\", \"material\": \"m\", \"spacing\": 0.0005,"
                          "\"geometry\": {\"cylinder\": {\"base\": [0,0,0], \"axis\": [1,1,0.5],"
                          "\"radius\": 0.005, \"length\": 0.02}}}",
                          NULL);
    assert_near_count(n, M_PI * 25 * 20 / 0.125, 0.03);
    /* sphere R = 5 mm, h = 0.5 mm: 4/3 pi 10^3 = 4188.8 */
    n = body_count(3,
                   "{\"name\": \"s\", \"material\": \"m\", \"spacing\": 0.0005,"
                   "\"geometry\": {\"sphere\": {\"center\": [0.1,0.2,0.3], \"radius\": 0.005}}}",
                   NULL);
    assert_near_count(n, 4.0 / 3.0 * M_PI * 1000, 0.03);
    /* 2-D disk R = 5 mm, h = 0.25 mm: pi 20^2 = 1256.6 */
    n = body_count(2,
                   "{\"name\": \"d\", \"material\": \"m\", \"spacing\": 0.00025,"
                   "\"geometry\": {\"sphere\": {\"center\": [0,0,0], \"radius\": 0.005}}}",
                   NULL);
    assert_near_count(n, M_PI * 400, 0.03);
    /* plate 20 x 10 x 2 mm with an oblique normal, h = 0.5 mm: 3200 */
    n = body_count(3,
                   "{\"name\": \"p\", \"material\": \"m\", \"spacing\": 0.0005,"
                   "\"geometry\": {\"plate\": {\"center\": [0,0,0], \"normal\": [1,2,3],"
                   "\"size\": [0.02, 0.01], \"thickness\": 0.002}}}",
                   NULL);
    assert_near_count(n, 20.0 * 10 * 2 / 0.125, 0.03);
}
END_TEST

START_TEST(test_boolean)
{
    /* two overlapping 10x10x10 boxes offset by 5 along x: 15x10x10 = 1500, not 2000 */
    size_t n = body_count(3,
                          "{\"name\": \"u\", \"material\": \"m\", \"spacing\": 0.001,"
                          "\"geometry\": {\"union\": ["
                          "{\"box\": {\"min\": [0,0,0], \"max\": [0.01,0.01,0.01]}},"
                          "{\"box\": {\"min\": [0.005,0,0], \"max\": [0.015,0.01,0.01]}}]}}",
                          NULL);
    ck_assert_uint_eq(n, 1500);
    /* box minus a box: 10x10x10 - 4x10x10 = 600 (cut aligned with the lattice) */
    n = body_count(3,
                   "{\"name\": \"d\", \"material\": \"m\", \"spacing\": 0.001,"
                   "\"geometry\": {\"difference\": ["
                   "{\"box\": {\"min\": [0,0,0], \"max\": [0.01,0.01,0.01]}},"
                   "{\"box\": {\"min\": [0.006,-1,-1], \"max\": [1,1,1]}}]}}",
                   NULL);
    ck_assert_uint_eq(n, 600);
    /* 40x40x4 mm plate minus a through hole of radius 10 mm (h = 0.5 mm) */
    n = body_count(3,
                   "{\"name\": \"h\", \"material\": \"m\", \"spacing\": 0.0005,"
                   "\"geometry\": {\"difference\": ["
                   "{\"box\": {\"min\": [0,0,0], \"max\": [0.04,0.04,0.004]}},"
                   "{\"cylinder\": {\"base\": [0.02,0.02,-0.001], \"axis\": [0,0,1],"
                   "\"radius\": 0.01, \"length\": 0.006}}]}}",
                   NULL);
    assert_near_count(n, (1600.0 - M_PI * 100) * 4 / 0.125, 0.03);
}
END_TEST

START_TEST(test_notched_bar)
{
    const char *body = "{\"name\": \"n\", \"material\": \"m\", \"spacing\": 0.0005,"
                       "\"geometry\": {\"notched_bar\": {\"base\": [0,0,0], \"axis\": [0,0,2],"
                       "\"radius\": 0.005, \"length\": 0.03, \"notch_root_radius\": 0.003,"
                       "\"notch_radius\": 0.004, \"notch_position\": 0.015}}}";
    char text[2048];
    snprintf(text, sizeof text,
             "{\"dimension\": 3, \"time\": {\"end\": 1e-4}, \"materials\": {\"m\": {\"density\": "
             "1000, \"youngs_modulus\": 1e9, \"poisson_ratio\": 0.25}}, \"bodies\": [%s]}",
             body);
    struct tlsph_scene s;
    struct tlsph_errors e;
    ck_assert_int_eq(parse(text, &s, &e), 0);
    const struct tlsph_geometry *g = &s.bodies[0].geometry;
    ck_assert(g->type == TLSPH_GEOM_NOTCHED_BAR && g->a[5] == 1.0); /* axis normalised */
    const double root_in[3] = {0.003 - 1e-7, 0, 0.015}, root_on[3] = {0, 0.003, 0.015},
                 root_out[3] = {0.003 + 1e-6, 0, 0.015}, far[3] = {0.0049, 0, 0.002},
                 flank[3] = {0.0045, 0, 0.015 + 0.003}, past[3] = {0, 0, 0.0301},
                 outside[3] = {0.0051, 0, 0.002};
    ck_assert(tlsph_geometry_contains(g, root_in));
    ck_assert(tlsph_geometry_contains(g, root_on));
    ck_assert(!tlsph_geometry_contains(g, root_out));
    ck_assert(tlsph_geometry_contains(g, far));
    /* (0.0045 - 0.007)^2 + 0.003^2 = 1.525e-5 < R^2 = 1.6e-5: cut away */
    ck_assert(!tlsph_geometry_contains(g, flank));
    ck_assert(!tlsph_geometry_contains(g, past));
    ck_assert(!tlsph_geometry_contains(g, outside));
    double lo[3], hi[3];
    tlsph_geometry_bounds(g, lo, hi);
    ck_assert(fabs(lo[0] + 0.005) < 1e-15 && fabs(hi[2] - 0.03) < 1e-15);
    tlsph_scene_free(&s);
    tlsph_errors_free(&e);

    /* volume: bar minus the notch ring; the ring volume by numerical integration */
    const double R0 = 0.005, r = 0.003, R = 0.004, rc = r + R;
    double ring = 0.0;
    const int N = 20000;
    for (int i = 0; i < N; i++) { /* integrate over z in (-R, R) */
        const double z = -R + (i + 0.5) * 2 * R / N, half = sqrt(R * R - z * z);
        const double inner = fmax(rc - half, 0.0), outer = fmin(rc + half, R0);
        if (outer > inner)
            ring += M_PI * (outer * outer - inner * inner) * 2 * R / N;
    }
    const double volume = M_PI * R0 * R0 * 0.03 - ring;
    assert_near_count(body_count(3, body, NULL), volume / 1.25e-10, 0.03);
}
END_TEST

/* A notch deeper than its radius is a U-notch: round root of radius R, straight
 * flanks 2R apart out to the surface.  Reference volume: bar minus the ring of
 * the half disc plus the rectangle (exact, Pappus). */
START_TEST(test_u_notch)
{
    const double R0 = 0.005, r = 0.003, R = 0.0004, zc = 0.005, L = 0.01;
    char body[512], text[2048];
    snprintf(body, sizeof body,
             "{\"name\": \"n\", \"material\": \"m\", \"spacing\": 0.0001,"
             "\"geometry\": {\"notched_bar\": {\"base\": [0,0,0], \"axis\": [0,0,1],"
             "\"radius\": %g, \"length\": %g, \"notch_root_radius\": %g,"
             "\"notch_radius\": %g, \"notch_position\": %g}}}",
             R0, L, r, R, zc);
    snprintf(text, sizeof text,
             "{\"dimension\": 3, \"time\": {\"end\": 1e-4}, \"materials\": {\"m\": {\"density\": "
             "1000, \"youngs_modulus\": 1e9, \"poisson_ratio\": 0.25}}, \"bodies\": [%s]}",
             body);
    struct tlsph_scene s;
    struct tlsph_errors e;
    ck_assert_int_eq(parse(text, &s, &e), 0);
    const struct tlsph_geometry *g = &s.bodies[0].geometry;
    const double root[3] = {r, 0, zc}, below_root[3] = {r - 1e-6, 0, zc},
                 in_slot[3] = {0.0045, 0, zc + 0.00039}, flank[3] = {0.0045, 0, zc + 0.00041},
                 corner[3] = {r + 0.5 * R, 0, zc + 0.95 * R};
    ck_assert(tlsph_geometry_contains(g, root));
    ck_assert(tlsph_geometry_contains(g, below_root));
    ck_assert(!tlsph_geometry_contains(g, in_slot));
    ck_assert(tlsph_geometry_contains(g, flank));
    ck_assert(tlsph_geometry_contains(g, corner)); /* outside the root circle, below the slot */
    tlsph_scene_free(&s);
    tlsph_errors_free(&e);

    /* half disc of radius R centred at rho = r + R: area pi R^2 / 2, centroid at
     * r + R - 4R/(3 pi); slot rectangle 2R x (R0 - r - R) centred at (r + R + R0)/2 */
    const double disc = M_PI * R * R / 2 * 2 * M_PI * (r + R - 4 * R / (3 * M_PI));
    const double slot = 2 * R * (R0 - r - R) * 2 * M_PI * 0.5 * (r + R + R0);
    const double volume = M_PI * R0 * R0 * L - disc - slot;
    assert_near_count(body_count(3, body, NULL), volume / 1e-12, 0.01);
}
END_TEST

START_TEST(test_lattice_walk_matches_contains)
{
    /* difference(box, union(spheres), union(difference(sphere, box), cylinders)):
     * centres and radii on the lattice's half-spacing grid put points exactly
     * on surfaces, where a bounding box that is not conservative would show */
    const double h = 0.001;
    char *text = malloc(65536), *p = text;
    ck_assert_ptr_nonnull(text);
    p += sprintf(p,
                 "{\"dimension\": 3, \"time\": {\"end\": 1e-4}, \"materials\": {\"m\": "
                 "{\"density\": 1000, \"youngs_modulus\": 1e9, \"poisson_ratio\": 0.25}},"
                 "\"bodies\": [{\"name\": \"b\", \"material\": \"m\", \"spacing\": %g,"
                 "\"geometry\": {\"difference\": [{\"box\": {\"min\": [0,0,0], "
                 "\"max\": [0.03,0.02,0.015]}}, {\"union\": [",
                 h);
    unsigned seed = 7;
    for (int k = 0; k < 250; k++) {
        seed = seed * 1103515245u + 12345u;
        const double x = (double)(seed % 61) * 0.5 * h, y = (double)((seed >> 8) % 41) * 0.5 * h,
                     z = (double)((seed >> 16) % 31) * 0.5 * h,
                     r = (double)(1 + (seed >> 24) % 4) * h;
        p += sprintf(p, "%s{\"sphere\": {\"center\": [%.17g,%.17g,%.17g], \"radius\": %.17g}}",
                     k ? "," : "", x, y, z, r);
    }
    p += sprintf(p, "]}, {\"union\": [{\"difference\": [{\"sphere\": {\"center\": "
                    "[0.015,0.01,0.0075], \"radius\": 0.006}}, {\"box\": {\"min\": "
                    "[0.0125,0.0075,0], \"max\": [0.0175,0.0125,0.015]}}]}");
    for (int k = 0; k < 40; k++)
        p += sprintf(p,
                     ", {\"cylinder\": {\"base\": [%.17g,0,0.0075], \"axis\": [0,1,0.5],"
                     "\"radius\": 0.0005, \"length\": 0.02}}",
                     0.0005 + 0.00075 * k);
    sprintf(p, "]}]}}]}");
    struct tlsph_scene s;
    struct tlsph_errors e;
    const int rc = parse(text, &s, &e);
    if (rc != 0)
        dump(&e);
    ck_assert_int_eq(rc, 0);
    free(text);
    double *x = NULL;
    size_t n = 0;
    ck_assert_int_eq(tlsph_body_lattice(&s, 0, s.max_particles, &x, &n, &e), 0);
    const struct tlsph_body *b = &s.bodies[0];
    long lo[3], hi[3];
    ck_assert(tlsph_lattice_range(&s, 0, lo, hi) > 0);
    size_t m = 0;
    for (long k = lo[2]; k <= hi[2]; k++)
        for (long j = lo[1]; j <= hi[1]; j++)
            for (long i = lo[0]; i <= hi[0]; i++) {
                const double X[3] = {b->origin[0] + ((double)i + 0.5) * h,
                                     b->origin[1] + ((double)j + 0.5) * h,
                                     b->origin[2] + ((double)k + 0.5) * h};
                if (!tlsph_geometry_contains(&b->geometry, X))
                    continue;
                ck_assert_msg(m < n, "the walk found fewer than %zu points", m + 1);
                ck_assert_msg(memcmp(x + 3 * m, X, sizeof X) == 0, "point %zu differs", m);
                m++;
            }
    ck_assert_uint_eq(m, n);
    ck_assert(n > 500 && n < 8500); /* neither empty nor the whole box (9000 points) */
    free(x);
    tlsph_scene_free(&s);
    tlsph_errors_free(&e);
}
END_TEST

START_TEST(test_lattice_limit)
{
    const char *text = BASE_HEAD
        "\"bodies\": [{\"name\": \"bar\", \"material\": \"steel\", \"spacing\": 0.001,"
        "\"geometry\": {\"box\": {\"min\": [0,0,0], \"max\": [0.01,0.004,0.003]}}}]}";
    struct tlsph_scene s;
    struct tlsph_errors e;
    ck_assert_int_eq(parse(text, &s, &e), 0);
    double *x = (double *)&s; /* must be reset to NULL */
    size_t n = 7;
    ck_assert_int_eq(tlsph_body_lattice(&s, 0, 119, &x, &n, &e), -1);
    ck_assert_ptr_null(x);
    ck_assert_uint_eq(n, 0);
    ck_assert_uint_eq(e.count, 1);
    ck_assert_str_eq(e.items[0].pointer, "/bodies/0");
    tlsph_scene_free(&s);
    tlsph_errors_free(&e);
}
END_TEST

/* ------------------------------------------------------------------ errors */

static void expect_error(const char *text, const char *pointer)
{
    struct tlsph_scene s;
    struct tlsph_errors e;
    memset(&s, 0xab, sizeof s); /* garbage in: must come out zeroed */
    const int rc = parse(text, &s, &e);
    if (rc == 0 || !has_pointer(&e, pointer)) {
        fprintf(stderr, "expected an error at '%s', got:\n", pointer);
        dump(&e);
    }
    ck_assert_int_eq(rc, -1);
    ck_assert(has_pointer(&e, pointer));
    ck_assert(is_zero(&s));
    for (size_t i = 0; i < e.count; i++)
        ck_assert(strlen(e.items[i].message) > 10);
    tlsph_errors_free(&e);
}

#define BODY_OK                                                                              \
    "\"bodies\": [{\"name\": \"bar\", \"material\": \"steel\", \"spacing\": 0.001,"          \
    "\"geometry\": {\"box\": {\"min\": [0,0,0], \"max\": [0.01,0.004,0.003]}}}]"

START_TEST(test_error_pointers)
{
    expect_error("{\"dimension\": 3,", "");
    expect_error("[]", "");
    expect_error("{\"dimension\": 3, \"dimension\": 3}", "");
    expect_error("{\"dimension\": 3, \"time\": {\"end\": 1e-4}, \"materials\": {\"steel\": "
                 "{\"density\": 7850, \"youngs_modulus\": 2.1e11, \"poisson_ratio\": 0.5}}," BODY_OK
                 "}",
                 "/materials/steel/poisson_ratio");
    expect_error("{\"dimension\": 3, \"time\": {\"end\": 1e-4}, \"materials\": {\"a/b~c\": "
                 "{\"density\": -1, \"youngs_modulus\": 2.1e11, \"poisson_ratio\": 0.3}}}",
                 "/materials/a~1b~0c/density");
    expect_error(BASE_HEAD "\"bodies\": [{\"name\": \"bar\", \"material\": \"steel\", "
                           "\"spacing\": 0, \"geometry\": {\"box\": {\"min\": [0,0,0], "
                           "\"max\": [1,1,1]}}}]}",
                 "/bodies/0/spacing");
    expect_error(BASE_HEAD BODY_OK ", \"boundary_conditions\": ["
                                   "{\"type\": \"fixed\", \"select\": {\"body\": \"bar\"}},"
                                   "{\"type\": \"velocity\", \"select\": {\"body\": \"bar\"},"
                                   " \"velocity\": [null, 1, \"t*q\"]}]}",
                 "/boundary_conditions/1/velocity/2");
    expect_error(BASE_HEAD BODY_OK ", \"boundary_conditions\": ["
                                   "{\"type\": \"velocity\", \"select\": {\"body\": \"bar\"},"
                                   " \"velocity\": [null, null, null]}]}",
                 "/boundary_conditions/0/velocity");
    expect_error(BASE_HEAD BODY_OK ", \"boundary_conditions\": ["
                                   "{\"type\": \"fixed\", \"select\": {\"expression\": \"x <\"}}]}",
                 "/boundary_conditions/0/select/expression");
    expect_error(BASE_HEAD BODY_OK ", \"boundary_conditions\": ["
                                   "{\"type\": \"fixed\", \"select\": {}}]}",
                 "/boundary_conditions/0/select");
    expect_error(BASE_HEAD "\"bodies\": [{\"name\": \"bar\", \"material\": \"steel\", "
                           "\"spacing\": 1e-5, \"geometry\": {\"box\": {\"min\": [0,0,0], "
                           "\"max\": [1,1,1]}}}]}",
                 "/bodies/0/spacing");
    expect_error(BASE_HEAD "\"bodies\": [{\"name\": \"bar\", \"material\": \"steel\", "
                           "\"spacing\": 1e-3, \"origin\": [0,0,0], \"geometry\": {\"sphere\": "
                           "{\"center\": [0,0,0], \"radius\": 4e-4}}}]}",
                 "/bodies/0/geometry");
    expect_error(BASE_HEAD "\"bodies\": [{\"name\": \"bar\", \"material\": \"steel\", "
                           "\"spacing\": 1e-3, \"geometry\": {\"union\": [{\"union\": [{\"union\":"
                           "[{\"sphere\": {\"center\": [0,0], \"radius\": 1}}]}]}]}}]}",
                 "/bodies/0/geometry/union/0/union/0/union/0/sphere/center");
}
END_TEST

START_TEST(test_all_errors_collected)
{
    const char *text =
        "{\"dimension\": 3, \"bogus\": 1, \"time\": {\"end\": -1, \"cfl\": 0},"
        "\"materials\": {\"steel\": {\"density\": \"heavy\", \"youngs_modulus\": 2.1e11,"
        "\"poisson_ratio\": 0.7}},"
        "\"bodies\": [{\"name\": \"bar\", \"material\": \"copper\", \"spacing\": -1,"
        "\"geometry\": {\"box\": {\"min\": [0,0,0], \"max\": [1,1,1]}},"
        "\"initial_velocity\": [\"sin(x\", \"w\", 0]}],"
        "\"boundary_conditions\": [{\"type\": \"wall\", \"point\": [0,0,0], \"normal\": [0,0,0]}]}";
    struct tlsph_scene s;
    struct tlsph_errors e;
    ck_assert_int_eq(parse(text, &s, &e), -1);
    static const char *const want[] = {"/bogus", "/time/end", "/time/cfl",
                                       "/materials/steel/density",
                                       "/materials/steel/poisson_ratio", "/bodies/0/material",
                                       "/bodies/0/spacing", "/bodies/0/initial_velocity/0",
                                       "/bodies/0/initial_velocity/1",
                                       "/boundary_conditions/0/normal"};
    for (size_t i = 0; i < sizeof want / sizeof *want; i++) {
        if (!has_pointer(&e, want[i])) {
            fprintf(stderr, "missing error at %s\n", want[i]);
            dump(&e);
        }
        ck_assert(has_pointer(&e, want[i]));
    }
    ck_assert(is_zero(&s));
    tlsph_errors_free(&e);
}
END_TEST

START_TEST(test_files)
{
    struct tlsph_scene s;
    struct tlsph_errors e;
    tlsph_errors_init(&e);
    ck_assert_int_eq(tlsph_scene_load_file("/nonexistent/dir/scene.json", &s, &e), -1);
    ck_assert_uint_eq(e.count, 1);
    ck_assert_str_eq(e.items[0].pointer, "");
    ck_assert(strstr(e.items[0].message, "cannot open") != NULL);
    ck_assert(is_zero(&s));
    tlsph_errors_free(&e);

    char path[] = "/tmp/test_scene_XXXXXX";
    int fd = mkstemp(path);
    ck_assert(fd >= 0);
    FILE *f = fdopen(fd, "w");
    ck_assert_ptr_nonnull(f);
    /* 17 MiB of spaces: refused before parsing */
    static char block[1 << 20];
    memset(block, ' ', sizeof block);
    for (int i = 0; i < 17; i++)
        ck_assert_uint_eq(fwrite(block, 1, sizeof block, f), sizeof block);
    fclose(f);
    ck_assert_int_eq(tlsph_scene_load_file(path, &s, &e), -1);
    ck_assert_uint_eq(e.count, 1);
    ck_assert(strstr(e.items[0].message, "16 MiB") != NULL);
    tlsph_errors_free(&e);

    f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(BASE_HEAD BODY_OK "}", f);
    fclose(f);
    ck_assert_int_eq(tlsph_scene_load_file(path, &s, &e), 0);
    ck_assert_uint_eq(s.nbodies, 1);
    tlsph_scene_free(&s);
    tlsph_errors_free(&e);
    remove(path);
}
END_TEST

/* Every model family lists its accepted names from its table (the text of
 * "accepted: ..." errors), and finding a listed name returns the row whose
 * scene name it is: the list, the lookup and the descriptors agree. */
static int each_listed_name_finds_its_row(const char *list, const char *(*name_of)(const char *))
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", list);
    int n = 0;
    for (char *save = NULL, *tok = strtok_r(buf, ", ", &save); tok;
         tok = strtok_r(NULL, ", ", &save), n++) {
        const char *found = name_of(tok);
        ck_assert_msg(found && strcmp(found, tok) == 0, "'%s' finds %s", tok, found ? found : "nothing");
    }
    return n;
}

static const char *eos_name(const char *s)
{
    const struct tlsph_eos_model *m = tlsph_eos_find(s);
    return m ? m->name : NULL;
}
static const char *strength_name(const char *s)
{
    const struct tlsph_strength_model *m = tlsph_strength_find(s);
    return m ? m->name : NULL;
}
static const char *damage_name(const char *s)
{
    const struct tlsph_damage_model *m = tlsph_damage_find(s);
    return m ? m->name : NULL;
}
static const char *bc_name(const char *s)
{
    const struct tlsph_bc_kind *k = tlsph_bc_find(s);
    return k ? k->name : NULL;
}

START_TEST(test_registries_find_their_rows)
{
    ck_assert_int_eq(each_listed_name_finds_its_row(tlsph_eos_names(), eos_name), 2);
    ck_assert_int_eq(each_listed_name_finds_its_row(tlsph_strength_names(), strength_name), 5);
    ck_assert_int_eq(each_listed_name_finds_its_row(tlsph_strength_plastic_names(), strength_name), 4);
    ck_assert_int_eq(each_listed_name_finds_its_row(tlsph_damage_names(), damage_name), 9);
    char bcs[256];
    tlsph_bc_names(bcs, sizeof bcs, 0, "", ", ");
    ck_assert_int_eq(each_listed_name_finds_its_row(bcs, bc_name), 6);
    ck_assert_ptr_null(tlsph_eos_find("linearx"));
    ck_assert_ptr_null(tlsph_strength_find("johnson"));
    ck_assert_ptr_null(tlsph_damage_find(""));
    ck_assert_ptr_null(tlsph_bc_find("wal"));
}
END_TEST

static Suite *scene_suite(void)
{
    Suite *s = suite_create("scene");
    TCase *tc = tcase_create("parse");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_defaults_and_derived);
    tcase_add_test(tc, test_full_scene);
    tcase_add_test(tc, test_conditions);
    tcase_add_test(tc, test_box_exact);
    tcase_add_test(tc, test_curved_counts);
    tcase_add_test(tc, test_boolean);
    tcase_add_test(tc, test_notched_bar);
    tcase_add_test(tc, test_u_notch);
    tcase_add_test(tc, test_lattice_walk_matches_contains);
    tcase_add_test(tc, test_lattice_limit);
    tcase_add_test(tc, test_error_pointers);
    tcase_add_test(tc, test_all_errors_collected);
    tcase_add_test(tc, test_files);
    tcase_add_test(tc, test_registries_find_their_rows);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return tlsph_check_run(scene_suite());
}
