/* "box": a rigid rectangular block, given by its centre and half sizes, and
 * optionally turned about its centre by a rotation vector (axis x angle; in
 * 2-D about z only).  Volume 8abc (2-D: 4ab per metre, the box a prism along
 * z); inertia about the centre per unit mass along its edges
 * ((b^2 + c^2)/3, (a^2 + c^2)/3, (a^2 + b^2)/3) (2-D, about z: (a^2 + b^2)/3).
 * Distance: shapes.h. */
#include <math.h>

#include "rigid/frame.h"
#include "rigid/rigid.h"
#include "scene/parse_internal.h"

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    TLSPH_KEY_POINT("center", "centre"),
    TLSPH_KEY_POINT("half_sizes", "half the edge lengths [a, b, c] along the box's axes, each > "
                                  "0; c ignored in 2-D"),
    TLSPH_RIGID_VECTOR("rotation", "rad", "rotation vector (axis x angle) turning the box about "
                                          "its centre from the coordinate axes; absent = "
                                          "aligned; in 2-D only its z component may be non-zero"),
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/rigid_bodies/*/shape", "box", keys);
/* clang-format on */

static int parse(const json_t *obj, int dim, struct tlsph_rigid_spec *r, const char *P,
                 struct tlsph_errors *err)
{
    int bad = tlsph_rigid_read_shape(obj, &table, "center", r->centre, r, P, err) != 0;
    char p[TLSPH_POINTER_MAX];
    if (jc_vector(obj, "half_sizes", 1, 3, "m", P, r->size, err) != 0)
        bad = 1;
    else
        for (int k = 0; k < dim; k++)
            if (!(r->size[k] > 0.0)) {
                char q[TLSPH_POINTER_MAX];
                tlsph_pointer_join(p, sizeof p, P, "half_sizes");
                tlsph_pointer_index(q, sizeof q, p, (size_t)k);
                tlsph_errors_add(err, q, "half size %g m must be > 0 (m)", r->size[k]);
                bad = 1;
            }
    double w[3] = {0.0, 0.0, 0.0};
    const int rc = jc_vector(obj, "rotation", 0, 3, "rad", P, w, err);
    bad |= rc < 0;
    if (rc == 0 && dim == 2 && (w[0] != 0.0 || w[1] != 0.0)) {
        tlsph_pointer_join(p, sizeof p, P, "rotation");
        tlsph_errors_add(err, p,
                         "in a 2-D scene a box turns about z only: the x and y "
                         "components of 'rotation' must be 0 (rad)");
        bad = 1;
    }
    rigid_rotation(w, r->axes);
    if (dim == 2) {
        r->centre[2] = 0.0;
        r->size[2] = INFINITY; /* the section of a prism along z */
    }
    return bad ? -1 : 0;
}

static double mass_properties(const struct tlsph_rigid_spec *r, int dim, double inertia[3])
{
    const double a = r->size[0], b = r->size[1], c = r->size[2];
    if (dim == 2) {
        inertia[0] = inertia[1] = 0.0;
        inertia[2] = (a * a + b * b) / 3.0;
        return 4.0 * a * b;
    }
    inertia[0] = (b * b + c * c) / 3.0;
    inertia[1] = (a * a + c * c) / 3.0;
    inertia[2] = (a * a + b * b) / 3.0;
    return 8.0 * a * b * c;
}

static double extent(const struct tlsph_rigid_spec *r)
{
    const double c = isfinite(r->size[2]) ? r->size[2] : 0.0;
    return sqrt(r->size[0] * r->size[0] + r->size[1] * r->size[1] + c * c);
}

TLSPH_RIGID_SHAPE(box, TLSPH_RIGID_BOX, 1);
