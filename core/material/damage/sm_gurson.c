/* Shear-modified Gurson (Nahshon & Hutchinson 2008; paper 003 eqs. 49-51):
 * gtn_aravas plus void growth by shear, df_s = k_w f omega(sigma) d eps_q,
 * omega of eq. 50 (0 in axisymmetric states, 1 in pure shear). */
#include "material/damage/damage.h"
#include "material/damage/porous.h"
#include "material/damage/porous_keys.h"

/* clang-format off */
POROUS_NUCLEATION_TABLE("sm_gurson");
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    POROUS_KEY_Q("q1", 2.5, POR_Q1, "yield-surface factor q1 (eq. 43); Table 1: 2.5"),
    POROUS_KEY_Q("q2", 1.0, POR_Q2, "yield-surface factor q2 (eq. 43); Table 1: 1.0"),
    POROUS_KEY_Q("q3", 3.25, POR_Q3, "yield-surface factor q3 (eq. 43); Table 1: 3.25"),
    POROUS_KEY_F0,
    POROUS_KEY_COALESCENCE,
    POROUS_KEY_NUCLEATION,
    POROUS_KEY_SHEAR,
    POROUS_KEY_FRACTURE,
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/materials/*/damage", "sm_gurson", keys);
/* clang-format on */

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    return tlsph_porous_parse(obj, m, pointer, &table, POROUS_SHEAR_NH, err);
}

const struct tlsph_damage_model tlsph_damage_sm_gurson = {
    .name = "sm_gurson",
    .module = "damage:sm_gurson",
    .keys = &table,
    .porous = 1,
    .fields = TLSPH_DAMAGE_FIELD_VOID_FRACTION | TLSPH_DAMAGE_FIELD_POROUS,
    .parse = parse,
    .point_update = tlsph_porous_point_update,
    .point_init = tlsph_porous_point_init,
};
