/* Failed particles (D = 1), the phase after the stress update.
 *
 * A particle fails in the stress update (its damage model sets D = 1); from
 * then on it carries no stress and takes part in no pair (kinematics.c gives
 * it Fdot = 0 and no F update, forces.c no pair force), but it is not
 * deleted.  This phase, every evaluation:
 *   - counts the failed particles (m->failed);
 *   - releases the stress of the particles that failed in this update:
 *     sigma = 0 and P_tilde = 0, before the pair forces read them;
 *   - with "failed_particles": "arrest" (the paper's choice, §3.1: "for
 *     practical reasons only, its velocity is set to 0") stops them once, at
 *     their failure, and books the kinetic energy this removes as (negative)
 *     external work, so the energy balance stays closed.  With "free" they
 *     keep their momentum.
 *
 * A particle that failed in this update is told apart from one that had
 * failed before by what the earlier phases left on it: a particle failed at
 * the start of the step has Fdot = 0 (kinematics) and no stress (released by
 * this phase when it failed), while one that has just failed still carries
 * the stress of its last step or the strain rate of this one.  It cannot
 * have neither: failing takes plastic flow in this step, which takes stress.
 * So no per-particle flag is stored. */
#ifndef TLSPH_FAILURE_H
#define TLSPH_FAILURE_H

#include "run/model.h"

/* Reads p.damage, p.Fdot, p.P_tilde; writes p.sigma, p.P_tilde and p.v of the
 * particles that have just failed, m->failed, and m->energy.external_work. */
void tlsph_failure(struct tlsph_model *m);

#endif
