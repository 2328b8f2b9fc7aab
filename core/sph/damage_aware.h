/* The damage-aware approximation of paper 000 §3.1, eqs. 33-35: the crack
 * treatment of the paper, and the engine's default.
 *
 * A damaged neighbour j is a particle with a crack through its centre: the
 * part of its volume next to i moves with i, so j transmits only (1 - D_j) of
 * the velocity difference (eq. 33),
 *   Fdot_i = sum_j V_j (1 - D_j) (v_j - v_i) (x) grad W_i(X_ij) L_i^-1,
 * and F integrates exactly those transmitted increments (eq. 34),
 *   F_i = I + sum_j V_j int_0^t (1 - D_j)(v_j - v_i) dt (x) grad W_i(X_ij) L_i^-1.
 * F is computed from positions (kinematics.c), so eq. 34 is F_i = I + [G_i -
 * C_i] L_i^-1 with G_i the plain displacement sum and C_i the accumulated
 * untransmitted part sum_j V_j sum_steps dt D_j (v_j - v_i) (x) grad W_i
 * (p.crack_gradient, model.h).  The force conjugate to eq. 33 is eq. 35,
 *   f_i = sum_j V_i V_j [(1 - D_j) P_i L_i^-T + (1 - D_i) P_j L_j^-T] grad W_i(X_ij),
 * antisymmetric in i, j, so linear momentum stays exact.  The hourglass and
 * viscous forces of a pair act across the crack with the intact fractions of
 * both, (1 - D_i)(1 - D_j).  A failed particle (D = 1) gets Fdot = 0 and
 * neither exerts nor receives a pair force (kinematics.c, forces.c).
 *
 * These are the per-pair pieces; the loops that call them with the
 * treatment as a compile-time constant are in kinematics.c and forces.c, the
 * row in damage_aware.c. */
#ifndef TLSPH_DAMAGE_AWARE_H
#define TLSPH_DAMAGE_AWARE_H

#include "sph/crack_treatment.h"

extern const struct tlsph_crack_model tlsph_crack_damage_aware;

/* Eq. 33 for the pair i, j: dv = v_j - v_i is scaled in place to the part j
 * transmits, (1 - D_j) dv.  The rest moves the two apart by dt D_j dv over
 * the step (the drift moved every particle by dt v): the crack's opening,
 * added to Gc as dt D_j dv (x) g, with g = V_j grad W_i(X_ij). */
static inline __attribute__((always_inline)) void
tlsph_damage_aware_transmit(double dt, double Dj, const double g[3], double dv[3], double Gc[9])
{
    if (Dj > 0.0) {
        const double c = dt * Dj;
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                Gc[3 * a + b] += c * dv[a] * g[b];
        const double w = 1.0 - Dj;
        dv[0] *= w;
        dv[1] *= w;
        dv[2] *= w;
    }
}

/* Eq. 34 at the end of particle i's gather: the untransmitted gradient c_i
 * (p.crack_gradient + 9 i) grows by the step's Gc, and G, the plain sum of
 * V_j (u_j - u_i) (x) grad W_i, loses it, so that F_i = I + G L_i^-1. */
static inline __attribute__((always_inline)) void
tlsph_damage_aware_close(double *restrict ci, const double Gc[9], double G[9])
{
    for (int a = 0; a < 9; a++) {
        ci[a] += Gc[a];
        G[a] -= ci[a];
    }
}

/* Eq. 35: P~_i weighs (1 - D_j), P~_j weighs (1 - D_i). */
static inline __attribute__((always_inline)) struct tlsph_pair_weights
tlsph_damage_aware_force_weights(double Di, double Dj)
{
    return (struct tlsph_pair_weights){
        .wi = 1.0 - Dj, .wj = 1.0 - Di, .stab = (1.0 - Di) * (1.0 - Dj)};
}

#endif
