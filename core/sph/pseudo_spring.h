/* The pseudo-spring crack treatment (paper 000 §3.1; comparison only): every
 * pair's kernel is scaled by s_ij = (1 - D_i)(1 - D_j).  See pseudo_spring.c
 * for why it is unstable for ductile materials. */
#ifndef TLSPH_PSEUDO_SPRING_H
#define TLSPH_PSEUDO_SPRING_H

#include "run/model.h"
#include "sph/crack_treatment.h"

extern const struct tlsph_crack_model tlsph_crack_pseudo_spring;

/* The pair's kernel scale s_ij, symmetric in i, j. */
static inline __attribute__((always_inline)) double tlsph_pseudo_spring_scale(double Di,
                                                                             double Dj)
{
    return (1.0 - Di) * (1.0 - Dj);
}

/* Kinematics with every pair's kernel scaled by s_ij: recomputes L_i^-1 (p.Linv)
 * from the scaled kernels, F from the total displacements, Fdot, and the first
 * half of the internal-energy update (as kinematics.h).  Its own pass: the
 * correction matrices change with the damage. */
void tlsph_pseudo_spring_kinematics(struct tlsph_model *m, double dt);

/* The pair force with the scaled kernel: both stresses, and the stabilisation,
 * weigh s_ij. */
static inline __attribute__((always_inline)) struct tlsph_pair_weights
tlsph_pseudo_spring_force_weights(double Di, double Dj)
{
    const double s = tlsph_pseudo_spring_scale(Di, Dj);
    return (struct tlsph_pair_weights){.wi = s, .wj = s, .stab = s};
}

#endif
