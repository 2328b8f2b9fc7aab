/* Pair forces: the PK1 stress force of paper 000 eq. 31 plus, when the scene
 * enables them, hourglass control and artificial viscosity, in one gather pass.
 *
 *   f_i = sum_j V_i V_j (P_i L_i^-T + P_j L_j^-T) grad W_i(X_ij)
 *
 * Each particle sums only its own pairs (no atomics); since the pair list is
 * symmetric and grad W_i(X_ij) = -grad W_j(X_ji), f_ij = -f_ji to round-off and
 * linear momentum is conserved exactly. */
#ifndef TLSPH_FORCES_H
#define TLSPH_FORCES_H

#include "run/model.h"

struct tlsph_force_power {
    double hourglass; /* sum_i (f_hg,i(old) + f_hg,i(new))/2 . v_i, W */
    double viscous;   /* the same for the viscous forces, W */
};

/* Overwrites p.f and the stored hourglass/viscous forces.  Returns the power of
 * the optional forces at the current (half-step) velocities, averaged over the
 * previous and the new force (trapezoidal, like the kicks). */
struct tlsph_force_power tlsph_forces(struct tlsph_model *m);

/* tlsph_forces for the given rows of one body only (indices into the
 * particles, all in body's range): overwrites their p.f and stored hourglass
 * and viscous forces with the sums the full pass would give them, bit for bit;
 * books no power.  For a local change of the pairs (crack/split_forces.h). */
void tlsph_forces_rows(struct tlsph_model *m, size_t body, const size_t *rows, size_t nrows);

#endif
