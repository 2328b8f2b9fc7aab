/* "wall": a rigid, fixed, frictionless, impenetrable plane; the normal points
 * into the solid.  It is a one-sided constraint on every particle (no group).
 *
 * A particle resting on a wall is held like a symmetry-plane particle: after
 * every kick its velocity into the wall is removed, and that impulse does no
 * work (the wall does not move).  A particle arriving at a wall is stopped
 * inelastically on it, and the kinetic energy of the normal velocity it
 * arrived with is booked as (negative) work of the wall.  The stop takes two
 * hooks of one step: before the drift, stop_at_wall limits the normal velocity
 * to vmin = -gap/dt so that the drift ends on the wall, booking
 * m (vmin^2 - vn0^2) / 2; after the second kick, hold_on_wall removes what is
 * left, booking the m vmin^2 / 2 of the drift velocity.  Together:
 * m vn0^2 / 2, all the normal kinetic energy (one particle alone: exactly).
 *
 * Both hooks book the normal velocity a particle had before the kick just
 * made (vn0 before the drift, vmin after it), never the kick's own part: the
 * velocity a kick adds to a particle pressed against the wall is an artefact
 * of the half-step splitting (its kinetic energy appears in no full-step
 * state), and booking it would drift the energy balance by m (dt a)^2 / 2 per
 * resting particle and step (measured: 4 % of the impact energy of a Taylor
 * bar).  A resting particle enters each kick with no velocity into the wall,
 * so holding it books nothing.  (Booking in the first hook only left
 * m vmin^2 / 2 per arriving particle unbooked: 0.69 of the energy of a cube's
 * arriving layer, enough for a false "unstable" on energy_balance.) */
#include "bc/kind.h"
#include "bc/plane.h"
#include "run/model.h"
#include "util/parallel.h"

/* Distance below which a particle is on a wall: round-off of the drift that
 * ended on it, relative to the body's spacing. */
#define WALL_CONTACT 1e-9

/* (x - point) x normal, m: the torque about the wall's point of a unit push
 * along the normal at x.  The reaction's torque is the sum of these weighted
 * by each particle's impulse (the wall pushes along its normal only). */
static inline void lever(const struct tlsph_bc *bc, const double *x, double arm[3])
{
    const double r0 = x[0] - bc->point[0], r1 = x[1] - bc->point[1], r2 = x[2] - bc->point[2];
    const double *n = bc->normal;
    arm[0] = r1 * n[2] - r2 * n[1];
    arm[1] = r2 * n[0] - r0 * n[2];
    arm[2] = r0 * n[1] - r1 * n[0];
}

static int parse(const json_t *obj, struct tlsph_scene *s, struct tlsph_bc *bc,
                 const char *pointer, struct tlsph_errors *err)
{
    return tlsph_plane_parse(obj, s, bc, pointer, err);
}

/* Particles on the wall lose their velocity into it.  What the kick just made
 * added is held without work; the normal velocity a particle had before that
 * kick ends its arrival, and its kinetic energy is booked as the wall's work. */
static void hold_on_wall(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                         double t, double t_mid, double *work)
{
    (void)t, (void)t_mid;
    const double *nn = bc->normal;
    /* the kick just made was half the step (0 at setup, where m->dt is still 0) */
    const double half = 0.5 * m->dt;
    double lost = 0.0, imp0 = 0.0, imp1 = 0.0, imp2 = 0.0, ang0 = 0.0, ang1 = 0.0, ang2 = 0.0;
#pragma omp parallel for schedule(static) \
    reduction(+ : lost, imp0, imp1, imp2, ang0, ang1, ang2) if (m->p.n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < m->p.n; i++) {
        const double tol = WALL_CONTACT * tlsph_particle_spacing(m, i);
        if (tlsph_plane_distance(bc, m->p.x + 3 * i) > tol)
            continue;
        double *v = m->p.v + 3 * i;
        const double vn = v[0] * nn[0] + v[1] * nn[1] + v[2] * nn[2];
        if (vn >= 0.0)
            continue;
        const double mi = m->p.mass[i];
        const double *f = m->p.f + 3 * i;
        const double vn0 = vn - half * (f[0] * nn[0] + f[1] * nn[1] + f[2] * nn[2]) / mi;
        if (vn0 < 0.0)
            lost += 0.5 * mi * vn0 * vn0;
        for (int c = 0; c < 3; c++)
            v[c] -= vn * nn[c];
        imp0 -= mi * vn * nn[0];
        imp1 -= mi * vn * nn[1];
        imp2 -= mi * vn * nn[2];
        double arm[3];
        lever(bc, m->p.x + 3 * i, arm);
        ang0 -= mi * vn * arm[0];
        ang1 -= mi * vn * arm[1];
        ang2 -= mi * vn * arm[2];
    }
    g->impulse[0] += imp0;
    g->impulse[1] += imp1;
    g->impulse[2] += imp2;
    g->torque_impulse[0] += ang0;
    g->torque_impulse[1] += ang1;
    g->torque_impulse[2] += ang2;
    *work -= lost;
}

