/* The scene's "cracks" array: initial cracks as surfaces (paper 003 §5.3's
 * through pre-crack; core/crack/precrack.h cuts the reference pairs across
 * them).  Each item holds exactly one of
 *   "polygon": [[x, y, z], ...]  3-D: 3 to TLSPH_MAX_CRACK_CORNERS corners of a
 *                                planar convex polygon, in order around it (m);
 *   "segment": [[x, y, z], [x, y, z]]  2-D: the crack's trace in the x-y plane
 *                                (m; z ignored, as for the rigid shapes).
 * Refused, with the pointer of the item or the corner: the other dimension's
 * form, a point that is not 3 finite numbers, too few or too many corners, a
 * zero-length edge or segment, a polygon of zero area, one that is not planar
 * (a corner off the mean plane by more than 1e-6 of its diameter) or not convex
 * (a corner turning against the others; collinear corners are accepted).
 * A crack may reach beyond its body (a crack mouth written past the free edge
 * is the natural way to say "open at the edge"); one that cuts no pair at all
 * is refused when the particles exist (core/crack/precrack.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/parse_internal.h"

/* clang-format off */
static const struct tlsph_key crack_keys[] = {
    {.name = "polygon", .kind = TLSPH_KEY_ARRAY, .flags = TLSPH_KEY_CALLER, .unit = "m",
     .description = "3-D: the corners of a planar convex polygon, in order, each [x, y, z]"},
    {.name = "segment", .kind = TLSPH_KEY_ARRAY, .flags = TLSPH_KEY_CALLER, .unit = "m",
     .description = "2-D: the two ends of the crack's trace, each [x, y, z], z ignored"},
};
/* clang-format on */
const struct tlsph_key_table tlsph_crack_keys = {
    .path = "/cracks/*", .keys = crack_keys, .nkeys = sizeof crack_keys / sizeof *crack_keys,
    .one_of = 1};

/* "crack_growth" (core/crack/crack_driver.h).  Defaults: D_c = 0.1 is the
 * paper's for the Johnson-Cook damage of §5.3 (the engine's D); the paper
 * gives no fan angle or radius, so theta_c = 120 degrees (the lattice
 * neighbours at +-45 degrees ahead inside, the sideways ones at 90 outside)
 * and R = 1.5 spacings (the eight lattice neighbours of a fibre).  R below
 * 2 spacings: a hop of 2 along a lattice row or diagonal passes through the
 * fibre between, whose particles would lie on the new facets and lose every
 * neighbour. */
static const struct tlsph_key_choice growth_criteria[] = {
    {"damage", TLSPH_CRACK_CRITERION_DAMAGE},
    {"void_fraction", TLSPH_CRACK_CRITERION_VOID_FRACTION},
    {"plastic_strain", TLSPH_CRACK_CRITERION_PLASTIC_STRAIN},
    {0}};

