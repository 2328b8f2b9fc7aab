/* The contact phase's state (contact.h), shared by its files only: the search
 * (search.c) fills the candidate pairs, the force loops (forces.c) read them. */
#ifndef TLSPH_CONTACT_STATE_H
#define TLSPH_CONTACT_STATE_H

#include <stddef.h>
#include <stdint.h>

#include "crack/crack_surface.h"
#include "contact/contact.h"
#include "run/model.h"
#include "sph/virtual_links.h"

struct tlsph_contact {
    const struct tlsph_contact_law *law;
    struct tlsph_contact_body *bodies;  /* [nbodies] */
    double params[4];                   /* the law's parameters (scene) */
    enum tlsph_contact_variant variant; /* the pair loop (law->variant) */
    double skin;                        /* m */
    double max_radius;                  /* largest contact radius, m */

    /* Contact within a body (scenes with a damage model): only particles that
     * can touch enter such a pair, flagged in touch[] (NULL without damage):
     * TOUCH_SURFACE at setup, TOUCH_FAILED and TOUCH_NEAR_FAILED as particles
     * fail (tlsph_contact_watch).  all_particles: the grid holds every
     * particle (more than one body: pairs of different bodies need no flag),
     * else only the flagged ones. */
    uint8_t *touch; /* [n] */
    /* Reach factor of each particle, 1, [n] with touch: a pair of one body
     * touches at min(reach_i, reach_j) x (R_i + R_j).  1 at setup, unless a
     * law's radii reach past the nearest non-neighbours (a pin-ball of radius
     * factor near 1); when a particle is flagged (the surface layer at
     * setup, later as it or a neighbour fails), it is lowered to the
     * pair distance / (R_i + R_j) of any of its new candidates already
     * closer (tlsph_contact_settle), so every pair starts its contact
     * without overlap and the force rises only with a later approach.  Thus
     * contact does not push apart the still-compact material around a failed
     * particle (a necking bar's lateral neighbours sit closer than a
     * spacing: a reach of one spacing would release a force, and energy,
     * that no motion caused). */
    double *reach;
    size_t touching; /* particles flagged */
    /* a split (crack/split.h) flagged its halves anew: the next evaluation
     * settles them after its search, as for particles that failed */
    int settle_pending;
    int all_particles;

    /* Candidates: the pairs of i are j[start[i] .. start[i+1]-1], every pair
     * listed from both sides (gather form: each particle sums its own). */
    int64_t *start; /* [n+1] */
    int32_t *j;     /* [cap] */
    size_t cap;
    /* F / r of each candidate entry in the last evaluation (0: not in
     * contact), N/m [s_cap >= start[n]]: the force on i from j[k] was
     * -s_pair[k] (x_j - x_i), which the pair series sum (tlsph_contact_pair_force) */
    double *s_pair;
    size_t s_cap;
    double *x_search; /* positions at the last search, m [3n] */

    /* cell list of the last search, reused by the next one */
    int64_t *key;        /* cell of each particle [n] */
    int32_t *order;      /* particles sorted by cell, index order within a cell [n] */
    int64_t *cell_start; /* [cells + 1] */
    size_t cell_cap;     /* entries allocated in cell_start */

    double *f_old; /* contact force of the last evaluation, N [3n] (trapezoidal work) */

