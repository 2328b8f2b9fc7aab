/* Time integration: velocity Verlet (kick-drift-kick) with a CFL time step.
 *
 *   v(n+1/2) = v(n) + dt/2 f(n)/m,  constraints at t + dt/2, walls
 *   x(n+1)   = x(n) + dt v(n+1/2)
 *   f(n+1)   = forces at x(n+1), rates from v(n+1/2)
 *   v(n+1)   = v(n+1/2) + dt/2 f(n+1)/m, constraints at t + dt
 *
 * F is computed from positions, so F(n+1) - F(n) = dt Fdot(v(n+1/2)) exactly and
 * the trapezoidal internal-energy update matches the work of the stress forces. */
#ifndef TLSPH_INTEGRATE_H
#define TLSPH_INTEGRATE_H

#include "run/model.h"

/* Step 0, at setup: constraints at t = 0, the first evaluation (dt = 0), the
 * initial energies and the first time step. */
void tlsph_start(struct tlsph_model *m);
/* Kinematics, stress update, failure, pair forces, body forces for the current
 * positions; dt is the step that led here (0 at setup). Updates energy terms
 * (the phase contract is in integrate.c, above tlsph_model_step). */
void tlsph_evaluate(struct tlsph_model *m, double dt);
/* The step the physics allows: the fixed step, or cfl times the stable
 * estimate of the last force evaluation (s). */
double tlsph_stable_dt(const struct tlsph_model *m);
/* Time step for the next step: tlsph_stable_dt, ending at the next frame time
 * when it would pass two (the frame schedule, model.h), never past the end
 * time. */
double tlsph_next_dt(const struct tlsph_model *m);
/* Kinetic energy (J). */
double tlsph_kinetic_energy(const struct tlsph_model *m);
double tlsph_internal_energy(const struct tlsph_model *m);

#endif
