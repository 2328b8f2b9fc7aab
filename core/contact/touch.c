/* Which particles of a damaged body can touch another part of it
 * (contact/state.h touch[]): the search for contact within a body looks at
 * these only, so a damage scene's contact phase costs a small layer of its
 * particles, not all of them.
 *
 * A pair of one body can be in contact only when it is not a reference pair
 * or its link is broken (tlsph_contact_same_body_pair; with virtual links,
 * _links: not linked, or D_ij = 1, and the faces are the ends of broken links).  Two parts of a body
 * that the reference neighbourhood never linked meet with their surfaces
 * first: their surface layer, the particles with fewer reference neighbours
 * than the body's interior (within a support radius of the boundary), is
 * flagged at setup.  A broken link needs a failed particle, and a crack's
 * faces are the failed particles and their reference neighbours: flagged as
 * they fail (tlsph_contact_watch, once per evaluation, O(n)); after the
 * search that follows, tlsph_contact_settle lowers the reach factor of the
 * particles flagged anew (state.h reach[]) so that no pair starts
 * overlapped.  An interior
 * particle can meet another part of its body only after that part's flagged
 * layer has passed through its own, deeper than the stability contract lets
 * any pair go (TLSPH_CONTACT_MAX_OVERLAP). */
#include <math.h>

#include "contact/state.h"

/* Flags the surface layer of every body whose material damages (every body
 * with virtual links). */
void tlsph_contact_touch_setup(struct tlsph_model *m, struct tlsph_contact *c)
{
    const struct tlsph_scene *s = &m->scene;
    const int64_t *start = m->pairs.start;
    for (size_t b = 0; b < s->nbodies; b++) {
        if (!s->materials[s->bodies[b].material].damage.model && !m->links)
            continue;
        int64_t full = 0;
        for (size_t i = m->body_begin[b]; i < m->body_end[b]; i++)
            full = start[i + 1] - start[i] > full ? start[i + 1] - start[i] : full;
        for (size_t i = m->body_begin[b]; i < m->body_end[b]; i++)
            if (start[i + 1] - start[i] < full) /* settled after the first search */
                c->touch[i] |= TLSPH_TOUCH_SURFACE | TLSPH_TOUCH_NEW;
    }
    c->touching = 0;
    for (size_t i = 0; i < m->p.n; i++) {
        c->touching += c->touch[i] != 0;
        /* a graded body's particle reaches as far as its own spacing allows
         * (the law's radius is the body's, at its coarsest spacing): two fine
         * particles of one body touch at their spacing, not at the body's */
        c->reach[i] = m->p.spacing ? m->p.spacing[i] / s->bodies[m->p.body[i]].spacing : 1.0;
    }
}

/* Virtual links: a crack's faces are the ends of its broken links (each
 * link's two entries are in its two ends' rows).  Scans the links only when
 * more are broken than at the last watch. */
static size_t watch_links(struct tlsph_model *m, struct tlsph_contact *c)
{
    if (m->links->broken == m->links->broken_watched)
        return 0;
    m->links->broken_watched = m->links->broken;
    const int64_t *start = m->pairs.start;
    uint8_t *touch = c->touch;
    size_t fresh = 0;
    for (size_t i = 0; i < m->p.n; i++) {
        if (touch[i] & TLSPH_TOUCH_FAILED)
            continue;
        int broken = 0;
        for (int64_t k = start[i]; k < start[i + 1]; k++)
            broken |= m->links->D[k] >= 1.0;
        if (!broken)
            continue;
        c->touching += touch[i] == 0;
        touch[i] |= TLSPH_TOUCH_FAILED | TLSPH_TOUCH_NEW;
        fresh++;
    }
    return fresh;
}

size_t tlsph_contact_watch(struct tlsph_model *m, struct tlsph_contact *c)
{
    if (m->links)
        return watch_links(m, c);
    const double *D = m->p.damage;
    const int64_t *start = m->pairs.start;
    const int32_t *nbr = m->pairs.j;
    uint8_t *touch = c->touch;
    size_t fresh = 0;
    for (size_t i = 0; i < m->p.n; i++) {
        if (!(D[i] >= 1.0) || (touch[i] & TLSPH_TOUCH_FAILED))
            continue;
        c->touching += touch[i] == 0;
        touch[i] |= TLSPH_TOUCH_FAILED | TLSPH_TOUCH_NEW;
        for (int64_t k = start[i]; k < start[i + 1]; k++) {
            const size_t j = (size_t)nbr[k];
            c->touching += touch[j] == 0;
            if (!(touch[j] & TLSPH_TOUCH_NEAR_FAILED))
                touch[j] |= TLSPH_TOUCH_NEAR_FAILED | TLSPH_TOUCH_NEW;
        }
        fresh++;
    }
    return fresh;
}

void tlsph_contact_settle(struct tlsph_model *m, struct tlsph_contact *c)
{
    const double *x = m->p.x;
    const int32_t *body = m->p.body;
    double *reach = c->reach;
    for (size_t i = 0; i < m->p.n; i++) {
        if (!(c->touch[i] & TLSPH_TOUCH_NEW))
            continue;
        c->touch[i] &= (uint8_t)~TLSPH_TOUCH_NEW;
        for (int64_t k = c->start[i]; k < c->start[i + 1]; k++) {
            const size_t j = (size_t)c->j[k];
            if (body[j] != body[i])
                continue;
            double r2 = 0.0;
            for (int d = 0; d < 3; d++)
                r2 += (x[3 * j + d] - x[3 * i + d]) * (x[3 * j + d] - x[3 * i + d]);
            const double q = sqrt(r2) / (c->bodies[body[i]].radius + c->bodies[body[j]].radius);
            const double now = reach[i] < reach[j] ? reach[i] : reach[j];
            if (q < now)
                reach[i] = q;
        }
    }
}
