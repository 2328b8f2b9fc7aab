/* Scene boundary conditions: "boundary_conditions": [{type, name, ...}, ...]
 * -> s->bcs, with their particle selectors.  In 2-D the z components of points
 * and normals are ignored, z velocities and accelerations must be 0 (or null),
 * and a selector box spans all z. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/parse_internal.h"

static const char *const xyz[] = {"x", "y", "z"};
static const char *const tvar[] = {"t"};

static const char *const bc_types[] = {"fixed", "velocity", "wall", "symmetry", "body_force",
                                       NULL};

/* Returns 0, -1 on error. required = 0: an absent selector selects everything. */
static int parse_selector(const json_t *obj, int required, struct tlsph_scene *s,
                          struct tlsph_selector *sel, const char *P, struct tlsph_errors *err)
{
    static const char *const keys[] = {"body", "box", "expression", NULL};
    sel->body = -1;
    sel->has_box = 0;
    const json_t *v = json_object_get(obj, "select");
    char p[TLSPH_POINTER_MAX], q[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, P, "select");
    if (!v) {
        if (required) {
            tlsph_errors_add(err, p,
                             "required object 'select' is missing (give body, box and/or "
                             "expression)");
            return -1;
        }
        return 0;
    }
    if (!json_is_object(v)) {
        tlsph_errors_add(err, p, "'select' must be an object, got %s", jc_type_name(v));
        return -1;
    }
    int bad = jc_unknown_keys(v, keys, p, err) != 0;
    if (!json_object_get(v, "body") && !json_object_get(v, "box") &&
        !json_object_get(v, "expression")) {
        tlsph_errors_add(err, p, "'select' needs at least one of body, box, expression");
        bad = 1;
    }
    char name[TLSPH_NAME_MAX];
    int r = jc_string(v, "body", 0, p, name, sizeof name, err);
    if (r < 0) {
        bad = 1;
    } else if (r == 0 && (sel->body = tlsph_scene_find_body(s, name)) < 0) {
        tlsph_pointer_join(q, sizeof q, p, "body");
        tlsph_errors_add(err, q, "unknown body '%s' (not a name in /bodies)", name);
        bad = 1;
    }
    const json_t *box = jc_object(v, "box", 0, p, err);
    if (box) {
        static const char *const box_keys[] = {"min", "max", NULL};
        tlsph_pointer_join(q, sizeof q, p, "box");
        bad |= jc_unknown_keys(box, box_keys, q, err) != 0;
        int r1 = jc_vector(box, "min", 1, 3, "m", q, sel->box_min, err);
        int r2 = jc_vector(box, "max", 1, 3, "m", q, sel->box_max, err);
        if (r1 || r2) {
            bad = 1;
        } else {
            if (s->dimension == 2) {
                sel->box_min[2] = -1e300;
                sel->box_max[2] = 1e300;
            }
            for (int k = 0; k < s->dimension; k++)
                if (!(sel->box_max[k] > sel->box_min[k])) {
                    char m[TLSPH_POINTER_MAX], mk[TLSPH_POINTER_MAX];
                    tlsph_pointer_join(m, sizeof m, q, "max");
                    tlsph_pointer_index(mk, sizeof mk, m, (size_t)k);
                    tlsph_errors_add(err, mk,
                                     "selector box max[%d] = %g m must be greater than min[%d] "
                                     "= %g m",
                                     k, sel->box_max[k], k, sel->box_min[k]);
                    bad = 1;
                }
            sel->has_box = 1;
        }
    } else if (json_object_get(v, "box")) {
        bad = 1;
    }
    const json_t *e = json_object_get(v, "expression");
    if (e) {
        tlsph_pointer_join(q, sizeof q, p, "expression");
        if (!json_is_string(e)) {
            tlsph_errors_add(err, q,
                             "'expression' must be a string condition of x, y, z (m), got %s",
                             jc_type_name(e));
            bad = 1;
        } else if (tlsph_scene_expr(&sel->expression, e, xyz, 3, 1, s, q, err) != 0) {
            bad = 1;
        }
    }
    return bad ? -1 : 0;
}

