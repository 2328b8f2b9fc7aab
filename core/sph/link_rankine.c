/* Link criterion "rankine" (paper 001 §5.3, eq. 40): a link breaks at once
 * when its stretch reaches the threshold,
 *   D_ij = 1 if (r_t - r_0) / r_0 >= stretch, else 0,
 * r_t = |x_j - x_i| now, r_0 = |X_j - X_i| (the paper's Kalthoff-Winkler run:
 * eps_max = 0.0044, Table 4).  Brittle, and independent of the material model. */
#include "sph/link_criterion.h"
#include "sph/virtual_links.h"

enum { STRETCH };

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    {.name = "stretch", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 10.0, JC_OPEN, JC_CLOSED}, .unit = "1", .offset = TLSPH_PARAM(STRETCH),
     .description = "link stretch (r - r0) / r0 at which the link breaks, eps_max of eq. 40"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/discretization/damage/links", "rankine", keys);
/* clang-format on */

static inline double value(const struct tlsph_model *m, const struct tlsph_link_settings *ls,
                           size_t i, size_t j)
{
    const double *x = m->p.x, *X = m->p.X;
    double dx[3], dX[3];
    for (int a = 0; a < 3; a++) {
        dx[a] = x[3 * j + a] - x[3 * i + a];
        dX[a] = X[3 * j + a] - X[3 * i + a];
    }
    return tlsph_link_stretch(dx, dX) >= ls->params[STRETCH] ? 1.0 : 0.0;
}

TLSPH_LINK_SWEEP(update, value)

const struct tlsph_link_criterion tlsph_link_rankine = {
    .name = "rankine",
    .module = "link:rankine",
    .keys = &table,
    .needs_plasticity = 0,
    .update = update,
};
