/* Fibres and the crack-tip search of paper 003 §3.1 (eq. 20).
 *
 * A thin body (a plate or a shell discretised with a few particle layers
 * through its thickness) is read as fibres: the particles stacked along the
 * thickness direction at one in-plane position (Fig. 1(b); the paper uses
 * three layers).  A through-thickness crack's tip is always a fibre, and it
 * moves from fibre to fibre.
 *
 * The lattice rule.  Particles belong to the fibre of their in-plane lattice
 * cell: the two in-plane coordinates (the axes other than `axis`) divided by
 * the body's spacing, measured from the body's lowest particle, rounded.  A
 * particle more than TLSPH_FIBRE_OFFSET_TOL spacings from its cell's point
 * (a graded body's finer particles, conforming shells, a jittered set) is
 * refused: such sets have no unambiguous stacks, and a guess would attach
 * particles to the wrong fibre.  Fibres may hold different numbers of
 * particles (a notch or a chamfer through part of the thickness); their
 * particles are listed in increasing coordinate along `axis`.
 *
 * The fibre's damage.  D_J = sum over its particles of D_i, as the paper
 * defines it ("adding the damage value of each particle along the fiber",
 * D_j = sum_{i=1}^{M} D_ji with M = 3).  The sum, not the mean or the
 * maximum: it is the paper's choice, and D_c = 0.1 of §5.3 is calibrated on
 * it; it grows with the damaged share of the thickness, so one damaged
 * surface particle does not move the tip before the section is weakened
 * (the maximum would), while a fibre whose particles are all half-damaged
 * passes (the mean would need D_c / M).  The price: D_c depends on the number
 * of layers; a scene that changes M must scale D_c with it.
 *
 * The tip search (eq. 20).  From the current tip T (a point, m) with the crack
 * direction V1 (from the previous tip to T), a fibre J is a candidate when
 *   0 < |C_J - T| <= R                (inside the circle of radius R, not T),
 *   -theta_c/2 <= theta <= theta_c/2  (theta: the angle between V1 and
 *                                      V2 = C_J - T, in the plane),
 *   D_J >= D_c,
 * all measured in the body's plane (the `axis` components dropped), with C_J
 * the fibre's reference centre (the mean of its particles' X).  Of several
 * candidates the paper does not say which wins; here the most damaged (the
 * largest D_J), then the nearest, then the lowest index: deterministic, and
 * the fibre the damage criterion ranks first.  Fibres behind the tip
 * (|theta| > theta_c/2) are never chosen, which rules out the crack turning
 * back, as the paper intends.  tlsph_fibre_next_tip scans every fibre
 * (O(fibres)); the crack driver, which searches after every step, asks
 * tlsph_fibre_next_tip_among with the dozen fibres within R of its tip.
 *
 * Units: m, rad; damage dimensionless.  Ownership: the fibre set owns its
 * arrays; release frees them. */
#ifndef TLSPH_CRACK_FIBRE_H
#define TLSPH_CRACK_FIBRE_H

#include <stddef.h>
#include <stdint.h>

#define TLSPH_FIBRE_OFFSET_TOL 1e-6 /* spacings: a lattice point's distance to its cell's */
#define TLSPH_FIBRE_RADIAL 3         /* axis of a curved shell's fibres: the radius (below) */

#define TLSPH_FIBRE_MAX_REGIONS 8 /* regions of one body, each with its own axis (below) */

struct tlsph_fibres {
    int axis;             /* thickness direction: 0 = x, 1 = y, 2 = z, TLSPH_FIBRE_RADIAL
                             (a set with regions: region 0's; read it through a view) */
    size_t n;             /* fibres */
    size_t *start;        /* [n + 1]: fibre k's particles are particle[start[k] .. start[k+1]-1] */
    size_t *particle;     /* particle indices, each fibre ordered along axis */
    double (*centre)[3];  /* each fibre's reference centre, m */
    double base[3], dir[3]; /* TLSPH_FIBRE_RADIAL: a point of the shell's axis (m) and its
                               unit direction; unused otherwise */
    int nregions;           /* 0: one region, every fibre along axis; else region[] holds
                               each fibre's region, region_axis each region's axis (0..2) */
    int region_axis[TLSPH_FIBRE_MAX_REGIONS];
    int *region;            /* [n] with regions, else NULL */
    int only;               /* 0; in a view (tlsph_fibres_view) r + 1: region r's fibres only */
};

