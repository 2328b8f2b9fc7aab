/* Constitutive update: stress from the deformation gradient for every particle,
 * dispatched once per body (one material per body).  The per-particle physics
 * (Hencky strain in the unrotated frame, elastic predictor, J2 return mapping,
 * EOS, exact second Piola-Kirchhoff stress) is core/material/material_point.c; this file
 * moves the particles' arrays through it.  Bodies of an elastic material run the
 * elastic path: no plastic history is read or written and no return mapping runs. */
#ifndef TLSPH_CONSTITUTIVE_H
#define TLSPH_CONSTITUTIVE_H

#include "run/model.h"

/* Also finishes the trapezoidal energy update (e += dt/2 / rho0 * P_new : Fdot),
 * adds the step's plastic work to m->energy.plastic_work, records det F problems
 * (m->inverted, m->first_inverted_id, m->min_detF), return-mapping failures
 * (m->return_failures and m->first_return_failure_id, accumulated over the
 * run: a failure between two stability checks is not forgotten) and the stable time step
 * estimate m->dt_cfl and m->max_wave_speed.  A particle failed (D = 1) after
 * its update gets no new stress here: the failure phase that follows
 * (material/failure.h) releases what it carried. */
void tlsph_constitutive(struct tlsph_model *m, double dt);

/* tlsph_kinematics then tlsph_constitutive, in one parallel region per body
 * (each thread gathers the particles it updates), with the same results bit
 * for bit.  Only when tlsph_kinematics_fusable(m) (sph/kinematics.h). */
void tlsph_constitutive_with_kinematics(struct tlsph_model *m, double dt);

/* The material state of particle i at t = 0 (its body is set): temperature
 * (NaN where the material has none) and the damage model's initial point state
 * (point_init, material/damage/damage.h).  The rest of the history starts at 0. */
void tlsph_constitutive_init_particle(struct tlsph_model *m, size_t i);

#endif
