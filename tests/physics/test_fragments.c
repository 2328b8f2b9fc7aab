/* Contact between the separated parts of one body (core/contact/, the pair
 * filter of contact/state.h; docs/contact.md "Within a body").
 *
 * "Fragments": a 2-D steel bar, 20 x 4 mm, spacing 0.5 mm (320 particles),
 * Johnson-Cook damage with a failure strain of 5 %, is pulled apart by an
 * initial velocity jump at its middle (v_x = -V left of x = 10 mm, +V right,
 * V = 150 m/s): about 80 particles around the jump fail and the halves fly
 * apart (5.5 spacings between them at t1).  At t1 = 6 us every velocity is
 * reversed (the test drives the model), so the two halves, and the failed
 * particles between them, come back together; the run goes on to t2 = 24 us,
 * long enough for the halves to pass through each other without contact.
 *
 * The two parts are the intact (D < 1) particles whose reference position is
 * left, resp. right, of the middle.  References and tolerances:
 *  1. With contact (the default in a damage scene): the crack faces do not
 *     interpenetrate: the smallest distance between a particle of one part and
 *     one of the other stays >= 0.5 spacing over the whole run (a contact pair
 *     touches at one spacing; the stability contract would stop a pair at 0.5
 *     of it).
 *  2. Momentum: every force is a pair force f_ij = -f_ji (the damage-aware
 *     forces, eq. 35, and contact), and the reversal keeps the total at 0:
 *     |P| <= 1e-12 of sum m |v|, every step.
 *  3. Energy: the balance (kinetic + internal + hourglass + contact - initial)
 *     within 1e-2 of the initial kinetic energy every step (the failure
 *     phase's stress drop at fixed strain is booked by the trapezoid rule; the
 *     reversal changes no energy).
 *  4. The same run with "contact": {"enabled": false}: the parts pass through
 *     each other (the smallest distance falls below 0.2 spacing), so check 1
 *     can fail.
 * The pair filter: tlsph_contact_reference_pair equals membership in the
 * reference neighbour list for every pair of the bar, and after the run the
 * search's candidate lists equal a brute-force enumeration of the pairs of
 * flagged particles that are not a continuum, closer than R_i + R_j + skin.
 * Measured: with contact the parts stay 2.87 spacings apart (the failed
 * particles between them are squeezed, a cushion), |P| 3.9e-16, balance
 * 2.3e-3 of KE0; without, they come within 0.001 spacing (passing through). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact/state.h"
#include "run/model.h"
#include "support/check_main.h"
#include "support/contact_lists.h"
#include "support/scene_builder.h"

#define SPACING 0.0005
#define MID     0.01

static void scene(char *out, size_t size, int contact)
{
    snprintf(out, size,
             "{\"dimension\":2,\"time\":{\"end\":1.0,\"max_steps\":100000,\"cfl\":0.3},"
             "\"discretization\":{\"damage\":{\"failed_particles\":\"free\"}},"
             "\"materials\":{\"steel\":{\"density\":7800,\"youngs_modulus\":2e11,"
             "\"poisson_ratio\":0.3,"
             "\"strength\":{\"type\":\"linear_hardening\",\"yield_stress\":3e8,"
             "\"hardening_modulus\":5e8},"
             "\"damage\":{\"type\":\"johnson_cook\",\"d1\":0.05,\"d2\":0,\"d3\":0}}},"
             "\"bodies\":[{\"name\":\"bar\",\"material\":\"steel\",\"spacing\":%g,"
             "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.02,0.004,0]}},"
             "\"initial_velocity\":[\"300 * step(x - %g) - 150\",0,0]}]%s}",
             SPACING, MID, contact ? "" : ",\"contact\":{\"enabled\":false}");
}

struct outcome {
    double min_gap;   /* smallest distance between the two parts after t1, spacings */
    double momentum;  /* largest |P| / sum m|v| */
    double balance;   /* largest |balance| / initial kinetic energy */
    size_t failed;    /* at t1 */
    double gap_at_t1; /* the parts' smallest distance at t1, spacings */
};

/* Smallest distance between an intact particle left of the middle and one
 * right of it, m. */
static double parts_gap(const struct tlsph_model *m)
{
    const struct tlsph_particles *p = &m->p;
    double best = INFINITY;
    for (size_t i = 0; i < p->n; i++) {
        if (p->X[3 * i] > MID || p->damage[i] >= 1.0)
            continue;
        for (size_t j = 0; j < p->n; j++) {
            if (p->X[3 * j] < MID || p->damage[j] >= 1.0)
                continue;
            const double dx = p->x[3 * j] - p->x[3 * i], dy = p->x[3 * j + 1] - p->x[3 * i + 1];
            const double r = sqrt(dx * dx + dy * dy);
            best = r < best ? r : best;
        }
    }
    return best;
}

