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
    TLSPH_LINK_KEY_REACH,
    {.name = "stretch", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 10.0, JC_OPEN, JC_CLOSED}, .unit = "1", .offset = TLSPH_LINK_PARAM(STRETCH),
     .description = "link stretch (r - r0) / r0 at which the link breaks, eps_max of eq. 40"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/discretization/damage/links", "rankine", keys);
/* clang-format on */

static inline double value(const struct tlsph_model *m, const struct tlsph_link_settings *ls,
                           size_t i, size_t j)
{
    return tlsph_link_stretch_of(m, i, j) >= ls->params[STRETCH] ? 1.0 : 0.0;
}

TLSPH_LINK_ROW(rankine, 0)
