/* The stability contract (cheap checks, run every scene.check_every steps and
 * before every output frame, so no frame ever holds garbage), in this order, so
 * that the first quantity to fail is a particle's own when it can be:
 *   - non-finite position, velocity, stress, specific internal energy, plastic
 *     strain, damage or temperature;
 *   - det F <= 0 (an inverted particle), recorded by the constitutive update;
 *   - a plastic return mapping that did not converge (value: how many points);
 *   - a particle faster than speed_limit_factor times the largest wave speed;
 *   - an energy balance (kinetic + internal + hourglass + viscous - external work
 *     - initial) larger than energy_tolerance times the largest energy seen.
 *     The balance is a sum over the bodies; it names the particles whose energy
 *     (kinetic + internal) changed most since t = 0: where a blow-up put its
 *     excess, or where a boundary took energy away.
 * Before every step, simulated time must advance (tlsph_time_check).  And the
 * writer refuses any value that is not finite (io/output/output.h): the run
 * then stops with this contract's diagnostic when it finds one, else with the
 * refused value's (tlsph_refusal_diagnostic).
 * The correction matrices L_i never change in TLSPH; their conditioning is
 * checked once at setup (see correction.c) and reported with the run. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact/contact.h"
#include "rigid/rigid.h"
#include "material/eos/eos.h"
#include "run/integrate.h"
#include "run/model.h"
#include "util/mat3.h"

#define NIDS (sizeof((struct tlsph_diagnostic *)0)->ids / sizeof(int64_t))

static void add_id(struct tlsph_diagnostic *d, int64_t id)
{
    if (d->nids < NIDS)
        d->ids[d->nids++] = id;
}

/* The NIDS particles of highest score, best first. */
struct ranking {
    size_t n;
    double score[NIDS];
    size_t index[NIDS];
};

static void rank(struct ranking *r, double score, size_t i)
{
    if (!(score == score))
        return; /* NaN: the non-finite check reports those */
    if (r->n == NIDS && score <= r->score[NIDS - 1])
        return;
    size_t k = r->n < NIDS ? r->n++ : NIDS - 1;
    for (; k > 0 && r->score[k - 1] < score; k--) {
        r->score[k] = r->score[k - 1];
        r->index[k] = r->index[k - 1];
    }
    r->score[k] = score;
    r->index[k] = i;
}

static void add_ranked(struct tlsph_diagnostic *d, const struct tlsph_model *m,
                       const struct ranking *r)
{
    for (size_t k = 0; k < r->n; k++)
        add_id(d, m->p.id[r->index[k]]);
}

static int failed_particle(const struct tlsph_particles *p, size_t i)
{
    return p->damage && p->damage[i] >= 1.0;
}

/* what: the finding, "<quantity> = <value> (limit <limit>)" when NULL; which:
 * what the particle list is, when not the offending particles themselves. */
static int fail(struct tlsph_model *m, struct tlsph_diagnostic *d, const char *quantity,
                double value, double limit, const char *what, const char *which)
{
    d->step = m->step;
    d->time = m->t;
    snprintf(d->quantity, sizeof d->quantity, "%s", quantity);
    d->value = value;
    d->limit = limit;
    char ids[160] = "", finding[96];
    size_t len = 0;
    for (size_t k = 0; k < d->nids && len + 1 < sizeof ids; k++)
        len += (size_t)snprintf(ids + len, sizeof ids - len, "%s%lld", k ? "," : "",
                                (long long)d->ids[k]);
    if (!what) {
        snprintf(finding, sizeof finding, "%.40s = %.6g (limit %.6g)", quantity, value, limit);
        what = finding;
    }
    snprintf(d->message, sizeof d->message,
             "numerically unstable at step %ld, t = %.6g s: %.90s, particles [%.80s]%s%.30s",
             d->step, d->time, what, ids, which ? " " : "", which ? which : "");
    return -1;
}

/* The particles whose energy changed most since t = 0: |m (e + v^2/2) - m v0^2/2|,
 * e starting at 0 and v0 the body's initial velocity at the particle (a
 * condition's velocity at t = 0 is not counted: a guess for those particles). */
