/* The crack driver (paper 003 §3): grows the scene's cracks during a run, from
 * fibre to fibre, by the tip search of eq. 20, particle splitting (eqs. 21-32)
 * and new facets of the crack surface (§3.3).
 *
 * A growing tip (scene "crack_growth": tips, each the end of a pre-crack's
 * trace in the plane of a body with fibres) holds
 *   T      the tip (m, reference): the pre-crack's end, then a fibre's centre;
 *   V1     the crack's direction (previous tip -> T, in the plane);
 *   fibre  the tip fibre (an index of m->fibres[body], -1 while T is the
 *          pre-crack's end, which is no fibre);
 *   end    where the crack surface ends (m): the cut front.
 * After each step (after the damage update), per tip: eq. 20 among the fibres
 * within R of T (a list kept per tip, refreshed after an advance: a search
 * each step costs that list, a dozen fibres, not the body; each step, because
 * a tip that qualifies between two searches would wait with its damage
 * growing past D_c, and the search is cheaper than a force pass by orders of
 * magnitude).  When fibre J qualifies, with V2 = C_J - T:
 *   - the old tip fibre I (when T is one) is split (crack/split.h), its halves
 *     at +-delta, delta = TLSPH_CRACK_DELTA spacings normal to V2 in the plane
 *     ("|delta| << 1" in the paper: here 1 % of the spacing, far below the
 *     support and far above the visibility test's round-off), with the sector
 *     angles of V1 and V2;
 *   - facets spanning the thickness (the fibres' extent along the axis plus
 *     half a spacing each side, the plate's faces) are added along end -> C_I
 *     and C_I -> C_J - eta V2/|V2|, eta = |delta|: the surface runs through
 *     the split fibre (the paper's facets join the crack-tip fibres the crack
 *     has passed) and stops just short of the new tip, whose particles would
 *     otherwise lie on the facets' edge and be cut from every neighbour (a
 *     point on a facet's side is "blocked", eq. 42); the split's local rebuild
 *     cuts the pairs crossing them (first_new_facet);
 *   - T = C_J, V1 = V2, fibre = J.
 * The first advance from a pre-crack's end moves the tip to J without a split
 * or facet: the end is no fibre, there is nothing to split, and the local
 * rebuild grows its region from split particles; its facets (end -> C_J) come
 * with J's split at the next advance.
 * At the body's edge (the new tip fibre has fewer than 8 fibres within 1.5
 * spacings: a lattice fibre inside has 8 neighbours, more after splits beside
 * it) the crack goes through: the edge fibre is split too (straight, V1 = V2)
 * and the facets run past the edge by a spacing; the tip stops growing.
 * One advance per tip and step: the damage field answers the cut before the
 * next search.
 * In a body with fibres per region (thickness_regions, crack/fibre.h) "the
 * plane" is the tip's region's (tip.region: the region of the fibre a started
 * tip started at; for a listed tip the one region whose fibres' cells hold it,
 * within half a spacing of a fibre in the region's plane and within its
 * extent along the region's axis plus half a spacing; none or two: refused):
 * every geometric step below reads the body's fibres through that region's
 * view, and a tip never steps into another region.
 * On a curved shell (radial fibres, crack/fibre.h) "the plane" is the shell's
 * tangent plane at the point in question: V1 and V2 are projected on it, V1
 * once more at the tip before a split, delta is normal to V2 in it, and the
 * facets span the thickness along the radial lines at their ends.
 *
 * Initiation (crack_growth.initiate; paper 003 §6.2-6.3: in the stiffened
 * plates "once the increasing void volume fraction reaches the threshold,
 * crack is set to grow", with no pre-crack).  After the tips' searches, each
 * step scans every fibre of every thin body (O(fibres), the criterion sums):
 * a fibre whose sum reaches D_c and that is not "near a crack" starts one, in
 * ascending fibre index (deterministic; each start marks its surroundings
 * near, so one damaged patch starts one crack).  Near: within
 * TLSPH_CRACK_CLEAR spacings of a through-thickness pre-crack's trace, of a
 * fibre a tip has reached, or of a started crack, and every fibre a split
 * made (a face's fibre).  The crack's direction u: the paper gives none; here
 * normal to the largest principal stress of the fibre in the plane (the
 * Cauchy stress averaged over its particles, projected on the plane): the
 * opening mode's plane, the direction a mode-I crack runs, and the one the
 * tip search then keeps within its fan.  The fibre is split straight
 * (V1 = V2 = u, halves at +-delta across u) with facets spanning the
 * thickness from C - s/2 u to C + s/2 u (s the spacing), and two tips start
 * at C (no fibre, as a pre-crack's end) with directions +u and -u, their
 * surface ends at C (so a first advance through the edge cuts along C -> C_J,
 * between the edge fibre's halves).  On the body's edge (at_edge's rule) u is turned
 * inward (towards the mean of the neighbours' centres), the facets start a
 * spacing past the edge and one tip grows.  Started tips follow the scene's
 * tips in the tip array (tip[ntips + j]); the crack_tips series lists the
 * scene's tips only (its item count is fixed at output setup); the events
 * (started = 1) and the globals crack_length / crack_advances count them.
 * Meeting: with initiation on, a tip whose next fibre is a crack's face (a
 * fibre a split made or split) or another tip's fibre stops there, logged:
 * cracks are not joined (the last fibre between them stays whole), but no
 * fibre is split twice and no tip runs along another crack's faces.
 * At most TLSPH_CRACK_MAX_TIPS tips in all: past that the scan stops (logged
 * once).  fan_angle must be below 180 degrees (checked at setup): a started
 * tip sits between its fibre's halves, which a wider fan would take.
 *
 * Energy: splitting books nothing (split.h); cutting pairs releases the
 * stored energy of the cut pairs into the next steps' kinetic and internal
 * energy through the forces, which the account follows.
 *
 * Ownership: the driver owns its tips and event list (m->crack_driver,
 * released with the model).  Units: m, s; damage dimensionless. */