enum tlsph_fibre_status {
    TLSPH_FIBRE_OK = 0,
    TLSPH_FIBRE_NO_MEMORY = -1,
    TLSPH_FIBRE_BAD_INPUT = -2,  /* axis not 0..2, spacing <= 0 or not finite, no particle */
    TLSPH_FIBRE_NOT_LATTICE = -3, /* a particle off its in-plane lattice point */
    TLSPH_FIBRE_NOT_STACKED = -4 /* radial: fibres of different sizes (the shells' particles
                                    are not on common rays) */
};

/* Builds the fibres of the particles index[0..count-1] (positions X, 3 per
 * particle, m) with in-plane lattice spacing `spacing` (m) and thickness
 * direction `axis`.  Fibres are numbered by their in-plane cell (the second
 * in-plane axis slowest).  *bad (when not NULL) gets the first particle
 * refused by the lattice rule.  On error f is left empty. */
enum tlsph_fibre_status tlsph_fibres_build(struct tlsph_fibres *f, const double *X,
                                           const size_t *index, size_t count, double spacing,
                                           int axis, size_t *bad);

/* Fibres through a curved shell (a cylindrical wall, paper 003 §6.4): the
 * thickness is radial, about the axis through `base` along `dir` (any
 * length > 0).  A fibre is the particles on one ray from the axis: the same
 * axial coordinate z = (X - base).dir and the same azimuth theta, both to
 * TLSPH_FIBRE_OFFSET_TOL spacings (theta times the particle's radius), ordered
 * by increasing radius.  The shell's particles must stack: every fibre holds
 * the same number of particles (the conforming tube with "thickness_axis":
 * "radial" puts the same count on every shell, scene/conforming.c); otherwise
 * TLSPH_FIBRE_NOT_STACKED with *bad the first particle of a fibre of another
 * size (a conforming cylinder's shells each hold their own count, so their
 * particles lie on different rays; a guess would mix the layers).  Fibres are
 * numbered by z, then theta.  A particle on the axis is refused (bad input).
 *
 * Everything measured "in the plane" is measured in the shell's tangent
 * plane at the point in question (tlsph_fibres_local): eq. 20's angle, the
 * driver's directions, lengths and facets; eq. 20's circle and
 * tlsph_fibres_within take the chord |C_J - T| (the arc to second order in
 * R / r; the tangent projection alone would bring the tube's far side to the
 * tip). */
enum tlsph_fibre_status tlsph_fibres_build_radial(struct tlsph_fibres *f, const double *X,
                                                  const size_t *index, size_t count,
                                                  double spacing, const double base[3],
                                                  const double dir[3], size_t *bad);

/* Fibres of several regions of one body (a stiffened plate: the plate's
 * region thin along z, each stiffener's along y).  Particle index[k] belongs
 * to region region_of[k] (0 .. nregions-1, or -1: in no region and no fibre);
 * each region's fibres are built by the lattice rule along its own axis
 * axes[r] (0..2) from its own lowest particle, and appended region by region
 * (the fibres of region 0 first).  *bad as tlsph_fibres_build; a region with
 * no particle: bad input with *bad = (size_t)-1 - r.
 *
 * A set with regions is read through views: tlsph_fibres_view(f, r) is f with
 * region r's axis whose queries (the tip search, tlsph_fibres_within) see
 * region r's fibres only; the geometry (normal, local, depth) then measures in
 * r's plane.  A crack stays in the region it grows in: a fibre of another
 * region is no candidate (projected on r's plane it would lie anywhere: two
 * stiffeners' fibres coincide there), and a particle in no region is no fibre,
 * so the tip treats it as the body's edge. */
enum tlsph_fibre_status tlsph_fibres_build_regions(struct tlsph_fibres *f, const double *X,
                                                   const size_t *index, const int *region_of,
                                                   size_t count, double spacing,
                                                   const int *axes, int nregions, size_t *bad);

/* Fibre k's region (0 for a set without regions). */
static inline int tlsph_fibres_region_of(const struct tlsph_fibres *f, size_t k)
{
    return f->region ? f->region[k] : 0;
}

/* The view of region r of f (f itself for a set without regions): a copy of
 * the header sharing f's arrays, valid until f changes (a split). */
static inline struct tlsph_fibres tlsph_fibres_view(const struct tlsph_fibres *f, int r)
{
    struct tlsph_fibres v = *f;
    if (f->nregions > 0 && r >= 0 && r < f->nregions) {
        v.axis = f->region_axis[r];
        v.only = r + 1;
    }
    return v;
}

/* Does the view f see fibre k? */
static inline int tlsph_fibres_sees(const struct tlsph_fibres *f, size_t k)
{
    return !f->only || !f->region || f->region[k] == f->only - 1;
}

/* The thickness direction at point P (unit): e_axis for a plate, the radial
 * direction at P (away from the axis) for a shell; 0, or -1 for a point on a
 * shell's axis. */
