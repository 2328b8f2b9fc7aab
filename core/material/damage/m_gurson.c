/* Modified Gurson (Nielsen & Tvergaard 2010; paper 003 eqs. 52-54):
 * sm_gurson with the shear term scaled by Omega(T): 1 below the triaxiality
 * T1, 0 above T2, linear between. */
#include "material/damage/porous_keys.h"

/* clang-format off */
POROUS_NUCLEATION_TABLE("m_gurson");
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    POROUS_KEYS_GTN,
    POROUS_KEY_SHEAR,
    POROUS_NUMBER("low_triaxiality", -10.0, 10.0, JC_CLOSED, JC_CLOSED, 0.2, POR_T1,
                  "triaxiality T1 below which the shear term is whole (eq. 54); Table 1: 0.2"),
    POROUS_NUMBER("high_triaxiality", -10.0, 10.0, JC_CLOSED, JC_CLOSED, 0.7, POR_T2,
                  "triaxiality T2 above which the shear term is off (eq. 54), above "
                  "low_triaxiality; Table 1: 0.7"),
    POROUS_KEY_FRACTURE,
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/materials/*/damage", "m_gurson", keys);
/* clang-format on */

POROUS_ROW(m_gurson, POROUS_SHEAR_SWITCHED);
