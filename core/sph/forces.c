#include "sph/forces.h"

#include "sph/crack_treatment.h"
#include "sph/damage_aware.h"
#include "sph/hourglass.h"
#include "sph/pseudo_spring.h"
#include "sph/viscosity.h"
#include "sph/virtual_links.h"
#include "util/parallel.h"

struct body_constants {
    double hg_coeff;  /* alpha/2 E */
    double c, rho0;   /* wave speed m/s, density kg/m^3 */
    double beta1, beta2;
};

/* The weights of a pair's forces under each crack treatment (crack_treatment.h)
 * from the particles' damages D_i, D_j or the link's D_ij, called with a
 * constant variant: the switch folds away. */
static inline __attribute__((always_inline)) struct tlsph_pair_weights
pair_weights(const enum tlsph_approximation variant, double Di, double Dj, double Dij)
{
    switch (variant) {
    case TLSPH_APPROX_VIRTUAL_LINKS:
        return tlsph_virtual_links_force_weights(Dij);
    case TLSPH_APPROX_DAMAGE_AWARE:
        return tlsph_damage_aware_force_weights(Di, Dj);
    case TLSPH_APPROX_PSEUDO_SPRING:
        return tlsph_pseudo_spring_force_weights(Di, Dj);
    default:
        return (struct tlsph_pair_weights){.wi = 1.0, .wj = 1.0, .stab = 1.0};
    }
}

/* Two pairs in the two lanes of an SSE2 vector (GCC's vector extension; the
 * x86-64-v2 build has no wider one).  The compiler does not vectorise the
 * pair loop itself (a gather of the neighbour's data, and the ordered sums),
 * so the loop below gathers the data of pairs k and k+1 into lanes, computes
 * both pairs' contributions with packed operations, and adds them to the
 * particle's sums one after the other: every contribution gets exactly the
 * operations of the scalar loop, and the sums their order, so the forces are
 * the same bit for bit (-std=c11 contracts no multiply-add). */
typedef double v2d __attribute__((vector_size(16)));

static inline __attribute__((always_inline)) v2d lanes(const double *a, size_t o0, size_t o1)
{
    return (v2d){a[o0], a[o1]};
}

/* sum += v[0], then sum += v[1]: the scalar loop's order */
static inline __attribute__((always_inline)) void add_lanes(double *sum, v2d v)
{
    *sum += v[0];
    *sum += v[1];
}

/* sum += v[l] if the lane's pair has stabilisation (weight > 0; always
 * without a crack treatment): the scalar loop skips the other pairs */
static inline __attribute__((always_inline)) void add_stab_lanes(double *sum, v2d v, v2d stab)
{
    if (stab[0] > 0.0)
        *sum += v[0];
    if (stab[1] > 0.0)
        *sum += v[1];
}

/* Lane l of v, or +0.0 where mask is set: the 0 viscosity_pair() returns */
typedef long long v2l __attribute__((vector_size(16)));
static inline __attribute__((always_inline)) v2d zero_where(v2l mask, v2d v)
{
    return (v2d)((v2l)v & ~mask);
}

/* The sums over pairs k .. k_end - 1 of particle i into acc: the stress
 * force's f0 f1 f2, the hourglass's h0 h1 h2 and the viscosity's q0 q1 q2
 * (before the factors V_i and m_i).  Two pairs at a time with
 * hourglass_pair()'s and viscosity_pair()'s operations per lane (each square
 * root per lane), then the last pair of an odd count alone with the functions
 * themselves; the treatment's weights are taken per pair and packed (constant
 * 1 without a treatment: folded away). */
