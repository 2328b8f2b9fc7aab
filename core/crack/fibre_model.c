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

_Static_assert(TLSPH_MAX_THICKNESS_REGIONS == TLSPH_FIBRE_MAX_REGIONS,
               "the scene's regions are the fibre set's regions");

/* Body b's fibres per region ("thickness_regions", fibre.h): each particle's
 * region by its reference position; a particle in two regions, a region
 * without particles, particles off the lattice and a fibre with a gap (two
 * separate parts in one region, whose fibres would join across the gap) are
 * refused at the region's pointer.  0 or -1. */
static int by_region(struct tlsph_model *m, size_t b, size_t *index, size_t count,
                     const char *P, struct tlsph_errors *err)
{
    const struct tlsph_body *body = &m->scene.bodies[b];
    const int nr = body->nthickness_regions;
    char p[TLSPH_POINTER_MAX], q[TLSPH_POINTER_MAX];
    tlsph_pointer_join(q, sizeof q, P, "thickness_regions");
    int *region = malloc(count * sizeof *region);
    if (!region) {
        tlsph_errors_add(err, q, "out of memory for the fibres");
        return -1;
    }
    int axes[TLSPH_MAX_THICKNESS_REGIONS];
    for (int r = 0; r < nr; r++)
        axes[r] = body->thickness_region[r].axis;
    for (size_t k = 0; k < count; k++) {
        const double *x = m->p.X + 3 * index[k];
        region[k] = -1;
        for (int r = 0; r < nr; r++) {
            const struct tlsph_thickness_region *g = &body->thickness_region[r];
            if (!(x[0] >= g->min[0] && x[0] <= g->max[0] && x[1] >= g->min[1] &&
                  x[1] <= g->max[1] && x[2] >= g->min[2] && x[2] <= g->max[2]))
                continue;
            if (region[k] >= 0) {
                tlsph_pointer_index(p, sizeof p, q, (size_t)r);
                tlsph_errors_add(err, p,
                                 "body '%s': particle %lld at (%g, %g, %g) m lies in regions "
                                 "%d and %d: a particle's fibre runs along one axis (make the "
                                 "boxes hold disjoint particles)",
                                 body->name, (long long)m->p.id[index[k]], x[0], x[1], x[2],
                                 region[k], r);
                free(region);
                return -1;
            }
            region[k] = r;
        }
    }
    size_t bad = 0;
    struct tlsph_fibres *f = &m->fibres[b];
    const enum tlsph_fibre_status st = tlsph_fibres_build_regions(
        f, m->p.X, index, region, count, body->spacing, axes, nr, &bad);
    int rc = 0;
    if (st == TLSPH_FIBRE_BAD_INPUT && bad >= (size_t)-TLSPH_MAX_THICKNESS_REGIONS) {
        tlsph_pointer_index(p, sizeof p, q, (size_t)-1 - bad);
        tlsph_errors_add(err, p, "body '%s': the region's box holds none of its particles",
                         body->name);
        rc = -1;
    } else if (st == TLSPH_FIBRE_NOT_LATTICE) {
        int r = 0;
        for (size_t k = 0; k < count; k++)
            if (index[k] == bad)
                r = region[k];
        tlsph_pointer_index(p, sizeof p, q, (size_t)r);
        tlsph_errors_add(err, p,
                         "body '%s': particle %lld at (%g, %g, %g) m is off its in-plane "
                         "lattice point: its fibres cannot be built",
                         body->name, (long long)m->p.id[bad], m->p.X[3 * bad],
                         m->p.X[3 * bad + 1], m->p.X[3 * bad + 2]);
        rc = -1;
    } else if (st != TLSPH_FIBRE_OK) {
        tlsph_errors_add(err, q, "body '%s': cannot build its fibres (%s)", body->name,
                         st == TLSPH_FIBRE_NO_MEMORY ? "out of memory" : "invalid input");
        rc = -1;
    }
    for (size_t j = 0; rc == 0 && j < f->n; j++) { /* a fibre's particles are neighbours */
        const int a = f->region_axis[f->region[j]];
        for (size_t k = f->start[j] + 1; k < f->start[j + 1]; k++) {
            const double gap = m->p.X[3 * f->particle[k] + a] - m->p.X[3 * f->particle[k - 1] + a];
            if (gap > 1.5 * body->spacing) {
                const size_t i = f->particle[k];
                tlsph_pointer_index(p, sizeof p, q, (size_t)f->region[j]);
                tlsph_errors_add(err, p,
                                 "body '%s': the fibre of particle %lld at (%g, %g, %g) m "
                                 "jumps %g spacings along the region's axis: two separate "
                                 "parts in one region (give each its own box)",
                                 body->name, (long long)m->p.id[i], m->p.X[3 * i],
                                 m->p.X[3 * i + 1], m->p.X[3 * i + 2], gap / body->spacing);
                rc = -1;
                break;
            }
        }
    }
    free(region);
    return rc;
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
        if (body->nthickness_regions > 0) {
            const int rc = by_region(m, b, index, count, q, err);
            free(index);
            if (rc != 0)
                return -1;
            m->bytes_allocated += (2 * m->fibres[b].n + 1) * sizeof(size_t) +
                                  count * sizeof(size_t) +
                                  m->fibres[b].n * sizeof *m->fibres[b].centre;
            continue;
        }
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
