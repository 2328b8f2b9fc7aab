/* "sphere": a rigid ball (a disc in 2-D).  Volume 4/3 pi r^3 (2-D: pi r^2 per
 * metre); inertia about the centre per unit mass 2/5 r^2 (2-D, about z:
 * r^2 / 2).  Distance: shapes.h. */
#include <math.h>

#include "rigid/frame.h"
#include "rigid/rigid.h"
#include "scene/parse_internal.h"

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    TLSPH_KEY_POINT("center", "centre"),
    TLSPH_RIGID_LENGTH("radius", 0, "radius"),
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/rigid_bodies/*/shape", "sphere", keys);
/* clang-format on */

static int parse(const json_t *obj, int dim, struct tlsph_rigid_spec *r, const char *P,
                 struct tlsph_errors *err)
{
    const int bad = tlsph_rigid_read_shape(obj, &table, "center", r->centre, r, P, err) != 0;
    if (dim == 2)
        r->centre[2] = 0.0;
    const double z[3] = {0.0, 0.0, 1.0};
    rigid_axes_from_z(z, r->axes);
    return bad ? -1 : 0;
}

static double mass_properties(const struct tlsph_rigid_spec *r, int dim, double inertia[3])
{
    const double a = r->size[0];
    if (dim == 2) {
        inertia[0] = inertia[1] = 0.0;
        inertia[2] = 0.5 * a * a;
        return M_PI * a * a;
    }
    inertia[0] = inertia[1] = inertia[2] = 0.4 * a * a;
    return 4.0 / 3.0 * M_PI * a * a * a;
}

static double extent(const struct tlsph_rigid_spec *r)
{
    return r->size[0];
}

TLSPH_RIGID_SHAPE(sphere, TLSPH_RIGID_SPHERE, 1);