static inline __attribute__((always_inline)) void
pair_sums(const struct tlsph_model *m, size_t i, int64_t k, int64_t k_end,
          const struct body_constants *bc, const int with_hg, const int with_visc,
          const enum tlsph_approximation variant, double acc[9])
{
    /* particle damage (D_i, D_j), or link damage (D_ij): never both */
    const int with_damage =
        variant == TLSPH_APPROX_DAMAGE_AWARE || variant == TLSPH_APPROX_PSEUDO_SPRING;
    const int with_links = variant == TLSPH_APPROX_VIRTUAL_LINKS;
    const double *restrict Dlink = with_links ? m->links->D : NULL;
    const double *restrict D = m->p.damage;
    const double *restrict X = m->p.X, *restrict x = m->p.x, *restrict v = m->p.v;
    const double *restrict vol0 = m->p.vol0, *restrict mass = m->p.mass;
    const double *restrict Pt = m->p.P_tilde, *restrict F = m->p.F;
    const int32_t *restrict nbr = m->pairs.j;
    const double *restrict dw = m->pairs.dw, *restrict w = m->pairs.w;
    const double *restrict hs = m->p.hg_scale;
    const double *restrict hsm = m->p.h;
    const double Xi0 = X[3 * i], Xi1 = X[3 * i + 1], Xi2 = X[3 * i + 2];
    const double xi0 = x[3 * i], xi1 = x[3 * i + 1], xi2 = x[3 * i + 2];
    const double vi0 = v[3 * i], vi1 = v[3 * i + 1], vi2 = v[3 * i + 2];
    const double *Pi = Pt + 9 * i, *Fi = F + 9 * i;
    const double Di = with_damage ? D[i] : 0.0;
    const double hs_i = hs ? hs[i] : 1.0;
    const double neg_coeff = -bc->hg_coeff;
    for (; k + 1 < k_end; k += 2) {
        const size_t j0 = (size_t)nbr[k], j1 = (size_t)nbr[k + 1];
        const struct tlsph_pair_weights w0 =
            pair_weights(variant, Di, with_damage ? D[j0] : 0.0, with_links ? Dlink[k] : 0.0);
        const struct tlsph_pair_weights w1 = pair_weights(
            variant, Di, with_damage ? D[j1] : 0.0, with_links ? Dlink[k + 1] : 0.0);
        const v2d wi = {w0.wi, w1.wi}, wj = {w0.wj, w1.wj}, stab = {w0.stab, w1.stab};
        const v2d d0 = lanes(X, 3 * j0, 3 * j1) - Xi0;
        const v2d d1 = lanes(X, 3 * j0 + 1, 3 * j1 + 1) - Xi1;
        const v2d d2 = lanes(X, 3 * j0 + 2, 3 * j1 + 2) - Xi2;
        const v2d Vj = lanes(vol0, j0, j1);
        const v2d s = Vj * (v2d){dw[k], dw[k + 1]};
        v2d t[3];
        for (int r = 0; r < 3; r++) {
            const size_t a0 = 9 * j0 + 3 * r, a1 = 9 * j1 + 3 * r;
            t[r] = (wi * Pi[3 * r] + wj * lanes(Pt, a0, a1)) * d0 +
                   (wi * Pi[3 * r + 1] + wj * lanes(Pt, a0 + 1, a1 + 1)) * d1 +
                   (wi * Pi[3 * r + 2] + wj * lanes(Pt, a0 + 2, a1 + 2)) * d2;
        }
        add_lanes(&acc[0], s * t[0]);
        add_lanes(&acc[1], s * t[1]);
        add_lanes(&acc[2], s * t[2]);
        if (!with_hg && !with_visc)
            continue;
        const v2d x0 = lanes(x, 3 * j0, 3 * j1) - xi0;
        const v2d x1 = lanes(x, 3 * j0 + 1, 3 * j1 + 1) - xi1;
        const v2d x2 = lanes(x, 3 * j0 + 2, 3 * j1 + 2) - xi2;
        const v2d r2 = x0 * x0 + x1 * x1 + x2 * x2;
        const v2d R2 = d0 * d0 + d1 * d1 + d2 * d2;
        if (with_hg) {
            v2d p[3];
            for (int r = 0; r < 3; r++) {
                const size_t a0 = 9 * j0 + 3 * r, a1 = 9 * j1 + 3 * r;
                p[r] = (Fi[3 * r] + lanes(F, a0, a1)) * d0 +
                       (Fi[3 * r + 1] + lanes(F, a0 + 1, a1 + 1)) * d1 +
                       (Fi[3 * r + 2] + lanes(F, a0 + 2, a1 + 2)) * d2;
            }
            const v2d delta_over_r =
                ((p[0] - 2.0 * x0) * x0 + (p[1] - 2.0 * x1) * x1 + (p[2] - 2.0 * x2) * x2) / r2;
            const v2d hgp = neg_coeff * Vj * (v2d){w[k], w[k + 1]} / R2 * delta_over_r;
            const v2d stiff = hs ? 0.5 * (hs_i + lanes(hs, j0, j1)) : (v2d){1.0, 1.0};
            const v2d c = stab * stiff * hgp;
            add_stab_lanes(&acc[3], c * x0, stab);
            add_stab_lanes(&acc[4], c * x1, stab);
            add_stab_lanes(&acc[5], c * x2, stab);
        }
        if (with_visc) {
            const v2d vx = x0 * (lanes(v, 3 * j0, 3 * j1) - vi0) +
                           x1 * (lanes(v, 3 * j0 + 1, 3 * j1 + 1) - vi1) +
                           x2 * (lanes(v, 3 * j0 + 2, 3 * j1 + 2) - vi2);
            const v2d hij = 0.5 * (hsm[i] + lanes(hsm, j0, j1));
            const v2d mu = hij * vx / (r2 + 0.01 * hij * hij);
            const v2d pi = (-bc->beta1 * bc->c * mu + bc->beta2 * mu * mu) / bc->rho0;
            const v2d R = {sqrt(R2[0]), sqrt(R2[1])}, r = {sqrt(r2[0]), sqrt(r2[1])};
            const v2d q = lanes(mass, j0, j1) * pi * (v2d){dw[k], dw[k + 1]} * R / r;
            const v2d c = stab * zero_where(vx >= 0.0, q);
            add_stab_lanes(&acc[6], c * x0, stab);
            add_stab_lanes(&acc[7], c * x1, stab);
            add_stab_lanes(&acc[8], c * x2, stab);
        }
    }
    /* the last pair of an odd count: one at a time */
    for (; k < k_end; k++) {
        const size_t j = (size_t)nbr[k];
        const double d0 = X[3 * j] - Xi0, d1 = X[3 * j + 1] - Xi1, d2 = X[3 * j + 2] - Xi2;
        const double s = vol0[j] * dw[k];
        const double *Pj = Pt + 9 * j;
        /* weights of P_i and P_j, and of the stabilisation: the treatment's
         * (1 without damage); symmetric or swapped in i, j, so f_ij = -f_ji */
        const struct tlsph_pair_weights wt =
            pair_weights(variant, Di, with_damage ? D[j] : 0.0, with_links ? Dlink[k] : 0.0);
        const double wi = wt.wi, wj = wt.wj, pair = wt.stab;
        acc[0] += s * ((wi * Pi[0] + wj * Pj[0]) * d0 + (wi * Pi[1] + wj * Pj[1]) * d1 +
                       (wi * Pi[2] + wj * Pj[2]) * d2);
        acc[1] += s * ((wi * Pi[3] + wj * Pj[3]) * d0 + (wi * Pi[4] + wj * Pj[4]) * d1 +
                       (wi * Pi[5] + wj * Pj[5]) * d2);
        acc[2] += s * ((wi * Pi[6] + wj * Pj[6]) * d0 + (wi * Pi[7] + wj * Pj[7]) * d1 +
                       (wi * Pi[8] + wj * Pj[8]) * d2);
        /* stabilisation across a crack: scaled by the intact fractions of both */
        if ((with_hg || with_visc) && pair > 0.0) {
            const double x0 = x[3 * j] - xi0, x1 = x[3 * j + 1] - xi1, x2 = x[3 * j + 2] - xi2;
            if (with_hg) {
                /* the pair's modulus: the mean of both particles' (symmetric in
                 * i, j, so the force stays antisymmetric) */
                const double stiff = hs ? 0.5 * (hs_i + hs[j]) : 1.0;
                const double c = pair * stiff *
                                 hourglass_pair(bc->hg_coeff, vol0[j], w[k], Fi, F + 9 * j, d0,
                                                d1, d2, x0, x1, x2);
                acc[3] += c * x0;
                acc[4] += c * x1;
                acc[5] += c * x2;
            }
            if (with_visc) {
                const double R = sqrt(d0 * d0 + d1 * d1 + d2 * d2);
                /* the pair's symmetric smoothing length (the body's on a uniform lattice) */
                const double hij = 0.5 * (hsm[i] + hsm[j]);
                const double c =
                    pair * viscosity_pair(mass[j], hij, bc->c, bc->rho0, bc->beta1,
                                          bc->beta2, dw[k], R, x0, x1, x2, v[3 * j] - vi0,
                                          v[3 * j + 1] - vi1, v[3 * j + 2] - vi2);
                acc[6] += c * x0;
                acc[7] += c * x1;
                acc[8] += c * x2;
            }
        }
    }
}

