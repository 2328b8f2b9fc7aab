#include "run/integrate.h"

#include <math.h>
#include <string.h>

#include "bc/boundary.h"
#include "contact/contact.h"
#include "material/constitutive.h"
#include "material/failure.h"
#include "rigid/rigid.h"
#include "sph/crack_treatment.h"
#include "sph/forces.h"
#include "sph/kinematics.h"
#include "util/clock.h"
#include "util/parallel.h"

/* The phases of a force evaluation, in order (the contract of each is above
 * tlsph_model_step). */
void tlsph_evaluate(struct tlsph_model *m, double dt)
{
    if (tlsph_kinematics_fusable(m)) {
        /* one region and one barrier for both phases (never a porous model,
         * whose constitutive phase is timed alone) */
        tlsph_constitutive_with_kinematics(m, dt);
    } else {
        tlsph_kinematics(m, dt);
        /* the phase timed as a whole (two clock reads a step), never per particle */
        const double t0 = tlsph_monotonic_seconds();
        tlsph_constitutive(m, dt);
        m->material_seconds += tlsph_monotonic_seconds() - t0;
    }
    tlsph_failure(m);
    if (m->crack->update) /* the treatment's own state: virtual links' damage */
        m->crack->update(m);
    const struct tlsph_force_power pw = tlsph_forces(m);
    if (m->contact)
        m->energy.contact -= dt * tlsph_contact_forces(m, dt);
    if (m->rigid) /* books its own work: contact, and external for driven bodies */
        tlsph_rigid_forces(m, dt);
    const double body_power = tlsph_boundary_forces(m);
    /* Work of the optional forces and body forces over the step, at the
     * half-step velocities: first order in dt, and these terms are small. */
    m->energy.hourglass -= dt * pw.hourglass;
    m->energy.viscous -= dt * pw.viscous;
    m->energy.external_work += dt * body_power;
}

double tlsph_stable_dt(const struct tlsph_model *m)
{
    return m->scene.fixed_dt > 0.0 ? m->scene.fixed_dt : m->scene.cfl * m->dt_cfl;
}

double tlsph_next_dt(const struct tlsph_model *m)
{
    double dt = tlsph_stable_dt(m);
    /* A step that would pass the frame time after next ends at the next one, so
     * that every frame time gets a frame (docs/output.md).  Only a step longer
     * than the frame interval can pass two, so a run whose steps are shorter
     * is never touched; validation refuses a fixed step longer than the
     * interval. */
    if (m->frame_interval > 0.0 && m->next_frame_time > m->t &&
        m->t + dt >= m->next_frame_time + m->frame_interval)
        dt = m->next_frame_time - m->t;
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
    if (m->rigid) /* the free rigid bodies' (translation and rotation) */
        ke += tlsph_rigid_kinetic_energy(m);
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

/* Kinetic and internal energy in one loop: tlsph_kinetic_energy and
 * tlsph_internal_energy with one parallel region and one barrier instead of
 * two.  The same static split and per-thread sums, so the same values bit for
 * bit. */
static void step_energies(struct tlsph_model *m, double *kinetic, double *internal)
{
    double ke = 0.0, ei = 0.0;
    const double *v = m->p.v, *mass = m->p.mass, *e = m->p.e;
#pragma omp parallel for schedule(static) reduction(+ : ke, ei) if (m->p.n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < m->p.n; i++) {
        ke += 0.5 * mass[i] *
              (v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]);
        ei += mass[i] * e[i];
    }
    if (m->rigid) /* as in tlsph_kinetic_energy */
        ke += tlsph_rigid_kinetic_energy(m);
    *kinetic = ke;
    *internal = ei;
}

