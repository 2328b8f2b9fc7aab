/* The scene's "contact" block: its own keys (scene_keys.c) and the law, whose
 * parameters its file in core/contact/ reads.
 *
 * A contact block in a scene of one body is refused: contact acts between
 * different bodies only (contact between the separated parts of a broken body
 * is not implemented yet), so the block would have no effect, and the
 * engine refuses settings that have none. */
#include "contact/contact.h"
#include "scene/parse_internal.h"

int tlsph_parse_contact(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err)
{
    const json_t *obj = json_object_get(root, "contact");
    if (!obj)
        return 0;
    const struct tlsph_key_target to = {.base = s};
    if (tlsph_keys_member(root, &tlsph_scene_keys, "contact", "", &to, err) < 0)
        return -1;
    int bad = 0;
    if (s->nbodies < 2) {
        tlsph_errors_add(err, "/contact",
                         "contact has no effect with one body: it acts between different bodies "
                         "only (contact between the parts of a broken body is not implemented "
                         "yet); remove the block or add a body");
        bad = 1;
    }
    const json_t *law = json_object_get(obj, "law");
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
    s->contact.law = model;
    bad |= model->parse(law, &s->contact, "/contact/law", err) != 0;
    return bad ? -1 : 0;
}
