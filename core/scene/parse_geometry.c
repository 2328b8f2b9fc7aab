/* Scene geometry objects: {"box"|"cylinder"|"sphere"|"plate"|"notched_bar"|
 * "union"|"difference": ...} -> struct tlsph_geometry (see core/scene/scene.h for the
 * meaning of a[]).  Each primitive's keys are a table (core/scene/keys.h): its
 * lengths are read by the generic reader into a[], its points and directions
 * here.  Vectors always have 3 components; in 2-D the z components
 * of points and directions are ignored (set to 0), a box spans z in
 * [-0.5, 0.5] (the unit thickness), a sphere is a disk in the x-y plane and a
 * plate is a rectangle of thickness "thickness" along its in-plane normal and
 * length size[0]; cylinders and notched bars are 3-D only. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/parse_internal.h"

/* clang-format off */
/* A length > 0 stored in a[slot]. */
#define LENGTH(key, slot, what)                                                                 \
    {.name = (key), .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,                      \
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "m", .offset = TLSPH_PARAM(slot),          \
     .description = (what)}
#define PRIMITIVE(name, keys) TLSPH_KEY_TABLE("/bodies/*/geometry/" name, NULL, keys)
/* clang-format on */

/* Reads the lengths of a primitive's table into a[]. */
static int read_lengths(const json_t *o, const struct tlsph_key_table *t, const char *P, double *a,
                        struct tlsph_errors *err)
{
    const struct tlsph_key_target to = {.base = a};
    return tlsph_keys_values(o, t, P, &to, err);
}

void tlsph_geometry_free(struct tlsph_geometry *g)
{
    for (size_t i = 0; i < g->nchildren; i++)
        tlsph_geometry_free(&g->children[i]);
    free(g->children);
    g->children = NULL;
    g->nchildren = 0;
}

/* Normalises v in place; 0 when it is (numerically) the zero vector. */
static int normalise(double v[3])
{
    const double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(n > 1e-300) || !isfinite(n))
        return 0;
    for (int k = 0; k < 3; k++)
        v[k] /= n;
    return 1;
}

/* A unit direction at pointer/key; in 2-D its z component is dropped first. */
int tlsph_parse_direction(const json_t *obj, const char *key, int dimension, const char *pointer,
                          double out[3], struct tlsph_errors *err)
{
    if (jc_vector(obj, key, 1, 3, "direction, any length", pointer, out, err) != 0)
        return -1;
    if (dimension == 2)
        out[2] = 0.0;
    if (!normalise(out)) {
        char p[TLSPH_POINTER_MAX];
        tlsph_pointer_join(p, sizeof p, pointer, key);
        tlsph_errors_add(err, p, "'%s' must be a non-zero vector%s", key,
                         dimension == 2 ? " in the x-y plane (2-D scene)" : "");
        return -1;
    }
    return 0;
}

/* clang-format off */
static const struct tlsph_key box_keys[] = {
    TLSPH_KEY_POINT("min", "minimum corner"),
    TLSPH_KEY_POINT("max", "maximum corner, greater than min in every used axis"),
};
static const struct tlsph_key_table box_table = PRIMITIVE("box", box_keys);
/* clang-format on */

int tlsph_parse_box_corners(const json_t *o, const struct tlsph_key_table *t, int naxes,
                            const char *what, const char *P, double lo[3], double hi[3],
                            struct tlsph_errors *err)
{
    int bad = tlsph_keys_unknown(o, t, P, err) != 0;
    int r1 = jc_vector(o, "min", 1, 3, "m", P, lo, err);
    int r2 = jc_vector(o, "max", 1, 3, "m", P, hi, err);
    if (r1 || r2)
        return -1;
    for (int k = 0; k < naxes; k++)
        if (!(hi[k] > lo[k])) {
            char p[TLSPH_POINTER_MAX], q[TLSPH_POINTER_MAX];
            tlsph_pointer_join(p, sizeof p, P, "max");
            tlsph_pointer_index(q, sizeof q, p, (size_t)k);
            tlsph_errors_add(err, q, "%s max[%d] = %g m must be greater than min[%d] = %g m",
                             what, k, hi[k], k, lo[k]);
            bad = 1;
        }
    return bad ? -1 : 0;
}

static int parse_box(const json_t *o, int dim, const char *P, double *a, struct tlsph_errors *err)
{
    const int rc = tlsph_parse_box_corners(o, &box_table, dim, "box", P, a, a + 3, err);
    if (dim == 2) {
        a[2] = -0.5;
        a[5] = 0.5;
    }
    return rc;
}

