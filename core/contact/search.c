/* Contact search in the current configuration (contact/state.h).
 *
 * A cell list over the current positions, cells at least as large as the
 * reach 2 R_max + skin, lists every pair of particles that may touch: of
 * different bodies (contact_candidate) and closer than R_i + R_j + skin.  The
 * list stays valid until some particle has moved more than half the skin
 * since the search (two particles closing the skin between them each moved at
 * least half of it), so the search runs again only then; between searches a
 * step only checks the displacements.
 *
 * The grid is sized from the particles' bounding box; when fragments fly far
 * apart the cells grow (doubling) until the grid has at most 4 n + 64 cells,
 * so memory stays O(n) at the price of more candidates examined.  Within a
 * cell particles keep index order, and each particle scans the 27 (9 in 2-D)
 * cells around its own in a fixed order, so the lists do not depend on the
 * thread count. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/state.h"
#include "run/model.h"
#include "util/clock.h"
#include "util/parallel.h"

/* May i and j touch?  Particles of different bodies always; two of one body
 * (only with a damage model or virtual links, touch != NULL) when both are
 * flagged as able to touch and the pair is not a continuum
 * (tlsph_contact_same_body_pair or tlsph_contact_cut_pair, or _links with
 * virtual links) and not the two halves of a split particle. */
static inline int contact_candidate(const struct tlsph_model *m, const uint8_t *touch, size_t i,
                                    size_t j)
{
    const struct tlsph_particles *p = &m->p;
    if (p->body[i] != p->body[j])
        return 1;
    if (!(touch && touch[i] && touch[j]))
        return 0;
    /* a pre-crack's faces (crack/precrack.h): their pairs were cut at setup,
     * so they touch like parts the reference neighbourhood never linked (with
     * virtual links the cut pairs are simply not linked) */
    if (m->links)
        return tlsph_contact_same_body_pair_links(m, i, j);
    return (tlsph_contact_same_body_pair(p, i, j) || tlsph_contact_cut_pair(m, i, j)) &&
           !tlsph_contact_split_halves(p, i, j);
}

/* Is i in the grid: every particle with more than one body, else only those
 * that can touch. */
static inline int in_grid(const struct tlsph_contact *c, size_t i)
{
    return c->all_particles || c->touch[i];
}

struct grid {
    double lo[3];
    double cell; /* m */
    int64_t dims[3];
    int dim;
};

/* Cells along each axis for the bounds lo..hi: the particles' cells plus one
 * on each side, so the 3 x 3 x 3 block around any particle's cell exists. */
static double grid_layout(struct grid *g, const double hi[3], double cell, double limit)
{
    double dims[3], total = 1.0;
    for (int d = 0; d < 3; d++) {
        dims[d] = d < g->dim ? floor((hi[d] - g->lo[d]) / cell) + 3.0 : 1.0;
        total *= dims[d];
    }
    if (total <= limit) { /* only then do the counts fit the integers */
        g->cell = cell;
        for (int d = 0; d < 3; d++)
            g->dims[d] = (int64_t)dims[d];
    }
    return total;
}

static int64_t grid_key(const struct grid *g, const double *x)
{
    int64_t c[3] = {0, 0, 0};
    for (int d = 0; d < g->dim; d++)
        c[d] = (int64_t)floor((x[d] - g->lo[d]) / g->cell) + 1;
    return (c[2] * g->dims[1] + c[1]) * g->dims[0] + c[0];
}

/* Candidates of particle i: counted (out NULL) or written to out. */
static size_t scan(const struct tlsph_model *m, const struct tlsph_contact *c, const struct grid *g,
                   size_t i, int32_t *out)
{
    const double *x = m->p.x;
    const int32_t *body = m->p.body;
    if (!in_grid(c, i))
        return 0;
    const double ri = c->bodies[body[i]].radius + c->skin;
    /* a graded body's pairs reach only min(reach_i, reach_j) x (R_i + R_j)
     * (touch.c): searched that far, not the coarse radius's (which made the
     * contact search 68 % of a graded notched bar's run) */
    const double *reach_f = m->p.spacing ? c->reach : NULL;
    const int64_t home = c->key[i];
    const int zr = g->dim == 3 ? 1 : 0;
    size_t n = 0;
    for (int dz = -zr; dz <= zr; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                const int64_t cell = home + (dz * g->dims[1] + dy) * g->dims[0] + dx;
                for (int64_t k = c->cell_start[cell]; k < c->cell_start[cell + 1]; k++) {
                    const size_t j = (size_t)c->order[k];
                    if (j == i || !contact_candidate(m, c->touch, i, j))
                        continue;
                    const double d0 = x[3 * j] - x[3 * i], d1 = x[3 * j + 1] - x[3 * i + 1],
                                 d2 = x[3 * j + 2] - x[3 * i + 2];
                    double reach = ri + c->bodies[body[j]].radius;
                    if (reach_f && body[j] == body[i])
                        reach = (reach - c->skin) * fmin(reach_f[i], reach_f[j]) + c->skin;
                    if (d0 * d0 + d1 * d1 + d2 * d2 >= reach * reach)
                        continue;
                    if (out)
                        out[n] = (int32_t)j;
                    n++;
                }
            }
    return n;
}