/* point + unit normal of a wall or symmetry plane. */
static int parse_plane(const json_t *obj, const struct tlsph_scene *s, struct tlsph_bc *bc,
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

static int parse_velocity(const json_t *obj, struct tlsph_scene *s, struct tlsph_bc *bc,
                          const char *P, struct tlsph_errors *err)
{
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, P, "velocity");
    const json_t *v = json_object_get(obj, "velocity");
    if (!v) {
        tlsph_errors_add(err, p, "required field 'velocity' (3 items: m/s, expression of t, or "
                                 "null) is missing");
        return -1;
    }
    if (!json_is_array(v) || json_array_size(v) != 3) {
        tlsph_errors_add(err, p,
                         "'velocity' must be an array of 3 items, each a number (m/s), an "
                         "expression string of t (s) giving m/s, or null (free component)");
        return -1;
    }
    int bad = 0, given = 0;
    for (int k = 0; k < 3; k++) {
        char q[TLSPH_POINTER_MAX];
        tlsph_pointer_index(q, sizeof q, p, (size_t)k);
        const json_t *c = json_array_get(v, (size_t)k);
        if (json_is_null(c))
            continue;
        if (tlsph_scene_expr(&bc->velocity[k], c, tvar, 1, 0, s, q, err) != 0) {
            bad = 1;
            continue;
        }
        if (k == 2 && s->dimension == 2) {
            const double t0 = 0.0;
            if (!bc->velocity[2].constant || tlsph_expr_eval(&bc->velocity[2], &t0) != 0.0) {
                tlsph_errors_add(err, q, "in a 2-D scene the z velocity must be null or 0");
                bad = 1;
            }
            tlsph_expr_free(&bc->velocity[2]);
            continue;
        }
        bc->velocity_set[k] = 1;
        given++;
    }
    if (!bad && given == 0) {
        tlsph_errors_add(err, p,
                         "'velocity' has no prescribed component: at least one of the %s items "
                         "must be a number or an expression of t",
                         s->dimension == 2 ? "first two" : "3");
        bad = 1;
    }
    return bad ? -1 : 0;
}

