/* A material's "damage" block: the model's own parameters are read by its
 * file in core/material/damage/.  (The discretization's "damage" block, how
 * damage enters the approximation, is a table in scene_keys.c.) */

#include "material/damage/damage.h"
#include "material/strength/strength.h"
#include "scene/parse_internal.h"

int tlsph_parse_material_damage(const json_t *mat, struct tlsph_material *m, const char *pointer,
                                struct tlsph_errors *err)
{
    const json_t *obj = jc_object(mat, "damage", 0, pointer, err);
    if (!obj)
        return json_object_get(mat, "damage") ? -1 : 0;
    char P[TLSPH_POINTER_MAX];
    tlsph_pointer_join(P, sizeof P, pointer, "damage");
    char type[64];
    if (jc_string(obj, "type", 1, P, type, sizeof type, err) != 0)
        return -1;
    const struct tlsph_damage_model *model = tlsph_damage_find(type);
    if (!model) {
        tlsph_key_error(err, P, "type", "unknown damage model '%s' (accepted: %s)", type,
                        tlsph_damage_names());
        return -1;
    }
    int bad = model->parse(obj, m, P, err) != 0;
    if (!model->porous && !model->sudden)
        bad |= tlsph_damage_parse_evolution(obj, m, P, err) != 0;
    bad |= tlsph_require_plastic(m, "damage", "ductile damage grows with plastic strain", P, err);
    if (model->porous && m->thermal.enabled && m->thermal.expansion > 0.0) {
        char T[TLSPH_POINTER_MAX];
        tlsph_pointer_join(T, sizeof T, pointer, "thermal");
        tlsph_key_error(err, T, "expansion_coefficient",
                        "thermal expansion is not built for the porous model '%s' (its return "
                        "solves the pressure with the void growth); set it to 0",
                        model->name);
        bad = 1;
    }
    m->damage.model = model; /* even when invalid: later checks must see it */
    return bad ? -1 : 0;
}