/* The forces on particle i.  Always inlined into the variant loops below with
 * constant with_hg / with_visc / variant, so each variant's pair loop carries
 * no branch on the scene's choices (the OpenMP region must sit in the variant
 * itself: a parallel loop is outlined before inlining, and flags passed into
 * it would stay run-time values). */
static inline __attribute__((always_inline)) void
force_particle(struct tlsph_model *m, size_t i, const struct body_constants *bc, const int with_hg,
               const int with_visc, const enum tlsph_approximation variant, double *power_hg,
               double *power_visc)
{
    const int with_damage =
        variant == TLSPH_APPROX_DAMAGE_AWARE || variant == TLSPH_APPROX_PSEUDO_SPRING;
    const double *restrict v = m->p.v, *restrict vol0 = m->p.vol0, *restrict mass = m->p.mass;
    const int64_t *restrict start = m->pairs.start;
    double *restrict f = m->p.f;
    double *restrict f_hg = m->p.f_hourglass, *restrict f_visc = m->p.f_viscous;
    const double vi0 = v[3 * i], vi1 = v[3 * i + 1], vi2 = v[3 * i + 2];
    /* a failed particle (D = 1) neither exerts nor receives any pair force */
    const int64_t k_end = with_damage && m->p.damage[i] >= 1.0 ? start[i] : start[i + 1];
    double acc[9] = {0};
    pair_sums(m, i, start[i], k_end, bc, with_hg, with_visc, variant, acc);
    const double f0 = acc[0], f1 = acc[1], f2 = acc[2];
    double h0 = acc[3], h1 = acc[4], h2 = acc[5], q0 = acc[6], q1 = acc[7], q2 = acc[8];
    const double Vi = vol0[i];
    h0 *= Vi; h1 *= Vi; h2 *= Vi;
    q0 *= mass[i]; q1 *= mass[i]; q2 *= mass[i];
    f[3 * i] = Vi * f0 + h0 + q0;
    f[3 * i + 1] = Vi * f1 + h1 + q1;
    f[3 * i + 2] = Vi * f2 + h2 + q2;
    /* Trapezoidal power with the previous step's force: the same rule the
     * kicks apply to kinetic energy, so the energy balance closes. */
    if (with_hg) {
        double *o = f_hg + 3 * i;
        *power_hg += 0.5 * ((h0 + o[0]) * vi0 + (h1 + o[1]) * vi1 + (h2 + o[2]) * vi2);
        o[0] = h0;
        o[1] = h1;
        o[2] = h2;
    }
    if (with_visc) {
        double *o = f_visc + 3 * i;
        *power_visc += 0.5 * ((q0 + o[0]) * vi0 + (q1 + o[1]) * vi1 + (q2 + o[2]) * vi2);
        o[0] = q0;
        o[1] = q1;
        o[2] = q2;
    }
}