    /* Body pairs with a force series (a < b, scene order; none when there
     * would be more than TLSPH_MAX_CONTACT_PAIR_SERIES): names "<a>--<b>",
     * "" where that is not a valid, unique name (no series) */
    size_t npairs;
    int32_t (*pair)[2];
    char (*pair_name)[64];

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

/* touch[] flags */
#define TLSPH_TOUCH_SURFACE     1u /* fewer reference neighbours than the body's interior */
#define TLSPH_TOUCH_FAILED      2u /* failed (D = 1), or with virtual links an end of a
                                      broken link: seen by the watch */
#define TLSPH_TOUCH_NEAR_FAILED 4u /* a reference neighbour failed: a crack face */
#define TLSPH_TOUCH_NEW         8u /* flagged anew since the last settle */

/* touch.c: flags the surface layer of the damaged bodies (setup, touch
 * allocated and zero). */
void tlsph_contact_touch_setup(struct tlsph_model *m, struct tlsph_contact *c);
/* Flags the particles that failed since the last call and their reference
 * neighbours (TLSPH_TOUCH_NEW on each whose flags changed); returns how many
 * failed since (a new search is due: their pairs are candidates now). */
size_t tlsph_contact_watch(struct tlsph_model *m, struct tlsph_contact *c);
/* After that search: lowers the reach factor of every particle flagged anew
 * so that none of its pairs within its body starts overlapped, and clears
 * TLSPH_TOUCH_NEW.  Serial, in index order (deterministic). */
void tlsph_contact_settle(struct tlsph_model *m, struct tlsph_contact *c);

/* Are i and j (same body) reference neighbours?  The test of the reference
 * search (sph/neighbors.c), the same operations in the same order: |X_ij| <
 * h_i + h_j; symmetric in i, j. */
static inline __attribute__((always_inline)) int
tlsph_contact_reference_pair(const struct tlsph_particles *p, size_t i, size_t j)
{
    const double *X = p->X;
    const double dx = X[3 * j] - X[3 * i], dy = X[3 * j + 1] - X[3 * i + 1],
                 dz = X[3 * j + 2] - X[3 * i + 2];
    const double r2 = dx * dx + dy * dy + dz * dz;
    const double rc = p->h[i] + p->h[j];
    return r2 < rc * rc;
}

/* Does the pair i, j of one body interact by contact?  When they are not
 * reference neighbours (parts of the body that the reference neighbourhood
 * never linked: fragments, folds), or when their link is broken: one of them
 * failed (D = 1), so the pair exchanges no stress force (damage_aware.h eq.
 * 35: a failed particle carries no stress and its partner's stress is weighed
 * by 1 - D = 0; pseudo_spring.h: the kernel is scaled by 0).  A pair of intact
 * (D < 1) reference neighbours is still a continuum: never in contact. */
static inline __attribute__((always_inline)) int
tlsph_contact_same_body_pair(const struct tlsph_particles *p, size_t i, size_t j)
{
    return !tlsph_contact_reference_pair(p, i, j) || p->damage[i] >= 1.0 || p->damage[j] >= 1.0;
}

/* Is the pair i, j (same body) one that a pre-crack cut at setup (its
 * reference sight line crosses m->crack_surface, crack/precrack.h)?  Such a
 * pair is no continuum: the crack's faces may touch.  0 without cracks. */
static inline int tlsph_contact_cut_pair(const struct tlsph_model *m, size_t i, size_t j)
{
    return m->crack_surface &&
           tlsph_crack_surface_cuts_pair(m->crack_surface, m->p.X + 3 * i, i, m->p.X + 3 * j, j);
}

/* Are i and j (same body) the two halves of one split particle (crack/split.h:
 * X +- delta, |delta| a small share of the spacing)?  They are one material
 * point on the two faces of the crack, never a contact pair: their distance
 * is no approach, and as a candidate it would lower both reach factors to it
 * and leave the faces without contact.  No two particles of a lattice, graded
 * or conforming body sit closer than half of h_i + h_j otherwise. */
static inline int tlsph_contact_split_halves(const struct tlsph_particles *p, size_t i, size_t j)
{
    const double *X = p->X;
    const double dx = X[3 * j] - X[3 * i], dy = X[3 * j + 1] - X[3 * i + 1],
                 dz = X[3 * j + 2] - X[3 * i + 2];
    const double rc = 0.25 * (p->h[i] + p->h[j]);
    return dx * dx + dy * dy + dz * dz < rc * rc;
}

/* The same with virtual links (sph/virtual_links.h), where the continuum is
 * the links: a pair of one body can touch when it is not linked (the pairs
 * beyond the immediate neighbours never interact) or its link is broken. */
static inline int tlsph_contact_same_body_pair_links(const struct tlsph_model *m, size_t i,
                                                     size_t j)
{
    for (int64_t k = m->pairs.start[i]; k < m->pairs.start[i + 1]; k++)
        if ((size_t)m->pairs.j[k] == j)
            return m->links->D[k] >= 1.0;
    return 1;
}

#endif
