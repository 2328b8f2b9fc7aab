/* "cylinder": a rigid circular cylinder with flat end caps, from the centre
 * of its base disc along its axis; its reference point is the centroid, half
 * way.  In 2-D the axis must lie in the x-y plane and the section is a
 * rectangle, length x 2 radius.  Volume pi r^2 L; inertia about the centroid
 * per unit mass (3 r^2 + L^2)/12 across the axis, r^2/2 about it (2-D:
 * area 2 r L per metre, about z (L^2 + 4 r^2)/12).  Distance: shapes.h. */
#include <math.h>

#include "rigid/frame.h"
#include "rigid/rigid.h"
#include "scene/parse_internal.h"

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    TLSPH_KEY_POINT("base", "centre of the base disc"),
    TLSPH_KEY_DIRECTION("axis", "axis from the base, any non-zero length (in the x-y plane in "
                                "2-D)"),
    TLSPH_RIGID_LENGTH("radius", 0, "radius"),
    TLSPH_RIGID_LENGTH("length", 1, "length along the axis, between the end caps"),
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/rigid_bodies/*/shape", "cylinder", keys);
/* clang-format on */

static int parse(const json_t *obj, int dim, struct tlsph_rigid_spec *r, const char *P,
                 struct tlsph_errors *err)
{
    double base[3], a[3];
    const int bad = tlsph_rigid_read_shape(obj, &table, "base", base, r, P, err) != 0;
    if (tlsph_parse_direction(obj, "axis", dim, P, a, err) != 0 || bad)
        return -1;
    r->size[1] *= 0.5; /* half length */
    rigid_place_on_axis(base, a, r->size[1], dim, r->centre, r->axes);
    return 0;
}

static double mass_properties(const struct tlsph_rigid_spec *r, int dim, double inertia[3])
{
    const double a = r->size[0], L = 2.0 * r->size[1];
    if (dim == 2) {
        inertia[0] = inertia[1] = 0.0;
        inertia[2] = (L * L + 4.0 * a * a) / 12.0;
        return 2.0 * a * L;
    }
    inertia[0] = inertia[1] = (3.0 * a * a + L * L) / 12.0;
    inertia[2] = 0.5 * a * a;
    return M_PI * a * a * L;
}

static double extent(const struct tlsph_rigid_spec *r)
{
    return sqrt(r->size[0] * r->size[0] + r->size[1] * r->size[1]);
}

TLSPH_RIGID_SHAPE(cylinder, TLSPH_RIGID_CYLINDER, 1);
