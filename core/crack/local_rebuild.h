/* The reference pairs and correction matrices around a split, rebuilt locally
 * (paper 003 §3.2-3.3: after the old tip fibre is split, the pairs whose sight
 * line crosses the crack surface are cut and the supports around the tip
 * change).  Used by crack/split.h; split in two so that everything that can
 * fail (plan) happens before anything is changed (commit).
 *
 * The view.  A split of k particles of body b appends their second halves at
 * the end of b's range, at = body_end[b] (old), so the new index of an old
 * particle i is i below at and i + k from at; half 1 of parent[s] keeps the
 * parent's index at the position X1[s], half 2 is particle at + s at X2[s].
 *
 * Affected rows.  The particles of body b whose reference position lies
 * within 2 h_max + |X1 - X_parent| of a parent, or within 2 h_max of the
 * bounding box of a facet added to the crack surface since first_new_facet,
 * found by a breadth-first walk over the old pairs from the parents (the
 * region is a ball around the tip minus the crack behind it, which the pairs
 * ahead of the tip keep connected), plus the k second halves.  h_max is the
 * largest smoothing length of the body.  Every pair that can change is
 * between two affected rows: a pair within reach of a moved or new particle
 * has both ends within 2 h_max + |delta| of it, a pair cut by a new facet has
 * both ends within h_i + h_j <= 2 h_max of the crossing point.  The plan
 * checks this (an affected row may not gain or lose a partner outside the
 * set) and refuses the split otherwise.
 *
 * A row's pairs.  The partners j of an affected row a: the same body, |X_j -
 * X_a| < h_a + h_j (the reference search's test, sph/neighbors.c) and, when a
 * crack surface is given, a sight line X_a - X_j that no facet blocks
 * (crack/crack_surface.h; the surface is in the reference configuration).
 * The candidates are a's old partners and the affected set, so a row costs
 * its old pairs plus the affected count; rows are listed by ascending
 * index.  Unaffected rows keep their pairs, order and dw, w.
 *
 * Cost.  Computation: the affected rows (tens to a few hundred particles per
 * split of a fibre) times the affected set, plus the facet tests of their
 * candidate pairs.  Data: a new CSR is written each event (O(n + pairs)
 * copies), and h_max is a scan of the body; both are memory passes at the
 * rate of a copy, once per split event, not per step.
 *
 * Correction.  The committed rows get dw, w and L_i^-1 from the kernel and
 * the safe inverse (sph/correction.h, the same arithmetic as at setup);
 * deficient_supports and isolated are corrected by the rows' status before
 * and after, max_L_condition keeps the largest seen.  With p.F_carry (crack
 * growth) each row's F is then carried (crack/split_carry.h: p.Linv becomes
 * L_i^-1 G_i).  Their P_tilde = P Linv^T is refolded with the new p.Linv (P =
 * sigma cof F, the last evaluation's stress), so the next step's first
 * energy half sees the new supports. */
#ifndef TLSPH_CRACK_LOCAL_REBUILD_H
#define TLSPH_CRACK_LOCAL_REBUILD_H

#include <stddef.h>
#include <stdint.h>

#include "crack/crack_surface.h"
#include "run/model.h"
#include "util/errors.h"

struct tlsph_rebuild_view {
    const struct tlsph_model *m; /* before the split */
    size_t body;                 /* the body the parents belong to */
    size_t k;                    /* particles split */
    const size_t *parent;        /* [k] their (old) indices, distinct, in body */
    const double *X1, *X2;       /* [3k] reference positions of the halves, m */
};

/* What the commit installs: the new CSR and the affected rows. */
struct tlsph_rebuild_plan {
    int64_t *start; /* [n + k + 1] */
    int32_t *j;     /* [npairs] */
    double *dw, *w; /* [npairs]; w only when the model has pairs.w */
    size_t npairs;
    size_t k;       /* particles added */
    size_t *rows;   /* affected rows, new indices, ascending [nrows] */
    size_t nrows;
    size_t old_deficient, old_isolated; /* among the affected rows before */
};

/* Plans the rebuild; nothing of the model is changed.  0, or -1 with err
 * (out of memory, or a pair outside the affected set would change: see
 * above) and nothing allocated.  cs may be NULL (no crack surface). */
int tlsph_rebuild_plan(const struct tlsph_rebuild_view *v, const struct tlsph_crack_surface *cs,
                       size_t first_new_facet, struct tlsph_rebuild_plan *plan,
                       struct tlsph_errors *err);

/* Installs the plan's pairs into m (whose particles are already those after
 * the split: n + k, halves filled) and recomputes dw, w and L_i^-1 of the
 * affected rows; takes over the plan's arrays except rows (free with
 * tlsph_rebuild_plan_free).  Cannot fail. */
void tlsph_rebuild_commit(struct tlsph_model *m, struct tlsph_rebuild_plan *plan);

void tlsph_rebuild_plan_free(struct tlsph_rebuild_plan *plan);

#endif
