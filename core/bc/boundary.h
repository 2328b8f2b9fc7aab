/* Boundary conditions by particle groups: fixed and prescribed-velocity
 * constraints, frictionless rigid walls, symmetry planes and body forces.
 *
 * Constraints act on velocities (the integrator is velocity Verlet): after each
 * half kick the constrained components are overwritten, and the change of
 * momentum they cause is the support's impulse, from which the reaction force
 * of the group is reported.  The support's work is its impulse times the
 * prescribed mid-step velocity (zero for fixed particles and symmetry planes).
 *
 * Walls are one-sided constraints.  A particle resting on a wall is held like a
 * symmetry-plane particle: after every kick its velocity into the wall is
 * removed, and that impulse does no work (the wall does not move).  A particle
 * arriving at a wall is stopped inelastically on it; the kinetic energy this
 * removes from the normal velocity it had before the step's kick is booked as
 * (negative) work of the wall.  Only that part is real: the velocity a kick
 * adds to a particle pressed against the wall is an artefact of the half-step
 * splitting (its kinetic energy appears in no full-step state), and booking
 * it would drift the energy balance by m (dt a)^2 / 2 per resting particle and
 * step (measured: 4 % of the impact energy of a Taylor bar). */
#ifndef TLSPH_BOUNDARY_H
#define TLSPH_BOUNDARY_H

#include "run/model.h"

/* Selects each condition's particles (called once at setup). Returns 0 or -1. */
int tlsph_boundary_select(struct tlsph_model *m, struct tlsph_errors *err);
/* Applies fixed/velocity/symmetry constraints with the prescribed values at time
 * t, accumulating impulses and the external work at the prescribed velocity of
 * time t_mid (the middle of the current step). */
void tlsph_boundary_constrain(struct tlsph_model *m, double t, double t_mid);
/* Walls: limits the velocity of each particle heading for a wall so that the
 * drift of length dt ends on the wall at most (impenetrable, frictionless).
 * Called after the first kick; f must still hold the forces of that kick. */
void tlsph_boundary_walls(struct tlsph_model *m, double dt);
/* Adds body forces to p.f; returns their power at the current velocities (W). */
double tlsph_boundary_body_forces(struct tlsph_model *m);
/* Converts the step's impulses to reaction forces and clears them. */
void tlsph_boundary_end_step(struct tlsph_model *m, double dt);
/* Mean displacement of every group (for the time series). */
void tlsph_boundary_displacements(struct tlsph_model *m);

#endif
