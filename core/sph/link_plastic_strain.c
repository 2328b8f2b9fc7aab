/* Link criterion "plastic_strain" (paper 001 §5.2, eqs. 37-39): the plastic
 * strain of both particles projected on the link (eq. 37), averaged with the
 * other particle's impedance (eq. 38); the link breaks at once when that
 * reaches the threshold (eq. 39, the paper's (eps_pl)_max = 0.17 for its
 * aluminium beam):  D_ij = 1 if eps_link >= threshold, else 0. */
#include "sph/link_criterion.h"
#include "sph/virtual_links.h"

enum { THRESHOLD };

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    TLSPH_LINK_KEY_REACH,
    {.name = "threshold", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 10.0, JC_OPEN, JC_CLOSED}, .unit = "1", .offset = TLSPH_LINK_PARAM(THRESHOLD),
     .description = "link plastic strain (eqs. 37-38) at which the link breaks, "
                    "(eps_pl)_max of eq. 39"},
};
static const struct tlsph_key_table table =
    TLSPH_KEY_TABLE("/discretization/damage/links", "plastic_strain", keys);
/* clang-format on */

double tlsph_link_plastic_strain_of(const struct tlsph_model *m, size_t i, size_t j)
{
    const double *X = m->p.X;
    const double d[3] = {X[3 * j] - X[3 * i], X[3 * j + 1] - X[3 * i + 1],
                         X[3 * j + 2] - X[3 * i + 2]};
    const double ei = tlsph_link_projected_strain(m->p.plastic_strain + 6 * i, d);
    const double ej = tlsph_link_projected_strain(m->p.plastic_strain + 6 * j, d);
    return tlsph_link_average(tlsph_link_impedance(m, i), ei, tlsph_link_impedance(m, j), ej);
}

static inline double value(const struct tlsph_model *m, const struct tlsph_link_settings *ls,
                           size_t i, size_t j)
{
    return tlsph_link_plastic_strain_of(m, i, j) >= ls->params[THRESHOLD] ? 1.0 : 0.0;
}

TLSPH_LINK_ROW(plastic_strain, 1)
