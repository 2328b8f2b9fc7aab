/* "penalty": the default contact law, a Hertz-type penalty with damping; the
 * formulas and the choice of radius are in penalty.h. */
#include <math.h>
#include <stddef.h>

#include "contact/contact.h"
#include "contact/penalty.h"
#include "scene/keys.h"

_Static_assert(sizeof(enum tlsph_penalty_form) == sizeof(int), "form stored as int");

/* clang-format off */
static const struct tlsph_key_choice forms[] = {
    {"line", TLSPH_PENALTY_LINE}, {"point", TLSPH_PENALTY_POINT}, {0}};

/* offsets from the law's settings (struct tlsph_contact_settings) */
#define PARAM(i) (offsetof(struct tlsph_contact_settings, params) + TLSPH_PARAM(i))
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    {.name = "form", .kind = TLSPH_KEY_CHOICE, .flags = TLSPH_KEY_DEFAULT,
     .def = TLSPH_PENALTY_LINE, .size = 16, .choices = forms, .noun = "penalty form",
     .offset = offsetof(struct tlsph_contact_settings, choice),
     .description = "line: F = pi/4 E* w delta, the Hertz line contact over the particles' "
                    "width w (1 m per metre in 2-D); point: F = 4/3 E* sqrt(R*) delta^1.5, "
                    "Hertz spheres (3-D only; line in 2-D)"},
    {.name = "damping", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,
     .range = {0.0, 1.0, JC_CLOSED, JC_CLOSED}, .unit = "1",
     .said = "(fraction of critical damping)", .def = 0.0,
     .offset = PARAM(TLSPH_PENALTY_DAMPING),
     .description = "damping ratio zeta of each contact pair, a fraction of the critical "
                    "damping of its oscillator; 0 = elastic contact"},
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/contact/law", "penalty", keys);
/* clang-format on */

static int parse(const json_t *obj, struct tlsph_contact_settings *c, const char *pointer,
                 struct tlsph_errors *err)
{
    const struct tlsph_key_target to = {.base = c};
    if (!obj) {
        tlsph_keys_defaults(&table, c);
        return 0;
    }
    return tlsph_keys_read(obj, &table, pointer, &to, err);
}

static void body(const struct tlsph_scene *s, size_t b, struct tlsph_contact_body *out)
{
    const struct tlsph_body *bd = &s->bodies[b];
    const struct tlsph_material *mat = &s->materials[bd->material];
    /* V0^(1/d) is the spacing on the simple cubic lattice */
    out->radius = 0.5 * bd->spacing;
    out->a = (1.0 - mat->poisson_ratio * mat->poisson_ratio) / mat->youngs_modulus;
    out->b = s->dimension == 3 ? out->radius : 0.5;
}

/* The sphere form only in 3-D: in 2-D "point" is the line form (penalty.h). */
static enum tlsph_contact_variant variant(const struct tlsph_scene *s)
{
    return s->dimension == 3 && s->contact.choice == TLSPH_PENALTY_POINT
               ? TLSPH_CONTACT_PENALTY_POINT
               : TLSPH_CONTACT_PENALTY_LINE;
}

const struct tlsph_contact_law tlsph_contact_penalty = {
    .name = "penalty",
    .module = "contact:penalty_hertz",
    .variant = variant,
    .keys = &table,
    .parse = parse,
    .body = body,
};
