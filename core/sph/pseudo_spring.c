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
    const double *restrict X = m->p.X, *restrict x = m->p.x, *restrict v = m->p.v;
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
        const double Xi0 = X[3 * i], Xi1 = X[3 * i + 1], Xi2 = X[3 * i + 2];
        const double ui0 = x[3 * i] - Xi0, ui1 = x[3 * i + 1] - Xi1, ui2 = x[3 * i + 2] - Xi2;
        const double vi0 = v[3 * i], vi1 = v[3 * i + 1], vi2 = v[3 * i + 2];
        double G[9] = {0}, Gd[9] = {0}, L[9] = {0};
        for (int64_t k = start[i]; k < start[i + 1]; k++) {
            const size_t j = (size_t)nbr[k];
            const double sij = tlsph_pseudo_spring_scale(D[i], D[j]);
            if (sij <= 0.0)
                continue;
            const double d[3] = {X[3 * j] - Xi0, X[3 * j + 1] - Xi1, X[3 * j + 2] - Xi2};
            const double s = sij * vol0[j] * dw[k];
            const double du[3] = {x[3 * j] - X[3 * j] - ui0, x[3 * j + 1] - X[3 * j + 1] - ui1,
                                  x[3 * j + 2] - X[3 * j + 2] - ui2};
            const double dv[3] = {v[3 * j] - vi0, v[3 * j + 1] - vi1, v[3 * j + 2] - vi2};
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++) {
                    G[3 * a + b] += du[a] * s * d[b];
                    Gd[3 * a + b] += dv[a] * s * d[b];
                    L[3 * a + b] += s * d[a] * d[b];
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
