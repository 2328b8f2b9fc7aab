#include "bc/boundary.h"
#include "util/parallel.h"

#include <math.h>
#include <stdlib.h>

static int selected(const struct tlsph_model *m, struct tlsph_selector *sel, size_t i)
{
    if (sel->body >= 0 && m->p.body[i] != sel->body)
        return 0;
    const double *X = m->p.X + 3 * i;
    if (sel->has_box)
        for (int c = 0; c < m->dim; c++)
            if (X[c] < sel->box_min[c] || X[c] > sel->box_max[c])
                return 0;
    if (sel->expression.evaluator)
        return tlsph_expr_eval(&sel->expression, X) != 0.0;
    return 1;
}

/* Symmetry planes without an explicit selector take the particles within half
 * a lattice spacing of the plane. */
static int on_plane(const struct tlsph_model *m, const struct tlsph_bc *bc, size_t i)
{
    const double *X = m->p.X + 3 * i, *n = bc->normal, *q = bc->point;
    const double d = (X[0] - q[0]) * n[0] + (X[1] - q[1]) * n[1] + (X[2] - q[2]) * n[2];
    return fabs(d) <= 0.5 * m->scene.bodies[m->p.body[i]].spacing * (1.0 + 1e-9);
}

int tlsph_boundary_select(struct tlsph_model *m, struct tlsph_errors *err)
{
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        struct tlsph_bc *bc = &m->scene.bcs[k];
        struct tlsph_group *g = &m->groups[k];
        if (bc->type == TLSPH_BC_WALL)
            continue;
        int explicit_sel = bc->select.body >= 0 || bc->select.has_box || bc->select.expression.evaluator;
        size_t count = 0;
        for (size_t i = 0; i < m->p.n; i++)
            count += bc->type == TLSPH_BC_SYMMETRY && !explicit_sel ? on_plane(m, bc, i)
                                                                    : selected(m, &bc->select, i);
        char ptr[64];
        snprintf(ptr, sizeof ptr, "/boundary_conditions/%zu", k);
        if (count == 0) {
            tlsph_errors_add(err, ptr, "boundary condition '%s' selects no particle", bc->name);
            return -1;
        }
        g->index = tlsph_alloc(m, count, sizeof *g->index);
        if (!g->index) {
            tlsph_errors_add(err, ptr, "out of memory");
            return -1;
        }
        for (size_t i = 0; i < m->p.n; i++)
            if (bc->type == TLSPH_BC_SYMMETRY && !explicit_sel ? on_plane(m, bc, i)
                                                              : selected(m, &bc->select, i)) {
                g->index[g->n++] = (int32_t)i;
                g->mass += m->p.mass[i];
            }
    }
    return 0;
}

/* Sets component c of particle i to value; the support's impulse does work at
 * the mid-step velocity v_mid of the prescribed motion: W = impulse * v_mid.
 * (Counting the kinetic energy the reset removes instead would book the
 * dt^2 |f|^2 / 4m that each half kick adds to a constrained particle as
 * external work, a bias that grows with the reaction force.) */
static inline void impose(struct tlsph_model *m, struct tlsph_group *g, size_t i, int c,
                          double value, double v_mid, double *work)
{
    double *v = m->p.v + 3 * i;
    const double dp = m->p.mass[i] * (value - v[c]);
    g->impulse[c] += dp;
    *work += dp * v_mid;
    v[c] = value;
}

/* Distance below which a particle is on a wall: round-off of the drift that
 * ended on it, relative to the body's spacing. */
#define WALL_CONTACT 1e-9

static double wall_gap(const struct tlsph_bc *bc, const double *x)
{
    const double *nn = bc->normal, *q = bc->point;
    return (x[0] - q[0]) * nn[0] + (x[1] - q[1]) * nn[1] + (x[2] - q[2]) * nn[2];
}

/* Particles on the wall lose their velocity into it; the fixed wall does no work. */
static void hold_on_wall(struct tlsph_model *m, const struct tlsph_bc *bc, struct tlsph_group *g)
{
    const double *nn = bc->normal;
    double imp0 = 0.0, imp1 = 0.0, imp2 = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : imp0, imp1, imp2) if (m->p.n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < m->p.n; i++) {
        const double tol = WALL_CONTACT * m->scene.bodies[m->p.body[i]].spacing;
        if (wall_gap(bc, m->p.x + 3 * i) > tol)
            continue;
        double *v = m->p.v + 3 * i;
        const double vn = v[0] * nn[0] + v[1] * nn[1] + v[2] * nn[2];
        if (vn >= 0.0)
            continue;
        const double mi = m->p.mass[i];
        for (int c = 0; c < 3; c++)
            v[c] -= vn * nn[c];
        imp0 -= mi * vn * nn[0];
        imp1 -= mi * vn * nn[1];
        imp2 -= mi * vn * nn[2];
    }
    g->impulse[0] += imp0;
    g->impulse[1] += imp1;
    g->impulse[2] += imp2;
}

