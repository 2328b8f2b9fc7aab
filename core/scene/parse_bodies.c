/* Scene bodies: "bodies": [{name, material, spacing, lattice, placement, origin,
 * geometry, initial_velocity}, ...] -> s->bodies, and the particle-count checks that
 * keep a scene from asking for an absurd number of particles. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene/parse_internal.h"

static const char *const xyz[] = {"x", "y", "z"};

static int find_material(const struct tlsph_scene *s, const char *name)
{
    for (size_t i = 0; i < s->nmaterials; i++)
        if (strcmp(s->materials[i].name, name) == 0)
            return (int)i;
    return -1;
}

static int parse_initial_velocity(const json_t *obj, struct tlsph_scene *s, struct tlsph_body *b,
                                  const char *P, struct tlsph_errors *err)
{
    const json_t *v = json_object_get(obj, "initial_velocity");
    if (!v)
        return 0;
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, P, "initial_velocity");
    if (!json_is_array(v) || json_array_size(v) != 3) {
        tlsph_errors_add(err, p,
                         "'initial_velocity' must be an array of 3 items, each a number (m/s) or "
                         "an expression string of x, y, z (m) giving m/s");
        return -1;
    }
    int bad = 0;
    for (int k = 0; k < 3; k++) {
        char q[TLSPH_POINTER_MAX];
        tlsph_pointer_index(q, sizeof q, p, (size_t)k);
        if (tlsph_scene_expr(&b->initial_velocity[k], json_array_get(v, (size_t)k), xyz, 3, 0, s,
                             q, err) != 0) {
            bad = 1;
            continue;
        }
        if (k == 2 && s->dimension == 2) {
            const double X[3] = {0, 0, 0};
            struct tlsph_expr *ex = &b->initial_velocity[2];
            if (!ex->constant || tlsph_expr_eval(ex, X) != 0.0) {
                tlsph_errors_add(err, q, "in a 2-D scene the z velocity must be 0");
                bad = 1;
            }
            tlsph_expr_free(ex); /* evaluator NULL = 0 */
        }
    }
    return bad ? -1 : 0;
}

