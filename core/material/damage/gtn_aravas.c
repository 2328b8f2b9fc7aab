/* Gurson-Tvergaard-Needleman in paper 003's form (eqs. 43, 45-48): q1, q2,
 * q3 (q3 need not be q1^2: Table 1 has 2.5 and 3.25), f* (eq. 45) and
 * strain-controlled nucleation, on the Aravas update of porous_return.h.
 * Named apart from paper 000's `gtn` (gtn.h), which keeps its own return and
 * parameters (q3 = q1^2, nucleation off by default): scenes using it are
 * unchanged, and the two can be run side by side. */
#include "material/damage/damage.h"
#include "material/damage/porous.h"
#include "material/damage/porous_keys.h"

/* clang-format off */
POROUS_NUCLEATION_TABLE("gtn_aravas");
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    POROUS_KEY_Q("q1", 2.5, POR_Q1, "yield-surface factor q1 (eq. 43); Table 1: 2.5"),
    POROUS_KEY_Q("q2", 1.0, POR_Q2, "yield-surface factor q2 (eq. 43); Table 1: 1.0"),
    POROUS_KEY_Q("q3", 3.25, POR_Q3, "yield-surface factor q3 (eq. 43); Table 1: 3.25"),
    POROUS_KEY_F0,
    POROUS_KEY_COALESCENCE,
    POROUS_KEY_NUCLEATION,
    POROUS_KEY_FRACTURE,
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/materials/*/damage", "gtn_aravas", keys);
/* clang-format on */

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    return tlsph_porous_parse(obj, m, pointer, &table, POROUS_SHEAR_NONE, err);
}

const struct tlsph_damage_model tlsph_damage_gtn_aravas = {
    .name = "gtn_aravas",
    .module = "damage:gtn_aravas",
    .keys = &table,
    .porous = 1,
    .fields = TLSPH_DAMAGE_FIELD_VOID_FRACTION | TLSPH_DAMAGE_FIELD_POROUS,
    .parse = parse,
    .point_update = tlsph_porous_point_update,
    .point_init = tlsph_porous_point_init,
};
