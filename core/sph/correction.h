/* Per-pair kernel constants and the correction matrix L_i (paper 000 eqs. 16-17),
 * computed once from the reference configuration. */
#ifndef TLSPH_CORRECTION_H
#define TLSPH_CORRECTION_H

#include "run/model.h"

/* Fills pairs.dw (and pairs.w when non-NULL) from the kernel, then p.Linv from
 * L_i = sum_j V_j (X_j - X_i) (x) grad W_i(X_ij).  A support that leaves L_i
 * rank-deficient or ill-conditioned (smallest/largest eigenvalue below
 * TLSPH_L_RCOND) gets the pseudo-inverse restricted to the well-resolved
 * directions; such particles are counted in m->deficient_supports, and
 * particles with no neighbour at all in m->isolated. */
void tlsph_correction_build(struct tlsph_model *m);

/* The same for row i alone (the local rebuild after a split, crack/split.h):
 * pairs.dw (and w) of i's pairs from the kernel, then Linv_i.  Returns 1 when
 * L_i needed the safe inverse, else 0 with *condition. */
int tlsph_correction_row(struct tlsph_model *m, size_t i, double *condition);
/* What tlsph_correction_row would return for row i as the pairs stand (dw as
 * stored), writing nothing: the bookkeeping of a row before it is rebuilt. */
int tlsph_correction_row_status(const struct tlsph_model *m, size_t i, double *condition);

/* The safe inverse of one correction matrix L (symmetric; in 2-D its z row and
 * column are replaced by the identity, in place).  Returns 1 when L was
 * rank-deficient (the pseudo-inverse was used), else 0 with *condition =
 * largest/smallest |eigenvalue|. */
int tlsph_correction_invert(double L[9], int dim, double Linv[9], double *condition);
/* The same with the relative eigenvalue floor rcond instead of TLSPH_L_RCOND. */
int tlsph_correction_invert_rcond(double L[9], int dim, double Linv[9], double *condition,
                                  double rcond);
/* tlsph_correction_row with the floor rcond (the rows a crack split rebuilds,
 * crack/local_rebuild.h: TLSPH_L_RCOND_CUT). */
int tlsph_correction_row_rcond(struct tlsph_model *m, size_t i, double *condition, double rcond);

#define TLSPH_L_RCOND 1e-6
/* The floor for rows whose support a crack cut (crack/local_rebuild.c): a
 * support left nearly flat by the cut (the particles beside a crack face and
 * an edge) has an eigenvalue just above 1e-6 of the largest, and its inverse
 * (|L^-1| up to 8e4 in the stiffened plate of docs/crack-growth.md) turns
 * the next displacements' noise into F; below 1e-3 such a direction is
 * treated as unsupported (no gradient read along it), as at setup. */
#define TLSPH_L_RCOND_CUT 1e-3

#endif
