/* The contact phase's and the rigid bodies' per-particle state across a split
 * (crack/split.h): their arrays of n entries become arrays of n + k with the
 * split's index map (i -> i below `at`, i -> i + k from it), their candidate
 * lists keep their entries with the indices mapped, and the halves start with
 * no candidate.  A search is due at the next evaluation: the parents' and
 * halves' positions at the last search are set to infinity, so the "moved
 * more than the skin" test of both searches fires.  Forces of the last
 * evaluation (contact f_old, rigid f and f_old, for the trapezoidal work) are
 * shared by mass like the particle force; touch flags and reach factors are
 * the parent's.
 *
 * Limit: the same-body contact test is geometric (contact/state.h: |X_ij| <
 * h_i + h_j means a continuum pair), so the two halves of a split, 2 delta
 * apart, never touch each other: crack faces made by splitting do not close
 * on each other by contact yet.
 *
 * Prepare allocates everything (nothing changed; -1 out of memory); commit
 * cannot fail and frees what it replaced.  Cost: O(n) copies per split. */
#ifndef TLSPH_CRACK_SPLIT_STATE_H
#define TLSPH_CRACK_SPLIT_STATE_H

#include <stddef.h>

#include "crack/fibre.h"
#include "run/model.h"

#define TLSPH_SPLIT_STATE_MAX 12

struct tlsph_split_state {
    void *fresh[TLSPH_SPLIT_STATE_MAX]; /* the new arrays, in the order of the table */
    size_t count;
    int64_t *contact_start;             /* [n + k + 1] */
    struct tlsph_fibres fibres;          /* the split body's fibres after it (crack/fibre.h) */
    size_t body;
};

/* body: the body of the parents. */
int tlsph_split_state_prepare(struct tlsph_model *m, size_t body, size_t k,
                              struct tlsph_split_state *st);

/* n: the particle count before the split; share: m1/m of the halves. */
void tlsph_split_state_commit(struct tlsph_model *m, struct tlsph_split_state *st, size_t n,
                              size_t at, const size_t *parent, size_t k, double share);

/* The fibres (m->fibres) across the split: the split body's halves 2 form new
 * fibres (tlsph_fibres_split_commit), later bodies' indices shift by k.  Call
 * after the halves' X are set (the centres are recomputed from them).  Cannot
 * fail. */
void tlsph_split_state_fibres(struct tlsph_model *m, struct tlsph_split_state *st, size_t at,
                              const size_t *parent, size_t k);

void tlsph_split_state_free(struct tlsph_split_state *st);

#endif
