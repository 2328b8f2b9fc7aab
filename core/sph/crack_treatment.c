/* The table of crack treatments (crack_treatment.h): one row per treatment
 * the scene can name, and the intact row for scenes without damage. */
#include "sph/crack_treatment.h"

#include "sph/damage_aware.h"
#include "sph/pseudo_spring.h"
#include "sph/virtual_links.h"

static const struct tlsph_crack_model intact = {
    .name = "intact",
    .module = NULL, /* no damage, nothing to report */
    .variant = TLSPH_APPROX_INTACT,
    .fields = 0,
};

static const struct tlsph_crack_model *const treatments[] = {
    &tlsph_crack_damage_aware,
    &tlsph_crack_pseudo_spring,
};

const struct tlsph_crack_model *tlsph_crack_select(const struct tlsph_scene *s)
{
    if (s->crack_treatment == TLSPH_CRACK_VIRTUAL_LINKS && s->links.criterion)
        return &tlsph_crack_virtual_links;
    int damage = 0;
    for (size_t k = 0; k < s->nmaterials; k++)
        damage |= s->materials[k].damage.model != NULL;
    if (damage)
        for (size_t k = 0; k < sizeof treatments / sizeof *treatments; k++)
            if (treatments[k]->scene == s->crack_treatment)
                return treatments[k];
    return &intact;
}
