/* A crack surface as a growing set of triangular facets (paper 003 §3.2: the
 * facets join the first and last particles of the crack-tip fibres the crack
 * has passed), with a cell index so that asking "does this facet set block the
 * sight line A-B?" costs the facets near A-B, not the whole crack, and adding a
 * facet costs the cells it covers.  A crack that grows by one facet per tip
 * advance therefore costs in proportion to its length, and a body of any size
 * pays nothing for the cracks it does not have.
 *
 * Cells are cubes of edge `cell` (m), hashed by their integer coordinates, so
 * the index is sparse: memory follows the crack, not the body's bounding box.
 * A facet is listed in every cell its bounding box overlaps; a query visits
 * the cells of the segment's bounding box.  With `cell` of the order of the
 * kernel support a pair's segment touches at most 8 cells.
 *
 * Ownership: the surface owns its arrays; release frees them.  Not
 * thread-safe for add; queries only read and may run concurrently. */
#ifndef TLSPH_CRACK_SURFACE_H
#define TLSPH_CRACK_SURFACE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct tlsph_crack_cell_slot; /* crack_surface.c */
struct tlsph_crack_cell_entry;

struct tlsph_crack_surface {
    double cell;           /* cell edge, m */
    double (*facet)[3][3]; /* facet[f][vertex][x, y, z], m */
    size_t nfacets, facet_cap;
    struct tlsph_crack_cell_slot *slot; /* open addressing, power-of-two size */
    size_t nslots, nused;
    struct tlsph_crack_cell_entry *entry; /* chains of facet ids per cell */
    size_t nentries, entry_cap;
};

enum tlsph_crack_status {
    TLSPH_CRACK_OK = 0,
    TLSPH_CRACK_NO_MEMORY = -1,
    TLSPH_CRACK_BAD_INPUT = -2,  /* a non-finite coordinate or cell size <= 0 */
    TLSPH_CRACK_OUT_OF_GRID = -3 /* more than 2^20 cells from the origin on an axis */
};

/* An empty surface indexed by cells of edge `cell` (m, > 0 and finite). */
enum tlsph_crack_status tlsph_crack_surface_init(struct tlsph_crack_surface *s, double cell);

/* Appends the facet T (three vertices, m) and indexes it.  Storage grows by
 * doubling, so a run that adds n facets reallocates O(log n) times.  On any
 * error the surface is unchanged. */
enum tlsph_crack_status tlsph_crack_surface_add(struct tlsph_crack_surface *s, const double T[3][3]);

/* True when some facet blocks the sight line A-B (tlsph_sight_blocked of
 * tlsph_sight_through_facet).  If `tests` is not NULL it receives the number
 * of facet tests made (a facet listed in several cells may be tested more
 * than once): the cost measure the tests check. */
bool tlsph_crack_surface_blocks(const struct tlsph_crack_surface *s, const double A[3], const double B[3],
                                size_t *tests);

/* Is the reference pair i, j cut, with Xi, Xj their positions?  The sight
 * line is always tested from the lower index to the higher, so every caller
 * (the setup's cut, the local rebuild after a split, contact between crack
 * faces) gets the same answer for the same pair, in degenerate cases too. */
static inline bool tlsph_crack_surface_cuts_pair(const struct tlsph_crack_surface *s,
                                                 const double *Xi, size_t i, const double *Xj,
                                                 size_t j)
{
    return i < j ? tlsph_crack_surface_blocks(s, Xi, Xj, NULL)
                 : tlsph_crack_surface_blocks(s, Xj, Xi, NULL);
}

void tlsph_crack_surface_release(struct tlsph_crack_surface *s);

#endif
