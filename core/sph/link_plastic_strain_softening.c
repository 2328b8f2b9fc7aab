/* Link criterion "plastic_strain_softening": the link plastic strain of eqs.
 * 37-38 (link_plastic_strain.c), with a linear softening in place of eq. 39's
 * sudden break (the paper: "more sophisticated cracking criterion can be used"):
 *   D_ij = min(1, max(0, (eps_link - threshold) / softening))
 * so the link starts to soften at the threshold and is broken once its strain
 * has grown by `softening` more.  Damage never heals (link_criterion.h). */
#include "sph/link_criterion.h"
#include "sph/virtual_links.h"

enum { THRESHOLD, SOFTENING };

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    TLSPH_LINK_KEY_REACH,
    {.name = "threshold", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 10.0, JC_OPEN, JC_CLOSED}, .unit = "1", .offset = TLSPH_LINK_PARAM(THRESHOLD),
     .description = "link plastic strain (eqs. 37-38) at which the link starts to soften"},
    {.name = "softening", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 10.0, JC_OPEN, JC_CLOSED}, .unit = "1", .offset = TLSPH_LINK_PARAM(SOFTENING),
     .description = "further link plastic strain from the threshold to the broken link "
                    "(D_ij grows linearly over it)"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/discretization/damage/links", "plastic_strain_softening", keys);
/* clang-format on */

static inline double value(const struct tlsph_model *m, const struct tlsph_link_settings *ls,
                           size_t i, size_t j)
{
    const double e = tlsph_link_plastic_strain_of(m, i, j);
    return fmax(0.0, (e - ls->params[THRESHOLD]) / ls->params[SOFTENING]);
}

TLSPH_LINK_ROW(plastic_strain_softening, 1)
