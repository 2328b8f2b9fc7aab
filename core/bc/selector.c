#include "bc/selector.h"

#include "bc/kind.h"
#include "run/model.h"
#include "scene/parse_internal.h"

/* clang-format off */
static const struct tlsph_key box_keys[] = {
    TLSPH_KEY_POINT("min", "minimum corner"),
    TLSPH_KEY_POINT("max", "maximum corner, greater than min in every used axis"),
};
/* The same keys under each owner of a selector: a table knows the one path it
 * is documented and checked at. */
static const struct tlsph_key_table box_table =
    TLSPH_KEY_TABLE("/boundary_conditions/*/select/box", NULL, box_keys);
static const struct tlsph_key_table probe_box_table =
    TLSPH_KEY_TABLE("/output/probes/*/select/box", NULL, box_keys);
static const struct tlsph_key_table extent_box_table =
    TLSPH_KEY_TABLE("/output/extents/*/select/box", NULL, box_keys);

#define SELECTOR_KEYS(box_table_)                                                              \
    {.name = "body", .kind = TLSPH_KEY_STRING, .flags = TLSPH_KEY_CALLER, .size = TLSPH_NAME_MAX, \
     .description = "name of a body; absent = every body"},                                    \
    {.name = "box", .kind = TLSPH_KEY_OBJECT, .flags = TLSPH_KEY_CALLER, .table = &(box_table_), \
     .description = "axis-aligned box, closed, around the reference positions; z ignored in 2-D"}, \
    {.name = "expression", .kind = TLSPH_KEY_EXPRESSION, .flags = TLSPH_KEY_CALLER,             \
     .description = "condition of the reference position x, y, z: non-zero selects"}

static const struct tlsph_key selector_keys[] = {SELECTOR_KEYS(box_table)};
static const struct tlsph_key probe_selector_keys[] = {SELECTOR_KEYS(probe_box_table)};
static const struct tlsph_key extent_selector_keys[] = {SELECTOR_KEYS(extent_box_table)};
const struct tlsph_key_table tlsph_selector_keys =
    TLSPH_KEY_TABLE("/boundary_conditions/*/select", NULL, selector_keys);
const struct tlsph_key_table tlsph_probe_selector_keys =
    TLSPH_KEY_TABLE("/output/probes/*/select", NULL, probe_selector_keys);
const struct tlsph_key_table tlsph_extent_selector_keys =
    TLSPH_KEY_TABLE("/output/extents/*/select", NULL, extent_selector_keys);
/* clang-format on */

static const char *const xyz[] = {"x", "y", "z"};

int tlsph_selector_parse(const json_t *obj, struct tlsph_scene *s, struct tlsph_bc *bc,
                         const char *P, struct tlsph_errors *err)
{
    const struct tlsph_key *row = tlsph_key_find(bc->kind->keys, "select");
    const int required = row && (row->flags & TLSPH_KEY_REQUIRED);
    return tlsph_selector_read(obj, required, s, &bc->select, P, err);
}

int tlsph_selector_read(const json_t *obj, int required, struct tlsph_scene *s,
                        struct tlsph_selector *sel, const char *P, struct tlsph_errors *err)
{
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
    int bad = tlsph_keys_unknown(v, &tlsph_selector_keys, p, err) != 0;
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
        tlsph_pointer_join(q, sizeof q, p, "box");
        const int rb = tlsph_parse_box_corners(box, &box_table, s->dimension, "selector box", q,
                                               sel->box_min, sel->box_max, err);
        bad |= rb != 0;
        if (s->dimension == 2) {
            sel->box_min[2] = -1e300;
            sel->box_max[2] = 1e300;
        }
        sel->has_box = 1;
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

int tlsph_selector_given(const struct tlsph_selector *sel)
{
    return sel->body >= 0 || sel->has_box || sel->expression.evaluator;
}

static int selected(const struct tlsph_model *m, struct tlsph_selector *sel, size_t i)
{
    if (sel->body >= 0 && m->p.body[i] != sel->body)
        return 0;
    const double *X = m->p.X + 3 * i;
    if (sel->has_box)
        for (int c = 0; c < m->dim; c++)
            if (X[c] < sel->box_min[c] || X[c] > sel->box_max[c])
                return 0;
    if (sel->expression.evaluator)
        return tlsph_expr_eval(&sel->expression, X) != 0.0;
    return 1;
}

size_t tlsph_selector_pick(const struct tlsph_model *m, struct tlsph_selector *sel,
                           int32_t *index)
{
    size_t count = 0;
    for (size_t i = 0; i < m->p.n; i++)
        if (selected(m, sel, i)) {
            if (index)
                index[count] = (int32_t)i;
            count++;
        }
    return count;
}

size_t tlsph_selector_select(const struct tlsph_model *m, struct tlsph_bc *bc, int32_t *index)
{
    return tlsph_selector_pick(m, &bc->select, index);
}
