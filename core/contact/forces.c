/* The contact phase (contact.h): search when needed, then one pair loop per
 * law variant (the penalty's two forms, the pin-ball), compiled from one
 * always_inline body with the variant as a constant, so no pair dispatches on
 * the scene's choices; the loop is picked once per evaluation.  Gather form:
 * each particle sums the forces of its own candidates, no atomics. */
#include <math.h>

#include "contact/penalty.h"
#include "contact/pinball.h"
#include "contact/state.h"
#include "run/model.h"
#include "util/clock.h"
#include "util/parallel.h"

/* What one loop returns, summed over its particles. */
struct contact_sums {
    double power;   /* trapezoidal power of the contact forces, W */
    double dt2;     /* smallest m* / k over the pairs in contact, s^2 */
    double overlap; /* largest overlap / (R_i + R_j), 1 */
    size_t active;  /* pairs in contact, each counted from both sides */
};

static inline __attribute__((always_inline)) void
contact_particle(struct tlsph_model *m, const struct tlsph_contact *c, size_t i,
                 const enum tlsph_contact_variant law, double inv_dt, struct contact_sums *sum)
{
    const double *restrict x = m->p.x, *restrict v = m->p.v, *restrict mass = m->p.mass;
    const int32_t *restrict body = m->p.body;
    const int64_t *restrict start = c->start;
    const int32_t *restrict cand = c->j;
    double *restrict f = m->p.f, *restrict f_old = c->f_old;
    const struct tlsph_contact_body *bi = &c->bodies[body[i]];
    const double xi0 = x[3 * i], xi1 = x[3 * i + 1], xi2 = x[3 * i + 2];
    const double vi0 = v[3 * i], vi1 = v[3 * i + 1], vi2 = v[3 * i + 2];
    const double mi = mass[i];
    double f0 = 0.0, f1 = 0.0, f2 = 0.0, dt2 = INFINITY, deepest = 0.0;
    size_t active = 0;
    double *restrict s_pair = c->s_pair;
    for (int64_t k = start[i]; k < start[i + 1]; k++) {
        const size_t j = (size_t)cand[k];
        s_pair[k] = 0.0;
        const struct tlsph_contact_body *bj = &c->bodies[body[j]];
        const double d0 = x[3 * j] - xi0, d1 = x[3 * j + 1] - xi1, d2 = x[3 * j + 2] - xi2;
        const double r2 = d0 * d0 + d1 * d1 + d2 * d2;
        double reach = bi->radius + bj->radius;
        if (body[j] == body[i]) /* two parts of one body (contact/state.h) */
            reach *= c->reach[i] < c->reach[j] ? c->reach[i] : c->reach[j];
        /* no direction at r = 0: such a pair pushes no way */
        if (r2 >= reach * reach || r2 == 0.0)
            continue;
        const double r = sqrt(r2);
        const double w0 = v[3 * j] - vi0, w1 = v[3 * j + 1] - vi1, w2 = v[3 * j + 2] - vi2;
        const double closing = w0 * d0 + w1 * d1 + w2 * d2; /* < 0: approaching */
        struct tlsph_contact_pair p;
        if (law != TLSPH_CONTACT_PINBALL)
            p = tlsph_penalty_pair(law == TLSPH_CONTACT_PENALTY_POINT, bi, bj, mi, mass[j],
                                   reach - r, -closing / r, c->params[TLSPH_PENALTY_DAMPING]);
        else
            p = tlsph_pinball_pair(bi, bj, reach - r, closing < 0.0,
                                   sqrt(w0 * w0 + w1 * w1 + w2 * w2), inv_dt,
                                   c->params[TLSPH_PINBALL_SCALE_FACTOR]);
        const double depth = (reach - r) / reach;
        deepest = depth > deepest ? depth : deepest;
        const double s = p.force / r;
        s_pair[k] = s;
        f0 -= s * d0;
        f1 -= s * d1;
        f2 -= s * d2;
        if (p.stiffness > 0.0) {
            const double t = mi * mass[j] / (mi + mass[j]) / p.stiffness;
            dt2 = t < dt2 ? t : dt2;
        }
        active++;
    }
    f[3 * i] += f0;
    f[3 * i + 1] += f1;
    f[3 * i + 2] += f2;
    double *o = f_old + 3 * i;
    sum->power += 0.5 * ((f0 + o[0]) * vi0 + (f1 + o[1]) * vi1 + (f2 + o[2]) * vi2);
    o[0] = f0;
    o[1] = f1;
    o[2] = f2;
    sum->dt2 = dt2 < sum->dt2 ? dt2 : sum->dt2;
    sum->overlap = deepest > sum->overlap ? deepest : sum->overlap;
    sum->active += active;
}