/* Largest squared displacement since the last search, m^2. */
static double moved(const struct tlsph_model *m, const struct tlsph_contact *c)
{
    const size_t n = m->p.n;
    const double *x = m->p.x, *x0 = c->x_search;
    double worst = 0.0;
#pragma omp parallel for schedule(static) reduction(max : worst) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++) {
        const double d0 = x[3 * i] - x0[3 * i], d1 = x[3 * i + 1] - x0[3 * i + 1],
                     d2 = x[3 * i + 2] - x0[3 * i + 2];
        const double d = d0 * d0 + d1 * d1 + d2 * d2;
        worst = d > worst ? d : worst;
    }
    return worst;
}

/* Grows *buf to at least count items of size bytes, counting the growth in
 * m->bytes_allocated. */
static int reserve(struct tlsph_model *m, void **buf, size_t *cap, size_t count, size_t size)
{
    if (count <= *cap)
        return 0;
    const size_t want = count + count / 4 + 16;
    void *p = realloc(*buf, want * size);
    if (!p)
        return -1;
    m->bytes_allocated += (want - *cap) * size;
    *buf = p;
    *cap = want;
    return 0;
}

int tlsph_contact_search(struct tlsph_model *m, struct tlsph_contact *c, int force)
{
    const size_t n = m->p.n;
    const double *x = m->p.x;
    if (!force && c->searches > 0 && moved(m, c) <= 0.25 * c->skin * c->skin)
        return 0;
    const double t0 = tlsph_monotonic_seconds();
    struct grid g = {.dim = m->dim};
    double hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int d = 0; d < 3; d++)
        g.lo[d] = INFINITY;
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 3 && in_grid(c, i); d++) {
            /* a run gone unstable: no cell for such a particle; the previous
             * candidates stay until the stability contract stops the run
             * (non_finite) */
            if (!isfinite(x[3 * i + d]))
                return 0;
            g.lo[d] = fmin(g.lo[d], x[3 * i + d]);
            hi[d] = fmax(hi[d], x[3 * i + d]);
        }
    if (!(g.lo[0] <= hi[0])) { /* no particle can touch yet: no candidate */
        memset(c->start, 0, (n + 1) * sizeof *c->start);
        memcpy(c->x_search, x, 3 * n * sizeof *x);
        c->searches++;
        c->search_seconds += tlsph_monotonic_seconds() - t0;
        return 0;
    }
    double cell = 2.0 * c->max_radius + c->skin;
    while (grid_layout(&g, hi, cell, 4.0 * (double)n + 64.0) > 4.0 * (double)n + 64.0)
        cell *= 2.0;
    const size_t cells = (size_t)(g.dims[0] * g.dims[1] * g.dims[2]);
    if (reserve(m, (void **)&c->cell_start, &c->cell_cap, cells + 1, sizeof *c->cell_start) != 0)
        return -1;

    /* counting sort by cell, stable: index order within a cell */
    memset(c->cell_start, 0, (cells + 1) * sizeof *c->cell_start);
    for (size_t i = 0; i < n; i++) {
        if (!in_grid(c, i))
            continue;
        c->key[i] = grid_key(&g, x + 3 * i);
        c->cell_start[c->key[i] + 1]++;
    }
    for (size_t k = 0; k < cells; k++)
        c->cell_start[k + 1] += c->cell_start[k];
    for (size_t i = 0; i < n; i++) { /* cell_start[key] counts up to the next cell's start */
        if (!in_grid(c, i))
            continue;
        const int64_t k = c->key[i];
        c->order[c->cell_start[k]++] = (int32_t)i;
    }
    for (size_t k = cells; k > 0; k--) /* back to starts */
        c->cell_start[k] = c->cell_start[k - 1];
    c->cell_start[0] = 0;

    int64_t *start = c->start;
#pragma omp parallel for schedule(static) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++)
        start[i + 1] = (int64_t)scan(m, c, &g, i, NULL);
    start[0] = 0;
    for (size_t i = 0; i < n; i++)
        start[i + 1] += start[i];
    if (reserve(m, (void **)&c->j, &c->cap, (size_t)start[n], sizeof *c->j) != 0 ||
        reserve(m, (void **)&c->s_pair, &c->s_cap, (size_t)start[n], sizeof *c->s_pair) != 0) {
        memset(start, 0, (n + 1) * sizeof *start);
        return -1;
    }
    if (start[n] > 0) {
#pragma omp parallel for schedule(static) if (n >= TLSPH_PARALLEL_MIN_ITEMS)
        for (size_t i = 0; i < n; i++)
            scan(m, c, &g, i, c->j + start[i]);
    }
    memcpy(c->x_search, x, 3 * n * sizeof *x);
    /* no force from the new candidates until the next evaluation (a search
     * may find none: then nothing was allocated) */
    if (start[n] > 0)
        memset(c->s_pair, 0, (size_t)start[n] * sizeof *c->s_pair);
    c->searches++;
    c->search_seconds += tlsph_monotonic_seconds() - t0;
    return 0;
}
