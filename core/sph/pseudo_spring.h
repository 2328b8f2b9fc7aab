/* The pseudo-spring crack treatment (comparison only; see pseudo_spring.c). */
#ifndef TLSPH_PSEUDO_SPRING_H
#define TLSPH_PSEUDO_SPRING_H

#include "run/model.h"

/* Kinematics with every pair's kernel scaled by (1 - D_i)(1 - D_j): recomputes
 * L_i^-1 (p.Linv) from the scaled kernels, F from the total displacements,
 * Fdot, and the first half of the internal-energy update (as kinematics.h). */
void tlsph_pseudo_spring_kinematics(struct tlsph_model *m, double dt);

#endif