/* clang-format off */
static const struct tlsph_key cylinder_keys[] = {
    TLSPH_KEY_POINT("base", "centre of the base disc"),
    TLSPH_KEY_DIRECTION("axis", "axis from the base, any non-zero length"),
    LENGTH("radius", 6, "radius"),
    LENGTH("length", 7, "length along the axis"),
};
static const struct tlsph_key_table cylinder_table = PRIMITIVE("cylinder", cylinder_keys);
/* clang-format on */

static int parse_cylinder(const json_t *o, int dim, const char *P, double *a,
                          struct tlsph_errors *err)
{
    (void)dim;
    int bad = tlsph_keys_unknown(o, &cylinder_table, P, err) != 0;
    bad |= jc_vector(o, "base", 1, 3, "m", P, a, err) != 0;
    bad |= tlsph_parse_direction(o, "axis", 3, P, a + 3, err) != 0;
    bad |= read_lengths(o, &cylinder_table, P, a, err) != 0;
    return bad ? -1 : 0;
}

/* clang-format off */
static const struct tlsph_key sphere_keys[] = {
    TLSPH_KEY_POINT("center", "centre"),
    LENGTH("radius", 3, "radius"),
};
static const struct tlsph_key_table sphere_table = PRIMITIVE("sphere", sphere_keys);
/* clang-format on */

static int parse_sphere(const json_t *o, int dim, const char *P, double *a,
                        struct tlsph_errors *err)
{
    int bad = tlsph_keys_unknown(o, &sphere_table, P, err) != 0;
    bad |= jc_vector(o, "center", 1, 3, "m", P, a, err) != 0;
    bad |= read_lengths(o, &sphere_table, P, a, err) != 0;
    if (dim == 2)
        a[2] = 0.0;
    return bad ? -1 : 0;
}

/* clang-format off */
static const struct tlsph_key plate_keys[] = {
    TLSPH_KEY_POINT("center", "centre"),
    TLSPH_KEY_DIRECTION("normal", "normal, any non-zero length"),
    {.name = "size", .kind = TLSPH_KEY_ARRAY, .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_CALLER,
     .unit = "m", .description = "in-plane side lengths [a, b] along the in-plane axes u and w, "
                                 "both > 0; b ignored in 2-D"},
    LENGTH("thickness", 6, "thickness along the normal"),
};
static const struct tlsph_key_table plate_table = PRIMITIVE("plate", plate_keys);
/* clang-format on */

/* In-plane axis u (stored in a[9..11]): 3-D: u = normalise(n x e_k), e_k the
 * coordinate axis least aligned with n (first on ties); 2-D: u = e_z x n. */
static void plate_axes(int dim, double *a)
{
    const double *n = a + 3;
    double *u = a + 9;
    if (dim == 2) {
        u[0] = -n[1];
        u[1] = n[0];
        u[2] = 0.0;
        return;
    }
    int k = 0;
    for (int i = 1; i < 3; i++)
        if (fabs(n[i]) < fabs(n[k]))
            k = i;
    double e[3] = {0, 0, 0};
    e[k] = 1.0;
    u[0] = n[1] * e[2] - n[2] * e[1];
    u[1] = n[2] * e[0] - n[0] * e[2];
    u[2] = n[0] * e[1] - n[1] * e[0];
    normalise(u); /* |n x e_k| >= sqrt(2/3) since |n_k| <= 1/sqrt(3) */
}

static int parse_plate(const json_t *o, int dim, const char *P, double *a,
                       struct tlsph_errors *err)
{
    int bad = tlsph_keys_unknown(o, &plate_table, P, err) != 0;
    bad |= jc_vector(o, "center", 1, 3, "m", P, a, err) != 0;
    const int normal_bad = tlsph_parse_direction(o, "normal", dim, P, a + 3, err) != 0;
    bad |= normal_bad;
    bad |= read_lengths(o, &plate_table, P, a, err) != 0;
    double size[2];
    if (jc_vector(o, "size", 1, 2, "m", P, size, err) != 0) {
        bad = 1;
    } else if (!(size[0] > 0.0) || !(size[1] > 0.0)) {
        char p[TLSPH_POINTER_MAX];
        tlsph_pointer_join(p, sizeof p, P, "size");
        tlsph_errors_add(err, p, "plate 'size' = [%g, %g] m: both sides must be > 0", size[0],
                         size[1]);
        bad = 1;
    } else {
        a[7] = size[0];
        a[8] = dim == 2 ? 1.0 : size[1];
    }
    if (dim == 2)
        a[2] = 0.0;
    if (!normal_bad)
        plate_axes(dim, a);
    return bad ? -1 : 0;
}

