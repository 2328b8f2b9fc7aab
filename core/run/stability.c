/* The stability contract (cheap checks, run every scene.check_every steps and
 * before every output frame, so no frame ever holds garbage):
 *   - non-finite position, velocity, stress, plastic strain or temperature;
 *   - det F <= 0 (an inverted particle), recorded by the constitutive update;
 *   - a plastic return mapping that did not converge (value: how many points);
 *   - a particle faster than speed_limit_factor times the largest wave speed;
 *   - an energy balance (kinetic + internal + hourglass + viscous - external work
 *     - initial) larger than energy_tolerance times the largest energy seen.
 * The correction matrices L_i never change in TLSPH; their conditioning is
 * checked once at setup (see correction.c) and reported with the run. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "util/mat3.h"
#include "run/model.h"

static void add_id(struct tlsph_diagnostic *d, int64_t id)
{
    if (d->nids < sizeof d->ids / sizeof *d->ids)
        d->ids[d->nids++] = id;
}

static int fail(struct tlsph_model *m, struct tlsph_diagnostic *d, const char *quantity,
                double value, double limit)
{
    d->step = m->step;
    d->time = m->t;
    snprintf(d->quantity, sizeof d->quantity, "%s", quantity);
    d->value = value;
    d->limit = limit;
    char ids[160] = "";
    size_t len = 0;
    for (size_t k = 0; k < d->nids && len + 1 < sizeof ids; k++)
        len += (size_t)snprintf(ids + len, sizeof ids - len, "%s%lld", k ? "," : "",
                                (long long)d->ids[k]);
    snprintf(d->message, sizeof d->message,
             "numerically unstable at step %ld, t = %.6g s: %.40s = %.6g (limit %.6g), particles [%.80s]",
             d->step, d->time, quantity, value, limit, ids);
    return -1;
}

int tlsph_model_check(struct tlsph_model *m, struct tlsph_diagnostic *d)
{
    memset(d, 0, sizeof *d);
    const struct tlsph_particles *p = &m->p;

    for (size_t i = 0; i < p->n; i++) {
        int ok = 1;
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
        return fail(m, d, "non_finite", NAN, 0.0);

    if (m->inverted) {
        for (size_t i = 0; i < p->n && d->nids < 16; i++) {
            const double *F = p->F + 9 * i;
            if (p->damage && p->damage[i] >= 1.0)
                continue; /* failed particles are not checked (constitutive.c) */
            if (!(mat3_det(F) > 0.0))
                add_id(d, p->id[i]);
        }
        return fail(m, d, "det_F", m->min_detF, 0.0);
    }

    if (m->return_failures) {
        add_id(d, m->first_return_failure_id);
        return fail(m, d, "return_mapping", (double)m->return_failures, 0.0);
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
        return fail(m, d, "speed", worst, vmax);

    const struct tlsph_energy *e = &m->energy;
    const double balance = tlsph_energy_balance(e);
    if (e->scale > 0.0 && fabs(balance) > m->scene.energy_tolerance * e->scale)
        return fail(m, d, "energy_balance", fabs(balance) / e->scale, m->scene.energy_tolerance);
    return 0;
}
