/* Neighbour search: the cell-list CSR pairs equal a brute-force O(n^2) search
 * exactly (same pair set) for a jittered cloud with varying smoothing lengths
 * and two bodies; the list is symmetric and never crosses bodies. */
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

TLSPH_CHECK_MAIN("neighbors", 60, matches_brute_force, cell_order_is_permutation)
