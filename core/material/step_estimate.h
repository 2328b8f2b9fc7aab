/* The stable-step estimate of one particle (the constitutive pass takes the
 * smallest over particles; core/run/integrate.c multiplies it by the CFL factor).
 *
 * The leapfrog update is stable while dt < 2 / omega_max.  For the corrected-
 * gradient stencil the highest mode of a particle is a longitudinal wave over
 * the stencil's reference length, shortened in the current configuration by
 * the principal stretch along it: omega ~ c_a / (l lambda_a).  Measured with the
 * linearised force evaluation (tests/support/stable_step.h) on undeformed
 * lattices, dt_crit = 0.9-1.1 x spacing / c_P for support factors 1.5-2.01
 * (1.4 at 3.0), and in the flowing foot of the Taylor bars dt_crit keeps
 * following the smallest stretch (docs/performance.md, "the stable step").  So:
 *
 *   dt_i = spacing * s_i / (c_i + |v_i|) * phi_i
 *
 * s_i the step's stretch (min_stretch, or with the "tangent" estimate the
 * wave_stretch of material_point.h, which uses the tangent's wave speed along
 * each principal direction), c_i the elastic P-wave speed, and phi_i the
 * factor of artificial viscosity, a damping: with damping ratio xi of the
 * highest mode, the limit is 2/omega (sqrt(1 + xi^2) - xi) (half-step
 * velocities, as the kick-drift-kick evaluation sees them).  Monaghan's pair
 * term pi = (-beta1 c mu + beta2 mu^2) / rho0 gives
 *
 *   xi_i = TLSPH_VISCOUS_XI * (beta1 + beta2 mu_i / c_i),   mu_i = h_i |Fdot_i| / s_min,i
 *
 * mu_i bounding the pair's mu = h v_ij.x_ij / r^2 through the rate of F (v_ij =
 * Fdot X_ij, |x_ij| >= s_min |X_ij|).  TLSPH_VISCOUS_XI: on a crushed block the
 * top mode's measured damping ratio is 0.38-0.41 per unit beta1 (relative to
 * omega_max, which c / (spacing s) puts up to 1.4x low); 0.3 keeps the measured
 * damped limit 1.1-1.3x above the estimate at beta1 = 10 and 1.4-1.8x at
 * beta1 = 1 (docs/performance.md, "The stable step"). */
#ifndef TLSPH_STEP_ESTIMATE_H
#define TLSPH_STEP_ESTIMATE_H

#include <math.h>

#define TLSPH_VISCOUS_XI 0.3

/* The leapfrog limit's factor for damping ratio xi >= 0: sqrt(1 + xi^2) - xi. */
static inline double tlsph_damped_step_factor(double xi)
{
    return sqrt(1.0 + xi * xi) - xi;
}

/* phi_i above. beta1, beta2: the viscosity's coefficients (1); h: smoothing length (m);
 * Fdot: rate of F (1/s, [9]); s_min: smallest principal stretch; c: P-wave speed (m/s). */
static inline double tlsph_viscous_step_factor(double beta1, double beta2, double h,
                                               const double *Fdot, double s_min, double c)
{
    double f2 = 0.0;
    for (int k = 0; k < 9; k++)
        f2 += Fdot[k] * Fdot[k];
    const double mu = h * sqrt(f2) / s_min;
    return tlsph_damped_step_factor(TLSPH_VISCOUS_XI * (beta1 + beta2 * mu / c));
}

#endif