/* clang-format off */
static const struct tlsph_key growth_keys[] = {
    {.name = "tips", .kind = TLSPH_KEY_ARRAY, .flags = TLSPH_KEY_CALLER,
     .unit = "m", .description = "the crack tips that grow, each [x, y, z]: an end of a crack's "
     "trace in the plane of a body with fibres (thickness_axis); required unless initiate"},
    {.name = "initiate", .kind = TLSPH_KEY_BOOLEAN, .flags = TLSPH_KEY_DEFAULT, .def = 0,
     .offset = offsetof(struct tlsph_scene, crack_growth.initiate),
     .description = "cracks also start where none is: after each step a fibre of a thin body "
     "whose criterion sum reaches critical_damage, away from every crack, is split and grows "
     "two tips (one, inward, at the body's edge)"},
    {.name = "critical_damage", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "1", .def = 0.1,
     .offset = offsetof(struct tlsph_scene, crack_growth.critical_damage),
     .description = "D_c of eq. 20: a fibre becomes the tip when the sum of its particles' "
     "damage reaches it"},
    {.name = "fan_angle", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,
     .range = {0.0, 360.0, JC_OPEN, JC_CLOSED}, .unit = "deg", .def = 120.0,
     .offset = offsetof(struct tlsph_scene, crack_growth.fan_angle),
     .description = "theta_c of eq. 20: the new tip lies within +-theta_c/2 of the crack's "
     "direction"},
    {.name = "search_radius", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,
     .range = {1.0, 2.0, JC_CLOSED, JC_OPEN}, .unit = "1", .said = "(spacings)", .def = 1.5,
     .offset = offsetof(struct tlsph_scene, crack_growth.search_radius),
     .above_max = "a hop of 2 spacings passes through the fibre between, which the new facets "
     "would cut off from every neighbour",
     .description = "R of eq. 20, in spacings of the tip's body: the new tip lies within R of "
     "the old"},
    {.name = "criterion", .kind = TLSPH_KEY_CHOICE, .flags = TLSPH_KEY_DEFAULT,
     .def = TLSPH_CRACK_CRITERION_DAMAGE, .size = 16, .choices = growth_criteria,
     .noun = "crack criterion", .offset = offsetof(struct tlsph_scene, crack_growth.criterion),
     .description = "the particle quantity summed over a fibre and compared with "
     "critical_damage (paper 003 §3.1, §6.1): damage (the damage variable D), void_fraction "
     "(the void volume fraction f of a porous damage model) or plastic_strain (the equivalent "
     "plastic strain of a plastic material)"},
};
/* clang-format on */
const struct tlsph_key_table tlsph_crack_growth_keys = {
    .path = "/crack_growth", .keys = growth_keys,
    .nkeys = sizeof growth_keys / sizeof *growth_keys};

/* Planarity and convexity tolerances, relative to the polygon's diameter: the
 * corners are typed by people, to a few digits. */
#define PLANAR_TOL 1e-6
#define AREA_TOL 1e-12

