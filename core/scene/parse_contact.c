/* The scene's "contact" block: its own keys (scene_keys.c) and the law, whose
 * parameters its file in core/contact/ reads.
 *
 * Contact is on by default wherever it can act: in a scene of more than one
 * body (two bodies passing through each other is never what a user meant)
 * the default law runs without any block, and so it does in a scene with a
 * damage model, whose broken parts may meet.  "enabled": false switches it off
 * (the law is still validated, so a typo is reported).  A block that enables
 * contact where it cannot act (one body) is refused, since the engine
 * refuses settings that have no effect.  Materials and bodies are parsed
 * before. */
#include "contact/contact.h"
#include "scene/parse_internal.h"

/* Can particles that are not linked as a continuum meet?  Those of different
 * bodies, and the separated parts of a body that can break (a damage model,
 * or virtual links). */
static int contact_can_act(const struct tlsph_scene *s)
{
    int damage = s->crack_treatment == TLSPH_CRACK_VIRTUAL_LINKS;
    for (size_t k = 0; k < s->nmaterials; k++)
        damage |= s->materials[k].damage.model != NULL;
    return s->nbodies > 1 || damage;
}

int tlsph_parse_contact(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err)
{
    const json_t *obj = json_object_get(root, "contact");
    if (obj) {
        const struct tlsph_key_target to = {.base = s};
        if (tlsph_keys_member(root, &tlsph_scene_keys, "contact", "", &to, err) < 0)
            return -1;
    }
    const int can = contact_can_act(s);
    if (!obj && !can)
        return 0; /* nothing allocated, nothing run */
    int bad = 0;
    if (obj && s->contact.enabled && !can) {
        tlsph_errors_add(err, "/contact",
                         "contact has no effect in a scene of one body without damage: it acts "
                         "between different bodies and between the separated parts of a broken "
                         "body; remove the block, add a body or a damage model");
        bad = 1;
    }
    const json_t *law = obj ? json_object_get(obj, "law") : NULL;
    const struct tlsph_contact_law *model = tlsph_contact_default();
    if (law) {
        char type[64];
        if (!json_is_object(law)) {
            tlsph_key_error(err, "/contact", "law",
                            "must be an object {\"type\": name, ...parameters}, got %s",
                            jc_type_name(law));
            return -1;
        }
        if (jc_string(law, "type", 1, "/contact/law", type, sizeof type, err) != 0)
            return -1;
        model = tlsph_contact_find(type);
        if (!model) {
            tlsph_key_error(err, "/contact/law", "type", "unknown contact law '%s' (accepted: %s)",
                            type, tlsph_contact_names());
            return -1;
        }
    }
    bad |= model->parse(law, &s->contact, "/contact/law", err) != 0;
    s->contact.law = s->contact.enabled ? model : NULL;
    return bad ? -1 : 0;
}
