/* Setup and teardown of the contact phase (contact.h), and what it reports. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact/state.h"
#include "run/model.h"
#include "scene/limits.h"
#include "util/names.h"

/* At t = 0 no two bodies may overlap: the lattice cells of two particles of
 * different bodies (edge s_i, s_j) may touch but not interpenetrate.  The
 * rule, with a touching tolerance: a pair is accepted when
 *   r >= (1 - TOUCH_TOLERANCE) (s_i + s_j)/2,
 * so bodies placed face to face (cells touching, particles exactly one
 * spacing apart, or closer by the round-off of their lattices' origins,
 * ~1e-16 of the coordinates) pass, while an overlap of a micrometre per metre
 * of spacing or more is refused.  Overlapping bodies would start with a
 * contact force that no motion caused, an explosion of their overlap's
 * energy.  Looks at the candidate pairs (closer than R_i + R_j + skin), which
 * hold every such pair unless a law's radius is far below half the spacing;
 * pairs within one body are the body's own business (its lattice). */
#define TOUCH_TOLERANCE 1e-6

static int check_start(const struct tlsph_model *m, struct tlsph_errors *err)
{
    const struct tlsph_contact *c = m->contact;
    const struct tlsph_scene *s = &m->scene;
    const double *x = m->p.x;
    size_t pairs = 0, bi = 0, bj = 0, at = 0;
    double worst = 0.0, gap = 0.0;
    for (size_t i = 0; i < m->p.n; i++)
        for (int64_t k = c->start[i]; k < c->start[i + 1]; k++) {
            const size_t j = (size_t)c->j[k];
            const size_t a = (size_t)m->p.body[i], b = (size_t)m->p.body[j];
            if (a >= b)
                continue; /* each pair of different bodies once */
            const double touch = 0.5 * (s->bodies[a].spacing + s->bodies[b].spacing);
            double r2 = 0.0;
            for (int d = 0; d < 3; d++)
                r2 += (x[3 * j + d] - x[3 * i + d]) * (x[3 * j + d] - x[3 * i + d]);
            const double depth = (touch - sqrt(r2)) / touch;
            if (depth <= TOUCH_TOLERANCE)
                continue;
            if (pairs++ == 0 || depth > worst) {
                worst = depth;
                gap = sqrt(r2);
                bi = a;
                bj = b;
                at = i;
            }
        }
    if (pairs == 0)
        return 0;
    char ptr[64];
    snprintf(ptr, sizeof ptr, "/bodies/%zu", bj);
    const double *X = x + 3 * at;
    tlsph_errors_add(err, ptr,
                     "body '%s' overlaps body '%s' at t = 0: %zu pairs of their particles are "
                     "closer than their lattice cells allow (the closest %.3g m apart, %.3g "
                     "spacings, near (%g, %g, %g) m); with contact the bodies must start apart "
                     "or touching",
                     s->bodies[bj].name, s->bodies[bi].name, pairs, gap,
                     gap / s->bodies[bj].spacing, X[0], X[1], X[2]);
    return -1;
}

/* The body pairs with a force series (state.h): every pair of different
 * bodies when there are at most TLSPH_MAX_CONTACT_PAIR_SERIES, named
 * "<a>--<b>" where that is a valid name (util/names.h: at most 63
 * characters) unique among the bodies and the other pairs ("" otherwise). */
static int pair_setup(struct tlsph_model *m, struct tlsph_contact *c)
{
    const struct tlsph_scene *s = &m->scene;
    const size_t nb = s->nbodies, np = nb * (nb - 1) / 2;
    if (np == 0 || np > TLSPH_MAX_CONTACT_PAIR_SERIES)
        return 0;
    c->pair = tlsph_alloc(m, np, sizeof *c->pair);
    c->pair_name = tlsph_alloc(m, np, sizeof *c->pair_name);
    if (!c->pair || !c->pair_name)
        return -1;
    c->npairs = np;
    size_t k = 0;
    for (size_t a = 0; a < nb; a++)
        for (size_t b = a + 1; b < nb; b++, k++) {
            c->pair[k][0] = (int32_t)a;
            c->pair[k][1] = (int32_t)b;
            char *name = c->pair_name[k];
            const int len = snprintf(name, sizeof c->pair_name[k], "%s--%s", s->bodies[a].name,
                                     s->bodies[b].name);
            if (len < 0 || (size_t)len >= sizeof c->pair_name[k] || !tlsph_name_ok(name))
                name[0] = '\0';
        }
    /* a name taken by a body or by another pair names no pair */
    for (k = 0; k < np; k++) {
        int taken = 0;
        for (size_t b = 0; b < nb && !taken; b++)
            taken = strcmp(c->pair_name[k], s->bodies[b].name) == 0;
        for (size_t q = 0; q < np && !taken; q++)
            taken = q != k && strcmp(c->pair_name[k], c->pair_name[q]) == 0;
        if (taken)
            c->pair_name[k][0] = '\0';
    }
    return 0;
}

