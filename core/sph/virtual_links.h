/* Virtual links (paper 001 §3): the third crack treatment.  Damage is a
 * property of the link between two immediate neighbours, not of a particle.
 *
 * Support.  A particle interacts only with its immediate neighbours (paper 001
 * Fig. 1): the reference pairs (same body, inside the kernel's support) with
 *   |X_j - X_i| < reach (s_i + s_j) / 2,   s_i = V_i^(1/d)
 * the local spacing (V_i the reference volume; 2-D: the area of the unit-thick
 * slab); reach is the scene's /discretization/damage/links/reach in spacings
 * (m->scene.links.reach, link_criterion.h).  Its default 1.85 sits between the
 * lattice shells it must keep and the first it must drop: on the 2-D square lattice it keeps the 8 at
 * distances 1 and sqrt 2 (the particles whose cells touch i's: the paper's
 * Fig. 1 draws, its text does not count them), on the 3-D cubic lattice the 26
 * at 1, sqrt 2 and sqrt 3 (the same rule: every point of the unit cell around
 * i), and drops the next shell at 2 on both; 6-8 % of slack on either side
 * lets an irregular set (conforming shells, graded volumes) keep a full first
 * shell without reaching the second.  The smoothing length stays the body's;
 * the correction L_i (eqs. 26-27) is built on this support, so a linear
 * displacement field still gives the exact F (tests/physics/test_links.c).
 *
 * Link state.  Each reference pair carries D_ij in [0, 1] (both CSR entries,
 * equal to the bit), f_ij = 1 - D_ij.  f_ij multiplies the corrected kernel
 * gradient in the momentum and energy equations (eqs. 29-30):
 *   Fdot_i = sum_j f_ij V_j (v_j - v_i) (x) grad W_i L_i^-1
 *   f_i    = sum_j f_ij V_i V_j (P_i L_i^-T + P_j L_j^-T) grad W_i   (and the
 *            hourglass and viscous forces of the pair times f_ij)
 * the force is the one conjugate to Fdot and antisymmetric in i, j (D_ij =
 * D_ji), so momentum is exact.  F integrates exactly the transmitted rates
 * (the paper leaves F open): a link that softens or breaks stops adding to F
 * from then on and keeps what it had carried, the damage-aware history of
 * paper 000 eq. 34 with D_j replaced by D_ij (p.crack_gradient).  So F never
 * jumps when a link breaks, the stress power P : Fdot is the work of the pair
 * forces.  One thing remains for the balance: the criteria run after the
 * stress update, so in the step where D_ij grows the second half of the
 * trapezoidal internal-energy update (constitutive.c, P_i : Fdot_i with the
 * old D_ij) and the second half kick (the forces, with the new D_ij) would
 * disagree by dt/2 x the power the link stopped carrying.  The update books
 * that half step with the new D_ij as well (it takes it off e_i and e_j), so
 * both halves of every step see one link state and the balance closes with no
 * term of its own.  The stored energy a crack face holds leaves it as it
 * unloads through its remaining links (kinetic energy of the opening), not at
 * the instant of breaking.  L_i is not rebuilt as links break (eq. 27 is
 * taken on the reference support).
 *
 * Criteria: sph/link_criterion.h, one file each.  Output: the particle damage
 * D_i = sum_j D_ij / n_i (n_i links of i), field "link_damage". */
#ifndef TLSPH_VIRTUAL_LINKS_H
#define TLSPH_VIRTUAL_LINKS_H

#include <math.h>

#include "run/model.h"
#include "sph/crack_treatment.h"
#include "sph/link_criterion.h"
#include "util/parallel.h"

/* The links of a run (m->links), allocated only with this treatment. */
struct tlsph_links {
    double *D;       /* D_ij per reference pair, CSR order of m->pairs [npairs], 1 */
    double *D_prev;  /* D_ij before the last update [npairs] (scratch of the update) */
    int64_t *mirror; /* the entry of the same link in j's row [npairs] */
    size_t broken;   /* links with D_ij = 1, each counted once (last update) */
    size_t broken_watched; /* `broken` when contact last looked for new crack faces
                              (contact/touch.c; kept here so that scenes without links
                              carry nothing for it) */
};

