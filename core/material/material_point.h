/* The stress update of one material point (one particle): deformation gradient
 * in, Piola and Cauchy stress out, history updated.  The engine's constitutive
 * loop (core/material/constitutive.c) calls this for every particle, and the single-point
 * tests drive it directly, so the tests exercise exactly the engine's code.
 *
 * Kinematics and frame.  With C = F^T F = Q diag(lambda) Q^T, the strain measure
 * is the Hencky strain H = ln U = Q diag(ln sqrt(lambda)) Q^T in the unrotated
 * frame of F = R U (R never needs to be formed).  A rigid rotation leaves U, and
 * so every stress and history variable, unchanged to round-off.
 *
 * Elasticity.  Stored energy psi(H - Ep) with the plastic strain Ep additive in
 * the logarithmic strain (Miehe, Apel & Lambrecht, CMAME 191, 2002):
 *   T = 2G dev(H - Ep) - J p(J, e) I        (Kirchhoff-type stress conjugate to H)
 * For the elastic strength model Ep = 0 and this is Hencky hyperelasticity.
 *
 * Plasticity (J2, every flow law): the trial T is returned radially onto
 * J sigma_y(eps_p, epsdot_p, T) by material/strength/j2_return.c; the plastic strain
 * grows along the normal, dEp = dgamma 3/2 dev(T_trial)/q_trial, so it stays
 * traceless (plastic incompressibility: J is carried by the elastic volumetric
 * strain alone, ln J = tr(H)).  Plastic work dgamma J sigma_y per unit reference
 * volume; with thermal coupling chi of it heats the point (rho0 C_p dT).
 *
 * Stress.  The second Piola-Kirchhoff stress is the exact derivative of psi:
 * in the eigenbasis of C, S_ab = T_ab theta_ab with theta_aa = 1/lambda_a and
 * theta_ab = (ln lambda_a - ln lambda_b)/(lambda_a - lambda_b) (the derivative of
 * the matrix logarithm).  Hence P : Fdot = T : dH/dt exactly, and the work of
 * the stress forces equals the stored energy plus the plastic work booked here,
 * even when the plastic strain is not coaxial with U.  P = F S, sigma = P F^T/J.
 *
 * Damage (paper 000 §4-5; only for materials with a damage model).  The
 * update above runs on the effective stress of the undamaged matrix; the stress
 * the point carries is T = (1 - D) 2G dev(H - Ep) - J p_D I with p_D = p in
 * compression and (1 - D) p in tension (eqs. 37-38: 2G(1 - D) and a flow stress
 * (1 - D) sigma_y, whose return is the effective one scaled by (1 - D)).  After
 * the return, the criterion grows D_init from the step's plastic strain and the
 * effective stress, eq. 45 gives the new D, and the stress is assembled with it.
 * The energy the drop of D releases at fixed strain, psi_eff dD with psi_eff =
 * G |dev(H - Ep)|^2 + the tensile volumetric energy, is the damage dissipation.
 * At D = 1 the point has failed: it carries no stress at all.
 *
 * A porous damage model (GTN, material/damage/gtn_point.c) replaces the J2 return and
 * the (1 - D) scaling by its own point update (the damage model's point_update
 * hook, material/damage/damage.h), built from the shared pieces declared at the
 * end of this header: the point carries the macroscopic stress of the porous
 * material, its plastic strain has a trace (void growth), and the EOS sees the
 * elastic volume ratio J exp(-tr Ep).
 *
 * Units: SI (Pa, K, J/kg, s). */
#ifndef TLSPH_MATERIAL_POINT_H
#define TLSPH_MATERIAL_POINT_H

#include <math.h>

#include "scene/scene.h"

/* History of a plastic material point. */
struct tlsph_point_state {
    double eps_p;             /* equivalent plastic strain, 1 */
    double plastic_strain[6]; /* plastic logarithmic strain Ep (unrotated frame), 1 */
    double rate;              /* equivalent plastic strain rate of the last step, 1/s */
    double T;                 /* temperature, K (read and written only with thermal coupling) */
    double yield;             /* cached sigma_y(eps_p, 0, T), Pa; 0 = not known (zero-initialised
                                 states are valid) */
    double damage;            /* D in [0, 1], 1 (read and written only with a damage model) */
    double damage_init;       /* damage-initiation variable D_init >= 0, 1 (idem; GTN: f/f_c) */
    double void_fraction;     /* void volume fraction f, 1 (porous damage models only) */
    /* The Gurson family (material/damage/porous.h) only: f* of eq. 45 and the
     * parts of f nucleated (eq. 47) and grown by shear (eqs. 49, 52) so far, 1 */
    double void_fstar, void_nucleated, void_shear;
};

