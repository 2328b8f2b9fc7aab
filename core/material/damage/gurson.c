/* Original Gurson model (paper 003 eqs. 43-44): q1 = q2 = q3 = 1,
 * f* = f, voids grow by plastic dilatation only (no nucleation, no shear). */
#include "material/damage/damage.h"
#include "material/damage/porous.h"
#include "material/damage/porous_keys.h"

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    POROUS_KEY_F0,
    POROUS_KEY_FRACTURE,
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/materials/*/damage", "gurson", keys);
/* clang-format on */

static int parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err)
{
    return tlsph_porous_parse(obj, m, pointer, &table, POROUS_SHEAR_NONE, err);
}

const struct tlsph_damage_model tlsph_damage_gurson = {
    .name = "gurson",
    .module = "damage:gurson",
    .keys = &table,
    .porous = 1,
    .fields = TLSPH_DAMAGE_FIELD_VOID_FRACTION | TLSPH_DAMAGE_FIELD_POROUS,
    .parse = parse,
    .point_update = tlsph_porous_point_update,
    .point_init = tlsph_porous_point_init,
};
