#include "run/integrate.h"

#include <math.h>

#include "bc/boundary.h"
#include "material/constitutive.h"
#include "sph/forces.h"
#include "sph/kinematics.h"
#include "util/parallel.h"

void tlsph_evaluate(struct tlsph_model *m, double dt)
{
    tlsph_kinematics(m, dt);
    tlsph_constitutive(m, dt);
    const struct tlsph_force_power pw = tlsph_forces(m);
    const double body_power = tlsph_boundary_forces(m);
    /* Work of the optional forces and body forces over the step, at the
     * half-step velocities: first order in dt, and these terms are small. */
    m->energy.hourglass -= dt * pw.hourglass;
    m->energy.viscous -= dt * pw.viscous;
    m->energy.external_work += dt * body_power;
}

double tlsph_next_dt(const struct tlsph_model *m)
{
    double dt = m->scene.fixed_dt > 0.0 ? m->scene.fixed_dt : m->scene.cfl * m->dt_cfl;
    const double left = m->scene.end_time - m->t;
    if (left > 0.0 && dt > left)
        dt = left;
    return dt;
}

static void kick(struct tlsph_model *m, double half)
{
    const size_t n = m->p.n;
    double *restrict v = m->p.v;
    const double *restrict f = m->p.f, *restrict mass = m->p.mass;
#pragma omp parallel for schedule(static) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++) {
        const double s = half / mass[i];
        v[3 * i] += s * f[3 * i];
        v[3 * i + 1] += s * f[3 * i + 1];
        v[3 * i + 2] += s * f[3 * i + 2];
    }
}

static void drift(struct tlsph_model *m, double dt)
{
    const size_t n3 = 3 * m->p.n;
    double *restrict x = m->p.x;
    const double *restrict v = m->p.v;
#pragma omp parallel for schedule(static) if (n3 >= 3 * TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t k = 0; k < n3; k++)
        x[k] += dt * v[k];
}

double tlsph_kinetic_energy(const struct tlsph_model *m)
{
    double ke = 0.0;
    const double *v = m->p.v;
#pragma omp parallel for schedule(static) reduction(+ : ke) if (m->p.n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < m->p.n; i++)
        ke += 0.5 * m->p.mass[i] *
              (v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]);
    return ke;
}

double tlsph_internal_energy(const struct tlsph_model *m)
{
    double ei = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : ei) if (m->p.n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < m->p.n; i++)
        ei += m->p.mass[i] * m->p.e[i];
    return ei;
}

void tlsph_model_step(struct tlsph_model *m)
{
    const double dt = tlsph_next_dt(m);
    m->dt = dt;
    kick(m, 0.5 * dt);
    tlsph_boundary_constrain(m, m->t + 0.5 * dt, m->t + 0.5 * dt);
    tlsph_boundary_before_drift(m, dt);
    drift(m, dt);
    m->t += dt;
    tlsph_evaluate(m, dt);
    kick(m, 0.5 * dt);
    tlsph_boundary_constrain(m, m->t, m->t - 0.5 * dt);
    tlsph_boundary_end_step(m, dt);
    m->step++;

    struct tlsph_energy *e = &m->energy;
    e->kinetic = tlsph_kinetic_energy(m);
    e->internal = tlsph_internal_energy(m);
    const double size = fabs(e->kinetic) + fabs(e->internal) + fabs(e->external_work) +
                        fabs(e->hourglass) + fabs(e->viscous);
    if (size > e->scale)
        e->scale = size;
}
