/* "penalty": the default contact law, a Hertz-type penalty with damping; the
 * formulas and the choice of radius are in penalty.h. */
#include <math.h>

#include "contact/contact.h"
#include "contact/penalty.h"
#include "scene/keys.h"

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    {.name = "damping", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,
     .range = {0.0, 1.0, JC_CLOSED, JC_CLOSED}, .unit = "1",
     .said = "(fraction of critical damping)", .def = 0.0,
     .offset = TLSPH_PARAM(TLSPH_PENALTY_DAMPING),
     .description = "damping ratio zeta of each contact pair, a fraction of the critical "
                    "damping of its oscillator; 0 = elastic contact"},
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/contact/law", "penalty", keys);
/* clang-format on */

static int parse(const json_t *obj, struct tlsph_contact_settings *c, const char *pointer,
                 struct tlsph_errors *err)
{
    const struct tlsph_key_target to = {.base = c->params};
    if (!obj) {
        tlsph_keys_defaults(&table, c->params);
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
    out->b = 0.0;
}

const struct tlsph_contact_law tlsph_contact_penalty = {
    .name = "penalty",
    .module = "contact:penalty_hertz",
    .variant = TLSPH_CONTACT_PENALTY,
    .keys = &table,
    .parse = parse,
    .body = body,
};
