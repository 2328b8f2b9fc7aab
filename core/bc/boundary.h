/* Boundary conditions in the step: each phase walks the scene's conditions in
 * scene order and calls the hook of each one's kind (core/bc/kind.h, which
 * also says what each hook books into the energy account).  Constraints act on
 * velocities (the integrator is velocity Verlet); the change of momentum they
 * cause is the support's impulse, from which the group's reaction is
 * reported. */
#ifndef TLSPH_BOUNDARY_H
#define TLSPH_BOUNDARY_H

#include "bc/kind.h"
#include "run/model.h"

/* Selects each condition's particle group (once, at setup; core/bc/groups.c).
 * Returns 0 or -1 with err (a condition selecting no particle). */
int tlsph_boundary_select(struct tlsph_model *m, struct tlsph_errors *err);
/* After the selection: the contradictions the particles reveal (a wall cutting
 * through a body at t = 0; one velocity component of a particle prescribed by
 * two conditions that can disagree; core/bc/contradictions.c).  Returns 0 or
 * -1 with every one in err. */
int tlsph_boundary_check(struct tlsph_model *m, struct tlsph_errors *err);
/* After each half kick: imposes the constraints with the prescribed values at
 * time t (s), accumulating impulses, and books their work at the prescribed
 * velocities of time t_mid (s, the middle of the current step). */
void tlsph_boundary_constrain(struct tlsph_model *m, double t, double t_mid);
/* After the first kick's constraints, before the drift of length dt (s):
 * m->p.f must still hold the forces of that kick (walls stop arriving
 * particles on their plane). */
void tlsph_boundary_before_drift(struct tlsph_model *m, double dt);
/* During force evaluation: adds the conditions' forces to m->p.f; returns
 * their power at the current velocities (W). */
double tlsph_boundary_forces(struct tlsph_model *m);
/* Ends the step: the kinds' end-of-step hooks, then every group's impulse
 * becomes its reaction force (N) and is cleared. */
void tlsph_boundary_end_step(struct tlsph_model *m, double dt);
/* Mean displacement of every group (for the time series; core/bc/groups.c). */
void tlsph_boundary_displacements(struct tlsph_model *m);

#endif
