/* A 3-vector whose items are numbers, expressions of t or null: the prescribed
 * velocity of a boundary condition and the prescribed (angular) velocity of a
 * rigid body are read by this one parser, so both say the same things about
 * the same mistakes. */
#include "scene/parse_internal.h"

static const char *const tvar[] = {"t"};

int tlsph_scene_time_vector(const json_t *obj, const char *key, const char *unit,
                            const char *null_means, const int off_plane[3],
                            const struct tlsph_scene *s, struct tlsph_expr ex[3], int set[3],
                            const char *pointer, struct tlsph_errors *err)
{
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, pointer, key);
    const json_t *v = json_object_get(obj, key);
    if (!json_is_array(v) || json_array_size(v) != 3) {
        tlsph_errors_add(err, p,
                         "'%s' must be an array of 3 items, each a number (%s), an expression "
                         "string of t (s) giving %s, or null (%s)",
                         key, unit, unit, null_means);
        return -1;
    }
    int bad = 0, given = 0;
    for (int k = 0; k < 3; k++) {
        char q[TLSPH_POINTER_MAX];
        tlsph_pointer_index(q, sizeof q, p, (size_t)k);
        const json_t *c = json_array_get(v, (size_t)k);
        if (json_is_null(c))
            continue;
        if (tlsph_scene_expr(&ex[k], c, tvar, 1, 0, s, q, err) != 0) {
            bad = 1;
            continue;
        }
        /* A 2-D scene cannot move out of its plane: accept only what says
         * "nothing" (0), and keep nothing of it. */
        if (off_plane[k]) {
            const double t0 = 0.0;
            if (!ex[k].constant || tlsph_expr_eval(&ex[k], &t0) != 0.0) {
                tlsph_errors_add(err, q,
                                 "in a 2-D scene this component of '%s' must be null or 0 "
                                 "(%s): the motion stays in the x-y plane",
                                 key, unit);
                bad = 1;
            }
            tlsph_expr_free(&ex[k]);
            continue;
        }
        if (tlsph_check_expr_of_time(&ex[k], s, key, q, err) != 0) {
            bad = 1;
            continue;
        }
        set[k] = 1;
        given++;
    }
    return bad ? -1 : given;
}
