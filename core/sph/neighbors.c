#include "sph/neighbors.h"
#include "util/parallel.h"

#include <math.h>
#include <stdlib.h>

struct cell_entry {
    int64_t key;
    size_t index;
};

struct grid {
    double lo[3];
    double size;
    int64_t dims[3];
};

static int cmp_entry(const void *a, const void *b)
{
    const struct cell_entry *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return x->index < y->index ? -1 : (x->index > y->index);
}

static void grid_init(struct grid *g, const double *X, size_t n, double size)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            lo[c] = fmin(lo[c], X[3 * i + c]);
            hi[c] = fmax(hi[c], X[3 * i + c]);
        }
    g->size = size;
    for (int c = 0; c < 3; c++) {
        g->lo[c] = lo[c] - size;
        g->dims[c] = (int64_t)floor((hi[c] - g->lo[c]) / size) + 2;
    }
}

static void cell_of(const struct grid *g, const double *x, int64_t c[3])
{
    for (int k = 0; k < 3; k++)
        c[k] = (int64_t)floor((x[k] - g->lo[k]) / g->size);
}

static int64_t cell_key(const struct grid *g, const int64_t c[3])
{
    return (c[2] * g->dims[1] + c[1]) * g->dims[0] + c[0];
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
    struct cell_entry *e = malloc(n * sizeof *e);
    if (!e)
        return -1;
    struct grid g;
    grid_init(&g, X, n, cell_size);
    const int64_t ncells = g.dims[0] * g.dims[1] * g.dims[2];
    for (size_t i = 0; i < n; i++) {
        int64_t c[3];
        cell_of(&g, X + 3 * i, c);
        e[i].key = (body ? (int64_t)body[i] * ncells : 0) + cell_key(&g, c);
        e[i].index = i;
    }
    qsort(e, n, sizeof *e, cmp_entry);
    for (size_t i = 0; i < n; i++)
        order[i] = e[i].index;
    free(e);
    return 0;
}

/* Visits the candidate neighbours of i; count-only when out == NULL. */
static size_t scan(const struct grid *g, const struct cell_entry *e, size_t n, const double *X,
                   const double *h, const int32_t *body, size_t i, int32_t *out)
{
    int64_t c[3];
    cell_of(g, X + 3 * i, c);
    size_t count = 0;
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++) {
            /* the three cells along x are contiguous in key order */
            int64_t a[3] = {c[0] - 1, c[1] + dy, c[2] + dz};
            int64_t k0 = cell_key(g, a);
            size_t s = lower_bound(e, n, k0);
            for (; s < n && e[s].key <= k0 + 2; s++) {
                size_t j = e[s].index;
                if (j == i || (body && body[j] != body[i]))
                    continue;
                const double dx = X[3 * j] - X[3 * i], dy_ = X[3 * j + 1] - X[3 * i + 1],
                             dz_ = X[3 * j + 2] - X[3 * i + 2];
                const double r2 = dx * dx + dy_ * dy_ + dz_ * dz_;
                const double rc = h[i] + h[j];
                if (r2 < rc * rc) {
                    if (out)
                        out[count] = (int32_t)j;
                    count++;
                }
            }
        }
    return count;
}

int tlsph_build_pairs(const double *X, const double *h, const int32_t *body, size_t n,
                      int64_t **start_out, int32_t **nbr_out)
{
    *start_out = NULL;
    *nbr_out = NULL;
    int64_t *start = calloc(n + 1, sizeof *start);
    struct cell_entry *e = malloc((n ? n : 1) * sizeof *e);
    if (!start || !e) {
        free(start);
        free(e);
        return -1;
    }
    double hmax = 0.0;
    for (size_t i = 0; i < n; i++)
        hmax = fmax(hmax, h[i]);
    struct grid g;
    if (n) {
        grid_init(&g, X, n, 2.0 * hmax);
        for (size_t i = 0; i < n; i++) {
            int64_t c[3];
            cell_of(&g, X + 3 * i, c);
            e[i].key = cell_key(&g, c);
            e[i].index = i;
        }
        qsort(e, n, sizeof *e, cmp_entry);
    }
#pragma omp parallel for schedule(dynamic, 256) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++)
        start[i + 1] = (int64_t)scan(&g, e, n, X, h, body, i, NULL);
    for (size_t i = 0; i < n; i++)
        start[i + 1] += start[i];
    int32_t *nbr = malloc((start[n] ? (size_t)start[n] : 1) * sizeof *nbr);
    if (!nbr) {
        free(start);
        free(e);
        return -1;
    }
#pragma omp parallel for schedule(dynamic, 256) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++)
        scan(&g, e, n, X, h, body, i, nbr + start[i]);
    free(e);
    *start_out = start;
    *nbr_out = nbr;
    return 0;
}