/* One parallel loop per combination of the optional terms and crack treatment. */
typedef void (*force_loop)(struct tlsph_model *, size_t, size_t, const struct body_constants *,
                           double *, double *);
#define FORCE_LOOP(NAME, HG, VISC, VARIANT)                                                       \
    static void NAME(struct tlsph_model *m, size_t lo, size_t hi,                                 \
                     const struct body_constants *bc, double *p_hg, double *p_visc)               \
    {                                                                                             \
        double hg = 0.0, visc = 0.0;                                                              \
        _Pragma("omp parallel for schedule(static) reduction(+ : hg, visc) if (hi - lo >= TLSPH_PARALLEL_MIN_ITEMS)") \
        for (size_t i = lo; i < hi; i++)                                                          \
            force_particle(m, i, bc, HG, VISC, VARIANT, &hg, &visc);                              \
        *p_hg += hg;                                                                              \
        *p_visc += visc;                                                                          \
    }
/* The same per particle for a list of rows (tlsph_forces_rows): the rows'
 * sums are those of the full pass bit for bit; the power is not wanted. */
typedef void (*force_rows_loop)(struct tlsph_model *, const size_t *, size_t,
                                const struct body_constants *);
#define FORCE_ROWS_LOOP(NAME, HG, VISC, VARIANT)                                                  \
    static void NAME(struct tlsph_model *m, const size_t *rows, size_t nrows,                     \
                     const struct body_constants *bc)                                             \
    {                                                                                             \
        double hg = 0.0, visc = 0.0;                                                              \
        _Pragma("omp parallel for schedule(static) reduction(+ : hg, visc) if (nrows >= TLSPH_PARALLEL_MIN_ITEMS)") \
        for (size_t r = 0; r < nrows; r++)                                                        \
            force_particle(m, rows[r], bc, HG, VISC, VARIANT, &hg, &visc);                        \
        (void)hg;                                                                                 \
        (void)visc;                                                                               \
    }
