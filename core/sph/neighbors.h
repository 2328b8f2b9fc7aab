/* Reference-configuration neighbour search.  Built once per run (the reference
 * configuration never changes in TLSPH), so clarity beats speed here; it is
 * still O(n log n): particles are binned into cubic cells of the largest
 * support radius, the cells are sorted by key, and each particle scans the 27
 * (9 in 2-D) adjacent cells.  No dense grid is allocated, so far-apart bodies
 * cost nothing. */
#ifndef TLSPH_NEIGHBORS_H
#define TLSPH_NEIGHBORS_H

#include <stddef.h>
#include <stdint.h>

/* Permutation of 0..n-1 that orders particles by cell key (bodies kept in the
 * given order when body != NULL and bodies are contiguous).  order[k] = old index.
 * Returns 0 or -1 on allocation failure. */
int tlsph_cell_order(const double *X, const int32_t *body, size_t n, double cell_size,
                     size_t *order);

/* CSR pair list: pairs (i, j), i != j, same body, |X_j - X_i| < h_i + h_j
 * (the support radius of the pair kernel, smoothing length (h_i + h_j)/2).
 * *start gets n+1 entries and *nbr start[n] entries (both malloc'ed, owned by
 * the caller).  Returns 0 or -1 on allocation failure. */
int tlsph_build_pairs(const double *X, const double *h, const int32_t *body, size_t n,
                      int64_t **start, int32_t **nbr);

#endif
