/* Particle-rigid contact (rigid.h; docs/contact.md "Rigid bodies").
 *
 * Law: the contact block's penalty law in its line form, against an
 * infinitely stiff body.  A particle of radius R = spacing/2 whose centre is
 * at signed distance d from the surface overlaps it by delta = R - d; the
 * normal force along the outward normal n is
 *   F_n = max(k delta + 2 zeta sqrt(m_i k) w_n, 0),  k = pi/4 E* w,
 * E* = E / (1 - nu^2) of the particle's material (1/E* = (1 - nu^2)/E + 0 for
 * a rigid partner), w = 2R (the particle's width) in 3-D and 1 m in 2-D, w_n
 * the speed of approach of the particle towards the surface (relative to the
 * surface's own velocity u = V + w x (x - c)).  m_i is the particle's mass
 * (the pair's reduced mass with a rigid partner).
 * Friction (Coulomb, mu): with the tangential relative velocity w_t, the
 * tangential force is -min(mu F_n, m_i |w_t| / dt) w_t/|w_t|: the force that
 * stops the sliding within the step (stick), capped by mu F_n (slip).  Its
 * work is part of the contact work, all dissipated.
 * Reaction: the body gets minus the sum of the particles' forces, and their
 * torque about c with the lever at the particle's centre, so that momentum
 * and angular momentum are exchanged exactly.
 *
 * Search: a particle is a candidate of body k when d < R + skin at the search
 * (a bounding-sphere test first, then the exact distance); a candidate list
 * stays valid while the particles moved at most d_p and the body's surface at
 * most d_b with d_p + d_b < skin (d is 1-Lipschitz in the point, and a
 * surface moving by d_b changes it by at most d_b); d_b = |c - c_s| +
 * theta reach, theta the angle turned since the search and reach the distance
 * from c of the farthest point that matters (the shape's extent; a plane: the
 * farthest particle at the search plus the skin).  One O(n) scan per body and
 * search, none in between: no n^2.
 *
 * Loops: one per shape, compiled from one always_inline body with the shape's
 * distance function (shapes.h), chosen once per body and evaluation.  Within a
 * body a particle appears once, so its loop runs in parallel without atomics;
 * the bodies follow one another. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rigid/shapes.h"
#include "rigid/state.h"
#include "run/model.h"
#include "util/clock.h"
#include "util/parallel.h"

/* The shape frame in the world now, R = Q axes (columns: the local axes). */
static void frame(const struct tlsph_rigid_body *k, double R[9])
{
    const double *Q = k->Q, *A = k->spec->axes;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            R[3 * i + j] = Q[3 * i] * A[j] + Q[3 * i + 1] * A[3 + j] + Q[3 * i + 2] * A[6 + j];
}

/* d and n (world) of x, with the shape's function dist (a constant wherever
 * this is inlined). */
static inline __attribute__((always_inline)) double
world_distance(double (*const dist)(const double *, const double *, double *),
               const struct tlsph_rigid_body *k, const double R[9], const double x[3], double n[3])
{
    const double r0 = x[0] - k->c[0], r1 = x[1] - k->c[1], r2 = x[2] - k->c[2];
    const double y[3] = {R[0] * r0 + R[3] * r1 + R[6] * r2, R[1] * r0 + R[4] * r1 + R[7] * r2,
                         R[2] * r0 + R[5] * r1 + R[8] * r2};
    double nl[3];
    const double d = dist(k->spec->size, y, nl);
    for (int c = 0; c < 3; c++)
        n[c] = R[3 * c] * nl[0] + R[3 * c + 1] * nl[1] + R[3 * c + 2] * nl[2];
    return d;
}

double tlsph_rigid_distance(const struct tlsph_rigid_body *k, const double x[3], double n[3])
{
    double R[9];
    frame(k, R);
    switch (k->spec->shape->id) {
    case TLSPH_RIGID_PLANE: return world_distance(rigid_plane_distance, k, R, x, n);
    case TLSPH_RIGID_BOX: return world_distance(rigid_box_distance, k, R, x, n);
    case TLSPH_RIGID_SPHERE: return world_distance(rigid_sphere_distance, k, R, x, n);
    case TLSPH_RIGID_CYLINDER: return world_distance(rigid_cylinder_distance, k, R, x, n);
    default: return world_distance(rigid_cone_distance, k, R, x, n);
    }
}