void tlsph_boundary_constrain(struct tlsph_model *m, double t, double t_mid)
{
    double work = 0.0;
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        struct tlsph_bc *bc = &m->scene.bcs[k];
        struct tlsph_group *g = &m->groups[k];
        switch (bc->type) {
        case TLSPH_BC_FIXED:
            for (size_t a = 0; a < g->n; a++)
                for (int c = 0; c < 3; c++)
                    impose(m, g, (size_t)g->index[a], c, 0.0, 0.0, &work);
            break;
        case TLSPH_BC_VELOCITY: {
            double val[3], mid[3];
            for (int c = 0; c < 3; c++) {
                val[c] = bc->velocity_set[c] ? tlsph_expr_eval(&bc->velocity[c], &t) : 0.0;
                mid[c] = bc->velocity_set[c] ? tlsph_expr_eval(&bc->velocity[c], &t_mid) : 0.0;
            }
            for (size_t a = 0; a < g->n; a++)
                for (int c = 0; c < 3; c++)
                    if (bc->velocity_set[c])
                        impose(m, g, (size_t)g->index[a], c, val[c], mid[c], &work);
            break;
        }
        case TLSPH_BC_SYMMETRY: {
            /* the plane does not move: its impulse does no work */
            const double *nn = bc->normal;
            for (size_t a = 0; a < g->n; a++) {
                const size_t i = (size_t)g->index[a];
                double *v = m->p.v + 3 * i;
                const double vn = v[0] * nn[0] + v[1] * nn[1] + v[2] * nn[2];
                const double mi = m->p.mass[i];
                for (int c = 0; c < 3; c++) {
                    g->impulse[c] -= mi * vn * nn[c];
                    v[c] -= vn * nn[c];
                }
            }
            break;
        }
        case TLSPH_BC_WALL:
            hold_on_wall(m, bc, &m->groups[k]);
            break;
        case TLSPH_BC_BODY_FORCE:
            break;
        }
    }
    m->energy.external_work += work;
}

void tlsph_boundary_walls(struct tlsph_model *m, double dt)
{
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        const struct tlsph_bc *bc = &m->scene.bcs[k];
        if (bc->type != TLSPH_BC_WALL)
            continue;
        const double *nn = bc->normal;
        struct tlsph_group *g = &m->groups[k];
        double work = 0.0, imp0 = 0.0, imp1 = 0.0, imp2 = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : work, imp0, imp1, imp2) \
    if (m->p.n >= TLSPH_PARALLEL_MIN_ITEMS)
        for (size_t i = 0; i < m->p.n; i++) {
            double *v = m->p.v + 3 * i;
            const double gap = wall_gap(bc, m->p.x + 3 * i);
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
            }
        }
        g->impulse[0] += imp0;
        g->impulse[1] += imp1;
        g->impulse[2] += imp2;
        m->energy.external_work += work;
    }
}

double tlsph_boundary_body_forces(struct tlsph_model *m)
{
    double power = 0.0;
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        const struct tlsph_bc *bc = &m->scene.bcs[k];
        if (bc->type != TLSPH_BC_BODY_FORCE)
            continue;
        const struct tlsph_group *g = &m->groups[k];
        const double *acc = bc->acceleration;
        for (size_t a = 0; a < g->n; a++) {
            const size_t i = (size_t)g->index[a];
            const double mi = m->p.mass[i];
            const double *v = m->p.v + 3 * i;
            for (int c = 0; c < 3; c++)
                m->p.f[3 * i + c] += mi * acc[c];
            power += mi * (acc[0] * v[0] + acc[1] * v[1] + acc[2] * v[2]);
        }
    }
    return power;
}

void tlsph_boundary_end_step(struct tlsph_model *m, double dt)
{
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        struct tlsph_group *g = &m->groups[k];
        for (int c = 0; c < 3; c++) {
            g->reaction[c] = g->impulse[c] / dt;
            g->impulse[c] = 0.0;
        }
    }
}

void tlsph_boundary_displacements(struct tlsph_model *m)
{
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        struct tlsph_group *g = &m->groups[k];
        double u[3] = {0, 0, 0};
        for (size_t a = 0; a < g->n; a++) {
            const size_t i = (size_t)g->index[a];
            for (int c = 0; c < 3; c++)
                u[c] += m->p.x[3 * i + c] - m->p.X[3 * i + c];
        }
        for (int c = 0; c < 3; c++)
            g->displacement[c] = g->n ? u[c] / (double)g->n : 0.0;
    }
}
