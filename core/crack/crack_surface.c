/* Crack facets in a sparse cell hash; the design is in crack_surface.h. */
#include "crack/crack_surface.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "crack/visibility.h"

#define GRID_HALF (1L << 20) /* cells from the origin per axis: 21 bits per key part */
#define EMPTY_KEY UINT64_MAX

struct tlsph_crack_cell_slot {
    uint64_t key;
    size_t head; /* first entry + 1; 0: none */
};

struct tlsph_crack_cell_entry {
    size_t facet;
    size_t next; /* next entry + 1; 0: end of the chain */
};

static uint64_t mix(uint64_t x)
{
    /* splitmix64's finaliser: neighbouring cells land in unrelated slots */
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

static uint64_t cell_key(const long c[3])
{
    return ((uint64_t)(c[0] + GRID_HALF) << 42) | ((uint64_t)(c[1] + GRID_HALF) << 21) |
           (uint64_t)(c[2] + GRID_HALF);
}

/* The cell range covering [lo, hi] on every axis; false when out of the grid. */
static bool cell_range(const struct tlsph_crack_surface *s, const double lo[3], const double hi[3], long c0[3],
                       long c1[3])
{
    for (int a = 0; a < 3; a++) {
        const double f0 = floor(lo[a] / s->cell), f1 = floor(hi[a] / s->cell);
        if (!(f0 >= -GRID_HALF && f1 < GRID_HALF))
            return false;
        c0[a] = (long)f0;
        c1[a] = (long)f1;
    }
    return true;
}

static size_t find_slot(const struct tlsph_crack_cell_slot *slot, size_t nslots, uint64_t key)
{
    size_t i = (size_t)mix(key) & (nslots - 1);
    while (slot[i].key != key && slot[i].key != EMPTY_KEY)
        i = (i + 1) & (nslots - 1);
    return i;
}

static enum tlsph_crack_status grow_slots(struct tlsph_crack_surface *s)
{
    const size_t n = s->nslots ? 2 * s->nslots : 64;
    struct tlsph_crack_cell_slot *slot = malloc(n * sizeof *slot);
    if (!slot)
        return TLSPH_CRACK_NO_MEMORY;
    for (size_t i = 0; i < n; i++)
        slot[i] = (struct tlsph_crack_cell_slot){EMPTY_KEY, 0};
    for (size_t i = 0; i < s->nslots; i++)
        if (s->slot[i].key != EMPTY_KEY)
            slot[find_slot(slot, n, s->slot[i].key)] = s->slot[i];
    free(s->slot);
    s->slot = slot;
    s->nslots = n;
    return TLSPH_CRACK_OK;
}

static enum tlsph_crack_status reserve(void **p, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap)
        return TLSPH_CRACK_OK;
    size_t n = *cap ? *cap : 16;
    while (n < need)
        n *= 2;
    void *q = realloc(*p, n * size);
    if (!q)
        return TLSPH_CRACK_NO_MEMORY;
    *p = q;
    *cap = n;
    return TLSPH_CRACK_OK;
}

enum tlsph_crack_status tlsph_crack_surface_init(struct tlsph_crack_surface *s, double cell)
{
    memset(s, 0, sizeof *s);
    if (!(cell > 0) || !isfinite(cell))
        return TLSPH_CRACK_BAD_INPUT;
    s->cell = cell;
    return TLSPH_CRACK_OK;
}

static void facet_box(const double T[3][3], double lo[3], double hi[3])
{
    for (int a = 0; a < 3; a++) {
        lo[a] = fmin(fmin(T[0][a], T[1][a]), T[2][a]);
        hi[a] = fmax(fmax(T[0][a], T[1][a]), T[2][a]);
    }
}

