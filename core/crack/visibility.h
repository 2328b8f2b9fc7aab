/* The 3-D parametric visibility condition of paper 003 §3.3 (eqs. 33-42): does
 * the straight sight line between two particles A and B pass through a crack
 * facet, the triangle T1 T2 T3?  A crack surface is a set of such facets; a
 * reference pair whose sight line is blocked by any of them is cut (its two
 * particles no longer interact).
 *
 * With N = T1T2 x T1T3 (eq. 33) and Delta = B - A (eq. 36):
 *  1. N.Delta = 0, A off the plane (eq. 34): the segment is parallel to the
 *     facet: A sees B.
 *  2. N.Delta = 0, A on the plane (eq. 35): the segment lies in the facet's
 *     plane; the test becomes the 2-D visibility condition (Li & Simonsen
 *     2005): A is blind to B when AB meets one of the facet's three sides.
 *  3. Otherwise the segment's line meets the plane at P = A + lambda Delta
 *     with lambda = N.(T1 - A) / N.Delta (eq. 38 is this quotient written out
 *     in coordinates).  lambda outside [0, 1]: A sees B.  Inside, P is in the
 *     facet when N.N_k >= 0 for the three sub-normals N_1 = PT1 x PT2,
 *     N_2 = PT2 x PT3, N_3 = PT3 x PT1 (eqs. 39-42); then A is blind to B.
 *
 * Choices where the paper leaves one:
 *  - "= 0" is tested with tolerances relative to the geometry's own scale
 *    (TLSPH_SIGHT_EPS times the product of the lengths involved), so the
 *    answer does not depend on units or on round-off in coordinates that
 *    are only meant to be parallel or coplanar.
 *  - N.N_k / |N|^2 are the barycentric coordinates of P (they sum to 1);
 *    the inside test uses them, with the same relative tolerance, so that
 *    points on a side or at a corner count as inside, as eq. 42's ">= 0"
 *    says: a sight line through the crack front is blocked.
 *  - In case 2 the paper projects the facet on all three coordinate planes;
 *    one projection suffices: the plane dropping the axis of N's largest
 *    component, where the facet's image has the largest area and the 2-D
 *    test is best conditioned.
 *  - A segment that lies in the facet's plane strictly inside the facet
 *    (touching no side) is not blocked: it is the 2-D condition, and such a
 *    pair lies on the crack surface itself, which splitting (eqs. 25-26,
 *    offset +-delta off the surface) never produces.
 * A facet of zero area blocks nothing.  All lengths in metres; any consistent
 * unit gives the same answer. */
#ifndef TLSPH_CRACK_VISIBILITY_H
#define TLSPH_CRACK_VISIBILITY_H

#include <stdbool.h>

#define TLSPH_SIGHT_EPS 1e-12

/* Why a sight line is clear or blocked; the unit tests name Fig. 4's cases. */
enum tlsph_sight {
    TLSPH_SIGHT_PARALLEL,         /* case 1: parallel to the facet, off its plane */
    TLSPH_SIGHT_SHORT,            /* case 3: the plane is crossed beyond A or B */
    TLSPH_SIGHT_OUTSIDE,          /* case 3: P outside the facet */
    TLSPH_SIGHT_INSIDE,           /* case 3: P strictly inside: blocked */
    TLSPH_SIGHT_ON_SIDE,          /* case 3: P on a side or at a corner: blocked */
    TLSPH_SIGHT_COPLANAR_CLEAR,   /* case 2: in the plane, meets no side */
    TLSPH_SIGHT_COPLANAR_BLOCKED, /* case 2: in the plane, meets a side: blocked */
    TLSPH_SIGHT_NO_FACET,         /* the facet has zero area */
};

/* Classifies the sight line A-B against the facet T[0..2] (each a point
 * x, y, z).  Pure function of its arguments. */
enum tlsph_sight tlsph_sight_through_facet(const double A[3], const double B[3], const double T[3][3]);

static inline bool tlsph_sight_blocked(enum tlsph_sight s)
{
    return s == TLSPH_SIGHT_INSIDE || s == TLSPH_SIGHT_ON_SIDE || s == TLSPH_SIGHT_COPLANAR_BLOCKED;
}

#endif