static void largest_energy_change(struct tlsph_model *m, struct tlsph_diagnostic *d)
{
    const struct tlsph_particles *p = &m->p;
    struct ranking r = {0};
    for (size_t i = 0; i < p->n; i++) {
        struct tlsph_body *body = &m->scene.bodies[p->body[i]];
        const double *v = p->v + 3 * i;
        double v0[3];
        for (int c = 0; c < 3; c++) {
            struct tlsph_expr *ex = &body->initial_velocity[c];
            v0[c] = ex->evaluator ? tlsph_expr_eval(ex, p->X + 3 * i) : 0.0;
        }
        const double now = p->e[i] + 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        const double then = 0.5 * (v0[0] * v0[0] + v0[1] * v0[1] + v0[2] * v0[2]);
        rank(&r, p->mass[i] * fabs(now - then), i);
    }
    add_ranked(d, m, &r);
}

int tlsph_model_check(struct tlsph_model *m, struct tlsph_diagnostic *d)
{
    memset(d, 0, sizeof *d);
    const struct tlsph_particles *p = &m->p;

    for (size_t i = 0; i < p->n; i++) {
        int ok = isfinite(p->e[i]);
        for (int c = 0; c < 3; c++)
            ok &= isfinite(p->x[3 * i + c]) && isfinite(p->v[3 * i + c]);
        for (int c = 0; c < 6; c++)
            ok &= isfinite(p->sigma[6 * i + c]);
        if (p->eps_p)
            ok &= isfinite(p->eps_p[i]);
        if (p->damage)
            ok &= isfinite(p->damage[i]) && isfinite(p->damage_init[i]);
        if (p->T && m->scene.materials[m->scene.bodies[p->body[i]].material].thermal.enabled)
            ok &= isfinite(p->T[i]);
        if (!ok)
            add_id(d, p->id[i]);
    }
    if (d->nids)
        return fail(m, d, "non_finite", NAN, 0.0, NULL, NULL);

    if (m->inverted) {
        for (size_t i = 0; i < p->n && d->nids < NIDS; i++) {
            const double *F = p->F + 9 * i;
            if (failed_particle(p, i))
                continue; /* failed particles are not checked (constitutive.c) */
            if (!(mat3_det(F) > 0.0))
                add_id(d, p->id[i]);
        }
        return fail(m, d, "det_F", m->min_detF, 0.0, NULL, NULL);
    }

    if (m->return_failures) {
        add_id(d, m->first_return_failure_id);
        return fail(m, d, "return_mapping", (double)m->return_failures, 0.0, NULL, NULL);
    }

    /* without its candidates the contact forces are missing: the bodies would
     * pass through each other */
    if (m->contact && tlsph_contact_failed(m))
        return fail(m, d, "contact_search", 0.0, 0.0,
                    "the contact search ran out of memory", NULL);
    if (m->contact) {
        const double overlap = tlsph_contact_take_overlap(m);
        if (overlap > TLSPH_CONTACT_MAX_OVERLAP) {
            int64_t ids[2];
            tlsph_contact_deepest_pair(m, ids);
            for (int k = 0; k < 2; k++)
                if (ids[k] >= 0)
                    add_id(d, ids[k]);
            return fail(m, d, "contact_penetration", overlap, TLSPH_CONTACT_MAX_OVERLAP, NULL,
                        "(deepest pair now)");
        }
    }

    if (m->rigid && tlsph_rigid_failed(m))
        return fail(m, d, "rigid_search", 0.0, 0.0, "the rigid-body search ran out of memory",
                    NULL);
    if (m->rigid) {
        int64_t id;
        long body;
        const double overlap = tlsph_rigid_take_overlap(m, &id, &body);
        if (overlap > TLSPH_CONTACT_MAX_OVERLAP) {
            if (id >= 0)
                add_id(d, id);
            char what[96]; /* the particle (deepest now) and the body it is passing */
            snprintf(what, sizeof what, "overlap %.3g of R (limit %.3g) into rigid body '%.40s'",
                     overlap, TLSPH_CONTACT_MAX_OVERLAP, body >= 0 ? m->scene.rigid[body].name : "?");
            return fail(m, d, "rigid_penetration", overlap, TLSPH_CONTACT_MAX_OVERLAP, what,
                        "(deepest now)");
        }
    }

    const double vmax = m->scene.speed_limit_factor * m->max_wave_speed;
    double worst = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        const double *v = p->v + 3 * i;
        const double s = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (s > vmax) {
            add_id(d, p->id[i]);
            worst = fmax(worst, s);
        }
    }
    if (d->nids)
        return fail(m, d, "speed", worst, vmax, NULL, NULL);

    const struct tlsph_energy *e = &m->energy;
    const double balance = tlsph_energy_balance(e);
    if (e->scale > 0.0 && fabs(balance) > m->scene.energy_tolerance * e->scale) {
        largest_energy_change(m, d);
        return fail(m, d, "energy_balance", fabs(balance) / e->scale, m->scene.energy_tolerance,
                    NULL, "(largest energy change)");
    }
    return 0;
}

