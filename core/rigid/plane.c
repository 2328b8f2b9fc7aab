/* "plane": a rigid half-space; the normal points out of the rigid side, into
 * the space the particles may occupy (as a wall's normal points into the
 * solid).  It has no volume, so it moves only as prescribed.  Distance:
 * shapes.h. */
#include <math.h>

#include "rigid/frame.h"
#include "rigid/rigid.h"
#include "scene/parse_internal.h"

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    TLSPH_KEY_POINT("point", "a point of the plane (its reference point)"),
    TLSPH_KEY_DIRECTION("normal", "normal, out of the rigid side towards the particles; any "
                                  "non-zero length"),
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/rigid_bodies/*/shape", "plane", keys);
/* clang-format on */

static int parse(const json_t *obj, int dim, struct tlsph_rigid_spec *r, const char *P,
                 struct tlsph_errors *err)
{
    const int bad = tlsph_rigid_read_shape(obj, &table, "point", r->centre, r, P, err) != 0;
    double n[3];
    if (tlsph_parse_direction(obj, "normal", dim, P, n, err) != 0)
        return -1;
    rigid_axes_from_z(n, r->axes);
    if (dim == 2)
        r->centre[2] = 0.0;
    return bad ? -1 : 0;
}

static double mass_properties(const struct tlsph_rigid_spec *r, int dim, double inertia[3])
{
    (void)r, (void)dim;
    inertia[0] = inertia[1] = inertia[2] = INFINITY;
    return INFINITY;
}

static double extent(const struct tlsph_rigid_spec *r)
{
    (void)r;
    return INFINITY;
}

TLSPH_RIGID_SHAPE(plane, TLSPH_RIGID_PLANE, 0);
