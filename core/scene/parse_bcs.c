/* Scene boundary conditions: "boundary_conditions": [{type, name, ...}, ...]
 * -> s->bcs.  This file reads what every condition has (its type, which names
 * its kind in core/bc/registry.c, and its name: TLSPH_BC_KEYS) and reports the
 * keys the kind's table does not list; the kind reads the rest
 * (core/bc/<type>.c).  In 2-D the z components of points and normals are
 * ignored, z velocities and accelerations must be 0 (or null), and a selector
 * box spans all z. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bc/kind.h"
#include "scene/parse_internal.h"

/* The rows every kind's table starts with, read before the kind is known. */
static const struct tlsph_key common_keys[] = {TLSPH_BC_KEYS};
static const struct tlsph_key_table common_table =
    TLSPH_KEY_TABLE("/boundary_conditions/*", NULL, common_keys);

static int parse_bc(const json_t *obj, size_t index, struct tlsph_scene *s,
                    struct tlsph_errors *err)
{
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
    const struct tlsph_key_target to = {.base = bc};
    int bad = tlsph_keys_values(obj, &common_table, P, &to, err) != 0;
    char type[TLSPH_BC_TYPE_SIZE];
    if (jc_string(obj, "type", 1, P, type, sizeof type, err) != 0)
        return -1;
    bc->kind = tlsph_bc_find(type);
    if (!bc->kind) {
        char names[256];
        tlsph_bc_names(names, sizeof names, 0, "", ", ");
        tlsph_key_error(err, P, "type", "unknown boundary condition type '%s' (accepted: %s)",
                        type, names);
        return -1;
    }
    bad |= tlsph_keys_unknown(obj, bc->kind->keys, P, err) != 0;
    bad |= bc->kind->parse(obj, s, bc, P, err) != 0;
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