/* Brute force within the bar: both flagged, not a continuum. */
static int same_body_admitted(const struct tlsph_model *m, size_t i, size_t j)
{
    const uint8_t *touch = m->contact->touch;
    return touch[i] && touch[j] && tlsph_contact_same_body_pair(&m->p, i, j);
}

/* The reference test against the pair list, and the candidates against brute
 * force (one body: pairs of flagged particles, not a continuum, in reach). */
static void check_filter(struct tlsph_model *m)
{
    struct tlsph_contact *c = m->contact;
    const size_t n = m->p.n;
    ck_assert_int_eq(tlsph_contact_search(m, c, 1), 0);
    char *linked = calloc(n, 1);
    ck_assert(linked);
    for (size_t i = 0; i < n; i++) {
        for (int64_t k = m->pairs.start[i]; k < m->pairs.start[i + 1]; k++)
            linked[m->pairs.j[k]] = 1;
        for (size_t j = 0; j < n; j++)
            ck_assert_int_eq(j != i && tlsph_contact_reference_pair(&m->p, i, j), linked[j]);
        for (int64_t k = m->pairs.start[i]; k < m->pairs.start[i + 1]; k++)
            linked[m->pairs.j[k]] = 0;
    }
    free(linked);
    const size_t total = check_candidates(m, same_body_admitted);
    fprintf(stderr,
            "filter: %zu of %zu particles can touch, %zu candidate entries, brute force "
            "agrees\n",
            c->touching, n, total);
    ck_assert(total > 0);
}

static struct outcome fragments(int contact)
{
    char json[4096];
    scene(json, sizeof json, contact);
    struct tlsph_model *m = build_model(json);
    ck_assert(contact ? m->contact != NULL : m->contact == NULL);
    const double scale = momentum_scale(m), e0 = m->energy.kinetic;
    struct outcome o = {INFINITY, 0.0, 0.0, 0, 0.0};
    struct tlsph_diagnostic d;
    const double t1 = 6e-6, t2 = 24e-6;
    int reversed = 0;
    while (m->t < t2) {
        if (!reversed && m->t >= t1) {
            for (size_t k = 0; k < 3 * m->p.n; k++)
                m->p.v[k] = -m->p.v[k];
            reversed = 1;
            o.failed = m->failed;
            o.gap_at_t1 = parts_gap(m) / SPACING;
        }
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &d) == 0, "unstable at t = %g: %s", m->t, d.message);
        double P[3];
        tlsph_model_momentum(m, P);
        o.momentum = fmax(o.momentum, sqrt(P[0] * P[0] + P[1] * P[1]) / scale);
        o.balance = fmax(o.balance, fabs(tlsph_energy_balance(&m->energy)) / e0);
        if (reversed)
            o.min_gap = fmin(o.min_gap, parts_gap(m) / SPACING);
    }
    fprintf(stderr,
            "contact %s: %zu failed at t1, parts %.3f spacings apart at t1, closest after %.3f "
            "spacings; |P| %.2e of sum m|v|, balance %.2e of KE0, contact work %.3e J/m\n",
            contact ? "on" : "off", o.failed, o.gap_at_t1, o.min_gap, o.momentum, o.balance,
            m->energy.contact);
    if (contact)
        check_filter(m);
    tlsph_model_free(m);
    return o;
}

START_TEST(crack_faces_do_not_interpenetrate)
{
    const struct outcome on = fragments(1);
    ck_assert_msg(on.failed > 0, "the bar did not break");
    ck_assert_msg(on.gap_at_t1 > 1.5, "the parts did not separate: %.3f spacings", on.gap_at_t1);
    ck_assert_msg(on.min_gap >= 0.5, "crack faces interpenetrate: %.3f spacings", on.min_gap);
    ck_assert_msg(on.momentum <= 1e-12, "momentum %.3e", on.momentum);
    ck_assert_msg(on.balance <= 1e-2, "energy balance %.3e of KE0", on.balance);
}
END_TEST

START_TEST(without_contact_the_parts_pass_through)
{
    const struct outcome off = fragments(0);
    ck_assert_msg(off.min_gap < 0.2, "parts kept %.3f spacings apart without contact", off.min_gap);
}
END_TEST

TLSPH_CHECK_MAIN("fragments", 300, crack_faces_do_not_interpenetrate,
                 without_contact_the_parts_pass_through)
