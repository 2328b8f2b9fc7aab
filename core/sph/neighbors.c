/* Reference neighbour search (neighbors.h).
 *
 * Bodies never pair with each other, so each body gets its own grid, of cells
 * of the body's own support diameter: a body with a fine spacing beside a
 * coarse one scans its own few neighbours, not the coarse body's cell size
 * worth of candidates (two bodies 50x apart in spacing took minutes to set up
 * with one grid of the largest cell, ~50^3 candidates per particle).  Every
 * grid is anchored at the lower corner of all particles minus one cell, as the
 * single grid was, so for bodies of equal spacing the cells, and with them the
 * neighbour lists and their order, are exactly those of one shared grid.  Keys
 * count from the body's own lowest cell, so they stay small however far apart
 * the bodies are. */
#include "sph/neighbors.h"
#include "util/parallel.h"

#include <math.h>
#include <stdlib.h>

struct cell_entry {
    int64_t key;
    size_t index;
    int32_t body;
};

/* One body's grid: cells of `size` from lo (the common anchoring), shifted by
 * base so that the body's particles sit in cells 1..dims-2 along each axis and
 * the cells next to them (0..dims-1) never wrap into another row. */
struct grid {
    double lo[3];
    double size;
    int64_t base[3], top[3]; /* lowest cell - 1, highest cell (before the shift) */
    int64_t dims[3];
    size_t first, count; /* the body's entries in the sorted entry array */
};

static int cmp_entry(const void *a, const void *b)
{
    const struct cell_entry *x = a, *y = b;
    if (x->body != y->body)
        return x->body < y->body ? -1 : 1;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return x->index < y->index ? -1 : (x->index > y->index);
}

static int32_t body_of(const int32_t *body, size_t i)
{
    return body ? body[i] : 0;
}

/* Cell of x in the common anchoring (before the body's shift). */
static void raw_cell(const struct grid *g, const double *x, int64_t c[3])
{
    for (int k = 0; k < 3; k++)
        c[k] = (int64_t)floor((x[k] - g->lo[k]) / g->size);
}

static void cell_of(const struct grid *g, const double *x, int64_t c[3])
{
    raw_cell(g, x, c);
    for (int k = 0; k < 3; k++)
        c[k] -= g->base[k];
}

static int64_t cell_key(const struct grid *g, const int64_t c[3])
{
    return (c[2] * g->dims[1] + c[1]) * g->dims[0] + c[0];
}

/* Number of bodies: 1 + the largest body index (1 when body is NULL). */
static size_t count_bodies(const int32_t *body, size_t n)
{
    int32_t last = 0;
    for (size_t i = 0; body && i < n; i++)
        if (body[i] > last)
            last = body[i];
    return (size_t)last + 1;
}

/* Lays out the grids of bodies 0..nb-1 (g[b].size set by the caller), then
 * fills e (n entries) and sorts it by body, cell and index. */
static void grids_build(struct grid *g, size_t nb, const double *X, const int32_t *body, size_t n,
                        struct cell_entry *e)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            lo[c] = fmin(lo[c], X[3 * i + c]);
    for (size_t b = 0; b < nb; b++)
        for (int c = 0; c < 3; c++) {
            g[b].lo[c] = lo[c] - g[b].size;
            g[b].base[c] = INT64_MAX;
            g[b].top[c] = INT64_MIN;
        }
    for (size_t i = 0; i < n; i++) {
        struct grid *gb = &g[body_of(body, i)];
        int64_t c[3];
        raw_cell(gb, X + 3 * i, c);
        for (int k = 0; k < 3; k++) {
            gb->base[k] = c[k] < gb->base[k] ? c[k] : gb->base[k];
            gb->top[k] = c[k] > gb->top[k] ? c[k] : gb->top[k];
        }
    }
    for (size_t b = 0; b < nb; b++) {
        g[b].first = g[b].count = 0;
        for (int c = 0; c < 3; c++) {
            if (g[b].base[c] == INT64_MAX) { /* no particle */
                g[b].base[c] = 0;
                g[b].dims[c] = 1;
                continue;
            }
            g[b].base[c] -= 1;
            g[b].dims[c] = g[b].top[c] - g[b].base[c] + 2;
        }
    }
    for (size_t i = 0; i < n; i++) {
        const struct grid *gb = &g[body_of(body, i)];
        int64_t c[3];
        cell_of(gb, X + 3 * i, c);
        e[i] = (struct cell_entry){cell_key(gb, c), i, body_of(body, i)};
    }
    qsort(e, n, sizeof *e, cmp_entry);
    for (size_t k = 0; k < n; k++) {
        struct grid *gb = &g[e[k].body];
        if (gb->count++ == 0)
            gb->first = k;
    }
}

