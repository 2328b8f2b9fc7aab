/* Pre-cracks from the scene: facets and the pair cut (precrack.h). */
#include "crack/precrack.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run/model.h"
#include "util/parallel.h"

/* Deep enough for any crack within the surface's grid (each level halves the
 * edges; the grid is 2^21 cells wide). */
#define MAX_SPLIT_DEPTH 24

static double dist3(const double a[3], const double b[3])
{
    const double d0 = b[0] - a[0], d1 = b[1] - a[1], d2 = b[2] - a[2];
    return sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

/* Adds T, halved into four by its edges' midpoints until no edge exceeds the
 * cell. */
static enum tlsph_crack_status add_split(struct tlsph_crack_surface *s, const double T[3][3],
                                         int depth, size_t *count)
{
    const double longest =
        fmax(fmax(dist3(T[0], T[1]), dist3(T[1], T[2])), dist3(T[2], T[0]));
    if (longest <= s->cell || depth >= MAX_SPLIT_DEPTH) {
        const enum tlsph_crack_status st = tlsph_crack_surface_add(s, T);
        *count += st == TLSPH_CRACK_OK;
        return st;
    }
    double M[3][3]; /* midpoints of sides 01, 12, 20 */
    for (int k = 0; k < 3; k++)
        for (int a = 0; a < 3; a++)
            M[k][a] = 0.5 * (T[k][a] + T[(k + 1) % 3][a]);
    const double sub[4][3][3] = {
        {{T[0][0], T[0][1], T[0][2]}, {M[0][0], M[0][1], M[0][2]}, {M[2][0], M[2][1], M[2][2]}},
        {{M[0][0], M[0][1], M[0][2]}, {T[1][0], T[1][1], T[1][2]}, {M[1][0], M[1][1], M[1][2]}},
        {{M[2][0], M[2][1], M[2][2]}, {M[1][0], M[1][1], M[1][2]}, {T[2][0], T[2][1], T[2][2]}},
        {{M[0][0], M[0][1], M[0][2]}, {M[1][0], M[1][1], M[1][2]}, {M[2][0], M[2][1], M[2][2]}},
    };
    for (int q = 0; q < 4; q++) {
        const enum tlsph_crack_status st = add_split(s, sub[q], depth + 1, count);
        if (st != TLSPH_CRACK_OK)
            return st;
    }
    return TLSPH_CRACK_OK;
}

enum tlsph_crack_status tlsph_precrack_add(struct tlsph_crack_surface *s,
                                           const struct tlsph_crack_spec *c, int dim,
                                           size_t *nfacets)
{
    size_t count = 0;
    enum tlsph_crack_status st = TLSPH_CRACK_OK;
    if (dim == 2) {
        const double *a = c->corner[0], *b = c->corner[1];
        const double len = hypot(b[0] - a[0], b[1] - a[1]), w = 0.5 * s->cell;
        const double pieces = ceil(len / s->cell);
        if (!(pieces >= 1.0 && pieces < 1e9))
            return TLSPH_CRACK_BAD_INPUT;
        const long np = (long)pieces;
        for (long k = 0; k < np && st == TLSPH_CRACK_OK; k++) {
            const double t0 = (double)k / (double)np, t1 = (double)(k + 1) / (double)np;
            const double p0[2] = {a[0] + t0 * (b[0] - a[0]), a[1] + t0 * (b[1] - a[1])};
            const double p1[2] = {k + 1 == np ? b[0] : a[0] + t1 * (b[0] - a[0]),
                                  k + 1 == np ? b[1] : a[1] + t1 * (b[1] - a[1])};
            const double lower[3][3] = {{p0[0], p0[1], -w}, {p1[0], p1[1], -w}, {p1[0], p1[1], w}};
            const double upper[3][3] = {{p0[0], p0[1], -w}, {p1[0], p1[1], w}, {p0[0], p0[1], w}};
            if ((st = tlsph_crack_surface_add(s, lower)) == TLSPH_CRACK_OK) {
                count++;
                if ((st = tlsph_crack_surface_add(s, upper)) == TLSPH_CRACK_OK)
                    count++;
            }
        }
    } else {
        const int n = c->ncorners;
        double centre[3] = {0, 0, 0};
        for (int k = 0; k < n; k++)
            for (int a = 0; a < 3; a++)
                centre[a] += c->corner[k][a] / n;
        for (int k = 0; k < n && st == TLSPH_CRACK_OK; k++) {
            double T[3][3];
            memcpy(T[0], centre, sizeof T[0]);
            memcpy(T[1], c->corner[k], sizeof T[1]);
            memcpy(T[2], c->corner[(k + 1) % n], sizeof T[2]);
            st = add_split(s, (const double(*)[3])T, 0, &count);
        }
    }
    if (nfacets)
        *nfacets = count;
    return st;
}

size_t tlsph_precrack_cut_pairs(const struct tlsph_crack_surface *s, const double *X, size_t n,
                                int64_t *start, int32_t *j)
{
    int64_t *kept = malloc((n ? n : 1) * sizeof *kept);
    if (!kept)
        return SIZE_MAX;
    /* the facets' bounding box, widened by a hair (the facet test's own
     * tolerances are 1e-12 relative): a pair whose segment lies outside it
     * crosses no facet, and most pairs of a body are far from its crack */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t f = 0; f < s->nfacets; f++)
        for (int v = 0; v < 3; v++)
            for (int a = 0; a < 3; a++) {
                lo[a] = fmin(lo[a], s->facet[f][v][a]);
                hi[a] = fmax(hi[a], s->facet[f][v][a]);
            }
    for (int a = 0; a < 3; a++) {
        lo[a] -= 1e-9 * s->cell;
        hi[a] += 1e-9 * s->cell;
    }
    /* each row compacted within itself (rows are independent), then the rows
     * moved down in order */
#pragma omp parallel for schedule(dynamic, 256) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++) {
        int64_t w = start[i];
        for (int64_t k = start[i]; k < start[i + 1]; k++) {
            const size_t o = (size_t)j[k];
            const double *a = X + 3 * i, *b = X + 3 * o;
            int near = 1;
            for (int c = 0; c < 3; c++)
                near &= fmax(a[c], b[c]) >= lo[c] && fmin(a[c], b[c]) <= hi[c];
            if (!near || !tlsph_crack_surface_cuts_pair(s, a, i, b, o))
                j[w++] = j[k];
        }
        kept[i] = w - start[i];
    }
    const int64_t before = start[n];
    int64_t w = 0;
    for (size_t i = 0; i < n; i++) {
        const int64_t from = start[i];
        start[i] = w;
        if (from != w)
            memmove(j + w, j + from, (size_t)kept[i] * sizeof *j);
        w += kept[i];
    }
    start[n] = w;
    free(kept);
    return (size_t)(before - w);
}

