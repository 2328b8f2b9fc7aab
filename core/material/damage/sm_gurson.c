/* Shear-modified Gurson (Nahshon & Hutchinson 2008; paper 003 eqs. 49-51):
 * gtn_aravas plus void growth by shear, df_s = k_w f omega(sigma) d eps_q,
 * omega of eq. 50 (0 in axisymmetric states, 1 in pure shear). */
#include "material/damage/porous_keys.h"

/* clang-format off */
POROUS_NUCLEATION_TABLE("sm_gurson");
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    POROUS_KEYS_GTN,
    POROUS_KEY_SHEAR,
    POROUS_KEY_FRACTURE,
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/materials/*/damage", "sm_gurson", keys);
/* clang-format on */

POROUS_ROW(sm_gurson, POROUS_SHEAR_NH);
