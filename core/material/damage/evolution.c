/* Damage evolution after initiation (paper 000 eq. 45): D = factor (D_init - 1).
 * The paper fixes factor = 10 ("arbitrarily", as it says): damage grows from 0
 * to 1 while D_init goes from 1 to 1.1.  The factor sets how much more plastic
 * strain (or plastic work) a point takes between initiation and failure, i.e.
 * the energy the fracture process dissipates, so it is a parameter here. */
#include "scene/json_check.h"
#include "material/damage/damage.h"

int tlsph_damage_parse_evolution(const json_t *obj, struct tlsph_material *m, const char *pointer,
                                 struct tlsph_errors *err)
{
    static const char *const keys[] = {"factor", NULL};
    m->damage.evolution_factor = 10.0;
    const json_t *ev = jc_object(obj, "evolution", 0, pointer, err);
    if (!ev)
        return json_object_get(obj, "evolution") ? -1 : 0;
    char P[TLSPH_POINTER_MAX];
    tlsph_pointer_join(P, sizeof P, pointer, "evolution");
    int bad = jc_unknown_keys(ev, keys, P, err) != 0;
    bad |= jc_number(ev, "factor", 0, ((struct jc_range){0.0, 1e6, JC_OPEN, JC_CLOSED}),
                     "(dimensionless: D = factor (D_init - 1))", P, &m->damage.evolution_factor,
                     err) < 0;
    return bad ? -1 : 0;
}
