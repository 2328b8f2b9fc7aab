/* What the flow-law parsers in core/material/strength/ share: where their
 * parameters go, the parse of a law that is its key table, and the rows of
 * flow-stress parameters. */
#ifndef TLSPH_STRENGTH_PARSE_UTIL_H
#define TLSPH_STRENGTH_PARSE_UTIL_H

#include "scene/keys.h"
#include "scene/scene.h"

/* A law's parameters go to m->strength_params, its optional terms to
 * m->strength_terms; its flow stresses must stay below m's Young's modulus
 * (0 when that is invalid: not compared). */
static inline struct tlsph_key_target strength_target(struct tlsph_material *m)
{
    m->strength_terms = 0;
    return (struct tlsph_key_target){.base = m->strength_params, .terms = &m->strength_terms,
                                     .youngs_modulus = m->youngs_modulus};
}

/* The parse of a law whose parameters are its key table (strength.h):
 * reads m->strength's keys into m (strength_target), then, when they read
 * cleanly, runs its check.  Returns 0 or -1. */
int tlsph_strength_parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                         struct tlsph_errors *err);

/* A required stress (Pa) at parameter index i: > 0, or >= 0 with lo = JC_CLOSED,
 * and below the Young's modulus. */
#define STRENGTH_STRESS(key, lo, i, text)                                                      \
    {.name = (key), .kind = TLSPH_KEY_NUMBER,                                                  \
     .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_BELOW_E, .range = {0.0, 0.0, (lo), JC_NONE},      \
     .unit = "Pa", .offset = TLSPH_PARAM(i), .description = (text)}

/* A required dimensionless parameter in (0, max] at parameter index i. */
#define STRENGTH_POSITIVE(key, max, i, text)                                                   \
    {.name = (key), .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,                     \
     .range = {0.0, (max), JC_OPEN, JC_CLOSED}, .unit = "1", .offset = TLSPH_PARAM(i),         \
     .description = (text)}

#endif
