/* Reference-configuration neighbour search.  Built once per run (the reference
 * configuration never changes in TLSPH), so clarity beats speed here; it is
 * still O(n log n): each body's particles are binned into cubic cells of the
 * body's largest support diameter (bodies never pair, so each body has its own
 * grid and a fine body beside a coarse one costs no more than alone), the
 * cells are sorted by key, and each particle scans the 27 (9 in 2-D) adjacent
 * cells.  No dense grid is allocated, so far-apart bodies cost nothing. */
#ifndef TLSPH_NEIGHBORS_H
#define TLSPH_NEIGHBORS_H

#include <stddef.h>
#include <stdint.h>

/* Permutation of 0..n-1 that orders particles by body (body != NULL: indices
 * 0, 1, ... in increasing order), then by cell of size cell_size, z-major then
 * y then x, then by index.  order[k] = old index.  Returns 0 or -1 on
 * allocation failure. */
int tlsph_cell_order(const double *X, const int32_t *body, size_t n, double cell_size,
                     size_t *order);

/* Is X_j within the support of the pair kernel of i and j, |X_j - X_i| <
 * h_i + h_j?  The one test of the setup's search and of the local rebuild
 * after a split (crack/local_rebuild.c), so that both find the same pairs. */
static inline int tlsph_pair_in_support(const double *Xi, const double *Xj, double hi, double hj)
{
    const double dx = Xj[0] - Xi[0], dy = Xj[1] - Xi[1], dz = Xj[2] - Xi[2];
    const double r2 = dx * dx + dy * dy + dz * dz;
    const double rc = hi + hj;
    return r2 < rc * rc;
}

/* CSR pair list: pairs (i, j), i != j, same body, |X_j - X_i| < h_i + h_j
 * (the support radius of the pair kernel, smoothing length (h_i + h_j)/2).
 * *start gets n+1 entries and *nbr start[n] entries (both malloc'ed, owned by
 * the caller).  Returns 0 or -1 on allocation failure. */
int tlsph_build_pairs(const double *X, const double *h, const int32_t *body, size_t n,
                      int64_t **start, int32_t **nbr);

/* The number of candidate pairs tlsph_build_pairs examines (distances it
 * computes) for the same input: the search's cost, which tests compare with a
 * reference.  SIZE_MAX on allocation failure. */
size_t tlsph_pair_candidates(const double *X, const double *h, const int32_t *body, size_t n);

#endif
