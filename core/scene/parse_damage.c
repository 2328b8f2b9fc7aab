/* The damage parts of a scene: a material's "damage" block (the model's own
 * parameters are read by its file in core/material/damage/) and the discretization's
 * "damage" block (how damage enters the approximation). */
#include <string.h>

#include "material/damage/damage.h"
#include "material/strength/strength.h"
#include "scene/parse_internal.h"

int tlsph_parse_material_damage(const json_t *mat, struct tlsph_material *m, const char *pointer,
                                struct tlsph_errors *err)
{
    const json_t *obj = jc_object(mat, "damage", 0, pointer, err);
    if (!obj)
        return json_object_get(mat, "damage") ? -1 : 0;
    char P[TLSPH_POINTER_MAX], q[TLSPH_POINTER_MAX];
    tlsph_pointer_join(P, sizeof P, pointer, "damage");
    char type[64];
    if (jc_string(obj, "type", 1, P, type, sizeof type, err) != 0)
        return -1;
    const struct tlsph_damage_model *model = tlsph_damage_find(type);
    if (!model) {
        tlsph_pointer_join(q, sizeof q, P, "type");
        tlsph_errors_add(err, q, "unknown damage model '%s' (accepted: %s)", type,
                         tlsph_damage_names());
        return -1;
    }
    int bad = model->parse(obj, m, P, err) != 0;
    if (!model->porous)
        bad |= tlsph_damage_parse_evolution(obj, m, P, err) != 0;
    if (m->strength && !tlsph_material_is_plastic(m)) {
        tlsph_errors_add(err, P,
                         "material '%s' has a damage block but strength '%s' is not plastic: "
                         "ductile damage grows with plastic strain (use a plastic strength "
                         "model: %s)",
                         m->name, m->strength->name, tlsph_strength_plastic_names());
        bad = 1;
    }
    m->damage.model = model; /* even when invalid: later checks must see it */
    return bad ? -1 : 0;
}

int tlsph_parse_damage_treatment(const json_t *d, struct tlsph_scene *s, struct tlsph_errors *err)
{
    static const char *const keys[] = {"treatment", "failed_particles", NULL};
    const char *P = "/discretization/damage";
    const json_t *obj = jc_object(d, "damage", 0, "/discretization", err);
    if (!obj)
        return json_object_get(d, "damage") ? -1 : 0;
    int bad = jc_unknown_keys(obj, keys, P, err) != 0;
    char v[32];
    int r = jc_string(obj, "treatment", 0, P, v, sizeof v, err);
    if (r < 0) {
        bad = 1;
    } else if (r == 0) {
        if (strcmp(v, "damage_aware") == 0) {
            s->crack_treatment = TLSPH_CRACK_DAMAGE_AWARE;
        } else if (strcmp(v, "pseudo_spring") == 0) {
            s->crack_treatment = TLSPH_CRACK_PSEUDO_SPRING;
        } else {
            tlsph_errors_add(err, "/discretization/damage/treatment",
                             "unknown damage treatment '%s' (accepted: damage_aware, "
                             "pseudo_spring)", v);
            bad = 1;
        }
    }
    r = jc_string(obj, "failed_particles", 0, P, v, sizeof v, err);
    if (r < 0) {
        bad = 1;
    } else if (r == 0) {
        if (strcmp(v, "free") == 0) {
            s->failed_motion = TLSPH_FAILED_FREE;
        } else if (strcmp(v, "arrest") == 0) {
            s->failed_motion = TLSPH_FAILED_ARREST;
        } else {
            tlsph_errors_add(err, "/discretization/damage/failed_particles",
                             "unknown failed-particle motion '%s' (accepted: free, arrest)", v);
            bad = 1;
        }
    }
    return bad ? -1 : 0;
}
