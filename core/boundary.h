/* Boundary conditions by particle groups: fixed and prescribed-velocity
 * constraints, frictionless rigid walls, symmetry planes and body forces.
 *
 * Constraints act on velocities (the integrator is velocity Verlet): after each
 * half kick the constrained components are overwritten, and the change of
 * momentum they cause is the support's impulse, from which the reaction force
 * of the group is reported.  The support's work is its impulse times the
 * prescribed mid-step velocity (zero for fixed particles and symmetry planes).
 * Walls are different: they stop particles inelastically, and the kinetic energy
 * that removes is booked as (negative) work of the wall. */
#ifndef TLSPH_BOUNDARY_H
#define TLSPH_BOUNDARY_H

#include "model.h"

/* Selects each condition's particles (called once at setup). Returns 0 or -1. */
int tlsph_boundary_select(struct tlsph_model *m, struct tlsph_errors *err);
/* Applies fixed/velocity/symmetry constraints with the prescribed values at time
 * t, accumulating impulses and the external work at the prescribed velocity of
 * time t_mid (the middle of the current step). */
void tlsph_boundary_constrain(struct tlsph_model *m, double t, double t_mid);
/* Walls: limits the velocity of each particle heading for a wall so that the
 * drift of length dt ends on the wall at most (impenetrable, frictionless). */
void tlsph_boundary_walls(struct tlsph_model *m, double dt);
/* Adds body forces to p.f; returns their power at the current velocities (W). */
double tlsph_boundary_body_forces(struct tlsph_model *m);
/* Converts the step's impulses to reaction forces and clears them. */
void tlsph_boundary_end_step(struct tlsph_model *m, double dt);
/* Mean displacement of every group (for the time series). */
void tlsph_boundary_displacements(struct tlsph_model *m);

#endif
