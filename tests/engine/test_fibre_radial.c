/* Fibres through a curved shell (core/crack/fibre.h tlsph_fibres_build_radial,
 * paper 003 §6.4: a cylinder's wall three particles thick) and eq. 20's tip
 * search in the shell's tangent plane; every expected answer is worked out
 * by hand in the comment next to it.
 *
 * The tube: axis through B = (0.1, -0.2, 0.3) m along a = (1, 2, 2)/3 (tilted,
 * so that no coordinate axis helps), NR = 3 shells at r = 95, 100, 105 mm,
 * NA = 128 rays at the angles (i + 1/2) 2 pi / NA from a unit vector e1
 * normal to a (not the builder's own reference), NZ = 5 layers at z = (l +
 * 1/2) DZ, DZ = 5 mm; spacing S = 5 mm.  Listed in a scrambled order. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crack/fibre.h"
#include "run/model.h"
#include "support/check_main.h"
#include "support/scene_builder.h"

#define S 5e-3
#define DZ 5e-3
#define NR 3
#define NA 128
#define NZ 5
#define NP (NR * NA * NZ)

static const double B[3] = {0.1, -0.2, 0.3};
static const double A[3] = {1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0};
/* e1 = (2, -1, 0)/sqrt(5) (normal to A), e2 = A x e1 */
static void frame(double e1[3], double e2[3])
{
    const double q = 1.0 / sqrt(5.0);
    e1[0] = 2.0 * q, e1[1] = -q, e1[2] = 0.0;
    e2[0] = A[1] * e1[2] - A[2] * e1[1];
    e2[1] = A[2] * e1[0] - A[0] * e1[2];
    e2[2] = A[0] * e1[1] - A[1] * e1[0];
}

static double radius(int k)
{
    return 0.095 + 0.005 * k;
}

/* The point of shell k, ray i (of n), layer l; its ray tangent (unit) in t. */
static void point(int k, int i, int n, int l, double X[3], double t[3])
{
    double e1[3], e2[3];
    frame(e1, e2);
    const double phi = ((double)i + 0.5) * 2.0 * M_PI / (double)n, z = ((double)l + 0.5) * DZ;
    for (int c = 0; c < 3; c++) {
        X[c] = B[c] + z * A[c] + radius(k) * (cos(phi) * e1[c] + sin(phi) * e2[c]);
        if (t)
            t[c] = -sin(phi) * e1[c] + cos(phi) * e2[c];
    }
}

struct tube {
    double X[3 * NP];
    size_t index[NP];
    int tag[NP]; /* (layer * NA + ray) * NR + shell of each particle */
};

/* Particle p = (l, i, k) stored at the scrambled slot (p * 7919) mod NP. */
static void make_tube(struct tube *tb, const int *count)
{
    for (int p = 0; p < NP; p++) {
        const int k = p % NR, i = (p / NR) % NA, l = p / (NR * NA);
        const size_t q = ((size_t)p * 7919u) % NP;
        point(k, i, count ? count[k] : NA, l, tb->X + 3 * q, NULL);
        tb->tag[q] = p;
        tb->index[q] = q;
    }
}

/* The fibre holding particle tag p (its (l, i) ray), or -1. */
static long fibre_of(const struct tlsph_fibres *f, const struct tube *tb, int p)
{
    for (size_t j = 0; j < f->n; j++)
        for (size_t q = f->start[j]; q < f->start[j + 1]; q++)
            if (tb->tag[f->particle[q]] == p)
                return (long)j;
    return -1;
}

/* 640 rays of three: every fibre holds the three shells of one (layer, ray),
 * ordered by radius, its centre their mean; numbered by z, then theta, so
 * the layers come in order (fibres 128 l .. 128 l + 127 are layer l). */
