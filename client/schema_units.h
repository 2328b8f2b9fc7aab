/* Units of scene values from the scene's JSON Schema: every number in
 * schemas/scene.schema.json carries "x-unit" ("s", "Pa", "1" for a pure
 * number, "user" for a parameter whose unit the scene's author chose). */
#ifndef TLSPH_CLIENT_SCHEMA_UNITS_H
#define TLSPH_CLIENT_SCHEMA_UNITS_H

#include <jansson.h>

/* The "x-unit" of the value at pointer (RFC 6901, relative to the scene, e.g.
 * "/time/end", "/bodies/0/spacing") in schema, following local "$ref"s,
 * properties, patternProperties, additionalProperties, items and
 * oneOf/anyOf/allOf.  NULL when the schema gives none.  The string belongs to
 * schema. */
const char *schema_unit(const json_t *schema, const char *pointer);

#endif