static void sub3(const double a[3], const double b[3], double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = a[k] - b[k];
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Reads the array of points at c[key] into spec; 0 or -1 after reporting. */
static int read_points(const json_t *arr, int min, int max, const char *p,
                       struct tlsph_crack_spec *spec, struct tlsph_errors *err)
{
    if (!json_is_array(arr)) {
        tlsph_errors_add(err, p, "must be an array of points [x, y, z] (m), got %s",
                         jc_type_name(arr));
        return -1;
    }
    const size_t n = json_array_size(arr);
    if (n < (size_t)min || n > (size_t)max) {
        if (min == max)
            tlsph_errors_add(err, p, "must hold exactly %d points, got %zu", min, n);
        else
            tlsph_errors_add(err, p, "must hold %d to %d corners, got %zu", min, max, n);
        return -1;
    }
    int bad = 0;
    for (size_t k = 0; k < n; k++) {
        char q[TLSPH_POINTER_MAX];
        tlsph_pointer_index(q, sizeof q, p, k);
        const json_t *pt = json_array_get(arr, k);
        int ok = json_is_array(pt) && json_array_size(pt) == 3;
        for (size_t c = 0; ok && c < 3; c++) {
            const json_t *v = json_array_get(pt, c);
            ok = json_is_number(v) && isfinite(json_number_value(v));
            if (ok)
                spec->corner[k][c] = json_number_value(v);
        }
        if (!ok) {
            tlsph_errors_add(err, q, "a point must be 3 finite numbers [x, y, z] (m)");
            bad = 1;
        }
    }
    spec->ncorners = (int)n;
    return bad ? -1 : 0;
}

/* A 2-D crack's segment: two distinct points in the x-y plane. */
static int check_segment(struct tlsph_crack_spec *c, const char *p, struct tlsph_errors *err)
{
    c->corner[0][2] = c->corner[1][2] = 0.0;
    const double dx = c->corner[1][0] - c->corner[0][0], dy = c->corner[1][1] - c->corner[0][1];
    const double scale = fmax(fmax(fabs(c->corner[0][0]), fabs(c->corner[0][1])),
                              fmax(fabs(c->corner[1][0]), fabs(c->corner[1][1])));
    if (!(hypot(dx, dy) > AREA_TOL * scale) || !(hypot(dx, dy) > 0.0)) {
        tlsph_errors_add(err, p, "the segment's two ends coincide (in x-y): a crack needs a length");
        return -1;
    }
    return 0;
}

/* A 3-D crack's polygon: no repeated corner, non-zero area, planar, convex. */
static int check_polygon(const struct tlsph_crack_spec *c, const char *p,
                         struct tlsph_errors *err)
{
    const int n = c->ncorners;
    double diameter = 0.0;
    for (int a = 0; a < n; a++)
        for (int b = a + 1; b < n; b++) {
            double d[3];
            sub3(c->corner[b], c->corner[a], d);
            diameter = fmax(diameter, sqrt(dot3(d, d)));
        }
    for (int a = 0; a < n; a++) {
        double e[3];
        sub3(c->corner[(a + 1) % n], c->corner[a], e);
        if (!(sqrt(dot3(e, e)) > AREA_TOL * diameter)) {
            tlsph_errors_add(err, p, "corners %d and %d coincide: a zero-length edge", a,
                             (a + 1) % n);
            return -1;
        }
    }
    /* Newell's normal: twice the area vector of the polygon */
    double N[3] = {0, 0, 0}, centre[3] = {0, 0, 0};
    for (int a = 0; a < n; a++) {
        double x[3];
        cross3(c->corner[a], c->corner[(a + 1) % n], x);
        for (int k = 0; k < 3; k++) {
            N[k] += x[k];
            centre[k] += c->corner[a][k] / n;
        }
    }
    const double twice_area = sqrt(dot3(N, N));
    if (!(twice_area > AREA_TOL * diameter * diameter)) {
        tlsph_errors_add(err, p,
                         "the polygon has zero area (its corners are on one line): a crack "
                         "surface needs an area");
        return -1;
    }
    for (int a = 0; a < n; a++) {
        double d[3];
        sub3(c->corner[a], centre, d);
        const double off = dot3(d, N) / twice_area;
        if (fabs(off) > PLANAR_TOL * diameter) {
            tlsph_errors_add(err, p,
                             "the polygon is not planar: corner %d is %g m off the plane of the "
                             "others (at most %g of its diameter %g m)",
                             a, off, PLANAR_TOL, diameter);
            return -1;
        }
    }
    for (int a = 0; a < n; a++) {
        double e1[3], e2[3], t[3];
        sub3(c->corner[(a + 1) % n], c->corner[a], e1);
        sub3(c->corner[(a + 2) % n], c->corner[(a + 1) % n], e2);
        cross3(e1, e2, t);
        if (dot3(t, N) < -AREA_TOL * diameter * diameter * twice_area) {
            tlsph_errors_add(err, p,
                             "the polygon is not convex at corner %d (or its corners are not in "
                             "order around it): split it into convex pieces, one crack each",
                             (a + 1) % n);
            return -1;
        }
    }
    return 0;
}

static int parse_crack(const json_t *e, int dim, struct tlsph_crack_spec *c, const char *P,
                       struct tlsph_errors *err)
{
    if (!json_is_object(e)) {
        tlsph_errors_add(err, P, "a crack must be an object {\"%s\": [...]}, got %s",
                         dim == 3 ? "polygon" : "segment", jc_type_name(e));
        return -1;
    }
    if (tlsph_keys_read(e, &tlsph_crack_keys, P, &(struct tlsph_key_target){.base = c}, err) !=
        0)
        return -1;
    /* the form the dimension asks for, and the other one */
    const char *form = dim == 3 ? "polygon" : "segment", *other = dim == 3 ? "segment" : "polygon";
    char p[TLSPH_POINTER_MAX];
    if (json_object_get(e, other)) {
        tlsph_pointer_join(p, sizeof p, P, other);
        tlsph_errors_add(err, p, "a crack of a %d-D scene is a \"%s\" (%s), not a %s", dim, form,
                         dim == 3 ? "a surface, >= 3 corners" : "its trace in the x-y plane, 2 points",
                         other);
        return -1;
    }
    const json_t *points = json_object_get(e, form);
    if (!points) {
        tlsph_errors_add(err, P, "a crack needs its \"%s\"", form);
        return -1;
    }
    tlsph_pointer_join(p, sizeof p, P, form);
    if (dim == 2)
        return read_points(points, 2, 2, p, c, err) == 0 ? check_segment(c, p, err) : -1;
    return read_points(points, 3, TLSPH_MAX_CRACK_CORNERS, p, c, err) == 0
               ? check_polygon(c, p, err)
               : -1;
}

int tlsph_parse_cracks(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err)
{
    const json_t *arr = json_object_get(root, "cracks");
    if (!arr)
        return 0;
    if (!json_is_array(arr)) {
        tlsph_errors_add(err, "/cracks", "'cracks' must be an array of objects, got %s",
                         jc_type_name(arr));
        return -1;
    }
    const size_t n = json_array_size(arr);
    if (n == 0)
        return 0;
    if (n > TLSPH_MAX_CRACKS) {
        tlsph_errors_add(err, "/cracks", "at most %d cracks are allowed, got %zu",
                         TLSPH_MAX_CRACKS, n);
        return -1;
    }
    s->cracks = calloc(n, sizeof *s->cracks);
    if (!s->cracks) {
        tlsph_errors_add(err, "/cracks", "out of memory");
        return -1;
    }
    s->ncracks = n;
    int bad = 0;
    for (size_t k = 0; k < n; k++) {
        char P[TLSPH_POINTER_MAX];
        tlsph_pointer_index(P, sizeof P, "/cracks", k);
        bad |= parse_crack(json_array_get(arr, k), s->dimension, &s->cracks[k], P, err) != 0;
    }
    return bad ? -1 : 0;
}

int tlsph_parse_crack_growth(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err)
{
    const json_t *g = json_object_get(root, "crack_growth");
    if (!g)
        return 0;
    const char *P = "/crack_growth";
    if (!json_is_object(g)) {
        tlsph_errors_add(err, P, "'crack_growth' must be an object, got %s", jc_type_name(g));
        return -1;
    }
    if (tlsph_keys_read(g, &tlsph_crack_growth_keys, P, &(struct tlsph_key_target){.base = s},
                        err) != 0)
        return -1;
    const json_t *tips = json_object_get(g, "tips");
    const int initiate = s->crack_growth.initiate;
    if (!tips && !initiate) {
        tlsph_errors_add(err, "/crack_growth/tips", "required (unless \"initiate\" is true): "
                         "the crack tips that grow");
        return -1;
    }
    if (json_is_array(tips) &&
        (json_array_size(tips) < 1 || json_array_size(tips) > TLSPH_MAX_GROWTH_TIPS)) {
        tlsph_errors_add(err, "/crack_growth/tips", "must hold 1 to %d tips, got %zu",
                         TLSPH_MAX_GROWTH_TIPS, json_array_size(tips));
        return -1;
    }
    struct tlsph_crack_spec pts = {0};
    if (tips && read_points(tips, 1, TLSPH_MAX_GROWTH_TIPS, "/crack_growth/tips", &pts, err) != 0)
        return -1;
    for (int k = 0; k < pts.ncorners; k++)
        memcpy(s->crack_growth.tip[k], pts.corner[k], sizeof pts.corner[k]);
    s->crack_growth.ntips = (size_t)pts.ncorners;
    if (s->dimension != 3) {
        tlsph_errors_add(err, P, "cracks grow through the thickness of a plate (fibres): a 3-D "
                         "scene only");
        return -1;
    }
    if (s->ncracks == 0 && !initiate) {
        tlsph_errors_add(err, P, "a crack grows from a pre-crack: the scene has no \"cracks\"");
        return -1;
    }
    int thin = 0;
    for (size_t b = 0; b < s->nbodies; b++)
        thin |= s->bodies[b].thickness_axis >= 0;
    if (!thin) {
        tlsph_errors_add(err, P, "a crack grows from fibre to fibre: no body has a "
                         "\"thickness_axis\" (give the plate's body one)");
        return -1;
    }
    s->crack_growth.on = 1;
    return 0;
}
