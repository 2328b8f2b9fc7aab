/* Gurson-Tvergaard-Needleman in paper 003's form (eqs. 43, 45-48): q1, q2,
 * q3 (q3 need not be q1^2: Table 1 has 2.5 and 3.25), f* (eq. 45) and
 * strain-controlled nucleation, on the Aravas update of porous_return.h.
 * Named apart from paper 000's `gtn` (gtn.h), which keeps its own return and
 * parameters (q3 = q1^2, nucleation off by default): scenes using it are
 * unchanged, and the two can be run side by side. */
#include "material/damage/porous_keys.h"

/* clang-format off */
POROUS_NUCLEATION_TABLE("gtn_aravas");
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    POROUS_KEYS_GTN,
    POROUS_KEY_FRACTURE,
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/materials/*/damage", "gtn_aravas", keys);
/* clang-format on */

POROUS_ROW(gtn_aravas, POROUS_SHEAR_NONE);
