/* Damage evolution after initiation (paper 000 eq. 45): D = factor (D_init - 1).
 * The paper fixes factor = 10 ("arbitrarily", as it says): damage grows from 0
 * to 1 while D_init goes from 1 to 1.1.  The factor sets how much more plastic
 * strain (or plastic work) a point takes between initiation and failure, i.e.
 * the energy the fracture process dissipates, so it is a parameter here. */
#include <stddef.h>

#include "scene/keys.h"
#include "material/damage/damage.h"

/* clang-format off */
static const struct tlsph_key keys[] = {
    {.name = "factor", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,
     .range = {0.0, 1e6, JC_OPEN, JC_CLOSED}, .unit = "1",
     .said = "(dimensionless: D = factor (D_init - 1))", .def = 10.0,
     .offset = offsetof(struct tlsph_damage, evolution_factor),
     .description = "evolution factor: D = min(1, factor (D_init - 1)) once D_init >= 1"},
};
const struct tlsph_key_table tlsph_damage_evolution_keys =
    TLSPH_KEY_TABLE("/materials/*/damage/evolution", NULL, keys);
/* clang-format on */

int tlsph_damage_parse_evolution(const json_t *obj, struct tlsph_material *m, const char *pointer,
                                 struct tlsph_errors *err)
{
    const struct tlsph_key_target to = {.base = &m->damage};
    tlsph_keys_defaults(&tlsph_damage_evolution_keys, to.base); /* also without the block */
    const int r = tlsph_keys_object(obj, "evolution", 0, &tlsph_damage_evolution_keys, pointer,
                                    &to, err);
    return r < 0 ? -1 : 0;
}

int tlsph_damage_refuse_evolution(const json_t *obj, const char *pointer, const char *what,
                                  struct tlsph_errors *err)
{
    if (!json_object_get(obj, "evolution"))
        return 0;
    tlsph_key_error(err, pointer, "evolution", "'evolution' does not apply to %s", what);
    return -1;
}
