/* Kinematics: deformation gradient and its rate (paper 000 eqs. 26-27) with the
 * corrected kernel gradient, one gather pass over the reference pairs. */
#ifndef TLSPH_KINEMATICS_H
#define TLSPH_KINEMATICS_H

#include "model.h"

/* F_i    = I + [sum_j V_j (u_j - u_i) (x) grad W_i(X_ij)] L_i^-1   (positions x)
 * Fdot_i =     [sum_j V_j (v_j - v_i) (x) grad W_i(X_ij)] L_i^-1   (velocities v)
 * and the first half of the trapezoidal internal-energy update,
 * e_i += dt/2 / rho0 * P_i(old) : Fdot_i, using P_tilde of the previous step
 * (P:Fdot = P_tilde : G_dot, so L_i never has to be re-applied).
 *
 * With damage (damage-aware treatment, paper 000 eqs. 33-34) neighbour j
 * transmits (1 - D_j) of the velocity difference, and F integrates exactly
 * those transmitted increments: F_i = I + [G_i - C_i] L_i^-1 with C_i the
 * accumulated untransmitted part (model.h: crack_gradient).  A failed particle
 * (D = 1) gets Fdot = 0 and no update. */
void tlsph_kinematics(struct tlsph_model *m, double dt);

#endif