/* clang-format off */
static const struct tlsph_key notched_bar_keys[] = {
    TLSPH_KEY_POINT("base", "centre of the base disc"),
    TLSPH_KEY_DIRECTION("axis", "axis from the base, any non-zero length"),
    LENGTH("radius", 6, "bar radius R0"),
    LENGTH("length", 7, "bar length L"),
    LENGTH("notch_root_radius", 8, "bar radius r at the notch root, r < R0"),
    LENGTH("notch_radius", 9, "radius R of the notch profile"),
    LENGTH("notch_position", 10, "axial position of the notch centre from the base; the notch "
                                 "lies inside the bar"),
};
static const struct tlsph_key_table notched_bar_table = PRIMITIVE("notched_bar", notched_bar_keys);
/* clang-format on */

static int parse_notched_bar(const json_t *o, int dim, const char *P, double *a,
                             struct tlsph_errors *err)
{
    (void)dim;
    int bad = tlsph_keys_unknown(o, &notched_bar_table, P, err) != 0;
    bad |= jc_vector(o, "base", 1, 3, "m", P, a, err) != 0;
    bad |= tlsph_parse_direction(o, "axis", 3, P, a + 3, err) != 0;
    if (read_lengths(o, &notched_bar_table, P, a, err) != 0)
        return -1;
    const double R0 = a[6], L = a[7], r = a[8], R = a[9], zc = a[10];
    char p[TLSPH_POINTER_MAX];
    if (!(r < R0)) {
        tlsph_pointer_join(p, sizeof p, P, "notch_root_radius");
        tlsph_errors_add(err, p,
                         "'notch_root_radius' = %g m must be smaller than the bar 'radius' = %g m",
                         r, R0);
        return -1;
    }
    /* Half-width of the notch where it meets the bar surface: the circle's
     * chord, or R for a U-notch (deeper than R, straight flanks). */
    const double c = r + R - R0, w = c < 0.0 ? R : sqrt(fmax(0.0, R * R - c * c));
    if (!(zc - w > 0.0) || !(zc + w < L)) {
        tlsph_pointer_join(p, sizeof p, P, "notch_position");
        tlsph_errors_add(err, p,
                         "'notch_position' = %g m: the notch (half-width %g m at the surface) "
                         "must lie inside the bar, i.e. notch_position in (%g, %g) m",
                         zc, w, w, L - w);
        return -1;
    }
    return bad ? -1 : 0;
}

/* A geometry holds exactly one of these keys: its name says what the geometry is. */
/* clang-format off */
static const struct tlsph_key geometry_keys[] = {
    {.name = "box", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_CALLER, .table = &box_table,
     .description = "axis-aligned box"},
    {.name = "cylinder", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_CALLER,
     .table = &cylinder_table, .description = "solid circular cylinder (3-D only)"},
    {.name = "sphere", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_CALLER, .table = &sphere_table,
     .description = "solid sphere; a disk in the x-y plane in 2-D"},
    {.name = "plate", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_CALLER, .table = &plate_table,
     .description = "thin rectangular plate"},
    {.name = "notched_bar", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_CALLER,
     .table = &notched_bar_table,
     .description = "round bar with a circumferential notch (3-D only)"},
    {.name = "union", .kind = TLSPH_KEY_ARRAY, .flags = TLSPH_KEY_CALLER,
     .description = "at least 1 geometry: points inside any of them"},
    {.name = "difference", .kind = TLSPH_KEY_ARRAY, .flags = TLSPH_KEY_CALLER,
     .description = "at least 2 geometries: points inside the first and none of the others"},
};
const struct tlsph_key_table tlsph_geometry_keys = {
    .path = "/bodies/*/geometry", .keys = geometry_keys,
    .nkeys = sizeof geometry_keys / sizeof *geometry_keys, .one_of = 1};

/* What each row of geometry_keys makes, in the same order. */
static const enum tlsph_geometry_type types[] = {
    TLSPH_GEOM_BOX,         TLSPH_GEOM_CYLINDER, TLSPH_GEOM_SPHERE,    TLSPH_GEOM_PLATE,
    TLSPH_GEOM_NOTCHED_BAR, TLSPH_GEOM_UNION,    TLSPH_GEOM_DIFFERENCE};
