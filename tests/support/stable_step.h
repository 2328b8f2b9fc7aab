/* Test and bench support: the stable step of the discretisation measured on a
 * model state, not estimated.
 *
 * The leapfrog (kick-drift-kick) update of a linear system M a = -K u is stable
 * for dt < 2 / omega_max, omega_max^2 the largest eigenvalue of M^-1 K.  Here K
 * is the engine's own force evaluation (tlsph_evaluate: kinematics,
 * constitutive update, stress, hourglass and viscous forces) linearised about
 * the current positions by central finite differences, and omega_max^2 is found
 * by power iteration on M^-1 K.  Treatment of the parts:
 *  - stress and hourglass forces depend on positions only: included;
 *  - the return mapping starts from the stored history of the last step, so a
 *    perturbation that loads a flowing point sees the plastic tangent and one
 *    that unloads it the elastic one: the central difference averages the two
 *    (a plastic point's elastic tangent is the bound; see docs/performance.md);
 *  - artificial viscosity depends on velocities (a damping matrix, not a
 *    stiffness): in the stiffness the velocities are held fixed, so only its
 *    position dependence enters; its damping is measured on its own (c_max).
 * Boundary conditions (constraints) remove degrees of freedom and are not
 * applied.  Scenes with contact, rigid bodies or virtual links are refused
 * (their state is not saved).  The model is left exactly as it was. */
#ifndef TLSPH_TEST_STABLE_STEP_H
#define TLSPH_TEST_STABLE_STEP_H

#include <stddef.h>

#include "run/model.h"

struct stable_step_measure {
    double omega_max; /* largest eigenfrequency of M^-1 K, rad/s */
    double dt_crit;   /* 2 / omega_max, s */
    /* the velocity dependence (artificial viscosity): c_max the largest eigenvalue
     * of M^-1 C (1/s), C = -df/dv by the same power iteration, positions fixed;
     * xi = c_max / (2 omega_max) the damping ratio it gives the top mode at worst,
     * and the leapfrog limit with it (velocities half a step behind, as the
     * kick-drift-kick evaluation has them): dt_crit (sqrt(1 + xi^2) - xi); equal
     * to dt_crit without viscosity */
    double c_max;
    double xi;
    double dt_crit_damped; /* s */
    double spread; /* relative spread of omega_max^2 (and c_max) over the last 10 iterations */
    size_t where;  /* particle index of the eigenvector's largest amplitude */
};

/* Power iteration with iters force-evaluation pairs (>= 20); 0, or -1 when the
 * scene has parts this does not handle or memory runs out. */
int stable_step_measure(struct tlsph_model *m, int iters, struct stable_step_measure *out);

/* The estimate dt_cfl (s, before the CFL factor) the given /time/step_estimate
 * (1 tangent, 0 elastic) makes of the model's current state: one force
 * evaluation, the model left exactly as it was; NAN when memory runs out.  The
 * re-evaluation starts from the history the step left, so no point flows in it:
 * the "elastic" estimate is the run's, the "tangent" one that of points at rest. */
double stable_step_estimate(struct tlsph_model *m, int estimate);

#endif