/* ------------------------------------------------------------------ search */

/* The angle of the rotation Q Q_s^T, rad. */
static double turned(const double Q[9], const double Qs[9])
{
    double tr = 0.0;
    for (int k = 0; k < 9; k++)
        tr += Q[k] * Qs[k]; /* trace(Q Qs^T) */
    const double c = 0.5 * (tr - 1.0);
    return acos(c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c));
}

static int push(struct tlsph_rigid *r, size_t at, int32_t i)
{
    if (at == r->cap) {
        const size_t cap = r->cap ? 2 * r->cap : 1024;
        int32_t *c = realloc(r->cand, cap * sizeof *c);
        if (!c)
            return -1;
        r->cand = c;
        r->cap = cap;
    }
    r->cand[at] = i;
    return 0;
}

int tlsph_rigid_search(struct tlsph_model *m, struct tlsph_rigid *r, int force)
{
    const size_t n = m->p.n;
    const double *x = m->p.x;
    if (!force) {
        double moved2 = 0.0;
        const double *xs = r->x_search;
#pragma omp parallel for schedule(static) reduction(max : moved2) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
        for (size_t i = 0; i < n; i++) {
            double d2 = 0.0;
            for (int c = 0; c < 3; c++)
                d2 += (x[3 * i + c] - xs[3 * i + c]) * (x[3 * i + c] - xs[3 * i + c]);
            moved2 = d2 > moved2 ? d2 : moved2;
        }
        double body = 0.0;
        for (size_t j = 0; j < r->nb; j++) {
            const struct tlsph_rigid_body *k = &r->b[j];
            double dc2 = 0.0;
            for (int c = 0; c < 3; c++)
                dc2 += (k->c[c] - k->c_search[c]) * (k->c[c] - k->c_search[c]);
            const double theta = turned(k->Q, k->Q_search);
            const double db = sqrt(dc2) + (theta > 0.0 ? theta * k->reach : 0.0);
            body = db > body ? db : body;
        }
        if (sqrt(moved2) + body < r->skin)
            return 0;
    }
    memcpy(r->x_search, x, 3 * n * sizeof *x);
    r->searches++;
    size_t at = 0;
    for (size_t j = 0; j < r->nb; j++) {
        struct tlsph_rigid_body *k = &r->b[j];
        memcpy(k->c_search, k->c, sizeof k->c);
        memcpy(k->Q_search, k->Q, sizeof k->Q);
        r->start[j] = (int64_t)at;
        const double near = k->extent + r->max_radius + r->skin;
        double far2 = 0.0;
        for (size_t i = 0; i < n; i++) {
            const double *xi = x + 3 * i;
            double d2 = 0.0;
            for (int c = 0; c < 3; c++)
                d2 += (xi[c] - k->c[c]) * (xi[c] - k->c[c]);
            far2 = d2 > far2 ? d2 : far2;
            if (d2 > near * near)
                continue;
            double nn[3];
            const double d = tlsph_rigid_distance(k, xi, nn);
            if (d < r->radius[m->p.body[i]] + r->skin && push(r, at++, (int32_t)i) != 0) {
                r->start[j + 1] = r->start[j]; /* nothing valid is left */
                for (size_t l = j + 1; l <= r->nb; l++)
                    r->start[l] = 0;
                return -1;
            }
        }
        k->reach = isfinite(k->extent) ? k->extent : sqrt(far2) + r->skin;
    }
    r->start[r->nb] = (int64_t)at;
    return 0;
}

/* ------------------------------------------------------------------ forces */

/* What one body's loop returns. */
struct rigid_sums {
    double F[3], T[3]; /* on the body */
    double dt2;        /* smallest m_i / k, s^2 */
    double overlap;    /* largest delta / R */
    size_t active;
};

/* Candidate a of body k: its contact force, added to the particle's force and
 * to r->f, and its reaction on the body into the partial sums s[0..5]
 * (force, torque). */
