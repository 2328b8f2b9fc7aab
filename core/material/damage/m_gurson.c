/* Modified Gurson (Nielsen & Tvergaard 2010; paper 003 eqs. 52-54):
 * sm_gurson with the shear term scaled by Omega(T): 1 below the triaxiality
 * T1, 0 above T2, linear between. */
#include "material/damage/damage.h"
#include "material/damage/porous.h"
#include "material/damage/porous_keys.h"

/* clang-format off */
POROUS_NUCLEATION_TABLE("m_gurson");
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    POROUS_KEY_Q("q1", 2.5, POR_Q1, "yield-surface factor q1 (eq. 43); Table 1: 2.5"),
    POROUS_KEY_Q("q2", 1.0, POR_Q2, "yield-surface factor q2 (eq. 43); Table 1: 1.0"),
    POROUS_KEY_Q("q3", 3.25, POR_Q3, "yield-surface factor q3 (eq. 43); Table 1: 3.25"),
    POROUS_KEY_F0,
    POROUS_KEY_COALESCENCE,
    POROUS_KEY_NUCLEATION,
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

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    return tlsph_porous_parse(obj, m, pointer, &table, POROUS_SHEAR_SWITCHED, err);
}

const struct tlsph_damage_model tlsph_damage_m_gurson = {
    .name = "m_gurson",
    .module = "damage:m_gurson",
    .keys = &table,
    .porous = 1,
    .fields = TLSPH_DAMAGE_FIELD_VOID_FRACTION | TLSPH_DAMAGE_FIELD_POROUS,
    .parse = parse,
    .point_update = tlsph_porous_point_update,
    .point_init = tlsph_porous_point_init,
};