/* First entry with key >= k. */
static size_t lower_bound(const struct cell_entry *e, size_t n, int64_t k)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (e[mid].key < k)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

int tlsph_cell_order(const double *X, const int32_t *body, size_t n, double cell_size,
                     size_t *order)
{
    if (n == 0)
        return 0;
    const size_t nb = count_bodies(body, n);
    struct cell_entry *e = malloc(n * sizeof *e);
    struct grid *g = malloc(nb * sizeof *g);
    if (!e || !g) {
        free(e);
        free(g);
        return -1;
    }
    for (size_t b = 0; b < nb; b++)
        g[b].size = cell_size;
    grids_build(g, nb, X, body, n, e);
    for (size_t i = 0; i < n; i++)
        order[i] = e[i].index;
    free(e);
    free(g);
    return 0;
}

/* Visits the candidate neighbours of i in its body's grid g (its entries e,
 * sorted by cell); count-only when out == NULL.  *examined (when not NULL)
 * grows by the number of candidates whose distance was computed. */
static size_t scan(const struct grid *g, const struct cell_entry *e, const double *X,
                   const double *h, size_t i, int32_t *out, size_t *examined)
{
    int64_t c[3];
    cell_of(g, X + 3 * i, c);
    size_t count = 0, seen = 0;
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++) {
            /* the three cells along x are contiguous in key order */
            int64_t a[3] = {c[0] - 1, c[1] + dy, c[2] + dz};
            int64_t k0 = cell_key(g, a);
            size_t s = lower_bound(e, g->count, k0);
            for (; s < g->count && e[s].key <= k0 + 2; s++) {
                size_t j = e[s].index;
                if (j == i)
                    continue;
                seen++;
                if (tlsph_pair_in_support(X + 3 * i, X + 3 * j, h[i], h[j])) {
                    if (out)
                        out[count] = (int32_t)j;
                    count++;
                }
            }
        }
    if (examined)
        *examined += seen;
    return count;
}

/* The grids and sorted entries of one search. */
struct search {
    struct grid *g;
    struct cell_entry *e;
};

static void search_free(struct search *s)
{
    free(s->g);
    free(s->e);
}

/* 0, or -1 on allocation failure (nothing left allocated). */
static int search_prepare(struct search *s, const double *X, const double *h, const int32_t *body,
                          size_t n)
{
    const size_t nb = n ? count_bodies(body, n) : 1;
    s->e = malloc((n ? n : 1) * sizeof *s->e);
    s->g = calloc(nb, sizeof *s->g);
    if (!s->e || !s->g) {
        search_free(s);
        return -1;
    }
    /* each body's cell: its largest support diameter */
    for (size_t i = 0; i < n; i++) {
        struct grid *gb = &s->g[body_of(body, i)];
        gb->size = fmax(gb->size, 2.0 * h[i]);
    }
    if (n)
        grids_build(s->g, nb, X, body, n, s->e);
    return 0;
}

int tlsph_build_pairs(const double *X, const double *h, const int32_t *body, size_t n,
                      int64_t **start_out, int32_t **nbr_out)
{
    *start_out = NULL;
    *nbr_out = NULL;
    struct search sr;
    int64_t *start = calloc(n + 1, sizeof *start);
    if (!start || search_prepare(&sr, X, h, body, n) != 0) {
        free(start);
        return -1;
    }
    const struct grid *g = sr.g;
    const struct cell_entry *e = sr.e;
#pragma omp parallel for schedule(dynamic, 256) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++) {
        const struct grid *gb = &g[body_of(body, i)];
        start[i + 1] = (int64_t)scan(gb, e + gb->first, X, h, i, NULL, NULL);
    }
    for (size_t i = 0; i < n; i++)
        start[i + 1] += start[i];
    int32_t *nbr = malloc((start[n] ? (size_t)start[n] : 1) * sizeof *nbr);
    if (!nbr) {
        free(start);
        search_free(&sr);
        return -1;
    }
#pragma omp parallel for schedule(dynamic, 256) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++) {
        const struct grid *gb = &g[body_of(body, i)];
        scan(gb, e + gb->first, X, h, i, nbr + start[i], NULL);
    }
    search_free(&sr);
    *start_out = start;
    *nbr_out = nbr;
    return 0;
}

size_t tlsph_pair_candidates(const double *X, const double *h, const int32_t *body, size_t n)
{
    struct search sr;
    if (search_prepare(&sr, X, h, body, n) != 0)
        return SIZE_MAX;
    size_t examined = 0;
    for (size_t i = 0; i < n; i++) {
        const struct grid *gb = &sr.g[body_of(body, i)];
        scan(gb, sr.e + gb->first, X, h, i, NULL, &examined);
    }
    search_free(&sr);
    return examined;
}