START_TEST(a_tube_stacks_along_its_radius)
{
    static struct tube tb;
    make_tube(&tb, NULL);
    struct tlsph_fibres f;
    size_t bad = 99;
    ck_assert_int_eq(tlsph_fibres_build_radial(&f, tb.X, tb.index, NP, S, B, A, &bad),
                     TLSPH_FIBRE_OK);
    ck_assert_int_eq(f.axis, TLSPH_FIBRE_RADIAL);
    ck_assert_uint_eq(f.n, NA * NZ);
    for (size_t j = 0; j < f.n; j++) {
        ck_assert_uint_eq(f.start[j + 1] - f.start[j], NR);
        const int p0 = tb.tag[f.particle[f.start[j]]];
        ck_assert_int_eq(p0 % NR, 0);                      /* the inner shell first */
        ck_assert_int_eq(p0 / (NR * NA), (int)(j / NA)); /* layer by layer */
        double c[3] = {0, 0, 0};
        for (size_t q = 0; q < NR; q++) {
            ck_assert_int_eq(tb.tag[f.particle[f.start[j] + q]], p0 + (int)q); /* one ray */
            for (int d = 0; d < 3; d++)
                c[d] += tb.X[3 * f.particle[f.start[j] + q] + d] / NR;
        }
        for (int d = 0; d < 3; d++)
            ck_assert_double_eq_tol(f.centre[j][d], c[d], 1e-15);
        /* depth: the middle shell's radius, to round-off */
        ck_assert_double_eq_tol(tlsph_fibres_depth(&f, tb.X + 3 * f.particle[f.start[j] + 1]),
                                0.1, 1e-15);
    }
    tlsph_fibres_release(&f);
}
END_TEST

/* Tolerance: every particle moved 1e-9 S along its ray's tangent (accepted,
 * the same 640 fibres); one particle moved 1e-4 S (it leaves its ray: a
 * fibre of one and one of two, refused as not stacked, bad naming one of
 * that ray's particles); the shells with their own counts (124, 128, 132:
 * a conforming cylinder's rings) refused; a particle on the axis refused as
 * bad input, naming it; zero direction refused. */
START_TEST(unstacked_shells_are_refused)
{
    static struct tube tb;
    make_tube(&tb, NULL);
    for (size_t q = 0; q < NP; q++) {
        const int p = tb.tag[q];
        double X[3], t[3];
        point(p % NR, (p / NR) % NA, NA, p / (NR * NA), X, t);
        for (int d = 0; d < 3; d++)
            tb.X[3 * q + d] = X[d] + 1e-9 * S * t[d];
    }
    struct tlsph_fibres f;
    size_t bad = 0;
    ck_assert_int_eq(tlsph_fibres_build_radial(&f, tb.X, tb.index, NP, S, B, A, &bad),
                     TLSPH_FIBRE_OK);
    ck_assert_uint_eq(f.n, NA * NZ);
    tlsph_fibres_release(&f);
    /* tag 3 * 40 + 1: layer 0, ray 40, middle shell */
    size_t moved = NP;
    for (size_t q = 0; q < NP; q++)
        if (tb.tag[q] == 3 * 40 + 1)
            moved = q;
    double X[3], t[3];
    point(1, 40, NA, 0, X, t);
    for (int d = 0; d < 3; d++)
        tb.X[3 * moved + d] = X[d] + 1e-4 * S * t[d];
    ck_assert_int_eq(tlsph_fibres_build_radial(&f, tb.X, tb.index, NP, S, B, A, &bad),
                     TLSPH_FIBRE_NOT_STACKED);
    ck_assert_int_eq(tb.tag[bad] / NR, 40);
    ck_assert_uint_eq(f.n, 0);
    const int counts[NR] = {124, 128, 132};
    make_tube(&tb, counts);
    ck_assert_int_eq(tlsph_fibres_build_radial(&f, tb.X, tb.index, NP, S, B, A, &bad),
                     TLSPH_FIBRE_NOT_STACKED);
    make_tube(&tb, NULL);
    memcpy(tb.X + 3 * 17, B, sizeof B);
    ck_assert_int_eq(tlsph_fibres_build_radial(&f, tb.X, tb.index, NP, S, B, A, &bad),
                     TLSPH_FIBRE_BAD_INPUT);
    ck_assert_uint_eq(bad, 17);
    const double zero[3] = {0, 0, 0};
    ck_assert_int_eq(tlsph_fibres_build_radial(&f, tb.X, tb.index, NP, S, B, zero, &bad),
                     TLSPH_FIBRE_BAD_INPUT);
}
END_TEST

