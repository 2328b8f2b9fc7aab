/* "cone": a rigid solid right circular cone with its base cap, from its apex
 * along its axis, of height h and base radius R (or half-angle a, R = h tan a).
 * Its reference point is the centroid, 3h/4 from the apex (2-D: the
 * triangle's, 2h/3).  In 2-D the axis must lie in the x-y plane and the
 * section is an isosceles triangle.  Volume pi R^2 h / 3; inertia about the
 * centroid per unit mass 3/10 R^2 about the axis, 3/20 R^2 + 3/80 h^2 across
 * it (2-D: area R h per metre, about z h^2/18 + R^2/6).  Distance: shapes.h. */
#include <math.h>

#include "rigid/frame.h"
#include "rigid/rigid.h"
#include "scene/parse_internal.h"

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    TLSPH_KEY_POINT("apex", "apex"),
    TLSPH_RIGID_LENGTH("height", 1, "height from the apex to the base"),
    {.name = "radius", .kind = TLSPH_KEY_NUMBER, .range = {0.0, 0.0, JC_OPEN, JC_NONE},
     .unit = "m", .offset = TLSPH_PARAM(0),
     .description = "base radius; exactly one of radius and half_angle"},
    {.name = "half_angle", .kind = TLSPH_KEY_NUMBER, .range = {0.0, 1.5707963267948966, JC_OPEN,
     JC_OPEN}, .unit = "rad", .offset = TLSPH_KEY_NOWHERE,
     .description = "half the apex angle; exactly one of radius and half_angle"},
    TLSPH_KEY_DIRECTION("axis", "axis from the apex to the base, any non-zero length (in the "
                                "x-y plane in 2-D)"),
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/rigid_bodies/*/shape", "cone", keys);
/* clang-format on */

static int parse(const json_t *obj, int dim, struct tlsph_rigid_spec *r, const char *P,
                 struct tlsph_errors *err)
{
    double apex[3], a[3];
    int bad = tlsph_rigid_read_shape(obj, &table, "apex", apex, r, P, err) != 0;
    const json_t *radius = json_object_get(obj, "radius"),
                 *angle = json_object_get(obj, "half_angle");
    if (!radius == !angle) {
        tlsph_errors_add(err, P,
                         "a cone needs exactly one of 'radius' (m) and 'half_angle' "
                         "(rad), got %s",
                         radius ? "both" : "neither");
        bad = 1;
    }
    if (tlsph_parse_direction(obj, "axis", dim, P, a, err) != 0 || bad)
        return -1;
    if (angle)
        r->size[0] = r->size[1] * tan(json_number_value(angle));
    const double h = r->size[1];
    r->size[2] = dim == 2 ? 2.0 * h / 3.0 : 0.75 * h; /* apex to centroid */
    rigid_place_on_axis(apex, a, r->size[2], dim, r->centre, r->axes);
    return 0;
}

static double mass_properties(const struct tlsph_rigid_spec *r, int dim, double inertia[3])
{
    const double R = r->size[0], h = r->size[1];
    if (dim == 2) {
        inertia[0] = inertia[1] = 0.0;
        inertia[2] = h * h / 18.0 + R * R / 6.0;
        return R * h;
    }
    inertia[0] = inertia[1] = 0.15 * R * R + 0.0375 * h * h;
    inertia[2] = 0.3 * R * R;
    return M_PI * R * R * h / 3.0;
}

static double extent(const struct tlsph_rigid_spec *r)
{
    const double R = r->size[0], h = r->size[1], za = r->size[2];
    return fmax(za, sqrt(R * R + (h - za) * (h - za)));
}

TLSPH_RIGID_SHAPE(cone, TLSPH_RIGID_CONE, 1);
