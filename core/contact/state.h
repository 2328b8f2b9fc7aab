/* The contact phase's state (contact.h), shared by its files only: the search
 * (search.c) fills the candidate pairs, the force loops (forces.c) read them. */
#ifndef TLSPH_CONTACT_STATE_H
#define TLSPH_CONTACT_STATE_H

#include <stddef.h>
#include <stdint.h>

#include "contact/contact.h"

struct tlsph_contact {
    const struct tlsph_contact_law *law;
    struct tlsph_contact_body *bodies;  /* [nbodies] */
    double params[4];                   /* the law's parameters (scene) */
    enum tlsph_contact_variant variant; /* the pair loop (law->variant) */
    double skin;                        /* m */
    double max_radius;                  /* largest contact radius, m */

    /* Candidates: the pairs of i are j[start[i] .. start[i+1]-1], every pair
     * listed from both sides (gather form: each particle sums its own). */
    int64_t *start; /* [n+1] */
    int32_t *j;     /* [cap] */
    size_t cap;
    double *x_search; /* positions at the last search, m [3n] */

    /* cell list of the last search, reused by the next one */
    int64_t *key;        /* cell of each particle [n] */
    int32_t *order;      /* particles sorted by cell, index order within a cell [n] */
    int64_t *cell_start; /* [cells + 1] */
    size_t cell_cap;     /* entries allocated in cell_start */

    double *f_old; /* contact force of the last evaluation, N [3n] (trapezoidal work) */

    long searches;
    double search_seconds, phase_seconds; /* wall-clock, s (contact.h) */
    size_t active; /* pairs in contact in the last evaluation (each counted once) */
    /* deepest overlap / (R_i + R_j) of any pair since the stability contract
     * last looked (tlsph_contact_take_overlap) */
    double max_overlap;
    int failed; /* a search ran out of memory */
};

/* A search at the current positions when some particle moved more than half
 * the skin since the last one (or when force is set).  Returns 0, or -1 out of
 * memory (then no candidate is left: the run must stop). */
int tlsph_contact_search(struct tlsph_model *m, struct tlsph_contact *c, int force);

#endif