/* LOOP instantiated as P_<hg><visc>_<treatment> for every combination, and
 * the [crack treatment][hourglass][viscosity] table of them */
#define FORCE_LOOPS(LOOP, P, SUFFIX, VARIANT)                                                     \
    LOOP(P##_00_##SUFFIX, 0, 0, VARIANT)                                                          \
    LOOP(P##_01_##SUFFIX, 0, 1, VARIANT)                                                          \
    LOOP(P##_10_##SUFFIX, 1, 0, VARIANT)                                                          \
    LOOP(P##_11_##SUFFIX, 1, 1, VARIANT)
#define FORCE_ALL(LOOP, P)                                                                        \
    FORCE_LOOPS(LOOP, P, intact, TLSPH_APPROX_INTACT)                                             \
    FORCE_LOOPS(LOOP, P, damage_aware, TLSPH_APPROX_DAMAGE_AWARE)                                 \
    FORCE_LOOPS(LOOP, P, pseudo_spring, TLSPH_APPROX_PSEUDO_SPRING)                               \
    FORCE_LOOPS(LOOP, P, virtual_links, TLSPH_APPROX_VIRTUAL_LINKS)
/* [hourglass][viscosity] of one treatment */
#define FORCE_ROW(P, SUFFIX)                                                                      \
    {{P##_00_##SUFFIX, P##_01_##SUFFIX}, {P##_10_##SUFFIX, P##_11_##SUFFIX}}
#define FORCE_TABLE(P)                                                                            \
    {                                                                                             \
        [TLSPH_APPROX_INTACT] = FORCE_ROW(P, intact),                                             \
        [TLSPH_APPROX_DAMAGE_AWARE] = FORCE_ROW(P, damage_aware),                                 \
        [TLSPH_APPROX_PSEUDO_SPRING] = FORCE_ROW(P, pseudo_spring),                               \
        [TLSPH_APPROX_VIRTUAL_LINKS] = FORCE_ROW(P, virtual_links),                               \
    }
FORCE_ALL(FORCE_LOOP, loop)
FORCE_ALL(FORCE_ROWS_LOOP, rows)
static const force_loop force_loops[TLSPH_APPROX_COUNT][2][2] = FORCE_TABLE(loop);
static const force_rows_loop force_rows_loops[TLSPH_APPROX_COUNT][2][2] = FORCE_TABLE(rows);

static struct body_constants body_constants(const struct tlsph_scene *s, size_t b)
{
    const struct tlsph_material *mat = &s->materials[s->bodies[b].material];
    return (struct body_constants){
        .hg_coeff = 0.5 * s->hourglass_coefficient * mat->youngs_modulus,
        .c = mat->wave_speed,
        .rho0 = mat->density,
        .beta1 = s->viscosity_linear,
        .beta2 = s->viscosity_quadratic,
    };
}

void tlsph_forces_rows(struct tlsph_model *m, size_t body, const size_t *rows, size_t nrows)
{
    const struct tlsph_scene *s = &m->scene;
    const struct body_constants bc = body_constants(s, body);
    force_rows_loops[m->crack->variant][s->hourglass != 0][s->viscosity != 0](m, rows, nrows, &bc);
}

struct tlsph_force_power tlsph_forces(struct tlsph_model *m)
{
    struct tlsph_force_power pw = {0.0, 0.0};
    const struct tlsph_scene *s = &m->scene;
    for (size_t b = 0; b < s->nbodies; b++) {
        const struct body_constants bc = body_constants(s, b);
        const size_t lo = m->body_begin[b], hi = m->body_end[b];
        force_loops[m->crack->variant][s->hourglass != 0][s->viscosity != 0](
            m, lo, hi, &bc, &pw.hourglass, &pw.viscous);
    }
    return pw;
}
