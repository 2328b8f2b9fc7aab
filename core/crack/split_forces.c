/* The split's force update on the rows it changes (split_forces.h). */
#include "crack/split_forces.h"

#include <stdlib.h>
#include <string.h>

#include "sph/forces.h"

static int cmp_size(const void *a, const void *b)
{
    const size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return (x > y) - (x < y);
}

void tlsph_split_forces_free(struct tlsph_split_forces *sf)
{
    free(sf->rows);
    for (int q = 0; q < 3; q++)
        free(sf->rest[q]);
    memset(sf, 0, sizeof *sf);
}

int tlsph_split_forces_prepare(const struct tlsph_model *m, const struct tlsph_rebuild_plan *plan,
                               size_t at, struct tlsph_split_forces *sf)
{
    memset(sf, 0, sizeof *sf);
    const size_t k = plan->k;
    const int64_t *start = m->pairs.start;
    /* the affected rows that existed before (the halves are new), old indices,
     * and their old partners: counted, then listed */
    size_t count = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t r = 0; r < plan->nrows; r++) {
            const size_t i = plan->rows[r];
            if (i >= at && i < at + k)
                continue;
            const size_t o = i < at ? i : i - k;
            if (pass == 0) {
                count += 1 + (size_t)(start[o + 1] - start[o]);
                continue;
            }
            sf->rows[sf->nrows++] = o;
            for (int64_t e = start[o]; e < start[o + 1]; e++)
                sf->rows[sf->nrows++] = (size_t)m->pairs.j[e];
        }
        if (pass == 0 && !(sf->rows = malloc((count + k) * sizeof *sf->rows)))
            return -1;
    }
    const size_t c = sf->nrows;
    qsort(sf->rows, c, sizeof *sf->rows, cmp_size);
    size_t u = 0;
    for (size_t a = 0; a < c; a++)
        if (u == 0 || sf->rows[a] != sf->rows[u - 1])
            sf->rows[u++] = sf->rows[a];
    sf->nrows = u;
    sf->k = k;
    const double *stored[3] = {m->p.f, m->p.f_hourglass, m->p.f_viscous};
    for (int q = 0; q < 3; q++)
        if (stored[q] && !(sf->rest[q] = malloc(3 * (u + k) * sizeof(double)))) {
            tlsph_split_forces_free(sf);
            return -1;
        }
    return 0;
}

/* Index of row i in the ascending rows, or n. */
static size_t find_row(const size_t *rows, size_t n, size_t i)
{
    const size_t *hit = bsearch(&i, rows, n, sizeof *rows, cmp_size);
    return hit ? (size_t)(hit - rows) : n;
}

void tlsph_split_forces_rest(struct tlsph_model *m, size_t body, struct tlsph_split_forces *sf,
                             const size_t *parent, double share)
{
    double *field[3] = {m->p.f, m->p.f_hourglass, m->p.f_viscous};
    const size_t n = sf->nrows;
    for (int q = 0; q < 3; q++)
        if (sf->rest[q])
            for (size_t r = 0; r < n; r++)
                memcpy(sf->rest[q] + 3 * r, field[q] + 3 * sf->rows[r], 3 * sizeof(double));
    tlsph_forces_rows(m, body, sf->rows, n); /* the old supports' pair sums */
    for (int q = 0; q < 3; q++) {
        double *rest = sf->rest[q];
        if (!rest)
            continue;
        for (size_t r = 0; r < n; r++)
            for (int c = 0; c < 3; c++)
                rest[3 * r + c] -= field[q][3 * sf->rows[r] + c];
        for (size_t s = 0; s < sf->k; s++) {
            /* every parent is an affected row (distance 0 from itself) */
            const size_t r = find_row(sf->rows, n, parent[s]);
            for (int c = 0; c < 3; c++) {
                double *e1 = rest + 3 * r + c, *e2 = rest + 3 * (n + s) + c;
                const double whole = *e1;
                *e1 = whole * share;
                *e2 = whole - *e1;
            }
        }
    }
}

void tlsph_split_forces_finish(struct tlsph_model *m, size_t body, struct tlsph_split_forces *sf,
                               size_t at)
{
    const size_t n = sf->nrows, k = sf->k;
    for (size_t r = 0; r < n; r++)
        sf->rows[r] += sf->rows[r] < at ? 0 : k;
    for (size_t s = 0; s < k; s++)
        sf->rows[n + s] = at + s;
    tlsph_forces_rows(m, body, sf->rows, n + k); /* the new supports' pair sums */
    double *field[3] = {m->p.f, m->p.f_hourglass, m->p.f_viscous};
    for (int q = 0; q < 3; q++)
        if (sf->rest[q])
            for (size_t r = 0; r < n + k; r++)
                for (int c = 0; c < 3; c++)
                    field[q][3 * sf->rows[r] + c] += sf->rest[q][3 * r + c];
}
