/* "pinball": the pin-ball contact law of paper 001 §4; formulas and choices
 * in pinball.h. */
#include "contact/contact.h"
#include "contact/pinball.h"
#include "scene/keys.h"

/* clang-format off */
static const struct tlsph_key keys[] = {
    TLSPH_KEY_MODEL_TYPE,
    {.name = "radius_factor", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,
     .range = {0.0, 2.0, JC_OPEN, JC_CLOSED}, .unit = "1", .said = "(ball radius / h)",
     .offset = TLSPH_PARAM(TLSPH_PINBALL_RADIUS_FACTOR),
     .description = "k: each particle's contact ball has radius k h, h the smoothing length "
                    "(support radius / 2 = support_factor x spacing / 2)"},
    {.name = "scale_factor", .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_DEFAULT,
     .range = {0.0, 1e6, JC_OPEN, JC_CLOSED}, .unit = "1", .def = 1.0,
     .offset = TLSPH_PARAM(TLSPH_PINBALL_SCALE_FACTOR),
     .description = "K_p, the paper's scale factor on the contact force (eq. 32)"},
};
static const struct tlsph_key_table table = TLSPH_KEY_TABLE("/contact/law", "pinball", keys);
/* clang-format on */

static int parse(const json_t *obj, struct tlsph_contact_settings *c, const char *pointer,
                 struct tlsph_errors *err)
{
    const struct tlsph_key_target to = {.base = c->params};
    return tlsph_keys_read(obj, &table, pointer, &to, err);
}

static void body(const struct tlsph_scene *s, size_t b, struct tlsph_contact_body *out)
{
    const struct tlsph_body *bd = &s->bodies[b];
    const struct tlsph_material *mat = &s->materials[bd->material];
    const double h = 0.5 * s->support_factor * bd->spacing;
    const double r = s->contact.params[TLSPH_PINBALL_RADIUS_FACTOR] * h;
    out->radius = r;
    out->a = mat->density * r * r * r;
    out->b = mat->shear_modulus;
}

static enum tlsph_contact_variant variant(const struct tlsph_scene *s)
{
    (void)s;
    return TLSPH_CONTACT_PINBALL;
}

const struct tlsph_contact_law tlsph_contact_pinball = {
    .name = "pinball",
    .module = "contact:pinball",
    .variant = variant,
    .keys = &table,
    .parse = parse,
    .body = body,
};