int tlsph_contact_create(struct tlsph_model *m, struct tlsph_errors *err)
{
    const struct tlsph_scene *s = &m->scene;
    const size_t n = m->p.n;
    struct tlsph_contact *c = calloc(1, sizeof *c);
    if (!c) {
        tlsph_errors_add(err, "/contact", "out of memory for the contact search");
        return -1;
    }
    m->contact = c;
    m->bytes_allocated += sizeof *c;
    c->law = s->contact.law;
    for (int k = 0; k < 4; k++)
        c->params[k] = s->contact.params[k];
    c->variant = c->law->variant(s);
    c->bodies = tlsph_alloc(m, s->nbodies, sizeof *c->bodies);
    c->start = tlsph_alloc(m, n + 1, sizeof *c->start);
    c->x_search = tlsph_alloc(m, 3 * n, sizeof *c->x_search);
    c->key = tlsph_alloc(m, n, sizeof *c->key);
    c->order = tlsph_alloc(m, n, sizeof *c->order);
    c->f_old = tlsph_alloc(m, 3 * n, sizeof *c->f_old);
    if (!c->bodies || !c->start || !c->x_search || !c->key || !c->order || !c->f_old) {
        tlsph_errors_add(err, "/contact", "out of memory for the contact search");
        return -1;
    }
    double spacing = 0.0;
    for (size_t b = 0; b < s->nbodies; b++) {
        c->law->body(s, b, &c->bodies[b]);
        c->max_radius = fmax(c->max_radius, c->bodies[b].radius);
        spacing = fmax(spacing, s->bodies[b].spacing);
    }
    c->skin = s->contact.skin * spacing;
    if (pair_setup(m, c) != 0) {
        tlsph_errors_add(err, "/contact", "out of memory for the contact search");
        return -1;
    }
    /* contact within a body: only where material can separate */
    c->all_particles = s->nbodies > 1;
    if (m->p.damage || m->links) {
        c->touch = tlsph_alloc(m, n, sizeof *c->touch);
        c->reach = tlsph_alloc(m, n, sizeof *c->reach);
        if (!c->touch || !c->reach) {
            tlsph_errors_add(err, "/contact", "out of memory for the contact search");
            return -1;
        }
        tlsph_contact_touch_setup(m, c);
    }
    if (tlsph_contact_search(m, c, 1) != 0) {
        tlsph_errors_add(err, "/contact", "out of memory for the contact search");
        return -1;
    }
    /* a law whose radii reach past the nearest non-neighbours (a pin-ball of
     * radius factor near 1) would start the surface pairs of a body overlapped */
    if (c->touch)
        tlsph_contact_settle(m, c);
    return check_start(m, err);
}

void tlsph_contact_free(struct tlsph_model *m)
{
    struct tlsph_contact *c = m->contact;
    if (!c)
        return;
    free(c->bodies);
    free(c->start);
    free(c->j);
    free(c->x_search);
    free(c->key);
    free(c->order);
    free(c->cell_start);
    free(c->f_old);
    free(c->touch);
    free(c->s_pair);
    free(c->pair);
    free(c->pair_name);
    free(c->reach);
    free(c);
    m->contact = NULL;
}

struct tlsph_contact_cost tlsph_contact_cost(const struct tlsph_model *m)
{
    const struct tlsph_contact *c = m->contact;
    return (struct tlsph_contact_cost){c->searches, c->search_seconds, c->phase_seconds};
}

void tlsph_contact_body_force(const struct tlsph_model *m, size_t b, double out[3])
{
    const double *f = m->contact->f_old; /* the last evaluation's contact forces */
    out[0] = out[1] = out[2] = 0.0;
    for (size_t i = m->body_begin[b]; i < m->body_end[b]; i++)
        for (int c = 0; c < 3; c++)
            out[c] += f[3 * i + c];
}

size_t tlsph_contact_pairs(const struct tlsph_model *m)
{
    return m->contact->npairs;
}

const char *tlsph_contact_pair_name(const struct tlsph_model *m, size_t k)
{
    const char *name = m->contact->pair_name[k];
    return name[0] ? name : NULL;
}

void tlsph_contact_pair_force(const struct tlsph_model *m, size_t k, double out[3])
{
    const struct tlsph_contact *c = m->contact;
    const int32_t a = c->pair[k][0], b = c->pair[k][1];
    const double *x = m->p.x;
    out[0] = out[1] = out[2] = 0.0;
    for (size_t i = m->body_begin[a]; i < m->body_end[a]; i++)
        for (int64_t q = c->start[i]; q < c->start[i + 1]; q++) {
            const size_t j = (size_t)c->j[q];
            if (m->p.body[j] != b || c->s_pair[q] == 0.0)
                continue;
            for (int d = 0; d < 3; d++)
                out[d] -= c->s_pair[q] * (x[3 * j + d] - x[3 * i + d]);
        }
}

size_t tlsph_contact_active(const struct tlsph_model *m)
{
    return m->contact->active;
}
long tlsph_contact_searches(const struct tlsph_model *m)
{
    return m->contact->searches;
}
double tlsph_contact_take_overlap(struct tlsph_model *m)
{
    const double seen = m->contact->max_overlap;
    m->contact->max_overlap = 0.0;
    return seen;
}

void tlsph_contact_deepest_pair(const struct tlsph_model *m, int64_t ids[2])
{
    const struct tlsph_contact *c = m->contact;
    ids[0] = ids[1] = -1;
    double deepest = 0.0;
    const double *x = m->p.x;
    for (size_t i = 0; i < m->p.n; i++)
        for (int64_t k = c->start[i]; k < c->start[i + 1]; k++) {
            const size_t j = (size_t)c->j[k];
            double reach = c->bodies[m->p.body[i]].radius + c->bodies[m->p.body[j]].radius;
            if (m->p.body[i] == m->p.body[j])
                reach *= c->reach[i] < c->reach[j] ? c->reach[i] : c->reach[j];
            double r2 = 0.0;
            for (int d = 0; d < 3; d++)
                r2 += (x[3 * j + d] - x[3 * i + d]) * (x[3 * j + d] - x[3 * i + d]);
            const double depth = (reach - sqrt(r2)) / reach;
            if (depth > deepest) {
                deepest = depth;
                ids[0] = m->p.id[i];
                ids[1] = m->p.id[j];
            }
        }
}

int tlsph_contact_failed(const struct tlsph_model *m)
{
    return m->contact->failed;
}

size_t tlsph_contact_candidates(const struct tlsph_model *m)
{
    return (size_t)m->contact->start[m->p.n];
}
