/* The forces at a split, updated on the rows they change only (crack/split.h).
 *
 * The velocity-Verlet step starts with a half kick by the stored force
 * (run/integrate.h), and the step's energy update is conjugate to it: the
 * kick must use the pair forces of the new supports, and the stored hourglass
 * and viscous forces (the trapezoidal power's previous values, sph/forces.h)
 * must be the ones in that kick.  For every field X of p.f, p.f_hourglass and
 * p.f_viscous:
 *
 *   X_i = X_i(stored) - pairs_i(old supports) + pairs_i(new supports)
 *
 * where the pair sums are taken at the current positions and velocities
 * (t_n).  The stored force came from the last evaluation (velocities at
 * t_n - dt/2 in the viscous term; contact, rigid and load forces in p.f), so
 * "rest" = stored - pairs(old) is what the pairs of the new supports do not
 * replace: the other forces plus the viscous force's velocity lag.  A parent's
 * rest is shared with its halves by mass (half 1 the share phi1 / 2 pi, half 2
 * the difference).
 *
 * The rows.  Only a row with a changed pair or a changed partner can change:
 * the rebuild's affected rows A (crack/local_rebuild.h: every pair that changes
 * lies between two of them, and their P_tilde, mass and volume are the only
 * ones that change) and their partners, R = A + partners(A), the same set
 * before and after (the plan refuses a split that would give a row of A a
 * partner outside A or take one).  Every other row's forces stay as stored,
 * which is what the formula gives them (its pair sums are equal before and
 * after), so the cost is the pair sums of R twice, not of the body.  Each row
 * of R gets the full pass's sums bit for bit (tlsph_forces_rows).
 *
 * Momentum: a pair between R and the rest is the same before and after and
 * enters both rows through the stored values; the changed pairs lie inside R
 * and are summed with the same velocities in both rows; so the forces still
 * sum to the stored total (to round-off). */
#ifndef TLSPH_CRACK_SPLIT_FORCES_H
#define TLSPH_CRACK_SPLIT_FORCES_H

#include <stddef.h>

#include "crack/local_rebuild.h"
#include "run/model.h"

struct tlsph_split_forces {
    size_t *rows;               /* R, old indices ascending [nrows], then the k second halves */
    size_t nrows;               /* rows of R before the split */
    size_t k;                   /* particles split */
    double *rest[3];            /* rest of p.f, f_hourglass, f_viscous [3 (nrows + k)]; NULL
                                   for a field the model does not store */
};

/* Before anything changes: R from the plan's affected rows (new indices) and
 * the old pairs, and the rest arrays.  at = the old body_end of the split
 * body.  0, or -1 out of memory (nothing left allocated). */
int tlsph_split_forces_prepare(const struct tlsph_model *m, const struct tlsph_rebuild_plan *plan,
                               size_t at, struct tlsph_split_forces *sf);

/* On the particles before the split (old indices and supports): the rest of
 * every row of R, the parents' shared with their halves (parent[s] is split
 * into shares share, 1 - share).  Overwrites R's stored forces. */
void tlsph_split_forces_rest(struct tlsph_model *m, size_t body, struct tlsph_split_forces *sf,
                             const size_t *parent, double share);

/* After the particles are split and the pairs rebuilt: the pair sums of R on
 * the new supports plus the rest (the halves of parent s at at + s). */
void tlsph_split_forces_finish(struct tlsph_model *m, size_t body, struct tlsph_split_forces *sf,
                               size_t at);

void tlsph_split_forces_free(struct tlsph_split_forces *sf);

#endif
