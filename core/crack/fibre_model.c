/* The fibres of a model's thin bodies (fibre.h): built once at setup from the
 * scene's "thickness_axis", kept in m->fibres for the crack-tip search. */
#include <stdlib.h>

#include "crack/fibre.h"
#include "run/model.h"
#include "scene/parse_internal.h"

/* A shell wall's radial fibres, about the axis of the body's cylinder (the
 * conforming base, scene/conforming.c: a[0..2] base, a[3..5] unit axis). */
static enum tlsph_fibre_status radial(struct tlsph_model *m, size_t b, const size_t *index,
                                      size_t count, size_t *bad)
{
    const struct tlsph_body *body = &m->scene.bodies[b];
    const struct tlsph_geometry *g = tlsph_conforming_base(&body->geometry);
    if (!g || g->type != TLSPH_GEOM_CYLINDER) /* refused at parse */
        return TLSPH_FIBRE_BAD_INPUT;
    *bad = index[0];
    return tlsph_fibres_build_radial(&m->fibres[b], m->p.X, index, count, body->spacing, g->a,
                                     g->a + 3, bad);
}

int tlsph_model_fibres_setup(struct tlsph_model *m, struct tlsph_errors *err)
{
    const struct tlsph_scene *s = &m->scene;
    m->fibres = calloc(s->nbodies, sizeof *m->fibres);
    if (!m->fibres) {
        tlsph_errors_add(err, "", "out of memory for the fibres");
        return -1;
    }
    for (size_t b = 0; b < s->nbodies; b++) {
        const struct tlsph_body *body = &s->bodies[b];
        if (body->thickness_axis < 0 || m->body_end[b] == m->body_begin[b])
            continue;
        const size_t count = m->body_end[b] - m->body_begin[b];
        size_t *index = malloc(count * sizeof *index);
        char p[TLSPH_POINTER_MAX], q[TLSPH_POINTER_MAX];
        tlsph_pointer_index(q, sizeof q, "/bodies", b);
        tlsph_pointer_join(p, sizeof p, q, "thickness_axis");
        if (!index) {
            tlsph_errors_add(err, p, "out of memory for the fibres");
            return -1;
        }
        for (size_t k = 0; k < count; k++)
            index[k] = m->body_begin[b] + k;
        size_t bad = 0;
        const enum tlsph_fibre_status st =
            body->thickness_axis == TLSPH_FIBRE_RADIAL
                ? radial(m, b, index, count, &bad)
                : tlsph_fibres_build(&m->fibres[b], m->p.X, index, count, body->spacing,
                                     body->thickness_axis, &bad);
        free(index);
        if (st == TLSPH_FIBRE_NOT_STACKED || (st == TLSPH_FIBRE_BAD_INPUT &&
                                              body->thickness_axis == TLSPH_FIBRE_RADIAL)) {
            tlsph_errors_add(err, p,
                             "body '%s': particle %lld at (%g, %g, %g) m %s: its radial fibres "
                             "cannot be built",
                             body->name, (long long)m->p.id[bad], m->p.X[3 * bad],
                             m->p.X[3 * bad + 1], m->p.X[3 * bad + 2],
                             st == TLSPH_FIBRE_NOT_STACKED
                                 ? "begins a stack of another size than the first (the shells' "
                                   "particles are not on common rays)"
                                 : "lies on the cylinder's axis");
            return -1;
        }
        if (st == TLSPH_FIBRE_NOT_LATTICE) {
            tlsph_errors_add(err, p,
                             "body '%s': particle %lld at (%g, %g, %g) m is off its in-plane "
                             "lattice point: its fibres cannot be built",
                             body->name, (long long)m->p.id[bad], m->p.X[3 * bad],
                             m->p.X[3 * bad + 1], m->p.X[3 * bad + 2]);
            return -1;
        }
        if (st != TLSPH_FIBRE_OK) {
            tlsph_errors_add(err, p, "body '%s': cannot build its fibres (%s)", body->name,
                             st == TLSPH_FIBRE_NO_MEMORY ? "out of memory" : "invalid input");
            return -1;
        }
        m->bytes_allocated += (m->fibres[b].n + 1) * sizeof(size_t) + count * sizeof(size_t) +
                              m->fibres[b].n * sizeof *m->fibres[b].centre;
    }
    return 0;
}

void tlsph_model_fibres_release(struct tlsph_model *m)
{
    if (!m->fibres)
        return;
    for (size_t b = 0; b < m->scene.nbodies; b++)
        tlsph_fibres_release(&m->fibres[b]);
    free(m->fibres);
    m->fibres = NULL;
}
