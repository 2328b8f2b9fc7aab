/* Scene measurements written as time series (see core/io/measures.h):
 *   "output": {"gauges": [{"name", "between": [GROUP, GROUP], "area", "length"?}],
 *              "sections": [{"name", "point", "normal", "thickness"}],
 *              "probes": [{"name", "select"}],
 *              "extents": [{"name", "select", "point", "axis", "radius_over"?}]}
 * A gauge's groups must be load-carrying boundary conditions (fixed or
 * velocity), since the gauge reads their reactions. */
#include <string.h>

#include "bc/kind.h"
#include "bc/selector.h"
#include "scene/parse_internal.h"

/* The array at out[key] (absent = empty): its size, or -1 with an error. */
static long measure_array(const json_t *out, const char *key, const json_t **arr,
                          struct tlsph_errors *err)
{
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, "/output", key);
    *arr = json_object_get(out, key);
    if (!*arr)
        return 0;
    if (!json_is_array(*arr)) {
        tlsph_errors_add(err, p, "'%s' must be an array, got %s", key, jc_type_name(*arr));
        return -1;
    }
    const size_t n = json_array_size(*arr);
    if (n > TLSPH_MAX_MEASURES) {
        tlsph_errors_add(err, p, "at most %d %s are allowed, got %zu", TLSPH_MAX_MEASURES, key,
                         n);
        return -1;
    }
    return (long)n;
}

/* Item i of an array of objects, with its name (a `noun` name) valid and unique
 * among items 0..i-1. */
static const json_t *measure_item(const json_t *arr, size_t i, const char *key, const char *noun,
                                  const struct tlsph_key_table *keys, char *name, const char *names,
                                  size_t stride, char *P, struct tlsph_errors *err)
{
    char base[TLSPH_POINTER_MAX];
    tlsph_pointer_join(base, sizeof base, "/output", key);
    tlsph_pointer_index(P, TLSPH_POINTER_MAX, base, i);
    const json_t *o = json_array_get(arr, i);
    if (!json_is_object(o)) {
        tlsph_errors_add(err, P, "must be an object, got %s", jc_type_name(o));
        return NULL;
    }
    int bad = tlsph_keys_unknown(o, keys, P, err) != 0;
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, P, "name");
    if (jc_string(o, "name", 1, P, name, TLSPH_NAME_MAX, err) != 0 ||
        tlsph_scene_check_name(name, noun, p, err) != 0)
        return NULL;
    for (size_t j = 0; j < i; j++)
        if (strcmp(names + j * stride, name) == 0) {
            tlsph_errors_add(err, p, "duplicate name '%s' (also used by %s/%zu)", name, base, j);
            return NULL;
        }
    return bad ? NULL : o;
}

static int find_load_group(const struct tlsph_scene *s, const json_t *v, const char *p,
                           struct tlsph_errors *err)
{
    if (!json_is_string(v)) {
        tlsph_errors_add(err, p, "must be the name of a boundary condition, got %s",
                         jc_type_name(v));
        return -1;
    }
    const char *name = json_string_value(v);
    for (size_t k = 0; k < s->nbcs; k++) {
        if (strcmp(s->bcs[k].name, name) != 0)
            continue;
        if (!s->bcs[k].kind->carries_load) {
            char kinds[256];
            tlsph_bc_names(kinds, sizeof kinds, 1, "'", " or ");
            tlsph_errors_add(err, p,
                             "boundary condition '%s' carries no reaction: a gauge needs a "
                             "%s condition",
                             name, kinds);
            return -1;
        }
        return (int)k;
    }
    tlsph_errors_add(err, p, "unknown boundary condition '%s' (not a name in "
                             "/boundary_conditions)", name);
    return -1;
}

static int parse_gauge(const json_t *o, const struct tlsph_scene *s, const char *P,
                       struct tlsph_gauge *g, struct tlsph_errors *err)
{
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, P, "between");
    const json_t *between = json_object_get(o, "between");
    int bad = 0;
    if (!between) {
        tlsph_errors_add(err, p, "required field 'between' is missing");
        bad = 1;
    } else if (!json_is_array(between) || json_array_size(between) != 2) {
        tlsph_errors_add(err, p, "'between' must be an array of two boundary condition names");
        bad = 1;
    } else {
        for (size_t k = 0; k < 2; k++) {
            char q[TLSPH_POINTER_MAX];
            tlsph_pointer_index(q, sizeof q, p, k);
            g->group[k] = find_load_group(s, json_array_get(between, k), q, err);
            bad |= g->group[k] < 0;
        }
        if (!bad && g->group[0] == g->group[1]) {
            tlsph_errors_add(err, p, "'between' names the same boundary condition twice");
            bad = 1;
        }
    }
    const struct tlsph_key_target to = {.base = g};
    bad |= tlsph_keys_values(o, &tlsph_gauge_keys, P, &to, err) != 0;
    return bad ? -1 : 0;
}

