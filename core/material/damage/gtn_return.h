/* Return mapping of GTN porous plasticity (paper 000 eqs. 46-66), in the
 * logarithmic-strain setting of core/material/material_point.h.
 *
 * The paper's Algorithm 2 freezes the triaxiality and the void fraction over
 * the step and linearises the pressure (eqs. 54-58, 65); the only public
 * implementation iterates its two Newton loops to a tolerance of 0.1, one of
 * them without an iteration cap.  Here the step is the fully implicit
 * (backward-Euler) one, solved to round-off.  With the trial Kirchhoff
 * deviator of von Mises value q_tr (its direction n = 3/2 dev/q_tr does not
 * change in an isotropic return), the unknowns are
 *   dq = equivalent deviatoric plastic strain increment,
 *   dv = tr(dEp), the plastic volume change (void growth),
 *   dM = the matrix plastic strain increment,
 * and the end-of-step state is
 *   tau_q = q_tr - 3G dq,   p = p_EOS(J exp(-(tr Ep_n + dv)), e)   (elastic volume),
 *   W     = tau_q dq - J p dv                 plastic work per reference volume,
 *   T     = T_n + chi/(rho0 C_p) W,
 *   sigma_M = sigma_y(eps_M + dM, dM/dt, T),  the matrix flow stress,
 *   f     = [1 - (1 - f_n) exp(-dv) + N(eps_M, eps_M + dM)] / (1 - k_w omega dq),
 * i.e. matrix incompressibility integrated exactly ((1 - f) exp(tr Ep) is the
 * matrix volume), exact integral N of Chu-Needleman nucleation, and the
 * Nahshon-Hutchinson shear term (omega from the trial deviator) implicit.
 * Three equations close it (x = tau_q/(J sigma_M), y = -p/sigma_M, D = q1 f*):
 *   R1 = x^2 + 2 D cosh(3/2 q2 y) - (1 + D^2) = 0             yield (eq. 48)
 *   R2 = dv Phi_x - dq Phi_y = 0                              normality (eq. 61)
 *   R3 = (1 - f) J sigma_M dM - W = 0                         equal work (eq. 63)
 * with Phi_x = 2x, Phi_y = 3 q1 q2 f* sinh(3/2 q2 y).
 *
 * Method: Newton on (dq, f, dM) (dv follows from f exactly) with the
 * analytic Jacobian, started from the return at frozen hardening and void
 * fraction (a bracketed scalar root), with a backtracking line search on
 * |R|^2 and the iterates kept in 0 <= dq <= q_tr/(3G), 0 <= f < 1, dM > 0.
 * Converged when each residual is below 1e-12 of the size of the terms it is
 * the difference of (its round-off floor; |R1| <= 1e-12 (1 + x^2 + 2D cosh +
 * D^2)).  A solve has at most TLSPH_GTN_MAX_ITERATIONS residual
 * evaluations.  When Newton fails (a single step of many yield strains with
 * strong void growth), the same end-of-step system is reached by continuation
 * through trial states scaled by k/n (n = 4, 16, 64), each solve started from
 * the last; if that fails too the point is reported as not converged (the
 * stability contract stops the run).  With f = 0 and no nucleation it is the
 * J2 radial return.
 *
 * Units: SI. */
#ifndef TLSPH_DAMAGE_GTN_RETURN_H
#define TLSPH_DAMAGE_GTN_RETURN_H

#include "material/damage/porous_step.h"
#include "scene/scene.h"

#define TLSPH_GTN_MAX_ITERATIONS 40


struct tlsph_gtn_result {
    /* the increments above (dq, dv, dM; all 0 after an elastic step), f and T at
     * the end, the plastic work per unit reference volume (J/m^3), the residual
     * evaluations after the yield check and converged (0 when
     * TLSPH_GTN_MAX_ITERATIONS and the continuation were not enough) */
    struct tlsph_porous_flow flow;
    double sigma_M;    /* matrix flow stress at the end of the step, Pa */
    double p, K_t;     /* EOS pressure and tangent bulk modulus at the end, Pa */
    double phi;        /* yield function at the end (about 0 after flow, < 0 if elastic) */
    double yield;      /* after an elastic step: sigma_y(eps_M, 0, T) to cache; else 0 */
};

/* m: a material whose damage model is gtn; in: the trial state
 * (porous_step.h).  Returns 1 when the step is plastic, 0 when elastic. */
int tlsph_gtn_return(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                     struct tlsph_gtn_result *out);

#endif