enum tlsph_crack_status tlsph_crack_surface_add(struct tlsph_crack_surface *s, const double T[3][3])
{
    for (int k = 0; k < 3; k++)
        for (int a = 0; a < 3; a++)
            if (!isfinite(T[k][a]))
                return TLSPH_CRACK_BAD_INPUT;
    double lo[3], hi[3];
    long c0[3], c1[3];
    facet_box(T, lo, hi);
    if (!cell_range(s, lo, hi, c0, c1))
        return TLSPH_CRACK_OUT_OF_GRID;
    const size_t ncells = (size_t)(c1[0] - c0[0] + 1) * (size_t)(c1[1] - c0[1] + 1) * (size_t)(c1[2] - c0[2] + 1);

    /* reserve everything first, so that a failure leaves the surface as it was */
    enum tlsph_crack_status st;
    if ((st = reserve((void **)&s->facet, &s->facet_cap, s->nfacets + 1, sizeof *s->facet)) != TLSPH_CRACK_OK ||
        (st = reserve((void **)&s->entry, &s->entry_cap, s->nentries + ncells, sizeof *s->entry)) != TLSPH_CRACK_OK)
        return st;
    while (2 * (s->nused + ncells) > s->nslots)
        if ((st = grow_slots(s)) != TLSPH_CRACK_OK)
            return st;

    const size_t f = s->nfacets++;
    memcpy(s->facet[f], T, sizeof s->facet[f]);
    long c[3];
    for (c[0] = c0[0]; c[0] <= c1[0]; c[0]++)
        for (c[1] = c0[1]; c[1] <= c1[1]; c[1]++)
            for (c[2] = c0[2]; c[2] <= c1[2]; c[2]++) {
                const uint64_t key = cell_key(c);
                const size_t i = find_slot(s->slot, s->nslots, key);
                if (s->slot[i].key == EMPTY_KEY) {
                    s->slot[i] = (struct tlsph_crack_cell_slot){key, 0};
                    s->nused++;
                }
                s->entry[s->nentries] = (struct tlsph_crack_cell_entry){f, s->slot[i].head};
                s->slot[i].head = ++s->nentries;
            }
    return TLSPH_CRACK_OK;
}

static bool facet_blocks(const struct tlsph_crack_surface *s, size_t f, const double A[3], const double B[3],
                         size_t *tests)
{
    ++*tests;
    return tlsph_sight_blocked(tlsph_sight_through_facet(A, B, (const double(*)[3])s->facet[f]));
}

bool tlsph_crack_surface_blocks(const struct tlsph_crack_surface *s, const double A[3], const double B[3],
                                size_t *tests)
{
    size_t count = 0, *n = tests ? tests : &count;
    *n = 0;
    if (s->nfacets == 0)
        return false;
    double lo[3], hi[3];
    long c0[3], c1[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = fmin(A[a], B[a]);
        hi[a] = fmax(A[a], B[a]);
    }
    /* a segment outside the grid, or one crossing more cells than there are
     * facets, is cheaper to test against every facet */
    double ncells = 0;
    if (cell_range(s, lo, hi, c0, c1))
        ncells = (double)(c1[0] - c0[0] + 1) * (double)(c1[1] - c0[1] + 1) * (double)(c1[2] - c0[2] + 1);
    if (ncells == 0 || ncells > (double)s->nfacets) {
        for (size_t f = 0; f < s->nfacets; f++)
            if (facet_blocks(s, f, A, B, n))
                return true;
        return false;
    }
    long c[3];
    for (c[0] = c0[0]; c[0] <= c1[0]; c[0]++)
        for (c[1] = c0[1]; c[1] <= c1[1]; c[1]++)
            for (c[2] = c0[2]; c[2] <= c1[2]; c[2]++) {
                const size_t i = find_slot(s->slot, s->nslots, cell_key(c));
                for (size_t e = s->slot[i].key == EMPTY_KEY ? 0 : s->slot[i].head; e; e = s->entry[e - 1].next)
                    if (facet_blocks(s, s->entry[e - 1].facet, A, B, n))
                        return true;
            }
    return false;
}

void tlsph_crack_surface_release(struct tlsph_crack_surface *s)
{
    free(s->facet);
    free(s->slot);
    free(s->entry);
    memset(s, 0, sizeof *s);
}