/* The keys of a section or an extent: "point", the direction dirkey (normalised),
 * and the keys' table's plain values into base. */
static int parse_point_direction(const json_t *o, int dim, const char *P, const char *dirkey,
                                 double point[3], double dir[3],
                                 const struct tlsph_key_table *keys, void *base,
                                 struct tlsph_errors *err)
{
    int bad = jc_vector(o, "point", 1, 3, "m", P, point, err) != 0;
    if (dim == 2)
        point[2] = 0.0;
    bad |= tlsph_parse_direction(o, dirkey, dim, P, dir, err) != 0;
    const struct tlsph_key_target to = {.base = base};
    bad |= tlsph_keys_values(o, keys, P, &to, err) != 0;
    return bad ? -1 : 0;
}

/* measure_item for an item with a required "select", read into sel. */
static const json_t *selecting_item(const json_t *arr, size_t i, const char *key,
                                    const char *noun, const struct tlsph_key_table *keys,
                                    char *name, const char *names, size_t stride,
                                    struct tlsph_selector *sel, struct tlsph_scene *s, char *P,
                                    struct tlsph_errors *err)
{
    sel->body = -1;
    const json_t *o = measure_item(arr, i, key, noun, keys, name, names, stride, P, err);
    return o && tlsph_selector_read(o, 1, s, sel, P, err) == 0 ? o : NULL;
}

int tlsph_parse_measures(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err)
{
    const json_t *out = json_object_get(root, "output");
    if (!json_is_object(out))
        return 0; /* absent, or already reported */
    int bad = 0;
    const json_t *arr;
    char P[TLSPH_POINTER_MAX];

    long n = measure_array(out, "gauges", &arr, err);
    bad |= n < 0;
    for (long i = 0; i < n; i++) {
        struct tlsph_gauge *g = &s->gauges[i];
        const json_t *o = measure_item(arr, (size_t)i, "gauges", "gauge name", &tlsph_gauge_keys,
                                       g->name, s->gauges[0].name, sizeof *g, P, err);
        if (!o || parse_gauge(o, s, P, g, err) != 0)
            bad = 1;
    }
    if (n > 0)
        s->ngauges = (size_t)n;

    n = measure_array(out, "sections", &arr, err);
    bad |= n < 0;
    for (long i = 0; i < n; i++) {
        struct tlsph_section *c = &s->sections[i];
        const json_t *o =
            measure_item(arr, (size_t)i, "sections", "section name", &tlsph_section_keys, c->name,
                         s->sections[0].name, sizeof *c, P, err);
        if (!o || parse_point_direction(o, s->dimension, P, "normal", c->point, c->normal,
                                        &tlsph_section_keys, c, err) != 0)
            bad = 1;
    }
    if (n > 0)
        s->nsections = (size_t)n;

    n = measure_array(out, "probes", &arr, err);
    bad |= n < 0;
    if (n > 0)
        s->nprobes = (size_t)n; /* before parsing: the scene frees what the items hold */
    for (long i = 0; i < n; i++) {
        struct tlsph_probe *q = &s->probes[i];
        bad |= !selecting_item(arr, (size_t)i, "probes", "probe name", &tlsph_probe_keys, q->name,
                               s->probes[0].name, sizeof *q, &q->select, s, P, err);
    }

    n = measure_array(out, "extents", &arr, err);
    bad |= n < 0;
    if (n > 0)
        s->nextents = (size_t)n;
    for (long i = 0; i < n; i++) {
        struct tlsph_extent *x = &s->extents[i];
        const json_t *o =
            selecting_item(arr, (size_t)i, "extents", "extent name", &tlsph_extent_keys, x->name,
                           s->extents[0].name, sizeof *x, &x->select, s, P, err);
        bad |= !o || parse_point_direction(o, s->dimension, P, "axis", x->point, x->axis,
                                           &tlsph_extent_keys, x, err) != 0;
    }
    return bad ? -1 : 0;
}
