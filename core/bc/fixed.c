/* "fixed": the selected particles are held at rest, v = 0 in every component.
 * The support does not move, so its impulse does no work; its reaction is a
 * support load. */
#include "bc/impulse.h"
#include "bc/kind.h"
#include "bc/selector.h"

static void constrain(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                      double t, double t_mid, double *work)
{
    (void)bc, (void)t, (void)t_mid;
    double w = *work; /* a local: the velocity stores cannot alias it */
    for (size_t a = 0; a < g->n; a++)
        for (int c = 0; c < 3; c++)
            tlsph_bc_impose(m, g, (size_t)g->index[a], c, 0.0, 0.0, &w);
    *work = w;
}

static enum tlsph_bc_prescription prescribes(struct tlsph_bc *bc, int c, double *value)
{
    (void)bc, (void)c;
    *value = 0.0;
    return TLSPH_BC_CONSTANT;
}

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_BC_KEYS,
    TLSPH_BC_SELECT(TLSPH_KEY_REQUIRED, "the particles held at rest"),
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/boundary_conditions/*", "fixed", keys);
/* clang-format on */

const struct tlsph_bc_kind tlsph_bc_fixed = {
    .name = "fixed",
    .module = "bc:fixed",
    .carries_load = 1,
    .keys = &table,
    .parse = tlsph_selector_parse,
    .select = tlsph_selector_select,
    .prescribes = prescribes,
    .constrain = constrain,
};
