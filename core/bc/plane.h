/* Planes of walls and symmetry conditions: bc->point (m) and the unit
 * bc->normal (into the solid for walls). */
#ifndef TLSPH_BC_PLANE_H
#define TLSPH_BC_PLANE_H

#include <jansson.h>

#include "scene/scene.h"
#include "util/errors.h"

/* Reads "point" (m) and "normal" (any non-zero length, normalised) of obj into
 * bc; in 2-D their z components are zeroed.  Returns 0 or -1 with err. */
int tlsph_plane_parse(const json_t *obj, const struct tlsph_scene *s, struct tlsph_bc *bc,
                      const char *pointer, struct tlsph_errors *err);

/* Signed distance of x (m) from the plane, positive on the normal's side, m. */
static inline double tlsph_plane_distance(const struct tlsph_bc *bc, const double *x)
{
    const double *n = bc->normal, *q = bc->point;
    return (x[0] - q[0]) * n[0] + (x[1] - q[1]) * n[1] + (x[2] - q[2]) * n[2];
}

#endif