#ifndef TLSPH_CRACK_DRIVER_H
#define TLSPH_CRACK_DRIVER_H

#include <stddef.h>
#include <stdio.h>

#include "run/model.h"
#include "util/errors.h"

#define TLSPH_CRACK_DELTA 0.01  /* |delta|, spacings */
#define TLSPH_CRACK_MAX_TIPS 256 /* scene tips plus started ones (64 was reached by the
                                    stiffened plate across its bars at 0.73 ms) */
#define TLSPH_CRACK_CLEAR 2.0   /* spacings: "near a crack" for initiation */
#define TLSPH_CRACK_MAX_CAND 64 /* fibres within R of a tip (R < 2 spacings: <= 16 lattice
                                   fibres, plus split halves) */

/* One tip advance. */
struct tlsph_crack_event {
    long step;
    double time;             /* s */
    size_t tip;              /* index in crack_growth.tips */
    double position[3];      /* the new tip (fibre centre, reference), m */
    long fibre;              /* the new tip fibre */
    size_t split;            /* particles split by this advance (0 or the fibre's, twice at an edge) */
    size_t particles;        /* particle count after it */
    int started;             /* 1: a crack started at this fibre (initiation) */
};

struct tlsph_crack_tip {
    size_t body;
    double T[3], V1[3], end[3];
    long fibre;
    int region;              /* the fibres' region it grows in (fibre.h; 0 without regions) */
    int stopped;             /* reached the body's edge */
    double length;           /* in-plane length of the facets added (the cut's growth), m */
    size_t advances;
    size_t cand[TLSPH_CRACK_MAX_CAND], ncand;
};

struct tlsph_crack_driver {
    struct tlsph_crack_tip tip[TLSPH_CRACK_MAX_TIPS];
    size_t ntips;            /* the scene's tips: tip[0 .. ntips-1] */
    size_t nstarted;         /* started tips: tip[ntips .. ntips+nstarted-1] */
    size_t starts;           /* cracks started (initiation) */
    int full;                /* the tip array is full: no more starts */
    unsigned char **near;    /* initiation: per body, per fibre, 1 = near a crack; NULL without */
    size_t *near_cap;        /* entries allocated per body */
    double scan_seconds;     /* wall time in the initiation scan without its starts, s
                                (part of seconds) */
    struct tlsph_crack_event *event;
    size_t nevents, event_cap;
    size_t particles_split;  /* over the run */
    double seconds;          /* wall time in the driver (searches and advances), s */
};

/* For a scene with "crack_growth": m->crack_driver, each tip matched to a
 * body with fibres (its in-plane position inside the body's) and to the end
 * of a crack's trace in that body's plane (the crack must be through the
 * thickness: its corners on one line in the plane), V1 outwards along the
 * trace.  Refused at /crack_growth/tips/<j> otherwise, and at /crack_growth
 * when the body's material has no damage model (D stays 0).  With initiate:
 * every thin body's material is checked (at /crack_growth/initiate), the
 * crack surface is made empty when the scene has no pre-crack, and the
 * fibres near the pre-cracks are marked.  Call after the
 * fibres and the pre-cracks are set up.  0, or -1 with err. */
int tlsph_crack_driver_setup(struct tlsph_model *m, struct tlsph_errors *err);

/* The search and any advances after a step.  log (may be NULL) gets a line per
 * advance.  0, or -1 with err (a split refused or out of memory: the run
 * cannot go on with a crack surface its pairs do not match). */
int tlsph_crack_driver_step(struct tlsph_model *m, FILE *log, struct tlsph_errors *err);

/* Sum of the tips' grown lengths (started tips included), m; 0 without a driver. */
double tlsph_crack_driver_length(const struct tlsph_model *m);

void tlsph_crack_driver_release(struct tlsph_model *m);

#endif
