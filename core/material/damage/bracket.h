/* A bracket around a sign change of a scalar residual r (r < 0 at the lower
 * end, r > 0 at the upper), closed by the Illinois variant of regula falsi:
 * the end kept twice in a row has its residual halved, so that a convex r
 * does not pin one end forever.  The porous returns' fallbacks bracket an
 * unknown (a matrix strain increment, a void fraction, a plastic dilatation)
 * at which the rest of the system is solved; where the rest has no solution
 * the point is still known to lie on one side, an end without a value (NaN):
 * the next point then bisects.  With geometric set, ends decades apart
 * (hi > 1e3 lo > 0) are closed in the logarithm: a bracket that starts at
 * 1e-300 reaches a root near 1e-17 in tens of steps, not thousands. */
#ifndef TLSPH_DAMAGE_BRACKET_H
#define TLSPH_DAMAGE_BRACKET_H

#include <math.h>

struct tlsph_bracket {
    double lo, hi;     /* the ends */
    double r_lo, r_hi; /* the residual there, NaN where only the side is known */
    int last;          /* the end moved last: -1 lower, +1 upper, 0 none */
};

static inline double tlsph_bracket_next(const struct tlsph_bracket *b, int geometric)
{
    double x = isfinite(b->r_lo) && isfinite(b->r_hi)
                   ? b->lo - b->r_lo * (b->hi - b->lo) / (b->r_hi - b->r_lo)
                   : 0.5 * (b->lo + b->hi);
    if (geometric && b->lo > 0.0 && b->hi > 1e3 * b->lo)
        x = sqrt(b->lo) * sqrt(b->hi);
    else if (!(x > b->lo && x < b->hi))
        x = 0.5 * (b->lo + b->hi);
    return x;
}

/* x becomes the lower end, with its residual r < 0 or NaN (side only) */
static inline void tlsph_bracket_lower(struct tlsph_bracket *b, double x, double r)
{
    b->lo = x, b->r_lo = r;
    if (b->last < 0)
        b->r_hi *= 0.5;
    b->last = -1;
}

/* x becomes the upper end, with its residual r > 0 or NaN (side only) */
static inline void tlsph_bracket_upper(struct tlsph_bracket *b, double x, double r)
{
    b->hi = x, b->r_hi = r;
    if (b->last > 0)
        b->r_lo *= 0.5;
    b->last = 1;
}

/* x is known only to lie below the root (side < 0) or above it (side > 0) */
static inline void tlsph_bracket_side(struct tlsph_bracket *b, double x, int side)
{
    if (side < 0)
        tlsph_bracket_lower(b, x, NAN);
    else
        tlsph_bracket_upper(b, x, NAN);
}

/* closed to the resolution of a double */
static inline int tlsph_bracket_closed(const struct tlsph_bracket *b)
{
    return b->hi - b->lo <= 4e-16 * b->hi;
}

#endif