struct tlsph_point_result {
    double P[9];         /* first Piola-Kirchhoff stress, Pa (row-major) */
    double sigma[6];     /* Cauchy stress, Pa */
    double J;            /* det F, 1 */
    double min_stretch;  /* smallest principal stretch, 1 */
    double K_t;          /* tangent bulk modulus of the EOS, Pa */
    /* The step's stretch: min over the principal directions a of lambda_a sqrt(M_el / M_a),
     * M_a the P-wave modulus of the tangent the return has along a (the elastic
     * M_el = K_t + 4/3 G where the point does not flow this step: then exactly
     * min_stretch), 1.  See core/material/constitutive.c, the step estimate. */
    double wave_stretch;
    double plastic_work; /* plastic work of this step per unit reference volume, J/m^3 */
    double damage_work;  /* energy released by damage growth this step, J/m^3 (reference) */
    double triaxiality;  /* sigma_m / sigma_eq of the effective stress (NaN when sigma_eq = 0,
                            and for materials without damage: only damage reads it) */
    int iterations;      /* return-mapping iterations (0: elastic step) */
    int converged;       /* 0 when the return mapping did not converge */
};

/* F: deformation gradient (1); e: specific internal energy for the EOS (J/kg);
 * dt: the step that led to F (s; 0 at setup).  s: the point's history, updated
 * in place; NULL for a material without plasticity (the elastic path: no return
 * mapping).  Requires det F > 0 for meaningful output (the caller checks). */
void tlsph_point_update(const struct tlsph_material *mat, const double F[9], double e, double dt,
                        struct tlsph_point_state *s, struct tlsph_point_result *r);
/* The same with C = F^T F already decomposed: lam [3] and Q [9] as
 * sym3_eigen (util/mat3.h) gives them for mat3_mul_at(F, F), so the results
 * are tlsph_point_update's bit for bit.  The constitutive phase decomposes a
 * few particles' C at once (sym3_eigen_batch) and calls this. */
void tlsph_point_update_eigen(const struct tlsph_material *mat, const double F[9],
                              const double lam[3], const double Q[9], double e, double dt,
                              struct tlsph_point_state *s, struct tlsph_point_result *r);

/* Shared pieces for the point updates of damage models (damage.h: point_update). */

/* The kinematics of one point: C = F^T F = Q diag(lam) Q^T. */
struct tlsph_point_kinematics {
    const double *F;    /* deformation gradient [9], 1 */
    double lam[3];      /* eigenvalues of C, 1 */
    double lns[3];      /* logarithmic principal stretches ln sqrt(lam), 1 */
    double Q[9];        /* eigenvectors of C (columns), row-major */
    double J;           /* det F, 1 */
    double min_stretch; /* smallest principal stretch, 1 */
};

/* Fills r's stresses from the total Kirchhoff-type stress tau conjugate to the
 * Hencky strain, in the eigenbasis of C: S by the derivative of the matrix
 * logarithm (general != 0; general = 0 when tau is diagonal there, as in
 * elasticity), P = F S, sigma = P F^T / J; and r->J, r->min_stretch, r->K_t. */
void tlsph_point_assemble(const struct tlsph_point_kinematics *k, const double tau[9], int general,
                          double K_t, struct tlsph_point_result *r);
/* The result of a failed point: no stress at all. */
void tlsph_point_no_stress(struct tlsph_point_result *r, double J, double min_stretch, double K_t);

/* Stored elastic energy per unit reference volume (J/m^3) of a stress state:
 * deviatoric G |dev He|^2 = q^2/(6G) (q the Kirchhoff von Mises value, Pa);
 * volumetric by the secant p (1 - J_e)/2 (exact for a linear EOS) per unit
 * intermediate volume, times the plastic volume ratio J_p. */
static inline double tlsph_deviatoric_energy(double G, double q) { return q * q / (6.0 * G); }
static inline double tlsph_volumetric_energy(double p, double Je, double Jp)
{
    return 0.5 * fmax(p * (1.0 - Je), 0.0) * Jp;
}

#endif
