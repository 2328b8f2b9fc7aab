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

/* The safe inverse of one correction matrix L (symmetric; in 2-D its z row and
 * column are replaced by the identity, in place).  Returns 1 when L was
 * rank-deficient (the pseudo-inverse was used), else 0 with *condition =
 * largest/smallest |eigenvalue|. */
int tlsph_correction_invert(double L[9], int dim, double Linv[9], double *condition);

#define TLSPH_L_RCOND 1e-6

#endif
