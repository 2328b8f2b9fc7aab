/* Paper 003's 3-D visibility condition (§3.3, eqs. 33-42) and the crack
 * surface's cell index.
 *
 * References: hand-placed particles against the facet T = (0,0,0), (1,0,0),
 * (0,1,0) in the plane z = 0, one case per scenario of the paper's Fig. 4 and
 * of its three cases (parallel, in the plane, crossing), each with the answer
 * worked out by hand in its comment; the answer must not change under a rigid
 * motion and a change of units (tolerances relative to the geometry); on
 * random configurations away from the facet's boundary, the answer equals an
 * independent test (solve A + lambda (B - A) = T1 + u e1 + v e2 by Cramer's
 * rule: blocked iff 0 <= lambda <= 1, u, v >= 0, u + v <= 1); the cell index
 * answers exactly as a test against every facet, and its cost per query does
 * not grow with facets far away. */
#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "crack/crack_surface.h"
#include "crack/visibility.h"
#include "support/check_main.h"
#include "util/mat3.h"

static const double T0[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

struct sight_case {
    const char *what;
    double A[3], B[3];
    enum tlsph_sight expect;
};

static const struct sight_case cases[] = {
    /* case 3, Fig. 4: P inside, outside, on a side, at a corner */
    {"crosses inside", {0.2, 0.2, 1}, {0.2, 0.2, -1}, TLSPH_SIGHT_INSIDE},
    {"crosses inside, oblique", {0.1, 0.1, 1}, {0.5, 0.3, -1}, TLSPH_SIGHT_INSIDE}, /* P = (0.3, 0.2) */
    {"crosses outside", {0.8, 0.8, 1}, {0.8, 0.8, -1}, TLSPH_SIGHT_OUTSIDE},         /* u + v = 1.6 */
    {"crosses outside, below y = 0", {0.5, -0.1, 1}, {0.5, -0.1, -1}, TLSPH_SIGHT_OUTSIDE},
    {"crosses on the side y = 0", {0.5, 0, 1}, {0.5, 0, -1}, TLSPH_SIGHT_ON_SIDE},
    {"crosses on the hypotenuse", {0.5, 0.5, 1}, {0.5, 0.5, -1}, TLSPH_SIGHT_ON_SIDE},
    {"crosses at the corner (1,0,0)", {1, 0, 1}, {1, 0, -1}, TLSPH_SIGHT_ON_SIDE},
    {"crosses 1e-9 outside the side", {0.5, -1e-9, 1}, {0.5, -1e-9, -1}, TLSPH_SIGHT_OUTSIDE},
    {"crosses 1e-9 inside the side", {0.5, 1e-9, 1}, {0.5, 1e-9, -1}, TLSPH_SIGHT_INSIDE},
    {"ends on the facet (lambda = 1)", {0.2, 0.2, 1}, {0.2, 0.2, 0}, TLSPH_SIGHT_INSIDE},
    {"starts on the facet (lambda = 0)", {0.2, 0.2, 0}, {0.2, 0.2, 1}, TLSPH_SIGHT_INSIDE},
    {"stops short of the plane", {0.2, 0.2, 1}, {0.2, 0.2, 0.5}, TLSPH_SIGHT_SHORT},        /* lambda = 2 */
    {"plane behind A", {0.2, 0.2, 1}, {0.2, 0.2, 2}, TLSPH_SIGHT_SHORT},                   /* lambda = -1 */
    /* case 1 (eq. 34): parallel, off the plane */
    {"parallel above the facet", {0.2, 0.2, 1}, {0.5, 0.1, 1}, TLSPH_SIGHT_PARALLEL},
    /* case 2 (eq. 35): in the plane */
    {"in the plane, across the hypotenuse", {0.2, 0.2, 0}, {2, 2, 0}, TLSPH_SIGHT_COPLANAR_BLOCKED},
    {"in the plane, across two sides", {-1, 0.5, 0}, {2, 0.5, 0}, TLSPH_SIGHT_COPLANAR_BLOCKED},
    {"in the plane, outside", {2, 2, 0}, {3, 2, 0}, TLSPH_SIGHT_COPLANAR_CLEAR},
    {"in the plane, strictly inside", {0.1, 0.1, 0}, {0.2, 0.1, 0}, TLSPH_SIGHT_COPLANAR_CLEAR},
    {"in the plane, along a side", {-1, 0, 0}, {0.5, 0, 0}, TLSPH_SIGHT_COPLANAR_BLOCKED},
    {"in the plane, on a side's line beyond it", {2, 0, 0}, {3, 0, 0}, TLSPH_SIGHT_COPLANAR_CLEAR},
    {"in the plane, ending on a corner", {0, 2, 0}, {0, 1, 0}, TLSPH_SIGHT_COPLANAR_BLOCKED},
};
#define NCASES (sizeof cases / sizeof *cases)

START_TEST(figure_4_cases)
{
    for (size_t k = 0; k < NCASES; k++) {
        const enum tlsph_sight s = tlsph_sight_through_facet(cases[k].A, cases[k].B, T0);
        ck_assert_msg(s == cases[k].expect, "%s: got %d, want %d", cases[k].what, s, cases[k].expect);
        /* the sight line is symmetric: B sees A iff A sees B */
        const enum tlsph_sight r = tlsph_sight_through_facet(cases[k].B, cases[k].A, T0);
        ck_assert_msg(tlsph_sight_blocked(r) == tlsph_sight_blocked(s), "%s reversed", cases[k].what);
    }
    const double flat[3][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    ck_assert_int_eq(tlsph_sight_through_facet(cases[0].A, cases[0].B, flat), TLSPH_SIGHT_NO_FACET);
}
END_TEST

/* x -> s Q x + t with Q a rotation (Rodrigues) */
static void rigid_scaled(const double Q[9], double s, const double t[3], const double x[3], double y[3])
{
    for (int r = 0; r < 3; r++)
        y[r] = s * (Q[3 * r] * x[0] + Q[3 * r + 1] * x[1] + Q[3 * r + 2] * x[2]) + t[r];
}

static void rotation(const double axis[3], double angle, double Q[9])
{
    const double n = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    const double k[3] = {axis[0] / n, axis[1] / n, axis[2] / n}, c = cos(angle), s = sin(angle);
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++)
            Q[3 * r + q] = (r == q ? c : 0) + (1 - c) * k[r] * k[q];
    Q[1] -= s * k[2];
    Q[2] += s * k[1];
    Q[3] += s * k[2];
    Q[5] -= s * k[0];
    Q[6] -= s * k[1];
    Q[7] += s * k[0];
}

START_TEST(frame_and_unit_independent)
{
    const double scales[] = {1e-3, 1, 1e3}; /* mm-sized to km-sized pictures */
    const double axis[3] = {0.3, -0.8, 0.5};
    for (size_t si = 0; si < 3; si++) {
        double Q[9];
        rotation(axis, 0.7 + si, Q);
        const double t[3] = {0.37 * scales[si], -1.3 * scales[si], 2.1 * scales[si]};
        double T[3][3];
        for (int v = 0; v < 3; v++)
            rigid_scaled(Q, scales[si], t, T0[v], T[v]);
        for (size_t k = 0; k < NCASES; k++) {
            double A[3], B[3];
            rigid_scaled(Q, scales[si], t, cases[k].A, A);
            rigid_scaled(Q, scales[si], t, cases[k].B, B);
            const enum tlsph_sight s = tlsph_sight_through_facet(A, B, T);
            ck_assert_msg(s == cases[k].expect, "%s at scale %g: got %d, want %d", cases[k].what, scales[si], s,
                          cases[k].expect);
        }
    }
}
END_TEST

static double urand(void)
{
    return rand() / (double)RAND_MAX;
}

/* The independent test: Cramer's rule on [ -Delta | e1 | e2 ] (lambda, u, v) = A - T1.
 * Returns the smallest distance of (lambda, u, v) from the boundary of the
 * blocked set, so the caller can skip configurations within round-off of it. */
static bool cramer_blocked(const double A[3], const double B[3], const double T[3][3], double *margin)
{
    double M[9], Mi[9], rhs[3], sol[3];
    for (int r = 0; r < 3; r++) {
        M[3 * r] = A[r] - B[r];
        M[3 * r + 1] = T[1][r] - T[0][r];
        M[3 * r + 2] = T[2][r] - T[0][r];
        rhs[r] = A[r] - T[0][r];
    }
    if (fabs(mat3_inverse(M, Mi)) < 1e-6) {
        *margin = 0;
        return false;
    }
    for (int r = 0; r < 3; r++)
        sol[r] = Mi[3 * r] * rhs[0] + Mi[3 * r + 1] * rhs[1] + Mi[3 * r + 2] * rhs[2];
    const double l = sol[0], u = sol[1], v = sol[2];
    *margin = fmin(fmin(fmin(fabs(l), fabs(1 - l)), fmin(fabs(u), fabs(v))), fabs(1 - u - v));
    return l >= 0 && l <= 1 && u >= 0 && v >= 0 && u + v <= 1;
}

START_TEST(agrees_with_cramer)
{
    srand(20261126);
    int blocked = 0, compared = 0;
    for (int n = 0; n < 20000; n++) {
        double A[3], B[3], T[3][3];
        for (int c = 0; c < 3; c++) {
            A[c] = 2 * urand() - 1;
            B[c] = 2 * urand() - 1;
            for (int v = 0; v < 3; v++)
                T[v][c] = 2 * urand() - 1;
        }
        double margin;
        const bool want = cramer_blocked(A, B, T, &margin);
        if (margin < 1e-6)
            continue;
        const bool got = tlsph_sight_blocked(tlsph_sight_through_facet(A, B, T));
        ck_assert_msg(got == want, "configuration %d: visibility %d, Cramer %d", n, got, want);
        blocked += want;
        compared++;
    }
    /* both answers must occur often, or the comparison proves little */
    ck_assert_int_gt(compared, 19000);
    ck_assert_int_gt(blocked, 1000);
    ck_assert_int_gt(compared - blocked, 1000);
}
END_TEST

/* A through-thickness crack in the plane x = 0 of a plate 0 <= z <= t: facets
 * joining fibre ends at y = 0, a, 2a, ... up to the crack length nseg a (paper 003
 * Fig. 2(b)), two per segment of front. */
static void add_crack(struct tlsph_crack_surface *s, double a, int nseg, double t, double y0)
{
    for (int m = 0; m < nseg; m++) {
        const double y = y0 + m * a;
        const double q[4][3] = {{0, y, 0}, {0, y + a, 0}, {0, y + a, t}, {0, y, t}};
        const double f1[3][3] = {{q[0][0], q[0][1], q[0][2]}, {q[1][0], q[1][1], q[1][2]}, {q[2][0], q[2][1], q[2][2]}};
        const double f2[3][3] = {{q[0][0], q[0][1], q[0][2]}, {q[2][0], q[2][1], q[2][2]}, {q[3][0], q[3][1], q[3][2]}};
        ck_assert_int_eq(tlsph_crack_surface_add(s, f1), TLSPH_CRACK_OK);
        ck_assert_int_eq(tlsph_crack_surface_add(s, f2), TLSPH_CRACK_OK);
    }
}

START_TEST(cell_index_matches_every_facet)
{
    /* particles of spacing h on both sides of the crack plane, offset by
     * +-delta as splitting places them (eqs. 25-26), three layers through t */
    const double h = 1e-3, t = 2 * h, delta = 1e-3 * h, c = 10 * h; /* the front at y = c */
    struct tlsph_crack_surface s;
    ck_assert_int_eq(tlsph_crack_surface_init(&s, 2 * h), TLSPH_CRACK_OK);
    add_crack(&s, h, 10, t, 0);
    enum { NX = 6, NY = 16, NZ = 3 };
    static double X[NX * NY * NZ][3];
    size_t n = 0;
    for (int i = 0; i < NX; i++)
        for (int j = 0; j < NY; j++)
            for (int k = 0; k < NZ; k++, n++) {
                X[n][0] = (i - NX / 2 + 0.5) * h + (i < NX / 2 ? -delta : delta);
                X[n][1] = (j - 2) * h;
                X[n][2] = k * h;
            }
    int cut = 0, kept_across = 0;
    for (size_t p = 0; p < n; p++)
        for (size_t q = p + 1; q < n; q++) {
            double d2 = 0;
            for (int a = 0; a < 3; a++)
                d2 += (X[p][a] - X[q][a]) * (X[p][a] - X[q][a]);
            if (d2 > 4 * h * h * 1.0001) /* pairs within a support of 2 h */
                continue;
            bool brute = false;
            for (size_t f = 0; f < s.nfacets && !brute; f++)
                brute = tlsph_sight_blocked(tlsph_sight_through_facet(X[p], X[q], (const double(*)[3])s.facet[f]));
            const bool indexed = tlsph_crack_surface_blocks(&s, X[p], X[q], NULL);
            ck_assert_msg(indexed == brute, "pair %zu-%zu: index %d, every facet %d", p, q, indexed, brute);
            /* the reference answer by hand: a pair is cut iff it crosses
             * x = 0 where the segment's y at x = 0 lies in [0, c]: a sight
             * line through the front itself is cut (eq. 42's ">= 0") */
            const bool across = (X[p][0] < 0) != (X[q][0] < 0);
            bool want = false;
            if (across) {
                const double l = -X[p][0] / (X[q][0] - X[p][0]);
                const double y = X[p][1] + l * (X[q][1] - X[p][1]);
                want = y >= 0 && y <= c;
                kept_across += !want;
            }
            ck_assert_msg(brute == want, "pair %zu-%zu: blocked %d, by hand %d", p, q, brute, want);
            cut += want;
        }
    ck_assert_int_gt(cut, 100);
    ck_assert_int_gt(kept_across, 20); /* pairs ahead of the crack tip still interact */
    tlsph_crack_surface_release(&s);
}
END_TEST

START_TEST(cell_index_random)
{
    /* 300 facets of about a cell's size scattered in a box of 10 cells, cells
     * smaller than some facets: every query answers as the test against every
     * facet */
    const double cell = 1e-3;
    struct tlsph_crack_surface s;
    ck_assert_int_eq(tlsph_crack_surface_init(&s, cell), TLSPH_CRACK_OK);
    srand(4711);
    for (int f = 0; f < 300; f++) {
        double T[3][3], c[3];
        for (int a = 0; a < 3; a++)
            c[a] = (10 * urand() - 5) * cell;
        for (int v = 0; v < 3; v++)
            for (int a = 0; a < 3; a++)
                T[v][a] = c[a] + (3 * urand() - 1.5) * cell;
        ck_assert_int_eq(tlsph_crack_surface_add(&s, T), TLSPH_CRACK_OK);
    }
    int blocked = 0;
    for (int n = 0; n < 20000; n++) {
        double A[3], B[3];
        for (int a = 0; a < 3; a++) {
            A[a] = (10 * urand() - 5) * cell;
            B[a] = A[a] + (4 * urand() - 2) * cell;
        }
        bool brute = false;
        for (size_t f = 0; f < s.nfacets && !brute; f++)
            brute = tlsph_sight_blocked(tlsph_sight_through_facet(A, B, (const double(*)[3])s.facet[f]));
        ck_assert_msg(tlsph_crack_surface_blocks(&s, A, B, NULL) == brute, "segment %d", n);
        blocked += brute;
    }
    ck_assert_int_gt(blocked, 2000);
    ck_assert_int_lt(blocked, 18000);
    tlsph_crack_surface_release(&s);
}
END_TEST

START_TEST(cost_follows_the_local_crack)
{
    const double h = 1e-3;
    struct tlsph_crack_surface s;
    ck_assert_int_eq(tlsph_crack_surface_init(&s, 2 * h), TLSPH_CRACK_OK);
    add_crack(&s, h, 6, 2 * h, 0);
    const double A[3] = {-0.5 * h, 3.2 * h, h}, B[3] = {0.5 * h, 3.4 * h, h};
    size_t before, after;
    ck_assert(tlsph_crack_surface_blocks(&s, A, B, &before));
    /* a crack 1000 spacings long elsewhere in the body */
    add_crack(&s, h, 1000, 2 * h, 100 * h);
    ck_assert_uint_eq(s.nfacets, 2 * 6 + 2 * 1000);
    ck_assert(tlsph_crack_surface_blocks(&s, A, B, &after));
    ck_assert_uint_eq(after, before);
    ck_assert_uint_le(after, 12); /* the facets of the cells A-B touches, not 2012 */
    /* a segment far from both cracks tests nothing */
    const double C[3] = {50 * h, 50 * h, h}, D[3] = {51 * h, 50 * h, h};
    ck_assert(!tlsph_crack_surface_blocks(&s, C, D, &after));
    ck_assert_uint_eq(after, 0);
    tlsph_crack_surface_release(&s);
}
END_TEST

START_TEST(bad_input)
{
    struct tlsph_crack_surface s;
    ck_assert_int_eq(tlsph_crack_surface_init(&s, 0), TLSPH_CRACK_BAD_INPUT);
    ck_assert_int_eq(tlsph_crack_surface_init(&s, NAN), TLSPH_CRACK_BAD_INPUT);
    ck_assert_int_eq(tlsph_crack_surface_init(&s, 1e-3), TLSPH_CRACK_OK);
    const double nan_facet[3][3] = {{0, 0, 0}, {NAN, 0, 0}, {0, 1, 0}};
    const double far_facet[3][3] = {{1e4, 0, 0}, {1e4 + 1, 0, 0}, {1e4, 1, 0}}; /* 1e7 cells away */
    ck_assert_int_eq(tlsph_crack_surface_add(&s, nan_facet), TLSPH_CRACK_BAD_INPUT);
    ck_assert_int_eq(tlsph_crack_surface_add(&s, far_facet), TLSPH_CRACK_OUT_OF_GRID);
    ck_assert_uint_eq(s.nfacets, 0); /* unchanged by the refusals */
    const double A[3] = {0, 0, 1}, B[3] = {0, 0, -1};
    ck_assert(!tlsph_crack_surface_blocks(&s, A, B, NULL));
    tlsph_crack_surface_release(&s);
}
END_TEST

TLSPH_CHECK_MAIN("visibility", 0, figure_4_cases, frame_and_unit_independent, agrees_with_cramer,
                 cell_index_matches_every_facet, cell_index_random, cost_follows_the_local_crack, bad_input)
