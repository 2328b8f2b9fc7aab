/* "velocity": the given components of the selected particles' velocity follow
 * expressions of t (s); null components are free.  The support's impulse does
 * work at the prescribed mid-step velocity; its reaction is a support load. */
#include "bc/impulse.h"
#include "bc/kind.h"
#include "bc/selector.h"
#include "scene/parse_internal.h"

static int parse_velocity(const json_t *obj, struct tlsph_scene *s, struct tlsph_bc *bc,
                          const char *P, struct tlsph_errors *err)
{
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, P, "velocity");
    if (!json_object_get(obj, "velocity")) {
        tlsph_errors_add(err, p, "required field 'velocity' (3 items: m/s, expression of t, or "
                                 "null) is missing");
        return -1;
    }
    const int off_plane[3] = {0, 0, s->dimension == 2};
    const int given = tlsph_scene_time_vector(obj, "velocity", "m/s", "a free component",
                                              off_plane, s, bc->velocity, bc->velocity_set, P,
                                              err);
    if (given == 0) {
        tlsph_errors_add(err, p,
                         "'velocity' has no prescribed component: at least one of the %s items "
                         "must be a number or an expression of t",
                         s->dimension == 2 ? "first two" : "3");
        return -1;
    }
    return given < 0 ? -1 : 0;
}

static int parse(const json_t *obj, struct tlsph_scene *s, struct tlsph_bc *bc,
                 const char *pointer, struct tlsph_errors *err)
{
    int bad = tlsph_selector_parse(obj, s, bc, pointer, err) != 0;
    bad |= parse_velocity(obj, s, bc, pointer, err) != 0;
    return bad ? -1 : 0;
}

static void constrain(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                      double t, double t_mid, double *work)
{
    double val[3], mid[3];
    for (int c = 0; c < 3; c++) {
        val[c] = bc->velocity_set[c] ? tlsph_expr_eval(&bc->velocity[c], &t) : 0.0;
        mid[c] = bc->velocity_set[c] ? tlsph_expr_eval(&bc->velocity[c], &t_mid) : 0.0;
    }
    double w = *work; /* a local: the velocity stores cannot alias it */
    for (size_t a = 0; a < g->n; a++)
        for (int c = 0; c < 3; c++)
            if (bc->velocity_set[c])
                tlsph_bc_impose(m, g, (size_t)g->index[a], c, val[c], mid[c], &w);
    *work = w;
}

static enum tlsph_bc_prescription prescribes(struct tlsph_bc *bc, int c, double *value)
{
    if (!bc->velocity_set[c])
        return TLSPH_BC_FREE;
    if (!bc->velocity[c].constant)
        return TLSPH_BC_VARYING;
    const double t0 = 0.0;
    *value = tlsph_expr_eval(&bc->velocity[c], &t0);
    return TLSPH_BC_CONSTANT;
}

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_BC_KEYS,
    TLSPH_BC_SELECT(TLSPH_KEY_REQUIRED, "the particles whose velocity is prescribed"),
    {.name = "velocity", .kind = TLSPH_KEY_ARRAY, .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_CALLER,
     .unit = "m/s", .description = "3 items, each a number, an expression of t (s) or null (a "
                                   "free component); at least one not null"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/boundary_conditions/*", "velocity", keys);
/* clang-format on */

const struct tlsph_bc_kind tlsph_bc_velocity = {
    .name = "velocity",
    .module = "bc:velocity",
    .carries_load = 1,
    .keys = &table,
    .parse = parse,
    .select = tlsph_selector_select,
    .prescribes = prescribes,
    .constrain = constrain,
};