static const char *status_text(enum tlsph_crack_status st)
{
    switch (st) {
    case TLSPH_CRACK_NO_MEMORY:
        return "out of memory";
    case TLSPH_CRACK_OUT_OF_GRID:
        return "the crack lies more than 2^20 kernel supports from the origin";
    default:
        return "invalid crack geometry";
    }
}

int tlsph_precrack_setup(struct tlsph_model *m, struct tlsph_errors *err)
{
    const struct tlsph_scene *sc = &m->scene;
    double cell = 0.0;
    for (size_t i = 0; i < m->p.n; i++)
        cell = fmax(cell, 2.0 * m->p.h[i]);
    m->crack_surface = calloc(1, sizeof *m->crack_surface);
    if (!m->crack_surface) {
        tlsph_errors_add(err, "/cracks", "out of memory");
        return -1;
    }
    if (tlsph_crack_surface_init(m->crack_surface, cell) != TLSPH_CRACK_OK) {
        tlsph_errors_add(err, "/cracks", "no particle to cut (kernel support %g m)", cell);
        return -1;
    }
    for (size_t c = 0; c < sc->ncracks; c++) {
        const enum tlsph_crack_status st =
            tlsph_precrack_add(m->crack_surface, &sc->cracks[c], m->dim, NULL);
        if (st != TLSPH_CRACK_OK) {
            char p[TLSPH_POINTER_MAX];
            tlsph_pointer_index(p, sizeof p, "/cracks", c);
            tlsph_errors_add(err, p, "cannot build the crack's facets: %s", status_text(st));
            return -1;
        }
    }
    const size_t removed = tlsph_precrack_cut_pairs(m->crack_surface, m->p.X, m->p.n,
                                                    m->pairs.start, m->pairs.j);
    if (removed == SIZE_MAX) {
        tlsph_errors_add(err, "/cracks", "out of memory cutting the pairs");
        return -1;
    }
    if (removed == 0) {
        tlsph_errors_add(err, "/cracks",
                         "the cracks cut no reference pair: they miss every body (check their "
                         "coordinates, in m)");
        return -1;
    }
    m->cut_pairs = removed / 2;
    m->pairs.npairs = (size_t)m->pairs.start[m->p.n];
    return 0;
}

void tlsph_precrack_release(struct tlsph_model *m)
{
    if (!m->crack_surface)
        return;
    tlsph_crack_surface_release(m->crack_surface);
    free(m->crack_surface);
    m->crack_surface = NULL;
}
