/* "body_force": a uniform acceleration a (m/s^2, e.g. gravity) of the selected
 * particles (all of them without a selector): a force m a on each, whose power
 * at the half-step velocities is booked as external work. */
#include "bc/kind.h"
#include "bc/selector.h"
#include "run/model.h"
#include "scene/json_check.h"

static int parse(const json_t *obj, struct tlsph_scene *s, struct tlsph_bc *bc,
                 const char *P, struct tlsph_errors *err)
{
    int bad = 0;
    if (jc_vector(obj, "acceleration", 1, 3, "m/s^2", P, bc->acceleration, err) != 0) {
        bad = 1;
    } else if (s->dimension == 2 && bc->acceleration[2] != 0.0) {
        char p[TLSPH_POINTER_MAX], q[TLSPH_POINTER_MAX];
        tlsph_pointer_join(p, sizeof p, P, "acceleration");
        tlsph_pointer_index(q, sizeof q, p, 2);
        tlsph_errors_add(err, q, "in a 2-D scene the z acceleration must be 0 m/s^2");
        bad = 1;
    }
    bad |= tlsph_selector_parse(obj, s, bc, P, err) != 0;
    return bad ? -1 : 0;
}

static void force(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                  double *power)
{
    const double *acc = bc->acceleration;
    double sum = *power; /* a local: the force stores cannot alias it */
    for (size_t a = 0; a < g->n; a++) {
        const size_t i = (size_t)g->index[a];
        const double mi = m->p.mass[i];
        const double *v = m->p.v + 3 * i;
        for (int c = 0; c < 3; c++)
            m->p.f[3 * i + c] += mi * acc[c];
        sum += mi * (acc[0] * v[0] + acc[1] * v[1] + acc[2] * v[2]);
    }
    *power = sum;
}

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_BC_KEYS,
    {.name = "acceleration", .kind = TLSPH_KEY_ARRAY,
     .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_CALLER, .unit = "m/s^2",
     .description = "uniform acceleration, 3 numbers; in 2-D the z one must be 0"},
    TLSPH_BC_SELECT(0, "the particles accelerated; absent = every particle"),
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/boundary_conditions/*", "body_force", keys);
/* clang-format on */

const struct tlsph_bc_kind tlsph_bc_body_force = {
    .name = "body_force",
    .module = "bc:body_force",
    .carries_load = 0,
    .keys = &table,
    .parse = parse,
    .select = tlsph_selector_select,
    .force = force,
};
