/* The virtual links' criterion, /discretization/damage/links {"type": name,
 * ...parameters}: the criterion's own keys are its table in core/sph/link_*.c.
 * Read with the virtual_links treatment only, where it is required; refused
 * with any other treatment (it would have no effect).  With virtual links the
 * damage is the links': a material damage model is refused, and a criterion
 * that reads the plastic strain needs a plastic material.  Materials and the
 * scene's sections are parsed before. */
#include "material/strength/strength.h"
#include "scene/parse_internal.h"
#include "sph/link_criterion.h"

#define LINKS "/discretization/damage/links"

int tlsph_parse_links(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err)
{
    const json_t *disc = json_object_get(root, "discretization");
    const json_t *dmg = json_is_object(disc) ? json_object_get(disc, "damage") : NULL;
    const json_t *obj = json_is_object(dmg) ? json_object_get(dmg, "links") : NULL;
    if (s->crack_treatment != TLSPH_CRACK_VIRTUAL_LINKS) {
        if (!obj)
            return 0;
        tlsph_key_error(err, "/discretization/damage", "links",
                        "has no effect without \"treatment\": \"virtual_links\"");
        return -1;
    }
    int bad = 0;
    for (size_t k = 0; k < s->nmaterials; k++)
        if (s->materials[k].damage.model) {
            char P[TLSPH_POINTER_MAX];
            tlsph_pointer_join(P, sizeof P, "/materials", s->materials[k].name);
            tlsph_key_error(err, P, "damage",
                            "a material damage model cannot be combined with the "
                            "virtual_links treatment: its links carry the damage (" LINKS
                            "); remove the block or choose another treatment");
            bad = 1;
        }
    if (!obj) {
        tlsph_key_error(err, "/discretization/damage", "links",
                        "is required with the virtual_links treatment: {\"type\": one of %s, "
                        "...parameters}",
                        tlsph_link_criterion_names());
        return -1;
    }
    if (!json_is_object(obj)) {
        tlsph_key_error(err, "/discretization/damage", "links",
                        "must be an object {\"type\": name, ...parameters}, got %s",
                        jc_type_name(obj));
        return -1;
    }
    char type[64];
    if (jc_string(obj, "type", 1, LINKS, type, sizeof type, err) != 0)
        return -1;
    const struct tlsph_link_criterion *c = tlsph_link_criterion_find(type);
    if (!c) {
        tlsph_key_error(err, LINKS, "type", "unknown link criterion '%s' (accepted: %s)", type,
                        tlsph_link_criterion_names());
        return -1;
    }
    const struct tlsph_key_target to = {.base = &s->links};
    bad |= tlsph_keys_read(obj, c->keys, LINKS, &to, err) != 0;
    if (c->needs_plasticity) {
        int plastic = 0;
        for (size_t k = 0; k < s->nmaterials; k++)
            plastic |= tlsph_material_is_plastic(&s->materials[k]);
        if (!plastic) {
            tlsph_key_error(err, LINKS, "type",
                            "'%s' reads the plastic strain, but no material is plastic "
                            "(give one a strength model, or use 'rankine')",
                            type);
            bad = 1;
        }
    }
    if (!bad)
        s->links.criterion = c;
    return bad ? -1 : 0;
}