extern const struct tlsph_crack_model tlsph_crack_virtual_links;

/* The pair's forces: both stresses and the stabilisation weigh f_ij. */
static inline __attribute__((always_inline)) struct tlsph_pair_weights
tlsph_virtual_links_force_weights(double Dij)
{
    const double f = 1.0 - Dij;
    return (struct tlsph_pair_weights){.wi = f, .wj = f, .stab = f};
}

/* The particle damage D_i = sum_j D_ij / n_i into out [n] (0 for a particle
 * without links). */
void tlsph_virtual_links_particle_damage(const struct tlsph_model *m, double *out);

/* The stretch of eq. 40 of the link i-j, now. */
static inline double tlsph_link_stretch_of(const struct tlsph_model *m, size_t i, size_t j)
{
    const double *x = m->p.x, *X = m->p.X;
    double dx[3], dX[3];
    for (int a = 0; a < 3; a++) {
        dx[a] = x[3 * j + a] - x[3 * i + a];
        dX[a] = X[3 * j + a] - X[3 * i + a];
    }
    return tlsph_link_stretch(dx, dX);
}

/* Acoustic impedance rho C = sqrt(E rho0 / J) of particle i (eq. 38), kg/(m^2 s). */
double tlsph_link_impedance(const struct tlsph_model *m, size_t i);

/* A criterion's update (link_criterion.h): NAME(m) raises each link once (from
 * the row of its lower index) to min(1, VALUE(m, ls, i, j)) and copies it to
 * the other entry; returns the broken links.  VALUE is a static inline
 * function of the criterion's file, so the loop is plain.  Each link is written
 * by the thread of its lower index only. */
#define TLSPH_LINK_SWEEP(NAME, VALUE)                                                             \
    static size_t NAME(struct tlsph_model *m)                                                     \
    {                                                                                             \
        const size_t n = m->p.n;                                                                  \
        const int64_t *restrict start = m->pairs.start;                                           \
        const int32_t *restrict nbr = m->pairs.j;                                                 \
        const int64_t *restrict mirror = m->links->mirror;                                        \
        const struct tlsph_link_settings *ls = &m->scene.links;                                   \
        double *D = m->links->D;                                                                  \
        size_t broken = 0;                                                                        \
        _Pragma("omp parallel for schedule(static) reduction(+ : broken) if (n >= TLSPH_PARALLEL_MIN_ITEMS)") \
        for (size_t i = 0; i < n; i++)                                                            \
            for (int64_t k = start[i]; k < start[i + 1]; k++) {                                   \
                const size_t j = (size_t)nbr[k];                                                  \
                if (j < i)                                                                        \
                    continue;                                                                     \
                if (D[k] < 1.0) {                                                                 \
                    const double Dn = fmax(D[k], fmin(1.0, VALUE(m, ls, i, j)));                  \
                    D[k] = Dn;                                                                    \
                    D[mirror[k]] = Dn;                                                            \
                }                                                                                 \
                broken += D[k] >= 1.0;                                                            \
            }                                                                                     \
        return broken;                                                                            \
    }

/* The end of a criterion's file (link_<ID>.c, which defines its key table
 * `table` and its per-link `value`): its loop and its row, needing the plastic
 * strain tensor when PLASTIC is 1. */
#define TLSPH_LINK_ROW(ID, PLASTIC)                                                               \
    TLSPH_LINK_SWEEP(update, value)                                                               \
    const struct tlsph_link_criterion tlsph_link_##ID = {                                         \
        .name = #ID,                                                                              \
        .module = "link:" #ID,                                                                    \
        .keys = &table,                                                                           \
        .needs_plasticity = (PLASTIC),                                                            \
        .update = update,                                                                         \
    };

#endif
