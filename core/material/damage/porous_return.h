/* The implicit Aravas-type porous return of paper 003 (Appendices A-B;
 * Aravas, IJNME 24, 1987), for every model of porous.h.
 *
 * Frame.  The paper integrates a hypoelastic Cauchy stress: its elastic trial
 * state (eqs. 73-74) is the old stress rotated by the Hughes-Winget increment
 * Q = I + (I - w/2)^-1 w plus C : d dt.  The engine has no rate to integrate:
 * its stress is hyperelastic in the logarithmic strain H = ln U of the
 * unrotated frame of F = R U (material_point.h), where the trial Kirchhoff
 * stress is 2G dev(H_{n+1} - Ep_n) - J p(J_e) I with the stored plastic strain
 * Ep_n.  That frame already removes the rigid rotation exactly (R never enters),
 * so Hughes-Winget's approximate rotation has no counterpart and must not be
 * applied on top: there is one frame, not two side by side.  The return
 * itself coincides: it depends only on the trial invariants and moves the
 * deviator along its own direction n = 3/2 s_tr/sigma_e^tr (eq. 84), and an
 * isotropic return commutes with any rotation, so the paper's return in its
 * rotated frame and this one in the unrotated frame are the same map.  What
 * differs is the elastic law around it (hyperelastic Hencky with the
 * material's EOS here, hypoelastic with a constant bulk modulus there); for
 * small elastic strains the two trial states agree to first order.
 *
 * Unknowns (eqs. 78-83): the plastic volume strain increment a = dt D_m and the
 * equivalent deviatoric increment b = dt D_e, so that
 *   sigma_e = (q_tr - 3G b)/J,    sigma_m = -p_EOS(J exp(-(tr Ep_n + a)), e)
 * (the paper's eq. 83 prints K for 3G; eq. 82 is the EOS linearised).  The
 * internal variables H = (eps_M, f) at the end of the step follow from (a, b)
 * by their own implicit equations (eqs. 85-88):
 *   (1 - f) sigma_M(eps_M) d eps_M = sigma_m a + sigma_e b    equal plastic work (eq. 86;
 *                                                             the paper's 1.5 is a misprint:
 *                                                             sigma : d^p = sigma_m D_m + sigma_e D_e)
 *   f = 1 - (1 - f_n) exp(-a) + N(eps_M,n, eps_M) + k_w omega Omega(T) b f
 * with growth (eq. 44) integrated exactly over the step (matrix volume
 * (1 - f) exp(tr Ep) conserved; the paper's forward form (1 - f) a differs by
 * O(a^2)), nucleation (eq. 47) as the exact integral N of A_N d eps_M, and the
 * shear term (eqs. 49, 52) backward Euler.  Given (a, b), f is explicit in
 * eps_M and the work equation is one scalar equation for d eps_M, solved by a
 * safeguarded Newton.  The two outer equations are
 *   F1 = a dPhi/dsigma_e - b dPhi/dsigma_m = 0   normality (eq. 89; the paper prints "+")
 *   F2 = Phi(sigma_e, sigma_m, eps_M, f)   = 0   yield (eq. 90)
 * solved by Newton (eqs. 91-94) with their consistent Jacobian: the partial
 * derivatives at fixed H plus dPhi/dH dH/d(a, b), dH/d(a, b) from the implicit
 * function theorem on the internal-variable equations (the chain of Appendix
 * B's dh/dH, dh/dsigma, dh/dD; tlsph_porous_residual exposes it for the
 * finite-difference test).  Matrix hardening enters through the strength
 * model's slope h_M = d sigma_M/d eps_M (eq. 55 prints its inverse), rate and
 * temperature through its other derivatives.
 *
 * Convergence: each residual below 1e-12 of the size of the terms it is the
 * difference of (its round-off floor).  At most TLSPH_POROUS_MAX_ITERATIONS
 * residual evaluations per solve, a backtracking line search, and when Newton
 * fails from the frozen first guess, continuation through trial states scaled
 * k/n (n = 4, 16, 64) as in gtn_return.c; a point that still does not converge
 * is reported (result .flow.converged = 0, the stability contract stops the run).
 * With f = 0, no nucleation and no shear it is the J2 radial return.
 *
 * Crushed voids close (gtn_return.h: when, why, the thresholds): where the
 * porous step ends below 1e-9 voids and compacts (a < 0), or its closed state
 * (f = 0, a = ln(1 - f_n) - ln(1 + N), the dense matrix's yield x = 1 solved
 * for b by Illinois regula falsi) lies beyond the cap of the 1e-9 surface,
 * or, when no solver resolves the step, beyond that of the 1e-6 surface.
 *
 * Units: SI. */
#ifndef TLSPH_DAMAGE_POROUS_RETURN_H
#define TLSPH_DAMAGE_POROUS_RETURN_H

#include "material/damage/porous_step.h"
#include "scene/scene.h"

#define TLSPH_POROUS_MAX_ITERATIONS 40


struct tlsph_porous_result {
    /* dq = b, dv = a, dM (all 0 after an elastic step), f and T at the end, the
     * plastic work per unit reference volume (J/m^3), the residual evaluations
     * after the yield check, converged (0 when the solve failed) */
    struct tlsph_porous_flow flow;
    double df_growth, df_nucleated, df_shear; /* the three parts of f's change, 1 */
    double sigma_M;    /* matrix flow stress at the end, Pa */
    double p, K_t;     /* EOS pressure and tangent bulk modulus at the end, Pa */
    double phi;        /* yield function at the end (about 0 after flow, < 0 if elastic) */
    double yield;      /* after an elastic step: sigma_M(eps_M, 0, T) to cache; else 0 */
};

/* m: a material whose damage model is of the porous family (porous.h).
 * Returns 1 when the step is plastic, 0 when elastic. */
int tlsph_porous_return(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                        struct tlsph_porous_result *out);

/* The outer residuals F = (F1, F2) at (a, b) (F1 divided by the strain scale
 * `scale`) and their consistent Jacobian dF[i][k] = dF_i/d(a, b)_k.  Returns 0
 * when (a, b) has no admissible internal state (f >= 1, no matrix strain
 * solution).  For the tests. */
int tlsph_porous_residual(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                          double scale, double a, double b, double F[2], double dF[2][2]);

#endif