static inline __attribute__((always_inline)) void
rigid_particle(struct tlsph_model *m, struct tlsph_rigid *r, const struct tlsph_rigid_body *k,
               const double R[9], double (*const dist)(const double *, const double *, double *),
               double inv_dt, int64_t a, double s[6], double *dt2, double *deep, size_t *active)
{
    const double *restrict x = m->p.x, *restrict v = m->p.v;
    double *restrict f = m->p.f, *restrict fr = r->f;
    const size_t i = (size_t)r->cand[a];
    const double *xi = x + 3 * i;
    double n[3];
    const double d = world_distance(dist, k, R, xi, n);
    const int32_t b = m->p.body[i];
    const double Ri = r->radius[b];
    const double delta = Ri - d;
    if (delta <= 0.0)
        return;
    const double r0 = xi[0] - k->c[0], r1 = xi[1] - k->c[1], r2 = xi[2] - k->c[2];
    /* velocity relative to the surface there, u = V + W x r */
    const double w0 = v[3 * i] - (k->V[0] + k->W[1] * r2 - k->W[2] * r1);
    const double w1 = v[3 * i + 1] - (k->V[1] + k->W[2] * r0 - k->W[0] * r2);
    const double w2 = v[3 * i + 2] - (k->V[2] + k->W[0] * r1 - k->W[1] * r0);
    const double wn = w0 * n[0] + w1 * n[1] + w2 * n[2];
    const double kk = r->stiffness[b], mi = m->p.mass[i];
    double fn = kk * delta - 2.0 * k->spec->damping * sqrt(mi * kk) * wn;
    fn = fn > 0.0 ? fn : 0.0;
    double g0 = fn * n[0], g1 = fn * n[1], g2 = fn * n[2];
    const double mu = k->spec->friction;
    if (mu > 0.0) {
        const double t0 = w0 - wn * n[0], t1 = w1 - wn * n[1], t2 = w2 - wn * n[2];
        const double wt = sqrt(t0 * t0 + t1 * t1 + t2 * t2);
        if (wt > 0.0) {
            const double stick = mi * wt * inv_dt, slip = mu * fn;
            const double q = (stick < slip ? stick : slip) / wt;
            g0 -= q * t0;
            g1 -= q * t1;
            g2 -= q * t2;
        }
    }
    f[3 * i] += g0;
    f[3 * i + 1] += g1;
    f[3 * i + 2] += g2;
    fr[3 * i] += g0;
    fr[3 * i + 1] += g1;
    fr[3 * i + 2] += g2;
    s[0] -= g0;
    s[1] -= g1;
    s[2] -= g2;
    s[3] -= r1 * g2 - r2 * g1;
    s[4] -= r2 * g0 - r0 * g2;
    s[5] -= r0 * g1 - r1 * g0;
    const double t = mi / kk;
    *dt2 = t < *dt2 ? t : *dt2;
    const double depth = delta / Ri;
    *deep = depth > *deep ? depth : *deep;
    (*active)++;
}

typedef struct rigid_sums (*rigid_shape_loop)(struct tlsph_model *, struct tlsph_rigid *,
                                              const struct tlsph_rigid_body *, double);
/* One loop per shape, its distance function named in the loop body (the
 * OpenMP region is outlined per loop, so the call stays direct and inlined). */
/* clang-format off */
#define RIGID_LOOP(NAME, DIST)                                                                    \
    static struct rigid_sums NAME(struct tlsph_model *m, struct tlsph_rigid *r,                  \
                                  const struct tlsph_rigid_body *k, double inv_dt)                \
    {                                                                                             \
        double R[9];                                                                              \
        frame(k, R);                                                                              \
        const int64_t a0 = r->start[k - r->b], a1 = r->start[k - r->b + 1];                       \
        double F0 = 0.0, F1 = 0.0, F2 = 0.0, T0 = 0.0, T1 = 0.0, T2 = 0.0, dt2 = INFINITY;        \
        double deep = 0.0;                                                                        \
        size_t active = 0;                                                                        \
        _Pragma("omp parallel for schedule(static) reduction(+ : F0, F1, F2, T0, T1, T2, active) reduction(min : dt2) reduction(max : deep) if (a1 - a0 >= TLSPH_PARALLEL_MIN_ITEMS)") \
        for (int64_t a = a0; a < a1; a++) {                                                       \
            double s[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}, t = INFINITY, o = 0.0;                  \
            size_t n = 0;                                                                         \
            rigid_particle(m, r, k, R, DIST, inv_dt, a, s, &t, &o, &n);                           \
            F0 += s[0];                                                                           \
            F1 += s[1];                                                                           \
            F2 += s[2];                                                                           \
            T0 += s[3];                                                                           \
            T1 += s[4];                                                                           \
            T2 += s[5];                                                                           \
            dt2 = t < dt2 ? t : dt2;                                                              \
            deep = o > deep ? o : deep;                                                           \
            active += n;                                                                          \
        }                                                                                         \
        return (struct rigid_sums){{F0, F1, F2}, {T0, T1, T2}, dt2, deep, active};                \
    }