/* Limits the velocity of each particle heading for the wall so that the drift
 * of length dt ends on the wall at most. */
static void stop_at_wall(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                         double dt)
{
    const double *nn = bc->normal;
    double work = 0.0, imp0 = 0.0, imp1 = 0.0, imp2 = 0.0, ang0 = 0.0, ang1 = 0.0, ang2 = 0.0;
#pragma omp parallel for schedule(static) \
    reduction(+ : work, imp0, imp1, imp2, ang0, ang1, ang2) if (m->p.n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < m->p.n; i++) {
        double *v = m->p.v + 3 * i;
        const double gap = tlsph_plane_distance(bc, m->p.x + 3 * i);
        const double vn = v[0] * nn[0] + v[1] * nn[1] + v[2] * nn[2];
        /* the drift x += dt v must not end behind the wall */
        const double vmin = -gap / dt;
        if (vn < vmin) {
            const double mi = m->p.mass[i], dv = vmin - vn;
            const double *f = m->p.f + 3 * i;
            /* normal velocity before this step's kick: what really hit the wall */
            const double vn0 = vn - 0.5 * dt * (f[0] * nn[0] + f[1] * nn[1] + f[2] * nn[2]) / mi;
            if (vn0 < vmin)
                work += 0.5 * mi * (vmin * vmin - vn0 * vn0);
            v[0] += dv * nn[0];
            v[1] += dv * nn[1];
            v[2] += dv * nn[2];
            imp0 += mi * dv * nn[0];
            imp1 += mi * dv * nn[1];
            imp2 += mi * dv * nn[2];
            double arm[3];
            lever(bc, m->p.x + 3 * i, arm);
            ang0 += mi * dv * arm[0];
            ang1 += mi * dv * arm[1];
            ang2 += mi * dv * arm[2];
        }
    }
    g->impulse[0] += imp0;
    g->impulse[1] += imp1;
    g->impulse[2] += imp2;
    g->torque_impulse[0] += ang0;
    g->torque_impulse[1] += ang1;
    g->torque_impulse[2] += ang2;
    m->energy.external_work += work;
}

/* At t = 0 no particle may lie behind the wall: the wall cannot push a body
 * through itself (it would stop those particles' motion away from the plane
 * and pull the body apart: non-finite values within a few steps). */
static int check_sides(const struct tlsph_model *m, const struct tlsph_bc *bc, const char *pointer,
                       struct tlsph_errors *err)
{
    size_t behind = 0, deepest = 0;
    double depth = 0.0;
    for (size_t i = 0; i < m->p.n; i++) {
        const double tol = WALL_CONTACT * tlsph_particle_spacing(m, i);
        const double d = tlsph_plane_distance(bc, m->p.X + 3 * i);
        if (d >= -tol)
            continue;
        if (behind++ == 0 || d < depth) {
            depth = d;
            deepest = i;
        }
    }
    if (behind == 0)
        return 0;
    const double *X = m->p.X + 3 * deepest;
    tlsph_errors_add(err, pointer,
                     "wall '%s' cuts through body '%s' at t = 0: %zu particles lie behind its "
                     "plane (the deepest %.3g m behind, at (%g, %g, %g) m); the normal points "
                     "into the solid, so every body must start on that side (move the plane or "
                     "the body, or reverse the normal)",
                     bc->name, m->scene.bodies[m->p.body[deepest]].name, behind, -depth, X[0], X[1],
                     X[2]);
    return -1;
}

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_BC_KEYS,
    TLSPH_KEY_POINT("point", "a point of the wall's plane"),
    TLSPH_KEY_DIRECTION("normal", "normal of the plane, pointing into the solid; any non-zero "
                                  "length"),
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/boundary_conditions/*", "wall", keys);
/* clang-format on */

const struct tlsph_bc_kind tlsph_bc_wall = {
    .name = "wall",
    .module = "bc:wall",
    .carries_load = 0,
    .reports_torque = 1,
    .keys = &table,
    .parse = parse,
    /* no select: a wall has no particle group; it stops whichever particle reaches it */
    .check = check_sides,
    .constrain = hold_on_wall,
    .before_drift = stop_at_wall,
};
