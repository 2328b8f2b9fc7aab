/* Constitutive update: stress from the deformation gradient, per body (one
 * material per body, dispatched once per body range).
 *
 * Objective stress rate: the response is computed in the unrotated
 * (corotational) frame of the polar decomposition F = R U, i.e. the
 * Green-Naghdi rate, with the Hencky strain ln U as the strain measure.  Why:
 *  - TLSPH knows F exactly from the reference configuration, so R and U come
 *    from it without integrating a spin; a rigid rotation leaves U, and so the
 *    stress, unchanged to round-off (the Jaumann rate, integrated with W dt,
 *    only approximates this and oscillates in large simple shear, Dienes 1979);
 *  - increments of ln U are exact for coaxial stretching, so a uniaxial test
 *    integrates to the true (logarithmic) strain with no dependence on dt;
 *  - for the elastic strength model the result is the isotropic Hencky
 *    hyperelastic material (Kirchhoff stress tau = K ln J I + 2G dev ln V), which
 *    conserves energy in the discrete system; the plasticity modules apply their
 *    return mapping to the same unrotated Kirchhoff stress.
 * Per particle: C = F^T F = Q diag(lam) Q^T (Jacobi), U^-1 = Q diag(lam^-1/2) Q^T,
 * tau_hat = tau_dev(dev ln U) - J p(J, e) I, S = U^-1 tau_hat U^-1 (second
 * Piola-Kirchhoff), P = F S, sigma = P F^T / J, P_tilde = P L^-T. */
#ifndef TLSPH_CONSTITUTIVE_H
#define TLSPH_CONSTITUTIVE_H

#include "model.h"

/* Also finishes the trapezoidal energy update (e += dt/2 / rho0 * P_new : Fdot),
 * records det F problems (m->inverted, m->first_inverted_id, m->min_detF) and
 * the stable time step estimate m->dt_cfl and m->max_wave_speed. */
void tlsph_constitutive(struct tlsph_model *m, double dt);

#endif
