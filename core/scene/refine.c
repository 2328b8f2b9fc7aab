/* A body's refinement regions: "refine": [{"region": {box | cylinder | sphere},
 * "spacing": s, "grading": g}, ...] under a body (graded.c fills them).
 *
 * Refused here, each at its pointer: more than TLSPH_MAX_REFINE regions, a
 * spacing not finer than the body's or finer than the body's / 2^
 * TLSPH_MAX_REFINE_LEVELS, a region of another kind, a region whose bounding
 * box misses the body's geometry's, and refinement of a conforming body. */
#include <math.h>
#include <stdlib.h>

#include "scene/parse_internal.h"

static const struct tlsph_key refine_keys[] = {
    {.name = "region", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_CALLER,
     .description = "where the spacing is finest: a geometry of one box, cylinder or sphere "
                    "(a disc in 2-D)"},
    {.name = "spacing", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "m",
     .offset = offsetof(struct tlsph_refine, spacing),
     .description = "the spacing inside the region: below the body's spacing and at least "
                    "the body's / 1024"},
    {.name = "grading", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {1.0, 10.0, JC_OPEN, JC_CLOSED}, .unit = "1",
     .offset = offsetof(struct tlsph_refine, grading),
     .description = "growth of the target spacing per spacing of distance from the region "
                    "(spacing + (grading - 1) x distance, up to the body's spacing)"},
};
const struct tlsph_key_table tlsph_refine_keys =
    TLSPH_KEY_TABLE("/bodies/*/refine/*", NULL, refine_keys);

void tlsph_refine_free(struct tlsph_body *b)
{
    for (size_t r = 0; r < b->nrefine; r++)
        tlsph_geometry_free(&b->refine[r].region);
    free(b->refine);
    b->refine = NULL;
    b->nrefine = 0;
}

/* 1 when the boxes lo..hi and LO..HI meet on the used axes. */
static int boxes_meet(const double lo[3], const double hi[3], const double LO[3],
                      const double HI[3], int naxes)
{
    for (int k = 0; k < naxes; k++)
        if (hi[k] < LO[k] || HI[k] < lo[k])
            return 0;
    return 1;
}

static int parse_item(const json_t *o, int dimension, const struct tlsph_body *b,
                      struct tlsph_refine *rf, const char *P, struct tlsph_errors *err)
{
    char p[TLSPH_POINTER_MAX];
    if (!json_is_object(o)) {
        tlsph_errors_add(err, P, "must be an object, got %s", jc_type_name(o));
        return -1;
    }
    int bad = tlsph_keys_unknown(o, &tlsph_refine_keys, P, err) != 0;
    bad |= tlsph_keys_values(o, &tlsph_refine_keys, P, &(struct tlsph_key_target){.base = rf},
                             err) != 0;
    tlsph_pointer_join(p, sizeof p, P, "region");
    const json_t *g = json_object_get(o, "region");
    if (!g) {
        tlsph_errors_add(err, p, "required object 'region' is missing");
        bad = 1;
    } else if (tlsph_parse_geometry(g, dimension, 0, p, &rf->region, err) != 0) {
        bad = 1;
    } else if (rf->region.type != TLSPH_GEOM_BOX && rf->region.type != TLSPH_GEOM_SPHERE &&
               rf->region.type != TLSPH_GEOM_CYLINDER) {
        tlsph_errors_add(err, p, "a refinement region is one box, cylinder or sphere");
        bad = 1;
    } else {
        double lo[3], hi[3], LO[3], HI[3];
        tlsph_geometry_bounds(&rf->region, lo, hi);
        tlsph_geometry_bounds(&b->geometry, LO, HI);
        if (!boxes_meet(lo, hi, LO, HI, dimension == 2 ? 2 : 3)) {
            tlsph_errors_add(err, p,
                             "body '%s': the region lies outside the body (its bounding box "
                             "misses the geometry's)",
                             b->name);
            bad = 1;
        }
    }
    /* relative to the body's spacing, when that one is valid */
    tlsph_pointer_join(p, sizeof p, P, "spacing");
    const double h = b->spacing, finest = ldexp(h, -TLSPH_MAX_REFINE_LEVELS);
    if (h > 0.0 && rf->spacing > 0.0) {
        if (rf->spacing >= h) {
            tlsph_errors_add(err, p,
                             "body '%s': refined spacing %g m is not finer than the body's "
                             "spacing %g m",
                             b->name, rf->spacing, h);
            bad = 1;
        } else if (rf->spacing < finest) {
            tlsph_errors_add(err, p,
                             "body '%s': refined spacing %g m is finer than allowed: at least "
                             "the body's spacing / %d = %g m",
                             b->name, rf->spacing, 1 << TLSPH_MAX_REFINE_LEVELS, finest);
            bad = 1;
        }
    }
    return bad ? -1 : 0;
}

int tlsph_parse_refine(const json_t *obj, int dimension, struct tlsph_body *b, const char *pointer,
                       struct tlsph_errors *err)
{
    const json_t *arr = json_object_get(obj, "refine");
    if (!arr)
        return 0;
    char P[TLSPH_POINTER_MAX], q[TLSPH_POINTER_MAX];
    tlsph_pointer_join(P, sizeof P, pointer, "refine");
    if (!json_is_array(arr) || json_array_size(arr) == 0 ||
        json_array_size(arr) > TLSPH_MAX_REFINE) {
        tlsph_errors_add(err, P, "'refine' must be an array of 1 to %d regions",
                         TLSPH_MAX_REFINE);
        return -1;
    }
    if (b->placement == TLSPH_PLACEMENT_CONFORMING) {
        tlsph_errors_add(err, P,
                         "body '%s': refinement fills the lattice; it needs \"placement\": "
                         "\"lattice\"",
                         b->name);
        return -1;
    }
    const size_t n = json_array_size(arr);
    b->refine = calloc(n, sizeof *b->refine);
    if (!b->refine) {
        tlsph_errors_add(err, P, "out of memory");
        return -1;
    }
    b->nrefine = n;
    int bad = 0;
    for (size_t i = 0; i < n; i++) {
        tlsph_pointer_index(q, sizeof q, P, i);
        bad |= parse_item(json_array_get(arr, i), dimension, b, &b->refine[i], q, err) != 0;
    }
    return bad ? -1 : 0;
}
