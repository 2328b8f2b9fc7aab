/* Pre-cracks from the scene ("cracks", core/scene/parse_cracks.c): each crack
 * becomes facets of the model's crack surface (crack_surface.h), and reference
 * pairs whose sight line X_i - X_j crosses a facet are not created (paper 003
 * §3.3's visibility condition applied once at setup).  A cut pair carries no
 * force of any kind: stress, hourglass and viscosity all run over the pair
 * list; the correction matrices are then built on the cut supports (the
 * particles along the crack faces and around its front see one-sided
 * supports; a rank-deficient one takes the safe inverse and is counted in
 * m->deficient_supports like any other).
 *
 * Facets:
 *  - 3-D polygon: a fan of triangles from the corners' mean (the polygon is
 *    convex, so the fan covers it exactly once), each triangle then halved
 *    into four (midpoints) until no edge is longer than the surface's cell,
 *    so a facet's bounding box covers a few cells, not the whole crack's.
 *  - 2-D segment: pieces no longer than the cell, each extruded to a
 *    rectangle z in [-cell/2, cell/2] made of two triangles; the particles and
 *    their sight lines lie in z = 0, so the 3-D test answers the 2-D question
 *    (does the sight line cross the segment), the ends of the segment
 *    included (eq. 42's ">= 0": a sight line through the crack tip is cut).
 * A particle exactly on a crack is cut from every neighbour not in the
 * crack's plane (lambda = 0 is "on the facet"); place cracks between lattice
 * rows (points sit at origin + (i + 1/2) spacing). */
#ifndef TLSPH_CRACK_PRECRACK_H
#define TLSPH_CRACK_PRECRACK_H

#include <stddef.h>
#include <stdint.h>

#include "crack/crack_surface.h"
#include "scene/scene.h"

struct tlsph_model;

/* Adds the facets of crack c (scene dimension dim: 2 = segment, 3 = polygon)
 * to s, subdivided to edges <= s->cell.  *nfacets (when not NULL) gets the
 * number added.  On an error facets already added stay. */
enum tlsph_crack_status tlsph_precrack_add(struct tlsph_crack_surface *s,
                                           const struct tlsph_crack_spec *c, int dim,
                                           size_t *nfacets);

/* Removes from the CSR pair list (start[n + 1], j[start[n]], compacted in
 * place, start rewritten) every pair (i, k) whose sight line X_i - X_k (X:
 * 3 n, m) s blocks.  Each pair is tested once with its lower index first, so
 * the list stays symmetric.  Returns the number of list entries removed
 * (twice the pairs cut), or SIZE_MAX when out of memory (list unchanged). */
size_t tlsph_precrack_cut_pairs(const struct tlsph_crack_surface *s, const double *X, size_t n,
                                int64_t *start, int32_t *j);

/* For a scene with cracks: m->crack_surface (cell = the largest support
 * diameter 2 h) with the facets of every crack, and the reference pairs cut
 * (m->cut_pairs, pairs).  Refuses a crack set that cuts no pair at all (it
 * misses every body: wrong units or place) at /cracks.  Call after the pairs
 * are built and before anything reads them.  0, or -1 with err. */
int tlsph_precrack_setup(struct tlsph_model *m, struct tlsph_errors *err);

/* Releases m->crack_surface (NULL is fine). */
void tlsph_precrack_release(struct tlsph_model *m);

#endif
