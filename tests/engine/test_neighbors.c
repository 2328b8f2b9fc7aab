/* Neighbour search: the cell-list CSR pairs equal a brute-force O(n^2) search
 * exactly (same pair set) for a jittered cloud with varying smoothing lengths
 * and two bodies; the list is symmetric and never crosses bodies.  Bodies are
 * searched each in its own grid: a body costs the same beside another of 50x
 * its spacing as alone, and bodies far apart along a diagonal still pair
 * correctly. */
#include <check.h>
#include <stdint.h>
#include <stdlib.h>

#include "sph/neighbors.h"
#include "support/check_main.h"

static int has_pair(const int64_t *start, const int32_t *nbr, size_t i, size_t j)
{
    for (int64_t k = start[i]; k < start[i + 1]; k++)
        if ((size_t)nbr[k] == j)
            return 1;
    return 0;
}

START_TEST(matches_brute_force)
{
    const size_t n = 1500;
    double *X = malloc(3 * n * sizeof *X), *h = malloc(n * sizeof *h);
    int32_t *body = malloc(n * sizeof *body);
    ck_assert(X && h && body);
    srand(12345);
    for (size_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++)
            X[3 * i + c] = 0.012 * rand() / (double)RAND_MAX - 0.005;
        h[i] = 0.001 + 0.001 * rand() / (double)RAND_MAX;
        body[i] = i < n / 2 ? 0 : 1;
    }
    int64_t *start;
    int32_t *nbr;
    ck_assert(tlsph_build_pairs(X, h, body, n, &start, &nbr) == 0);
    size_t brute = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++) {
            if (i == j)
                continue;
            const double dx = X[3 * j] - X[3 * i], dy = X[3 * j + 1] - X[3 * i + 1],
                         dz = X[3 * j + 2] - X[3 * i + 2];
            const double rc = h[i] + h[j];
            const int want = body[i] == body[j] && dx * dx + dy * dy + dz * dz < rc * rc;
            brute += (size_t)want;
            ck_assert_msg(want == has_pair(start, nbr, i, j), "pair %zu-%zu: brute %d", i, j, want);
        }
    ck_assert_uint_eq((size_t)start[n], brute);
    ck_assert(brute > 10 * n); /* the test actually exercises pairs */
    free(start);
    free(nbr);
    free(X);
    free(h);
    free(body);
}
END_TEST

START_TEST(cell_order_is_permutation)
{
    const size_t n = 1000;
    double *X = malloc(3 * n * sizeof *X);
    size_t *order = malloc(n * sizeof *order);
    char *seen = calloc(n, 1);
    ck_assert(X && order && seen);
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            X[3 * i + c] = (double)((i * 7919 + (size_t)c * 104729) % 1000) * 1e-3;
    ck_assert(tlsph_cell_order(X, NULL, n, 0.05, order) == 0);
    for (size_t k = 0; k < n; k++) {
        ck_assert(order[k] < n && !seen[order[k]]);
        seen[order[k]] = 1;
    }
    free(X);
    free(order);
    free(seen);
}
END_TEST

/* A simple cubic block of nx^3 points of spacing s from corner c, body index b,
 * smoothing length 1.005 s (support 2.01 s), appended at X + 3 * at. */
static void block(double *X, double *h, int32_t *body, size_t at, int nx, double s,
                  const double c[3], int32_t b)
{
    size_t k = at;
    for (int i = 0; i < nx; i++)
        for (int j = 0; j < nx; j++)
            for (int l = 0; l < nx; l++, k++) {
                X[3 * k] = c[0] + (i + 0.5) * s;
                X[3 * k + 1] = c[1] + (j + 0.5) * s;
                X[3 * k + 2] = c[2] + (l + 0.5) * s;
                h[k] = 1.005 * s;
                body[k] = b;
            }
}

/* Reference: a fine block of 16^3 particles beside a block of 6^3 particles
 * of 50x its spacing: the search examines no more candidate pairs than the
 * fine block alone plus every pair of the coarse block (6^3 (6^3 - 1): the
 * coarse grid's anchoring differs from its own search's, so its count is only
 * bounded).  With one grid of the coarse cell, each fine particle examined
 * every other fine particle (4095 instead of about 180): the validation of
 * such a scene took minutes (issue 13, item 5). */
START_TEST(body_cost_independent_of_other_spacing)
{
    const int nf = 16, nc = 6;
    const size_t n_fine = (size_t)nf * nf * nf, n = n_fine + (size_t)nc * nc * nc;
    const double s = 1e-3, corner_f[3] = {0, 0, 0}, corner_c[3] = {nf * s, 0, 0};
    double *X = malloc(3 * n * sizeof *X), *h = malloc(n * sizeof *h);
    int32_t *body = malloc(n * sizeof *body);
    ck_assert(X && h && body);
    block(X, h, body, 0, nf, s, corner_f, 0);
    block(X, h, body, n_fine, nc, 50 * s, corner_c, 1);
    const size_t both = tlsph_pair_candidates(X, h, body, n);
    const size_t fine = tlsph_pair_candidates(X, h, body, n_fine);
    const size_t n_coarse = n - n_fine;
    ck_assert_msg(both <= fine + n_coarse * (n_coarse - 1),
                  "two bodies examine %zu candidates, the fine block alone %zu", both, fine);
    ck_assert_msg(fine < 200 * n_fine, "%zu candidates for %zu particles", fine, n_fine);
    free(X);
    free(h);
    free(body);
}
END_TEST

/* Two blocks 1e5 m apart along the diagonal (spacing 1 mm: 5e7 cells per axis
 * between them, 1e23 cells in one grid, more than an int64 key holds): every
 * particle still finds exactly its brute-force neighbours. */
START_TEST(far_apart_bodies)
{
    const int nx = 6;
    const size_t nb = (size_t)nx * nx * nx, n = 2 * nb;
    const double s = 1e-3, c0[3] = {0, 0, 0}, c1[3] = {1e5, 1e5, 1e5};
    double *X = malloc(3 * n * sizeof *X), *h = malloc(n * sizeof *h);
    int32_t *body = malloc(n * sizeof *body);
    ck_assert(X && h && body);
    block(X, h, body, 0, nx, s, c0, 0);
    block(X, h, body, nb, nx, s, c1, 1);
    int64_t *start;
    int32_t *nbr;
    ck_assert(tlsph_build_pairs(X, h, body, n, &start, &nbr) == 0);
    for (size_t i = 0; i < n; i++) {
        size_t want = 0;
        for (size_t j = 0; j < n; j++) {
            const double dx = X[3 * j] - X[3 * i], dy = X[3 * j + 1] - X[3 * i + 1],
                         dz = X[3 * j + 2] - X[3 * i + 2], rc = h[i] + h[j];
            if (j != i && body[i] == body[j] && dx * dx + dy * dy + dz * dz < rc * rc) {
                ck_assert_msg(has_pair(start, nbr, i, j), "pair %zu-%zu missing", i, j);
                want++;
            }
        }
        ck_assert_uint_eq((size_t)(start[i + 1] - start[i]), want);
    }
    free(start);
    free(nbr);
    free(X);
    free(h);
    free(body);
}
END_TEST

TLSPH_CHECK_MAIN("neighbors", 60, matches_brute_force, cell_order_is_permutation,
                 body_cost_independent_of_other_spacing, far_apart_bodies)