/* Eq. 20 on the shell, from the tip at fibre C0 = (layer 2, ray 10) with R =
 * 1.5 S = 7.5 mm and the fan +-60 degrees.  The neighbours in the tangent
 * plane: hoop 2 pi 0.1 / 128 = 4.909 mm (chord 4.909 mm cos(pi/256) in the
 * plane at the tip), axial 5 mm, diagonal 7.007 mm: 8 within R, the next
 * ring (9.8 mm) out; so tlsph_fibres_within gives 9 with the tip's own.
 *  - V1 along the hoop tangent: the fibre ahead (ray 11) at D = 0.3 beats
 *    the diagonals (rays 11, layers 1 and 3, at 45.5 degrees) at D = 0.2;
 *    with only the diagonals damaged the lower index (layer 1) wins; with
 *    only the one behind (ray 9) or the axial ones (90 degrees) none.
 *  - V1 along the axis: the axial fibre ahead (layer 3, ray 10).
 *  - tlsph_fibres_local of C_ahead - C0 at C0: (4.909 mm cos(pi/256)... the
 *    chord's tangent part, sin(2 pi/128) r_c with r_c the centres' radius
 *    0.1 m), 0 along the axis (1e-15). */
START_TEST(the_fan_in_the_tangent_plane)
{
    static struct tube tb;
    make_tube(&tb, NULL);
    struct tlsph_fibres f;
    ck_assert_int_eq(tlsph_fibres_build_radial(&f, tb.X, tb.index, NP, S, B, A, NULL),
                     TLSPH_FIBRE_OK);
    const long c0 = fibre_of(&f, &tb, (2 * NA + 10) * NR), ahead = fibre_of(&f, &tb, (2 * NA + 11) * NR),
               behind = fibre_of(&f, &tb, (2 * NA + 9) * NR), up = fibre_of(&f, &tb, (3 * NA + 10) * NR),
               down = fibre_of(&f, &tb, (1 * NA + 10) * NR), diag_up = fibre_of(&f, &tb, (3 * NA + 11) * NR),
               diag_down = fibre_of(&f, &tb, (1 * NA + 11) * NR);
    ck_assert(c0 >= 0 && ahead >= 0 && behind >= 0 && up >= 0 && down >= 0 && diag_up >= 0 &&
              diag_down >= 0);
    ck_assert_uint_eq(tlsph_fibres_within(&f, f.centre[c0], 1.5 * S, NULL, 0), 9);
    double d[3], v[2];
    for (int c = 0; c < 3; c++)
        d[c] = f.centre[ahead][c] - f.centre[c0][c];
    tlsph_fibres_local(&f, f.centre[c0], d, v);
    ck_assert_double_eq_tol(v[0], 0.1 * sin(2.0 * M_PI / NA), 1e-15);
    ck_assert_double_eq_tol(v[1], 0.0, 1e-15);
    static double D[NP];
    struct tlsph_tip_search q = {.radius = 1.5 * S, .theta_c = 2.0 * M_PI / 3.0, .D_c = 0.1};
    double t[3], X[3];
    point(1, 10, NA, 2, X, t);
    memcpy(q.tip, f.centre[c0], sizeof q.tip);
    memcpy(q.direction, t, sizeof q.direction);
#define DAMAGE(j, val)                                                                          \
    for (size_t p_ = f.start[j]; p_ < f.start[(j) + 1]; p_++)                                  \
        D[f.particle[p_]] = (val) / NR;
    DAMAGE(ahead, 0.3);
    DAMAGE(diag_up, 0.2);
    DAMAGE(diag_down, 0.2);
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, D, &q), ahead);
    DAMAGE(ahead, 0.0);
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, D, &q), diag_down < diag_up ? diag_down : diag_up);
    DAMAGE(diag_up, 0.0);
    DAMAGE(diag_down, 0.0);
    DAMAGE(behind, 0.5);
    DAMAGE(up, 0.5);
    DAMAGE(down, 0.5);
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, D, &q), -1);
    memcpy(q.direction, A, sizeof q.direction); /* an axial crack: up is ahead */
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, D, &q), up);
#undef DAMAGE
    tlsph_fibres_release(&f);
}
END_TEST

