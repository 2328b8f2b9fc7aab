#include "sph/kinematics.h"

#include "sph/crack_treatment.h"
#include "sph/damage_aware.h"
#include "sph/pseudo_spring.h"
#include "sph/virtual_links.h"
#include "util/parallel.h"

/* A sum of outer products a (x) b (row-major 3x3) kept in two-double vectors:
 * (0 1) (3 4) (6 7) (2 5) and 8 alone, so that a pair's nine products and
 * sums take five vector operations of each kind instead of nine scalar ones.
 * Every entry gets exactly the scalar rounding (a_r b_c, then the sum in pair
 * order), so the result is the same bit for bit. */
typedef double v2d __attribute__((vector_size(16)));
struct outer9 {
    v2d r0, r1, r2, c2; /* (0 1), (3 4), (6 7), (2 5) */
    double e8;
};

static inline __attribute__((always_inline)) void outer9_add(struct outer9 *S, const double a[3],
                                                             const double b[3])
{
    const v2d b01 = {b[0], b[1]};
    S->r0 += a[0] * b01;
    S->r1 += a[1] * b01;
    S->r2 += a[2] * b01;
    S->c2 += (v2d){a[0], a[1]} * b[2];
    S->e8 += a[2] * b[2];
}

static inline void outer9_get(const struct outer9 *S, double M[9])
{
    M[0] = S->r0[0], M[1] = S->r0[1], M[2] = S->c2[0];
    M[3] = S->r1[0], M[4] = S->r1[1], M[5] = S->c2[1];
    M[6] = S->r2[0], M[7] = S->r2[1], M[8] = S->e8;
}

/* The gather of particle i, inlined with a constant variant into the loops
 * below (each with its own parallel region: a parallel loop is outlined before
 * inlining), so a scene without damage carries no per-pair damage branch. */
static inline __attribute__((always_inline)) void
gather_particle(struct tlsph_model *m, size_t i, double dt, const enum tlsph_approximation variant)
{
    const int damage_aware = variant == TLSPH_APPROX_DAMAGE_AWARE;
    /* virtual links: the same history as damage_aware, with the link's D_ij */
    const int links = variant == TLSPH_APPROX_VIRTUAL_LINKS;
    const double *restrict Dlink = links ? m->links->D : NULL;
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
    const struct tlsph_gather_origin o = tlsph_gather_origin(&m->p, i);
    struct outer9 G = {0}, Gd = {0};
    double Gc[9] = {0};
    for (int64_t k = start[i]; k < start[i + 1]; k++) {
        const size_t j = (size_t)nbr[k];
        struct tlsph_pair_delta q = tlsph_pair_delta(&m->p, &o, j);
        const double s = vol0[j] * dw[k];
        const double g[3] = {s * q.d[0], s * q.d[1], s * q.d[2]};
        outer9_add(&G, q.du, g);
        if (damage_aware)
            tlsph_damage_aware_transmit(dt, D[j], g, q.dv, Gc);
        if (links)
            tlsph_damage_aware_transmit(dt, Dlink[k], g, q.dv, Gc);
        outer9_add(&Gd, q.dv, g);
    }
    double Gs[9], Gds[9];
    outer9_get(&G, Gs);
    outer9_get(&Gd, Gds);
    if (damage_aware || links)
        tlsph_damage_aware_close(m->p.crack_gradient + 9 * i, Gc, Gs);
    tlsph_kinematics_finish(&m->p, i, dt, Gs, Gds);
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

static void gather_virtual_links(struct tlsph_model *m, double dt)
{
    const size_t n = m->p.n;
#pragma omp parallel for schedule(static) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++)
        gather_particle(m, i, dt, TLSPH_APPROX_VIRTUAL_LINKS);
}

/* One pass per crack treatment (sph/crack_treatment.h); the pseudo-spring
 * recomputes the correction matrices and has a pass of its own. */
static void (*const passes[TLSPH_APPROX_COUNT])(struct tlsph_model *, double) = {
    [TLSPH_APPROX_INTACT] = gather_intact,
    [TLSPH_APPROX_DAMAGE_AWARE] = gather_damage_aware,
    [TLSPH_APPROX_PSEUDO_SPRING] = tlsph_pseudo_spring_kinematics,
    [TLSPH_APPROX_VIRTUAL_LINKS] = gather_virtual_links,
};

/* The calling thread's share (kinematics.h): no parallel region of their own
 * and no barrier at the end. */
static void for_intact(struct tlsph_model *m, size_t lo, size_t hi, double dt)
{
    size_t a, b;
    tlsph_static_share(lo, hi, &a, &b);
    for (size_t i = a; i < b; i++)
        gather_particle(m, i, dt, TLSPH_APPROX_INTACT);
}

static void for_virtual_links(struct tlsph_model *m, size_t lo, size_t hi, double dt)
{
    size_t a, b;
    tlsph_static_share(lo, hi, &a, &b);
    for (size_t i = a; i < b; i++)
        gather_particle(m, i, dt, TLSPH_APPROX_VIRTUAL_LINKS);
}

int tlsph_kinematics_fusable(const struct tlsph_model *m)
{
    const enum tlsph_approximation v = m->crack->variant;
    const size_t nb = m->scene.nbodies;
    return (v == TLSPH_APPROX_INTACT || v == TLSPH_APPROX_VIRTUAL_LINKS) && !m->p.void_fraction &&
           nb > 0 && m->body_begin[0] == 0 && m->body_end[nb - 1] == m->p.n;
}

void tlsph_kinematics_for(struct tlsph_model *m, size_t lo, size_t hi, double dt)
{
    if (m->crack->variant == TLSPH_APPROX_VIRTUAL_LINKS)
        for_virtual_links(m, lo, hi, dt);
    else
        for_intact(m, lo, hi, dt);
}

void tlsph_kinematics(struct tlsph_model *m, double dt)
{
    passes[m->crack->variant](m, dt);
}
