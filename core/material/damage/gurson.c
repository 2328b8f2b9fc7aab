/* Original Gurson model (paper 003 eqs. 43-44): q1 = q2 = q3 = 1,
 * f* = f, voids grow by plastic dilatation only (no nucleation, no shear). */
#include "material/damage/porous_keys.h"

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    POROUS_KEY_F0,
    POROUS_KEY_FRACTURE,
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/materials/*/damage", "gurson", keys);
/* clang-format on */

POROUS_ROW(gurson, POROUS_SHEAR_NONE);