typedef struct contact_sums (*contact_loop)(struct tlsph_model *, const struct tlsph_contact *,
                                            double);
/* clang-format off */
#define CONTACT_LOOP(NAME, LAW)                                                                   \
    static struct contact_sums NAME(struct tlsph_model *m, const struct tlsph_contact *c,         \
                                    double inv_dt)                                                \
    {                                                                                             \
        const size_t n = m->p.n;                                                                  \
        double power = 0.0, dt2 = INFINITY, overlap = 0.0;                                        \
        size_t active = 0;                                                                        \
        _Pragma("omp parallel for schedule(static) reduction(+ : power, active) reduction(min : dt2) reduction(max : overlap) if (n >= TLSPH_PARALLEL_MIN_ITEMS)") \
        for (size_t i = 0; i < n; i++) {                                                          \
            struct contact_sums s = {0.0, INFINITY, 0.0, 0};                                      \
            contact_particle(m, c, i, LAW, inv_dt, &s);                                           \
            power += s.power;                                                                     \
            dt2 = s.dt2 < dt2 ? s.dt2 : dt2;                                                      \
            overlap = s.overlap > overlap ? s.overlap : overlap;                                  \
            active += s.active;                                                                   \
        }                                                                                         \
        return (struct contact_sums){power, dt2, overlap, active};                                \
    }
/* clang-format on */
CONTACT_LOOP(penalty_line, TLSPH_CONTACT_PENALTY_LINE)
CONTACT_LOOP(penalty_point, TLSPH_CONTACT_PENALTY_POINT)
CONTACT_LOOP(pinball, TLSPH_CONTACT_PINBALL)
static const contact_loop loops[TLSPH_CONTACT_VARIANTS] = {
    [TLSPH_CONTACT_PENALTY_LINE] = penalty_line,
    [TLSPH_CONTACT_PENALTY_POINT] = penalty_point,
    [TLSPH_CONTACT_PINBALL] = pinball,
};

double tlsph_contact_forces(struct tlsph_model *m, double dt)
{
    struct tlsph_contact *c = m->contact;
    const double t0 = tlsph_monotonic_seconds();
    /* particles failed since the last evaluation: their pairs are candidates now */
    const int fresh = c->touch && (tlsph_contact_watch(m, c) > 0 || c->settle_pending);
    if (tlsph_contact_search(m, c, fresh) != 0)
        c->failed = 1;
    else if (fresh) {
        tlsph_contact_settle(m, c);
        c->settle_pending = 0;
    }
    const struct contact_sums s = loops[c->variant](m, c, dt > 0.0 ? 1.0 / dt : INFINITY);
    c->active = s.active / 2;
    c->max_overlap = s.overlap > c->max_overlap ? s.overlap : c->max_overlap;
    if (s.dt2 < INFINITY) {
        const double dtc = sqrt(s.dt2);
        m->dt_cfl = dtc < m->dt_cfl ? dtc : m->dt_cfl;
    }
    c->phase_seconds += tlsph_monotonic_seconds() - t0;
    return s.power;
}
