/* The scene's "rigid_bodies" array (core/rigid/rigid.h): each entry's own keys
 * here, its shape's keys in the shape's file (core/rigid/<shape>.c), its
 * motion's in core/rigid/motion_parse.c. */
#include <stdlib.h>
#include <string.h>

#include "rigid/rigid.h"
#include "scene/parse_internal.h"

/* clang-format off */
static const struct tlsph_key rigid_keys[] = {
    {.name = "name", .kind = TLSPH_KEY_STRING, .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_NAME,
     .size = TLSPH_NAME_MAX, .offset = offsetof(struct tlsph_rigid_spec, name),
     .noun = "rigid body name",
     .description = "unique among the rigid bodies; names its output series"},
    {.name = "shape", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_CALLER,
     .description = "{\"type\": plane | box | sphere | cylinder | cone, ...its sizes}"},
    {.name = "motion", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_CALLER,
     .description = "{\"type\": prescribed | free, ...}; absent = at rest"},
    {.name = "friction", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,
     .range = {0.0, 10.0, JC_CLOSED, JC_CLOSED}, .unit = "1", .def = 0.0,
     .offset = offsetof(struct tlsph_rigid_spec, friction),
     .description = "Coulomb friction coefficient mu between the particles and the body; "
                    "0 = frictionless"},
    {.name = "damping", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,
     .range = {0.0, 1.0, JC_CLOSED, JC_CLOSED}, .unit = "1", .def = 0.0,
     .offset = offsetof(struct tlsph_rigid_spec, damping),
     .description = "damping ratio zeta of each particle's contact, a fraction of the critical "
                    "damping of its oscillator; 0 = elastic contact"},
};
/* clang-format on */
const struct tlsph_key_table tlsph_rigid_body_keys =
    TLSPH_KEY_TABLE("/rigid_bodies/*", NULL, rigid_keys);

static int parse_shape(const json_t *entry, int dim, struct tlsph_rigid_spec *r, const char *P,
                       struct tlsph_errors *err)
{
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, P, "shape");
    const json_t *obj = json_object_get(entry, "shape");
    if (!obj)
        return -1; /* reported by the key reader (required) */
    if (!json_is_object(obj)) {
        tlsph_errors_add(err, p, "'shape' must be an object {\"type\": name, ...}, got %s",
                         jc_type_name(obj));
        return -1;
    }
    char type[64];
    if (jc_string(obj, "type", 1, p, type, sizeof type, err) != 0)
        return -1;
    r->shape = tlsph_rigid_shape_find(type);
    if (!r->shape) {
        tlsph_key_error(err, p, "type", "unknown rigid shape '%s' (accepted: %s)", type,
                        tlsph_rigid_shape_names());
        return -1;
    }
    return r->shape->parse(obj, dim, r, p, err);
}

int tlsph_parse_rigid_bodies(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err)
{
    const json_t *arr = json_object_get(root, "rigid_bodies");
    if (!arr)
        return 0;
    if (!json_is_array(arr)) {
        tlsph_errors_add(err, "/rigid_bodies", "'rigid_bodies' must be an array of objects, got %s",
                         jc_type_name(arr));
        return -1;
    }
    const size_t n = json_array_size(arr);
    if (n == 0)
        return 0;
    if (n > TLSPH_MAX_RIGID_BODIES) {
        tlsph_errors_add(err, "/rigid_bodies", "at most %d rigid bodies are allowed, got %zu",
                         TLSPH_MAX_RIGID_BODIES, n);
        return -1;
    }
    s->rigid = calloc(n, sizeof *s->rigid);
    if (!s->rigid) {
        tlsph_errors_add(err, "/rigid_bodies", "out of memory");
        return -1;
    }
    s->nrigid = n;
    int bad = 0;
    for (size_t k = 0; k < n; k++) {
        char P[TLSPH_POINTER_MAX];
        tlsph_pointer_index(P, sizeof P, "/rigid_bodies", k);
        const json_t *e = json_array_get(arr, k);
        struct tlsph_rigid_spec *r = &s->rigid[k];
        if (!json_is_object(e)) {
            tlsph_errors_add(err, P, "a rigid body must be an object, got %s", jc_type_name(e));
            bad = 1;
            continue;
        }
        if (tlsph_keys_read(e, &tlsph_rigid_body_keys, P, &(struct tlsph_key_target){.base = r},
                            err) != 0)
            bad = 1;
        for (size_t j = 0; j < k; j++)
            if (r->name[0] && strcmp(s->rigid[j].name, r->name) == 0) {
                tlsph_key_error(err, P, "name",
                                "rigid body name '%s' is used twice (also at "
                                "/rigid_bodies/%zu)",
                                r->name, j);
                bad = 1;
            }
        if (parse_shape(e, s->dimension, r, P, err) != 0) {
            bad = 1;
            continue;
        }
        bad |= tlsph_rigid_parse_motion(e, s, r, P, err) != 0;
    }
    return bad ? -1 : 0;
}