/* The stable step of particle i in its current state, before the CFL factor:
 * the "elastic" estimate of core/material/constitutive.c, recomputed from F and
 * e, to rank the particles that limit the step.  (The "tangent" estimate also
 * needs whether the point flowed in the step, and the viscous factor, the same
 * for neighbours at the same rate: ranking by this one names the same region.) */
static double particle_step(const struct tlsph_model *m, size_t i)
{
    const struct tlsph_particles *p = &m->p;
    const struct tlsph_body *body = &m->scene.bodies[p->body[i]];
    const struct tlsph_material *mat = &m->scene.materials[body->material];
    const double *F = p->F + 9 * i;
    const double J = mat3_det(F);
    if (!(J > 0.0))
        return 0.0;
    double C[9], lam[3], Q[9], pressure, K_t;
    mat3_mul_at(F, F, C);
    sym3_eigen(C, lam, Q);
    const double smin = sqrt(fmax(fmin(lam[0], fmin(lam[1], lam[2])), 0.0));
    mat->eos->pressure(mat, J, p->e[i], &pressure, &K_t);
    const double G43 = 4.0 / 3.0 * mat->shear_modulus;
    const double c = sqrt(fmax(K_t + G43, G43) * J / mat->density);
    const double *v = p->v + 3 * i;
    const double speed = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return tlsph_particle_spacing(m, i) * smin / (c + speed);
}

int tlsph_time_check(struct tlsph_model *m, struct tlsph_diagnostic *d)
{
    const double dt = tlsph_next_dt(m);
    const struct tlsph_scene *s = &m->scene;
    /* The projection counts at the step the physics allows: a step cut short to
     * meet a frame time or the end is no sign that time stalls. */
    const double stable = tlsph_stable_dt(m);
    /* the smallest step that advances t, and that ends the run within the limit */
    double limit = m->t > 0.0 ? nextafter(m->t, INFINITY) - m->t : 0.0;
    const double left = s->end_time - m->t, steps_left = (double)TLSPH_MAX_STEPS - (double)m->step;
    if (s->max_steps == 0)
        limit = fmax(limit, steps_left > 0.0 ? left / steps_left : INFINITY);
    const int advances = dt > 0.0 && isfinite(dt) && m->t + dt != m->t;
    if (advances &&
        (s->max_steps > 0 || (double)m->step + left / stable <= (double)TLSPH_MAX_STEPS))
        return 0;
    memset(d, 0, sizeof *d);
    if (s->fixed_dt == 0.0) {
        struct ranking r = {0};
        for (size_t i = 0; i < m->p.n; i++)
            if (!failed_particle(&m->p, i))
                rank(&r, -particle_step(m, i), i);
        add_ranked(d, m, &r);
    }
    return fail(m, d, "time_step", advances ? stable : dt, limit, NULL,
                d->nids ? "(limiting the step)" : NULL);
}

void tlsph_refusal_diagnostic(struct tlsph_model *m, const char *dataset, double value,
                              const int64_t *ids, size_t nids, struct tlsph_diagnostic *d)
{
    if (tlsph_model_check(m, d) != 0)
        return;
    memset(d, 0, sizeof *d);
    for (size_t k = 0; k < nids; k++)
        add_id(d, ids[k]);
    if (d->nids == 0)
        largest_energy_change(m, d); /* a sum (energy, momentum, a reaction) overflowed */
    char what[96];
    snprintf(what, sizeof what, "%s in %.70s", isnan(value) ? "NaN" : "Inf", dataset);
    fail(m, d, "non_finite_output", value, 0.0, what, nids ? NULL : "(largest energy change)");
}
