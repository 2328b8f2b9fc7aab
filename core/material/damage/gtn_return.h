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
 * Void closure.  Under a pressure many times the matrix flow stress (an
 * impact face: 55 sigma_M on copper at 150 m/s) the return keeps the point
 * on the surface's cap by driving f down as exp(-3/2 q2 |y|): GTN to 1e-300
 * and then below what a double holds, where the system has no solution; the
 * Aravas-type return of the Gurson family (porous_return.h) loses f to
 * round-off earlier, near 1e-11, where it is the difference of the voids the
 * step starts with and those it crushes, and its solves stall (hundreds of
 * evaluations, then failure).  Either way the run would stop.  The voids are
 * then physically closed, and a porous model at f = 0 is the dense matrix
 * (J2; without nucleation f stays 0: growth is proportional to a plastic
 * volume change the dense matrix does not have).  The closed step ends with
 * f = 0: dv = log(1 - f_n) - log(1 + N) squeezes out every void, and yield
 * and equal work fix dq and dM.  It is taken
 *  - where the porous solution ends below TLSPH_VOIDS_CLOSED (1e-9) and the
 *    step compacts (dv < 0), or where the closed state lies beyond the cap of the
 *    surface with f = 1e-9 (a pressure above 13 sigma_M at q1 = 1.5,
 *    q2 = 1), where no end state with more voids exists (a trial state
 *    beyond that cap is tried closed first, saving the porous solvers'
 *    hundreds of evaluations);
 *  - always once f = 0 and nothing nucleates;
 *  - as the last resort, when no solver resolves the porous step and the
 *    closed state lies beyond the cap of TLSPH_VOIDS_CLOSED_UNRESOLVED
 *    (1e-6): the porous step would end with fewer voids than that, and the
 *    alternative is a stopped run; in both returns also where f plus the
 *    step's nucleation stays below 1e-9 (no voids to resolve).
 * Elsewhere (voids nucleating from f = 0 while the step dilates, under shear
 * or tension) the porous solution stands.  The thresholds: voids of 1e-9 regrow to 1e-4 only after
 * a plastic strain of about ln(1e5)/(3/2 q1 q2 sinh(3/2 q2 T)), 2.4 at
 * triaxiality T = 1 and 0.5 at T = 2 (from 1e-6: 1.0 and 0.2); shock-closed
 * voids do not reopen as the model would let them, so closure is the
 * physical reading, but it is a modelling choice and docs/damage.md says so.
 *
 * A kink in the flow stress.  Johnson-Cook's rate factor is 1 below the
 * reference rate and 1 + C ln(rate/rate_0) above, so the slope of sigma_M in
 * dM jumps at dM = rate_0 dt; when the root lies just past it, Newton on the
 * whole system bounces across the kink.  The fallback then solves equal work
 * in dM alone by a bracketing method (Illinois regula falsi), with yield and
 * normality solved for (dq, f) at each dM, where sigma_M is fixed and the
 * system smooth (nested_return in gtn_return.c).
 *
 * Tension the small voids cannot relieve.  With x near 1 normality reads
 * 2 (f - f_n) = 3 q1 q2 f sinh(3/2 q2 y) dq, which has a small positive f only
 * while 3 q1 q2 sinh(3/2 q2 y) dq < 2 (behind the shock of a copper Taylor bar
 * with Mie-Grueneisen it is 2.07).  The root then lies where the voids have
 * grown enough, and Newton slides towards the spurious one with f < 0.  The
 * last fallback follows the normality residual along f, from f_n (R2 < 0 in
 * tension) to the f whose dilatation relieves the elastic volume to J_e = 1
 * (R2 > 0), by a bracket, with yield and equal work solved for (dq, dM) at
 * each f (grown_return in gtn_return.c).
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