static int parse_body(const json_t *obj, size_t index, struct tlsph_scene *s,
                      struct tlsph_errors *err)
{
    struct tlsph_body *b = &s->bodies[index];
    char P[TLSPH_POINTER_MAX], p[TLSPH_POINTER_MAX];
    tlsph_pointer_index(P, sizeof P, "/bodies", index);
    if (!json_is_object(obj)) {
        tlsph_errors_add(err, P, "a body must be an object, got %s", jc_type_name(obj));
        return -1;
    }
    b->material = -1;
    int bad = tlsph_keys_unknown(obj, &tlsph_body_keys, P, err) != 0;
    tlsph_pointer_join(p, sizeof p, P, "name");
    if (jc_string(obj, "name", 1, P, b->name, sizeof b->name, err) != 0 ||
        tlsph_scene_check_name(b->name, "body name", p, err) != 0) {
        bad = 1;
    } else {
        for (size_t j = 0; j < index; j++)
            if (strcmp(s->bodies[j].name, b->name) == 0) {
                tlsph_errors_add(err, p, "duplicate body name '%s' (also used by /bodies/%zu)",
                                 b->name, j);
                bad = 1;
                break;
            }
    }
    char mat[TLSPH_NAME_MAX];
    if (jc_string(obj, "material", 1, P, mat, sizeof mat, err) != 0) {
        bad = 1;
    } else if ((b->material = find_material(s, mat)) < 0 && s->nmaterials > 0) {
        tlsph_pointer_join(p, sizeof p, P, "material");
        tlsph_errors_add(err, p, "unknown material '%s' (not a key of /materials)", mat);
        bad = 1;
    } else if (b->material < 0) {
        bad = 1; /* /materials itself is reported */
    }
    bad |= tlsph_keys_values(obj, &tlsph_body_keys, P, &(struct tlsph_key_target){.base = b},
                             err) != 0;
    tlsph_pointer_join(p, sizeof p, P, "geometry");
    const json_t *g = json_object_get(obj, "geometry");
    int geometry_ok = 0;
    if (!g) {
        tlsph_errors_add(err, p, "required object 'geometry' is missing");
        bad = 1;
    } else if (tlsph_parse_geometry(g, s->dimension, 0, p, &b->geometry, err) != 0) {
        bad = 1;
    } else if (tlsph_geometry_count(&b->geometry) > TLSPH_GEOMETRY_MAX_OBJECTS) {
        tlsph_errors_add(err, p,
                         "body '%s': the geometry has %zu objects (primitives, unions and "
                         "differences); at most %d are allowed",
                         b->name, tlsph_geometry_count(&b->geometry), TLSPH_GEOMETRY_MAX_OBJECTS);
        bad = 1;
    } else {
        geometry_ok = 1;
    }
    /* Absent: a plain sphere follows its surface (measured closer to Hertz, see
     * docs/contact.md), unless the scene pins its lattice with an origin or
     * refines it. */
    if (b->placement == TLSPH_PLACEMENT_AUTO)
        b->placement =
            geometry_ok && b->geometry.type == TLSPH_GEOM_SPHERE && !json_object_get(obj, "origin") &&
                    !json_object_get(obj, "refine")
                ? TLSPH_PLACEMENT_CONFORMING
                : TLSPH_PLACEMENT_LATTICE;
    if (geometry_ok && b->placement == TLSPH_PLACEMENT_CONFORMING &&
        !tlsph_conforming_base(&b->geometry)) {
        tlsph_pointer_join(p, sizeof p, P, "placement");
        tlsph_errors_add(err, p,
                         "body '%s': placement 'conforming' follows the curved surface of a "
                         "sphere (a disc in 2-D) or a cylinder: the geometry must be one, or a "
                         "difference whose first object is one; use 'lattice' for other shapes",
                         b->name);
        bad = 1;
    }
    const int r = jc_vector(obj, "origin", 0, 3, "m", P, b->origin, err);
    if (r < 0) {
        bad = 1;
    } else if (r == 1 && geometry_ok) {
        double hi[3];
        tlsph_geometry_bounds(&b->geometry, b->origin, hi);
    }
    if (s->dimension == 2)
        b->origin[2] = 0.0;
    if (geometry_ok && r >= 0)
        bad |= tlsph_check_body_precision(b, s->dimension, P, err) != 0;
    bad |= parse_initial_velocity(obj, s, b, P, err) != 0;
    if (geometry_ok)
        bad |= tlsph_parse_refine(obj, s->dimension, b, P, err) != 0;
    bad |= tlsph_parse_thickness_regions(obj, s->dimension, b, P, err) != 0;
    /* fibres stack the particles of a uniform lattice through a plate's
     * thickness (crack/fibre.h): other sets have no unambiguous stacks */
    const struct tlsph_geometry *base = geometry_ok ? tlsph_conforming_base(&b->geometry) : NULL;
    if (b->thickness_axis == 3 && geometry_ok &&
        (s->dimension == 2 || b->placement != TLSPH_PLACEMENT_CONFORMING || !base ||
         base->type != TLSPH_GEOM_CYLINDER)) {
        /* radial fibres stack a conforming cylinder's shells (crack/fibre.h) */
        tlsph_pointer_join(p, sizeof p, P, "thickness_axis");
        tlsph_errors_add(err, p,
                         "body '%s': a radial thickness is a cylindrical shell's: the body "
                         "must be 3-D with \"placement\": \"conforming\" and a cylinder (or a "
                         "difference whose first object is one) as its geometry",
                         b->name);
        bad = 1;
    } else if (b->thickness_axis >= 0 && b->thickness_axis != 3 &&
        (s->dimension == 2 || b->placement == TLSPH_PLACEMENT_CONFORMING ||
         json_object_get(obj, "refine"))) {
        tlsph_pointer_join(p, sizeof p, P,
                           b->nthickness_regions ? "thickness_regions" : "thickness_axis");
        tlsph_errors_add(err, p,
                         "body '%s': fibres stack a uniform lattice through a plate's thickness: "
                         "%s",
                         b->name,
                         s->dimension == 2 ? "a 2-D scene has no thickness to stack"
                         : json_object_get(obj, "refine")
                             ? "a refined body's finer particles have no stacks"
                             : "conforming shells have no stacks");
        bad = 1;
    }
    return bad ? -1 : 0;
}