/* One step, phase by phase: what each reads, writes, and books into the
 * energy account (m->energy; the balance is tlsph_energy_balance).
 *
 *   kick          v += dt/2 f/m                    reads f, mass; writes v; with rigid
 *                                                  bodies their momenta (rigid/rigid.h)
 *   constrain     BC velocities at t + dt/2        writes v of the groups; books the
 *                 (bc/boundary.h)                  supports' work (impulse x prescribed
 *                                                  mid-step velocity) into external_work
 *   walls         velocities into a wall limited   reads f; writes v; books the kinetic
 *                                                  energy of arrival into external_work
 *   drift         x += dt v, t += dt               reads v; writes x (and moves the rigid
 *                                                  bodies)
 *   evaluate (tlsph_evaluate), at the new positions with the half-step velocities:
 *     kinematics  F, Fdot by the crack treatment   reads x, v, D, P_tilde (old); writes F,
 *                 (sph/kinematics.h)               Fdot, crack_gradient (pseudo-spring:
 *                                                  Linv); e += first half of dt P:Fdot/rho0
 *     stress      the point update of every        reads F, Fdot, e, history; writes sigma,
 *                 particle                         P_tilde, history (eps_p, D, T, ...), e +=
 *                 (material/constitutive.h)        second half; books plastic_work and
 *                                                  damage_work; records dt_cfl, the wave
 *                                                  speed, inverted and non-converged points
 *     failure     failed particles                 reads D, Fdot, P_tilde; writes sigma,
 *                 (material/failure.h)             P_tilde, v of those just failed; books
 *                                                  their arrested kinetic energy into
 *                                                  external_work; records m->failed
 *     links       only with virtual links          reads F, plastic strain, x; raises D_ij
 *                 (sph/virtual_links.h)            by the scene's link criterion
 *     forces      pair forces (sph/forces.h)       reads x, v, F, P_tilde, D; writes f,
 *                                                  f_hourglass, f_viscous; books the work
 *                                                  against them into hourglass, viscous
 *     contact     only with a contact block        reads x, v; searches again when a
 *                 (contact/contact.h)              particle moved half the skin; adds to
 *                                                  f; lowers dt_cfl; books the work against
 *                                                  the contact forces into contact
 *     rigid       only with rigid bodies           reads x, v, the bodies' state; adds to f;
 *                 (rigid/rigid.h)                  sets the bodies' reactions; lowers dt_cfl;
 *                                                  books the interface's work into contact,
 *                                                  a driven body's into external_work
 *     body forces (bc/boundary.h)                  writes f; books their work into
 *                                                  external_work
 *   kick          v += dt/2 f/m                    as above
 *   constrain     BC velocities at t + dt          as above
 *   end step      reactions from the impulses      writes the groups' reactions
 *   energies      kinetic and internal energy      writes energy.kinetic, .internal, .scale
 *
 * Step 0 (tlsph_start) is constrain at t = 0 (no work: it defines the initial
 * state), evaluate with dt = 0 and the energies. */
void tlsph_model_step(struct tlsph_model *m)
{
    const double dt = tlsph_next_dt(m);
    m->dt = dt;
    kick(m, 0.5 * dt);
    if (m->rigid)
        tlsph_rigid_kick(m, 0.5 * dt, m->t + 0.5 * dt);
    tlsph_boundary_constrain(m, m->t + 0.5 * dt, m->t + 0.5 * dt);
    tlsph_boundary_before_drift(m, dt);
    drift(m, dt);
    if (m->rigid)
        tlsph_rigid_drift(m, m->t, dt);
    m->t += dt;
    tlsph_evaluate(m, dt);
    kick(m, 0.5 * dt);
    if (m->rigid)
        tlsph_rigid_kick(m, 0.5 * dt, m->t);
    tlsph_boundary_constrain(m, m->t, m->t - 0.5 * dt);
    tlsph_boundary_end_step(m, dt);
    m->step++;

    struct tlsph_energy *e = &m->energy;
    step_energies(m, &e->kinetic, &e->internal);
    const double size = fabs(e->kinetic) + fabs(e->internal) + fabs(e->external_work) +
                        fabs(e->hourglass) + fabs(e->viscous) + fabs(e->contact);
    if (size > e->scale)
        e->scale = size;
}

void tlsph_start(struct tlsph_model *m)
{
    /* constraints first: they define the initial state, their impulses are no work */
    tlsph_boundary_constrain(m, 0.0, 0.0);
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        memset(m->groups[k].impulse, 0, sizeof m->groups[k].impulse);
        memset(m->groups[k].torque_impulse, 0, sizeof m->groups[k].torque_impulse);
    }
    m->energy.external_work = 0.0;
    tlsph_evaluate(m, 0.0); /* the forces of the first half kick */
    struct tlsph_energy *e = &m->energy;
    e->kinetic = tlsph_kinetic_energy(m);
    e->internal = tlsph_internal_energy(m);
    e->initial = e->kinetic + e->internal;
    e->scale = fabs(e->initial);
    m->dt = tlsph_next_dt(m);
}
