/* The quantity a fibre's D sums (fibre_criterion.h). */
#include "crack/fibre_criterion.h"

#include "material/damage/damage.h"
#include "material/strength/strength.h"

const char *tlsph_crack_criterion_name(int criterion)
{
    switch (criterion) {
    case TLSPH_CRACK_CRITERION_VOID_FRACTION: return "void_fraction";
    case TLSPH_CRACK_CRITERION_PLASTIC_STRAIN: return "plastic_strain";
    default: return "damage";
    }
}

const double *tlsph_crack_criterion_field(const struct tlsph_model *m)
{
    switch (m->scene.crack_growth.criterion) {
    case TLSPH_CRACK_CRITERION_VOID_FRACTION: return m->p.void_fraction;
    case TLSPH_CRACK_CRITERION_PLASTIC_STRAIN: return m->p.eps_p;
    default: return m->p.damage;
    }
}

int tlsph_crack_criterion_check(const struct tlsph_model *m, size_t b, struct tlsph_errors *err)
{
    const int c = m->scene.crack_growth.criterion;
    const struct tlsph_body *body = &m->scene.bodies[b];
    const struct tlsph_material *mat = &m->scene.materials[body->material];
    int has = 1;
    const char *needs = "";
    if (c == TLSPH_CRACK_CRITERION_VOID_FRACTION) {
        has = mat->damage.model && (mat->damage.model->fields & TLSPH_DAMAGE_FIELD_VOID_FRACTION);
        needs = "a porous damage model (gtn, gurson, gtn_aravas, sm_gurson, m_gurson)";
    } else if (c == TLSPH_CRACK_CRITERION_PLASTIC_STRAIN) {
        has = tlsph_material_is_plastic(mat);
        needs = "a plastic strength model";
    }
    if (has && tlsph_crack_criterion_field(m))
        return 0;
    tlsph_errors_add(err, "/crack_growth/criterion",
                     "criterion '%s': body '%s' (material '%s') has no such quantity; it needs "
                     "%s", tlsph_crack_criterion_name(c), body->name, mat->name, needs);
    return -1;
}
