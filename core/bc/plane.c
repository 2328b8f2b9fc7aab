#include "bc/plane.h"

#include <math.h>

#include "scene/json_check.h"

int tlsph_plane_parse(const json_t *obj, const struct tlsph_scene *s, struct tlsph_bc *bc,
                      const char *P, struct tlsph_errors *err)
{
    int bad = jc_vector(obj, "point", 1, 3, "m", P, bc->point, err) != 0;
    if (jc_vector(obj, "normal", 1, 3, "direction, any length", P, bc->normal, err) != 0)
        return -1;
    if (s->dimension == 2) {
        bc->point[2] = 0.0;
        bc->normal[2] = 0.0;
    }
    double *n = bc->normal;
    const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 1e-300) || !isfinite(len)) {
        char p[TLSPH_POINTER_MAX];
        tlsph_pointer_join(p, sizeof p, P, "normal");
        tlsph_errors_add(err, p, "'normal' must be a non-zero vector%s",
                         s->dimension == 2 ? " in the x-y plane (2-D scene)" : "");
        return -1;
    }
    for (int k = 0; k < 3; k++)
        n[k] /= len;
    return bad ? -1 : 0;
}
