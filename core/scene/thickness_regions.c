/* A body's thickness per region: "thickness_regions": [{"axis": "z", "box":
 * {"min": [...], "max": [...]}}, ...] (crack/fibre.h tlsph_fibres_build_regions).
 * A body made of plates that are thin in different directions (a plate and its
 * stiffeners) gives each part its region: the particles in a region's box
 * stack into fibres along the region's axis, a particle in no region is in no
 * fibre.
 *
 * Refused here, each at its pointer: the key together with a "thickness_axis"
 * other than "none", an empty list or more than TLSPH_MAX_THICKNESS_REGIONS,
 * an axis other than x, y, z ("radial" included: a shell's radial fibres are
 * the whole conforming wall's, one region), a box whose max is not above its
 * min on every axis.  At model setup (crack/fibre_model.c): a region holding
 * no particle, a particle in two regions (the list's order would silently
 * decide it). */
#include <string.h>

#include "scene/parse_internal.h"

/* clang-format off */
static const struct tlsph_key box_keys[] = {
    TLSPH_KEY_POINT("min", "minimum corner"),
    TLSPH_KEY_POINT("max", "maximum corner, greater than min on every axis"),
};
static const struct tlsph_key_table box_table =
    TLSPH_KEY_TABLE("/bodies/*/thickness_regions/*/box", NULL, box_keys);

static const struct tlsph_key_choice plane_axes[] = {{"x", 0}, {"y", 1}, {"z", 2}, {0}};

static const struct tlsph_key region_keys[] = {
    {.name = "axis", .kind = TLSPH_KEY_CHOICE, .flags = TLSPH_KEY_REQUIRED, .size = 32,
     .choices = plane_axes, .noun = "thickness axis of a region",
     .offset = offsetof(struct tlsph_thickness_region, axis),
     .description = "the region's thickness direction: its particles stack into fibres "
                    "along it"},
    {.name = "box", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_CALLER,
     .table = &box_table,
     .description = "axis-aligned box, closed, around the reference positions: the particles "
                    "of the region"},
};
/* clang-format on */
const struct tlsph_key_table tlsph_thickness_region_keys =
    TLSPH_KEY_TABLE("/bodies/*/thickness_regions/*", NULL, region_keys);

static int parse_item(const json_t *o, struct tlsph_thickness_region *r, const char *P,
                      struct tlsph_errors *err)
{
    if (!json_is_object(o)) {
        tlsph_errors_add(err, P, "must be an object, got %s", jc_type_name(o));
        return -1;
    }
    char p[TLSPH_POINTER_MAX];
    const json_t *a = json_object_get(o, "axis");
    if (json_is_string(a) && strcmp(json_string_value(a), "radial") == 0) {
        tlsph_pointer_join(p, sizeof p, P, "axis");
        tlsph_errors_add(err, p, "a radial thickness is a whole cylindrical shell's (give the "
                         "body \"thickness_axis\": \"radial\"), not a region's: x, y or z");
        return -1;
    }
    int bad = tlsph_keys_unknown(o, &tlsph_thickness_region_keys, P, err) != 0;
    bad |= tlsph_keys_values(o, &tlsph_thickness_region_keys, P,
                             &(struct tlsph_key_target){.base = r}, err) != 0;
    const json_t *box = jc_object(o, "box", 1, P, err);
    if (!box)
        return -1;
    tlsph_pointer_join(p, sizeof p, P, "box");
    bad |= tlsph_parse_box_corners(box, &box_table, 3, "thickness region box", p, r->min, r->max,
                                   err) != 0;
    return bad ? -1 : 0;
}

int tlsph_parse_thickness_regions(const json_t *obj, int dimension, struct tlsph_body *b,
                                  const char *P, struct tlsph_errors *err)
{
    (void)dimension; /* 2-D is refused with thickness_axis's rule (parse_bodies.c) */
    const json_t *v = json_object_get(obj, "thickness_regions");
    if (!v)
        return 0;
    char p[TLSPH_POINTER_MAX], q[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, P, "thickness_regions");
    if (b->thickness_axis != -1) {
        tlsph_errors_add(err, p, "body '%s': give \"thickness_axis\" (one direction for the "
                         "whole body) or \"thickness_regions\" (one per region), not both",
                         b->name);
        return -1;
    }
    const size_t n = json_is_array(v) ? json_array_size(v) : 0;
    if (!json_is_array(v) || n == 0 || n > TLSPH_MAX_THICKNESS_REGIONS) {
        tlsph_errors_add(err, p, "must be an array of 1 to %d regions, got %s",
                         TLSPH_MAX_THICKNESS_REGIONS,
                         json_is_array(v) ? (n ? "more" : "none") : jc_type_name(v));
        return -1;
    }
    int bad = 0;
    for (size_t k = 0; k < n; k++) {
        tlsph_pointer_index(q, sizeof q, p, k);
        bad |= parse_item(json_array_get(v, k), &b->thickness_region[k], q, err) != 0;
    }
    if (bad)
        return -1;
    b->nthickness_regions = (int)n;
    b->thickness_axis = TLSPH_THICKNESS_REGIONS;
    return 0;
}