int tlsph_parse_bodies(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err)
{
    const json_t *arr = json_object_get(root, "bodies");
    if (!arr) {
        tlsph_errors_add(err, "/bodies", "required array 'bodies' is missing");
        return -1;
    }
    if (!json_is_array(arr) || json_array_size(arr) == 0) {
        tlsph_errors_add(err, "/bodies", "'bodies' must be a non-empty array of body objects");
        return -1;
    }
    const size_t n = json_array_size(arr);
    if (n > TLSPH_MAX_BODIES) {
        tlsph_errors_add(err, "/bodies", "at most %d bodies are allowed, got %zu",
                         TLSPH_MAX_BODIES, n);
        return -1;
    }
    s->bodies = calloc(n, sizeof *s->bodies);
    if (!s->bodies) {
        tlsph_errors_add(err, "/bodies", "out of memory");
        return -1;
    }
    s->nbodies = n;
    int bad = 0;
    for (size_t i = 0; i < n; i++)
        bad |= parse_body(json_array_get(arr, i), i, s, err) != 0;
    return bad ? -1 : 0;
}

int tlsph_check_particle_counts(struct tlsph_scene *s, struct tlsph_errors *err)
{
    int bad = 0;
    size_t total = 0;
    const long max = s->max_particles;
    /* The walk tests every lattice point of each body's bounding box: all
     * bodies together may hold at most 10 x the particle limit of them, so
     * that validation stays bounded however many bodies there are. */
    double candidates = 0.0;
    for (size_t i = 0; i < s->nbodies; i++) {
        long lo[3], hi[3];
        candidates += tlsph_lattice_range(s, i, lo, hi);
    }
    if (s->nbodies > 1 && isfinite(candidates) && candidates > 10.0 * (double)max) {
        tlsph_errors_add(err, "/bodies",
                         "the bounding boxes of the bodies' geometries hold about %.3g lattice "
                         "points in all, more than 10 x the limit of %ld particles "
                         "(/limits/max_particles); increase the spacings",
                         candidates, max);
        return -1;
    }
    for (size_t i = 0; i < s->nbodies; i++) {
        const struct tlsph_body *b = &s->bodies[i];
        char P[TLSPH_POINTER_MAX], p[TLSPH_POINTER_MAX];
        tlsph_pointer_index(P, sizeof P, "/bodies", i);
        long lo[3], hi[3];
        /* Estimate first: lattice points in the geometry's bounding box. */
        const double estimate = tlsph_lattice_range(s, i, lo, hi);
        if (!isfinite(estimate) || estimate > 10.0 * (double)max) {
            tlsph_pointer_join(p, sizeof p, P, "spacing");
            tlsph_errors_add(err, p,
                             "body '%s': spacing %g m gives about %.3g particles in the bounding "
                             "box of its geometry, far above the limit of %ld particles "
                             "(/limits/max_particles); increase the spacing",
                             b->name, b->spacing, estimate, max);
            bad = 1;
            continue;
        }
        size_t count;
        if (tlsph_lattice_count(s, i, &count) != 0) {
            tlsph_errors_add(err, P, "out of memory while counting the particles of body '%s'",
                             b->name);
            bad = 1;
            continue;
        }
        if (count == 0) {
            tlsph_pointer_join(p, sizeof p, P, "geometry");
            tlsph_errors_add(err, p,
                             "body '%s': the geometry contains no lattice point at spacing %g m "
                             "(it is smaller than the spacing, or the origin misses it)",
                             b->name, b->spacing);
            bad = 1;
            continue;
        }
        if (count > (size_t)max && b->nrefine) {
            tlsph_pointer_join(p, sizeof p, P, "refine");
            if (count == SIZE_MAX)
                tlsph_errors_add(err, p,
                                 "body '%s': its refinement visits more than 10 x the limit of "
                                 "%ld particles (/limits/max_particles) in cells",
                                 b->name, max);
            else
                tlsph_errors_add(err, p,
                                 "body '%s': its refinement gives %zu particles, above the limit "
                                 "of %ld (/limits/max_particles)",
                                 b->name, count, max);
            bad = 1;
            continue;
        }
        if (count > (size_t)max) {
            tlsph_pointer_join(p, sizeof p, P, "spacing");
            tlsph_errors_add(err, p,
                             "body '%s': spacing %g m gives %zu particles, above the limit of %ld "
                             "(/limits/max_particles)",
                             b->name, b->spacing, count, max);
            bad = 1;
            continue;
        }
        total += count;
    }
    if (!bad && total > (size_t)max) {
        tlsph_errors_add(err, "/bodies",
                         "the bodies have %zu particles in total, above the limit of %ld "
                         "(/limits/max_particles)",
                         total, max);
        bad = 1;
    }
    return bad ? -1 : 0;
}
