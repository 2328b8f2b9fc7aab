/* The pseudo-spring crack treatment, for comparison with the damage-aware one
 * (paper 000 §3.1; Chakraborty & Shaw 2013; LAMMPS SMD's degradation of pairs).
 *
 * Every pair's kernel is scaled by s_ij = (1 - D_i)(1 - D_j): the correction
 * matrix L_i, the deformation gradient from the total displacements, its rate
 * and the pair forces all see s_ij W.  When a link breaks its whole history
 * leaves F at once, as if the neighbour had never moved: for an elastic
 * material that is a full unload, but a plastically stretched link leaves a
 * jump in F that no stored energy pays for.  That is the instability the paper
 * describes, and this treatment exists to show it beside the damage-aware one.
 * It conserves linear momentum (s_ij is symmetric) but not energy. */
#include "sph/pseudo_spring.h"

#include "sph/correction.h"
#include "sph/kinematics.h"
#include "util/parallel.h"

void tlsph_pseudo_spring_kinematics(struct tlsph_model *m, double dt)
{
    const size_t n = m->p.n;
    const double *restrict vol0 = m->p.vol0;
    const double *restrict D = m->p.damage;
    const int64_t *restrict start = m->pairs.start;
    const int32_t *restrict nbr = m->pairs.j;
    const double *restrict dw = m->pairs.dw;
    double *restrict Linv = m->p.Linv;
    double *Fdot = m->p.Fdot; /* written here and in tlsph_kinematics_finish */
    const int dim = m->dim;

#pragma omp parallel for schedule(static) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++) {
        if (D[i] >= 1.0) {
            for (int a = 0; a < 9; a++)
                Fdot[9 * i + a] = 0.0;
            continue;
        }
        const struct tlsph_gather_origin o = tlsph_gather_origin(&m->p, i);
        double G[9] = {0}, Gd[9] = {0}, L[9] = {0};
        for (int64_t k = start[i]; k < start[i + 1]; k++) {
            const size_t j = (size_t)nbr[k];
            const double sij = tlsph_pseudo_spring_scale(D[i], D[j]);
            if (sij <= 0.0)
                continue;
            const double s = sij * vol0[j] * dw[k];
            const struct tlsph_pair_delta q = tlsph_pair_delta(&m->p, &o, j);
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++) {
                    G[3 * a + b] += q.du[a] * s * q.d[b];
                    Gd[3 * a + b] += q.dv[a] * s * q.d[b];
                    L[3 * a + b] += s * q.d[a] * q.d[b];
                }
        }
        /* the new L^-1 is for F and Fdot; the energy half-step still uses the old
         * P_tilde (and so the old L^-1), as the power of the last stress */
        double cond;
        tlsph_correction_invert(L, dim, Linv + 9 * i, &cond);
        tlsph_kinematics_finish(&m->p, i, dt, G, Gd);
    }
}

const struct tlsph_crack_model tlsph_crack_pseudo_spring = {
    .name = "pseudo_spring",
    .module = "approximation:pseudo_spring",
    .scene = TLSPH_CRACK_PSEUDO_SPRING,
    .variant = TLSPH_APPROX_PSEUDO_SPRING,
    .fields = 0, /* its F comes from the total displacements: no history */
};