_Static_assert(sizeof types / sizeof *types == sizeof geometry_keys / sizeof *geometry_keys,
               "one geometry type per row");
/* clang-format on */

static int parse_list(const json_t *v, int dim, int depth, int min_items, const char *kind,
                      const char *P, struct tlsph_geometry *g, struct tlsph_errors *err)
{
    if (!json_is_array(v) || json_array_size(v) < (size_t)min_items) {
        tlsph_errors_add(err, P, "'%s' must be an array of at least %d geometry objects", kind,
                         min_items);
        return -1;
    }
    const size_t n = json_array_size(v);
    if (n >= TLSPH_GEOMETRY_MAX_OBJECTS) {
        tlsph_errors_add(err, P,
                         "'%s' has %zu items; a body's geometry holds at most %d objects "
                         "(primitives, unions and differences)",
                         kind, n, TLSPH_GEOMETRY_MAX_OBJECTS);
        return -1;
    }
    g->children = calloc(n, sizeof *g->children);
    if (!g->children) {
        tlsph_errors_add(err, P, "out of memory");
        return -1;
    }
    g->nchildren = n;
    int bad = 0;
    for (size_t i = 0; i < n; i++) {
        char p[TLSPH_POINTER_MAX];
        tlsph_pointer_index(p, sizeof p, P, i);
        bad |= tlsph_parse_geometry(json_array_get(v, i), dim, depth + 1, p, &g->children[i],
                                    err) != 0;
    }
    return bad ? -1 : 0;
}

int tlsph_parse_geometry(const json_t *v, int dimension, int depth, const char *pointer,
                         struct tlsph_geometry *g, struct tlsph_errors *err)
{
    memset(g, 0, sizeof *g);
    if (depth > TLSPH_GEOMETRY_MAX_DEPTH) {
        tlsph_errors_add(err, pointer, "geometry nested deeper than %d levels",
                         TLSPH_GEOMETRY_MAX_DEPTH);
        return -1;
    }
    char names[128]; /* the accepted keys, for the messages */
    if (!json_is_object(v) || json_object_size(v) != 1) {
        tlsph_keys_names(&tlsph_geometry_keys, names, sizeof names);
        tlsph_errors_add(err, pointer, "a geometry must be an object with exactly one key (%s)",
                         names);
        return -1;
    }
    const char *kind = json_object_iter_key(json_object_iter((json_t *)v));
    const json_t *body = json_object_get(v, kind);
    char P[TLSPH_POINTER_MAX];
    tlsph_pointer_join(P, sizeof P, pointer, kind);
    const struct tlsph_key *row = tlsph_key_find(&tlsph_geometry_keys, kind);
    if (!row) {
        tlsph_keys_names(&tlsph_geometry_keys, names, sizeof names);
        tlsph_errors_add(err, P, "unknown geometry '%s' (accepted: %s)", kind, names);
        return -1;
    }
    g->type = types[row - geometry_keys];
    if (g->type == TLSPH_GEOM_UNION)
        return parse_list(body, dimension, depth, 1, kind, P, g, err);
    if (g->type == TLSPH_GEOM_DIFFERENCE)
        return parse_list(body, dimension, depth, 2, kind, P, g, err);
    if (dimension == 2 && (g->type == TLSPH_GEOM_CYLINDER || g->type == TLSPH_GEOM_NOTCHED_BAR)) {
        tlsph_errors_add(err, P,
                         "'%s' is a 3-D geometry; in a 2-D scene use box, plate or sphere (a "
                         "disk in the x-y plane)",
                         kind);
        return -1;
    }
    if (!json_is_object(body)) {
        tlsph_errors_add(err, P, "'%s' must be an object, got %s", kind,
                         jc_type_name(body));
        return -1;
    }
    switch (g->type) {
    case TLSPH_GEOM_BOX: return parse_box(body, dimension, P, g->a, err);
    case TLSPH_GEOM_CYLINDER: return parse_cylinder(body, dimension, P, g->a, err);
    case TLSPH_GEOM_SPHERE: return parse_sphere(body, dimension, P, g->a, err);
    case TLSPH_GEOM_PLATE: return parse_plate(body, dimension, P, g->a, err);
    case TLSPH_GEOM_NOTCHED_BAR: return parse_notched_bar(body, dimension, P, g->a, err);
    default: return -1;
    }
}
