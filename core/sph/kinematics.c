#include "sph/kinematics.h"

#include "sph/crack_treatment.h"
#include "sph/damage_aware.h"
#include "sph/pseudo_spring.h"
#include "util/parallel.h"

/* The gather of particle i, inlined with a constant variant into the loops
 * below (each with its own parallel region: a parallel loop is outlined before
 * inlining), so a scene without damage carries no per-pair damage branch. */
static inline __attribute__((always_inline)) void
gather_particle(struct tlsph_model *m, size_t i, double dt, const enum tlsph_approximation variant)
{
    const int damage_aware = variant == TLSPH_APPROX_DAMAGE_AWARE;
    const double *restrict X = m->p.X, *restrict x = m->p.x, *restrict v = m->p.v;
    const double *restrict D = m->p.damage;
    const int64_t *restrict start = m->pairs.start;
    const int32_t *restrict nbr = m->pairs.j;
    const double *restrict dw = m->pairs.dw;
    const double *restrict vol0 = m->p.vol0;
    if (damage_aware && D[i] >= 1.0) {
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
        const double g[3] = {s * d0, s * d1, s * d2};
        const double du0 = x[3 * j] - X[3 * j] - ui0, du1 = x[3 * j + 1] - X[3 * j + 1] - ui1,
                     du2 = x[3 * j + 2] - X[3 * j + 2] - ui2;
        double dv[3] = {v[3 * j] - vi0, v[3 * j + 1] - vi1, v[3 * j + 2] - vi2};
        G[0] += du0 * g[0]; G[1] += du0 * g[1]; G[2] += du0 * g[2];
        G[3] += du1 * g[0]; G[4] += du1 * g[1]; G[5] += du1 * g[2];
        G[6] += du2 * g[0]; G[7] += du2 * g[1]; G[8] += du2 * g[2];
        if (damage_aware)
            tlsph_damage_aware_transmit(dt, D[j], g, dv, Gc);
        Gd[0] += dv[0] * g[0]; Gd[1] += dv[0] * g[1]; Gd[2] += dv[0] * g[2];
        Gd[3] += dv[1] * g[0]; Gd[4] += dv[1] * g[1]; Gd[5] += dv[1] * g[2];
        Gd[6] += dv[2] * g[0]; Gd[7] += dv[2] * g[1]; Gd[8] += dv[2] * g[2];
    }
    if (damage_aware)
        tlsph_damage_aware_close(m->p.crack_gradient + 9 * i, Gc, G);
    tlsph_kinematics_finish(&m->p, i, dt, G, Gd);
}

static void gather_intact(struct tlsph_model *m, double dt)
{
    const size_t n = m->p.n;
#pragma omp parallel for schedule(static) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++)
        gather_particle(m, i, dt, TLSPH_APPROX_INTACT);
}

static void gather_damage_aware(struct tlsph_model *m, double dt)
{
    const size_t n = m->p.n;
#pragma omp parallel for schedule(static) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++)
        gather_particle(m, i, dt, TLSPH_APPROX_DAMAGE_AWARE);
}

/* One pass per crack treatment (sph/crack_treatment.h); the pseudo-spring
 * recomputes the correction matrices and has a pass of its own. */
static void (*const passes[TLSPH_APPROX_COUNT])(struct tlsph_model *, double) = {
    [TLSPH_APPROX_INTACT] = gather_intact,
    [TLSPH_APPROX_DAMAGE_AWARE] = gather_damage_aware,
    [TLSPH_APPROX_PSEUDO_SPRING] = tlsph_pseudo_spring_kinematics,
};

void tlsph_kinematics(struct tlsph_model *m, double dt)
{
    passes[m->crack->variant](m, dt);
}