int tlsph_fibres_normal(const struct tlsph_fibres *f, const double P[3], double n[3]);

/* v's coordinates in the plane at P (m, in v's units): for a plate its two
 * in-plane components (the axes other than `axis`, ascending), for a shell
 * its components along the tangent plane's azimuthal direction (dir x n) and
 * along dir.  The tip search and the fibre queries measure distances and
 * angles with them: along the surface to second order in the distance over
 * the radius. */
void tlsph_fibres_local(const struct tlsph_fibres *f, const double P[3], const double v[3],
                        double out[2]);

/* The coordinate along the thickness of X (m): X[axis] for a plate, the
 * distance from the axis for a shell. */
double tlsph_fibres_depth(const struct tlsph_fibres *f, const double X[3]);

/* The two in-plane axes of a plate with thickness direction `axis` (0..2), in
 * increasing order. */
static inline void tlsph_fibre_plane_axes(int axis, int out[2])
{
    out[0] = axis == 0 ? 1 : 0;
    out[1] = axis == 2 ? 1 : 2;
}

/* D_J: the sum of D over fibre k's particles (D indexed by particle). */
double tlsph_fibre_damage(const struct tlsph_fibres *f, size_t k, const double *D);

/* Eq. 20's question.  tip: the current tip (m); direction: V1, any non-zero
 * length (its `axis` component ignored); radius R (m) > 0; theta_c (rad) in
 * (0, 2 pi]; D_c the critical fibre damage. */
struct tlsph_tip_search {
    double tip[3];
    double direction[3];
    double radius;
    double theta_c;
    double D_c;
};

/* The next tip fibre by eq. 20 (the rule above), or -1 when no fibre
 * qualifies (or V1 has no in-plane part). */
long tlsph_fibre_next_tip(const struct tlsph_fibres *f, const double *D,
                          const struct tlsph_tip_search *q);

/* The same among the fibres cand[0..ncand-1] only (the crack driver's list of
 * the fibres within R of a tip, so that a search each step costs that list,
 * not the body); ties by the lowest index as above. */
long tlsph_fibre_next_tip_among(const struct tlsph_fibres *f, const double *D,
                                const struct tlsph_tip_search *q, const size_t *cand,
                                size_t ncand);

/* The fibres whose centre lies within radius (m) of point in the plane (the
 * axis component dropped), ascending: the first max into out (may be NULL);
 * returns how many there are. */
size_t tlsph_fibres_within(const struct tlsph_fibres *f, const double point[3], double radius,
                           size_t *out, size_t max);

void tlsph_fibres_release(struct tlsph_fibres *f);

/* Fibres through a particle split (crack/split.h).  Paper 003 §3.2: "the old
 * crack tip fiber will be split into two new fibers": the halves on the +delta
 * side (half 1, the parents' indices) stay the parent fibre, the halves on the
 * -delta side form a new fibre appended after the last one, so every fibre
 * keeps its index (the crack driver holds the tip's) and each face of the
 * crack has its own fibre, whose damage sum counts only its own particles
 * (both halves in one fibre would count the damage twice and pass D_c at half
 * the damage).  The halves keep their parents' coordinate along the axis
 * (delta is in the plane), so the new list is in the parents' order, sorted.
 *
 * Prepare allocates the split body's new arrays (worst case: k new fibres);
 * nothing is changed, -1 out of memory.  Commit cannot fail: for the split
 * body (f) its particles keep their indices (they lie below `at`, the end of
 * its range), the halves 2 (at + s for parent[s]) form the new fibres, and the
 * centres of the fibres touched are recomputed from X (after the split).
 * Returns the fibres added.  tlsph_fibres_shift maps another body's fibres
 * (i -> i + k from at). */
int tlsph_fibres_split_prepare(const struct tlsph_fibres *f, size_t k, struct tlsph_fibres *fresh);
size_t tlsph_fibres_split_commit(struct tlsph_fibres *f, struct tlsph_fibres *fresh,
                                 const size_t *parent, size_t k, size_t at, const double *X);
void tlsph_fibres_shift(struct tlsph_fibres *f, size_t at, size_t k);

/* fibre_model.c: for a scene where some body has a "thickness_axis",
 * m->fibres (one set per body, empty for the others) from the particles'
 * reference positions; a body whose particles break the lattice rule is
 * refused at /bodies/<b>/thickness_axis.  0, or -1 with err (what was built
 * stays for tlsph_model_fibres_release). */
struct tlsph_model;
struct tlsph_errors;
int tlsph_model_fibres_setup(struct tlsph_model *m, struct tlsph_errors *err);
void tlsph_model_fibres_release(struct tlsph_model *m);

#endif
