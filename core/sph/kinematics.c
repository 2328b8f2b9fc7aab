#include "sph/kinematics.h"
#include "util/parallel.h"
#include "sph/pseudo_spring.h"

/* The gather of particle i, inlined with a constant with_damage into the two
 * loops below (each with its own parallel region: a parallel loop is outlined
 * before inlining), so undamaged scenes carry no per-pair damage branch. */
static inline __attribute__((always_inline)) void
gather_particle(struct tlsph_model *m, size_t i, double dt, const int with_damage)
{
    const double *restrict X = m->p.X, *restrict x = m->p.x, *restrict v = m->p.v;
    const double *restrict D = m->p.damage;
    double *restrict crack = m->p.crack_gradient;
    const int64_t *restrict start = m->pairs.start;
    const int32_t *restrict nbr = m->pairs.j;
    const double *restrict dw = m->pairs.dw;
    const double *restrict vol0 = m->p.vol0;
    if (with_damage && D[i] >= 1.0) {
        /* failed: carries no stress, so its gradients serve nothing */
        for (int a = 0; a < 9; a++)
            m->p.Fdot[9 * i + a] = 0.0;
        return;
    }
    const double Xi0 = X[3 * i], Xi1 = X[3 * i + 1], Xi2 = X[3 * i + 2];
    const double ui0 = x[3 * i] - Xi0, ui1 = x[3 * i + 1] - Xi1, ui2 = x[3 * i + 2] - Xi2;
    const double vi0 = v[3 * i], vi1 = v[3 * i + 1], vi2 = v[3 * i + 2];
    double G[9] = {0}, Gd[9] = {0}, Gc[9] = {0};
    for (int64_t k = start[i]; k < start[i + 1]; k++) {
        const size_t j = (size_t)nbr[k];
        const double d0 = X[3 * j] - Xi0, d1 = X[3 * j + 1] - Xi1, d2 = X[3 * j + 2] - Xi2;
        const double s = vol0[j] * dw[k];
        const double g0 = s * d0, g1 = s * d1, g2 = s * d2;
        const double du0 = x[3 * j] - X[3 * j] - ui0, du1 = x[3 * j + 1] - X[3 * j + 1] - ui1,
                     du2 = x[3 * j + 2] - X[3 * j + 2] - ui2;
        double dv0 = v[3 * j] - vi0, dv1 = v[3 * j + 1] - vi1, dv2 = v[3 * j + 2] - vi2;
        G[0] += du0 * g0; G[1] += du0 * g1; G[2] += du0 * g2;
        G[3] += du1 * g0; G[4] += du1 * g1; G[5] += du1 * g2;
        G[6] += du2 * g0; G[7] += du2 * g1; G[8] += du2 * g2;
        if (with_damage && D[j] > 0.0) {
            /* eq. 33: j transmits (1 - D_j) of the velocity difference; the
             * rest of this step's displacement difference, dt D_j dv (the
             * drift moved every particle by dt v), is the crack's opening */
            const double c = dt * D[j];
            Gc[0] += c * dv0 * g0; Gc[1] += c * dv0 * g1; Gc[2] += c * dv0 * g2;
            Gc[3] += c * dv1 * g0; Gc[4] += c * dv1 * g1; Gc[5] += c * dv1 * g2;
            Gc[6] += c * dv2 * g0; Gc[7] += c * dv2 * g1; Gc[8] += c * dv2 * g2;
            const double w = 1.0 - D[j];
            dv0 *= w;
            dv1 *= w;
            dv2 *= w;
        }
        Gd[0] += dv0 * g0; Gd[1] += dv0 * g1; Gd[2] += dv0 * g2;
        Gd[3] += dv1 * g0; Gd[4] += dv1 * g1; Gd[5] += dv1 * g2;
        Gd[6] += dv2 * g0; Gd[7] += dv2 * g1; Gd[8] += dv2 * g2;
    }
    if (with_damage && crack) {
        /* eq. 34: F = I + (sum of transmitted displacement increments) L^-1 */
        double *ci = crack + 9 * i;
        for (int a = 0; a < 9; a++) {
            ci[a] += Gc[a];
            G[a] -= ci[a];
        }
    }
    tlsph_kinematics_finish(&m->p, i, dt, G, Gd);
}

static void gather_undamaged(struct tlsph_model *m, double dt)
{
    const size_t n = m->p.n;
#pragma omp parallel for schedule(static) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++)
        gather_particle(m, i, dt, 0);
}

static void gather_damage_aware(struct tlsph_model *m, double dt)
{
    const size_t n = m->p.n;
#pragma omp parallel for schedule(static) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++)
        gather_particle(m, i, dt, 1);
}

void tlsph_kinematics(struct tlsph_model *m, double dt)
{
    if (m->p.damage && m->scene.crack_treatment == TLSPH_CRACK_PSEUDO_SPRING)
        tlsph_pseudo_spring_kinematics(m, dt);
    else if (m->p.damage)
        gather_damage_aware(m, dt);
    else
        gather_undamaged(m, dt);
}