static int parse_bc(const json_t *obj, size_t index, struct tlsph_scene *s,
                    struct tlsph_errors *err)
{
    static const char *const keys_fixed[] = {"type", "name", "select", NULL};
    static const char *const keys_velocity[] = {"type", "name", "select", "velocity", NULL};
    static const char *const keys_wall[] = {"type", "name", "point", "normal", NULL};
    static const char *const keys_symmetry[] = {"type", "name", "point", "normal", "select",
                                                NULL};
    static const char *const keys_force[] = {"type", "name", "acceleration", "select", NULL};
    static const char *const *const keys[] = {keys_fixed, keys_velocity, keys_wall,
                                              keys_symmetry, keys_force};
    struct tlsph_bc *bc = &s->bcs[index];
    bc->select.body = -1;
    char P[TLSPH_POINTER_MAX];
    tlsph_pointer_index(P, sizeof P, "/boundary_conditions", index);
    snprintf(bc->name, sizeof bc->name, "bc%zu", index);
    if (!json_is_object(obj)) {
        tlsph_errors_add(err, P, "a boundary condition must be an object, got %s",
                         jc_type_name(obj));
        return -1;
    }
    int bad = jc_string(obj, "name", 0, P, bc->name, sizeof bc->name, err) < 0;
    char type[32];
    if (jc_string(obj, "type", 1, P, type, sizeof type, err) != 0)
        return -1;
    int t = 0;
    while (bc_types[t] && strcmp(bc_types[t], type) != 0)
        t++;
    if (!bc_types[t]) {
        char p[TLSPH_POINTER_MAX];
        tlsph_pointer_join(p, sizeof p, P, "type");
        tlsph_errors_add(err, p,
                         "unknown boundary condition type '%s' (accepted: fixed, velocity, wall, "
                         "symmetry, body_force)",
                         type);
        return -1;
    }
    static const enum tlsph_bc_type types[] = {TLSPH_BC_FIXED, TLSPH_BC_VELOCITY, TLSPH_BC_WALL,
                                               TLSPH_BC_SYMMETRY, TLSPH_BC_BODY_FORCE};
    bc->type = types[t];
    bad |= jc_unknown_keys(obj, keys[t], P, err) != 0;
    switch (bc->type) {
    case TLSPH_BC_FIXED:
        bad |= parse_selector(obj, 1, s, &bc->select, P, err) != 0;
        break;
    case TLSPH_BC_VELOCITY:
        bad |= parse_selector(obj, 1, s, &bc->select, P, err) != 0;
        bad |= parse_velocity(obj, s, bc, P, err) != 0;
        break;
    case TLSPH_BC_WALL:
        bad |= parse_plane(obj, s, bc, P, err) != 0;
        break;
    case TLSPH_BC_SYMMETRY:
        bad |= parse_plane(obj, s, bc, P, err) != 0;
        bad |= parse_selector(obj, 0, s, &bc->select, P, err) != 0;
        break;
    case TLSPH_BC_BODY_FORCE:
        if (jc_vector(obj, "acceleration", 1, 3, "m/s^2", P, bc->acceleration, err) != 0) {
            bad = 1;
        } else if (s->dimension == 2 && bc->acceleration[2] != 0.0) {
            char p[TLSPH_POINTER_MAX], q[TLSPH_POINTER_MAX];
            tlsph_pointer_join(p, sizeof p, P, "acceleration");
            tlsph_pointer_index(q, sizeof q, p, 2);
            tlsph_errors_add(err, q, "in a 2-D scene the z acceleration must be 0 m/s^2");
            bad = 1;
        }
        bad |= parse_selector(obj, 0, s, &bc->select, P, err) != 0;
        break;
    }
    return bad ? -1 : 0;
}

int tlsph_parse_bcs(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err)
{
    const json_t *arr = json_object_get(root, "boundary_conditions");
    if (!arr)
        return 0;
    if (!json_is_array(arr)) {
        tlsph_errors_add(err, "/boundary_conditions",
                         "'boundary_conditions' must be an array, got %s",
                         jc_type_name(arr));
        return -1;
    }
    const size_t n = json_array_size(arr);
    if (n == 0)
        return 0;
    if (n > 10000) {
        tlsph_errors_add(err, "/boundary_conditions",
                         "at most 10000 boundary conditions are allowed, got %zu", n);
        return -1;
    }
    s->bcs = calloc(n, sizeof *s->bcs);
    if (!s->bcs) {
        tlsph_errors_add(err, "/boundary_conditions", "out of memory");
        return -1;
    }
    s->nbcs = n;
    int bad = 0;
    for (size_t i = 0; i < n; i++) {
        bad |= parse_bc(json_array_get(arr, i), i, s, err) != 0;
        for (size_t j = 0; j < i; j++)
            if (strcmp(s->bcs[j].name, s->bcs[i].name) == 0) {
                char P[TLSPH_POINTER_MAX], p[TLSPH_POINTER_MAX];
                tlsph_pointer_index(P, sizeof P, "/boundary_conditions", i);
                const json_t *o = json_array_get(arr, i);
                if (json_object_get(o, "name"))
                    tlsph_pointer_join(p, sizeof p, P, "name");
                else
                    memcpy(p, P, sizeof P);
                tlsph_errors_add(err, p,
                                 "duplicate boundary condition name '%s' (also used by "
                                 "/boundary_conditions/%zu)",
                                 s->bcs[i].name, j);
                bad = 1;
                break;
            }
    }
    return bad ? -1 : 0;
}