/* clang-format on */
RIGID_LOOP(plane_loop, rigid_plane_distance)
RIGID_LOOP(box_loop, rigid_box_distance)
RIGID_LOOP(sphere_loop, rigid_sphere_distance)
RIGID_LOOP(cylinder_loop, rigid_cylinder_distance)
RIGID_LOOP(cone_loop, rigid_cone_distance)
static const rigid_shape_loop loops[TLSPH_RIGID_SHAPES] = {
    [TLSPH_RIGID_PLANE] = plane_loop,   [TLSPH_RIGID_BOX] = box_loop,
    [TLSPH_RIGID_SPHERE] = sphere_loop, [TLSPH_RIGID_CYLINDER] = cylinder_loop,
    [TLSPH_RIGID_CONE] = cone_loop,
};

void tlsph_rigid_forces(struct tlsph_model *m, double dt)
{
    struct tlsph_rigid *r = m->rigid;
    const size_t n = m->p.n;
    const double t0 = tlsph_monotonic_seconds();
    if (tlsph_rigid_search(m, r, 0) != 0)
        r->failed = 1;
    memset(r->f, 0, 3 * n * sizeof *r->f);
    const double inv_dt = dt > 0.0 ? 1.0 / dt : INFINITY;
    double dt2 = INFINITY, body_power = 0.0, driven_power = 0.0;
    r->active = 0;
    for (size_t j = 0; j < r->nb; j++) {
        struct tlsph_rigid_body *k = &r->b[j];
        const struct rigid_sums s = loops[k->spec->shape->id](m, r, k, inv_dt);
        memcpy(k->F_old, k->F, sizeof k->F);
        memcpy(k->T_old, k->T, sizeof k->T);
        memcpy(k->F, s.F, sizeof k->F);
        memcpy(k->T, s.T, sizeof k->T);
        dt2 = s.dt2 < dt2 ? s.dt2 : dt2;
        r->max_overlap = s.overlap > r->max_overlap ? s.overlap : r->max_overlap;
        r->active += s.active;
        /* power of the particles' forces on the body at its half-step velocities */
        double p = 0.0;
        for (int c = 0; c < 3; c++)
            p += 0.5 * ((k->F[c] + k->F_old[c]) * k->V[c] + (k->T[c] + k->T_old[c]) * k->W[c]);
        body_power += p;
        if (!k->free)
            driven_power += p;
    }
    /* power of the bodies' forces on the particles, trapezoidal as the kicks */
    const double *restrict v = m->p.v, *restrict fr = r->f;
    double *restrict fo = r->f_old;
    double power = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : power) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++) {
        power += 0.5 * ((fr[3 * i] + fo[3 * i]) * v[3 * i] +
                        (fr[3 * i + 1] + fo[3 * i + 1]) * v[3 * i + 1] +
                        (fr[3 * i + 2] + fo[3 * i + 2]) * v[3 * i + 2]);
        fo[3 * i] = fr[3 * i];
        fo[3 * i + 1] = fr[3 * i + 1];
        fo[3 * i + 2] = fr[3 * i + 2];
    }
    /* The interface takes what neither side gained: stored in the overlaps
     * plus dissipated (damping, friction).  A prescribed body's driver supplies
     * what the particles push into it: external work. */
    m->energy.contact -= dt * (power + body_power);
    m->energy.external_work -= dt * driven_power;
    if (dt2 < INFINITY) {
        const double dtc = sqrt(dt2);
        m->dt_cfl = dtc < m->dt_cfl ? dtc : m->dt_cfl;
    }
    r->phase_seconds += tlsph_monotonic_seconds() - t0;
}
