#include "material/strength/parse_util.h"

#include "material/strength/strength.h"

int tlsph_strength_parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                         struct tlsph_errors *err)
{
    const struct tlsph_strength_model *law = m->strength;
    const struct tlsph_key_target to = strength_target(m);
    if (tlsph_keys_read(obj, law->keys, pointer, &to, err) != 0)
        return -1;
    return law->check ? law->check(m, pointer, err) : 0;
}