/* The wall of the test below as a conforming tube; key: extra body keys. */
static struct tlsph_model *conforming_tube(const char *key)
{
    char json[1024];
    snprintf(json, sizeof json,
             "{\"dimension\":3,\"time\":{\"end\":1e-6},\"materials\":{\"steel\":{"
             "\"density\":7830,\"youngs_modulus\":2e11,\"poisson_ratio\":0.3}},\"bodies\":[{"
             "\"name\":\"wall\",\"material\":\"steel\",\"spacing\":0.013333333333333333,"
             "\"placement\":\"conforming\",\"geometry\":{\"difference\":[{\"cylinder\":{"
             "\"base\":[0,0,0],\"axis\":[0,0,1],\"radius\":0.246,\"length\":0.17}},"
             "{\"cylinder\":{\"base\":[0,0,-0.01],\"axis\":[0,0,1],\"radius\":0.206,"
             "\"length\":0.19}}]}%s}]}",
             key);
    return build_model(json);
}

/* A conforming tube (the capped cylinder's wall of paper 003 §6.4 at 1/4 of
 * its length): outer radius 0.246 m, inner 0.206 m, length 0.17 m, spacing
 * 0.04/3 m, "thickness_axis": "radial": round(0.246/S) = 18 shells of t =
 * 0.01367 m, the three at 0.2118, 0.2255, 0.2392 m inside the wall; every ring
 * the outer shell's 4 round(2 pi 0.2392 / 4 S) = 112; round(0.17/S) = 13
 * layers: 13 x 112 = 1456 fibres of three, ascending in radius.  Without the
 * key the same tube builds no fibres (and its shells hold 100, 108, 112:
 * no stacks). */
START_TEST(a_conforming_tube_has_radial_fibres)
{
    struct tlsph_model *m = conforming_tube(",\"thickness_axis\":\"radial\"");
    ck_assert_ptr_nonnull(m->fibres);
    const struct tlsph_fibres *f = &m->fibres[0];
    ck_assert_int_eq(f->axis, TLSPH_FIBRE_RADIAL);
    ck_assert_uint_eq(m->p.n, 3 * 1456);
    ck_assert_uint_eq(f->n, 1456);
    const double r[3] = {15.5, 16.5, 17.5};
    for (size_t k = 0; k < f->n; k++) {
        ck_assert_uint_eq(f->start[k + 1] - f->start[k], 3);
        for (size_t p = f->start[k]; p < f->start[k + 1]; p++)
            ck_assert_double_eq_tol(tlsph_fibres_depth(f, m->p.X + 3 * f->particle[p]),
                                    r[p - f->start[k]] * 0.246 / 18.0, 1e-12);
    }
    tlsph_model_free(m);
    m = conforming_tube("");
    ck_assert_ptr_null(m->fibres);
    ck_assert_uint_eq(m->p.n, 13 * (100 + 108 + 112));
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("fibre_radial", 60, a_tube_stacks_along_its_radius, unstacked_shells_are_refused,
                 the_fan_in_the_tangent_plane, a_conforming_tube_has_radial_fibres)
