/* Precision of a body's positions: every position is a double, the lattice
 * point origin + (i + 1/2) h as much as the positions the run reaches, and a
 * double carries ~16 significant digits.  A body far from the origin relative
 * to its spacing loses its lattice: at 1e16 m a double cannot tell positions
 * 1 m apart, and particles coincide (non-finite values follow).  So the
 * spacing must be at least TLSPH_MIN_RELATIVE_SPACING times the largest
 * coordinate of the body (its geometry's bounding box and its lattice origin). */
#include <math.h>

#include "scene/parse_internal.h"

int tlsph_check_body_precision(const struct tlsph_body *b, int dimension, const char *pointer,
                               struct tlsph_errors *err)
{
    double lo[3], hi[3], geometry = 0.0, origin = 0.0;
    tlsph_geometry_bounds(&b->geometry, lo, hi);
    const int naxes = dimension == 2 ? 2 : 3; /* in 2-D z is the unit thickness */
    for (int k = 0; k < naxes; k++) {
        geometry = fmax(geometry, fmax(fabs(lo[k]), fabs(hi[k])));
        origin = fmax(origin, fabs(b->origin[k]));
    }
    const double largest = fmax(geometry, origin);
    if (!(b->spacing > 0.0) || b->spacing >= TLSPH_MIN_RELATIVE_SPACING * largest)
        return 0;
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, pointer, origin > geometry ? "origin" : "geometry");
    tlsph_errors_add(err, p,
                     "body '%s': spacing %g m is below %g x its largest coordinate %g m (of its "
                     "%s): positions are doubles (about 16 digits), so its particles would "
                     "coincide or lose their spacing; move the body nearer the origin or "
                     "increase the spacing",
                     b->name, b->spacing, TLSPH_MIN_RELATIVE_SPACING, largest,
                     origin > geometry ? "lattice origin" : "geometry");
    return -1;
}
