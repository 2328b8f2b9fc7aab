/* Radial return of J2 (von Mises) plasticity for every flow-stress law, with
 * strain-rate hardening and adiabatic heating solved in the same implicit step.
 *
 * Given the von Mises value q of the elastic trial Kirchhoff deviator, the
 * equivalent plastic strain increment dgamma solves the consistency condition
 *
 *   r(dgamma) = q - 3G dgamma - J sigma_y(eps_n + dgamma, dgamma/dt, T(dgamma)) = 0,
 *   T(dgamma) = T_n + chi/(rho0 C_p) (q - 3G dgamma) dgamma,
 *
 * i.e. the end-of-step Cauchy von Mises stress equals the flow stress at the
 * end-of-step plastic strain, plastic strain rate and temperature (backward
 * Euler in all three; the heat is the plastic work at the end-of-step stress,
 * so the temperature rise is exactly chi/(rho0 C_p) times the dissipation
 * booked).  J sigma_y is the flow stress in Kirchhoff measure (tau = J sigma).
 *
 * Method: Newton on r with a bracket [0, q/(3G)] (r > 0 at 0 because the trial
 * state is outside the yield surface; r <= 0 at q/(3G), where the deviator
 * vanishes), started from the caller's guess (a point that flowed in the last
 * step flows at nearly the same rate: 1-2 iterations) or from the Newton step
 * at 0.  A Newton step that leaves the bracket, or a non-finite or
 * non-negative slope (the rate term's kink at epsdot_0, an infinite hardening
 * slope at eps_p = 0, thermal softening), is replaced by bisection, so the
 * iteration converges for every law; typical cost is 2-4 Newton steps.
 * Converged when |r| <= 1e-12 q or the bracket is narrower than 1e-14 of its
 * upper end; at most TLSPH_J2_MAX_ITERATIONS evaluations, after which the
 * point is reported as not converged (the stability contract stops the run). */
#ifndef TLSPH_J2_RETURN_H
#define TLSPH_J2_RETURN_H

#include "scene/scene.h"

#define TLSPH_J2_MAX_ITERATIONS 80

struct tlsph_j2_input {
    double q_trial; /* von Mises value of the trial Kirchhoff deviator, Pa */
    double J;       /* det F: Kirchhoff = J x Cauchy */
    double G;       /* shear modulus, Pa */
    double eps_p;   /* equivalent plastic strain at the start of the step, 1 */
    double T;       /* temperature at the start of the step, K (ignored without heating) */
    double dt;      /* time step, s (> 0 for rate-dependent laws; 0 treats the rate as 0) */
    double heating; /* chi/(rho0 C_p), K per (J/m^3 of reference volume); 0 = no heating */
    double yield;   /* sigma_y(eps_p, 0, T) when known (> 0), else 0: saves the flow-law
                       evaluation of the yield check for points that stay elastic */
    double guess;   /* expected dgamma (e.g. last step's plastic rate x dt), 0 = none */
};

struct tlsph_j2_result {
    double dgamma;  /* equivalent plastic strain increment, 1 (0: elastic step) */
    double sigma_y; /* flow stress at the end of the step, Pa */
    double T;       /* temperature at the end of the step, K */
    int iterations; /* residual evaluations after the yield check */
    int converged;  /* 1, or 0 when TLSPH_J2_MAX_ITERATIONS were not enough */
    double yield;   /* after an elastic step: sigma_y(eps_p, 0, T) to cache; else 0 */
};

/* Returns 1 when the step is plastic (out->dgamma > 0), 0 when elastic. */
int tlsph_j2_return(const struct tlsph_material *m, const struct tlsph_j2_input *in,
                    struct tlsph_j2_result *out);

#endif
