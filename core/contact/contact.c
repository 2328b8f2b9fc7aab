/* Setup and teardown of the contact phase (contact.h), and what it reports. */
#include <math.h>
#include <stdlib.h>

#include "contact/state.h"
#include "run/model.h"

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
    if (tlsph_contact_search(m, c, 1) != 0) {
        tlsph_errors_add(err, "/contact", "out of memory for the contact search");
        return -1;
    }
    return 0;
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

size_t tlsph_contact_active(const struct tlsph_model *m) { return m->contact->active; }
long tlsph_contact_searches(const struct tlsph_model *m) { return m->contact->searches; }
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
            const double reach = c->bodies[m->p.body[i]].radius + c->bodies[m->p.body[j]].radius;
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

int tlsph_contact_failed(const struct tlsph_model *m) { return m->contact->failed; }

size_t tlsph_contact_candidates(const struct tlsph_model *m)
{
    return (size_t)m->contact->start[m->p.n];
}
