/* Particle selectors ("select": {body, box, expression}), shared by the kinds
 * that act on a group of particles.  The fields are described in
 * core/scene/scene.h (struct tlsph_selector). */
#ifndef TLSPH_BC_SELECTOR_H
#define TLSPH_BC_SELECTOR_H

#include <stddef.h>
#include <stdint.h>
#include <jansson.h>

#include "scene/keys.h"
#include "scene/scene.h"
#include "util/errors.h"

struct tlsph_model;

/* The keys of "select" ("/boundary_conditions/<i>/select"), and of its box. */
extern const struct tlsph_key_table tlsph_selector_keys;
/* The same keys under "/output/probes/<i>/select" (core/io/measures.h). */
extern const struct tlsph_key_table tlsph_probe_selector_keys;
/* And under "/output/extents/<i>/select". */
extern const struct tlsph_key_table tlsph_extent_selector_keys;

/* A kind's "select" row: flags TLSPH_KEY_REQUIRED, or 0 when an absent selector
 * has a meaning the description gives. */
/* clang-format off */
#define TLSPH_BC_SELECT(flags_, what)                                                          \
    {.name = "select", .kind = TLSPH_KEY_OBJECT, .flags = (flags_) | TLSPH_KEY_CALLER,       \
     .table = &tlsph_selector_keys, .description = (what)}
/* clang-format on */

/* Reads obj's "select" into bc->select (body index, box in m, expression of x,
 * y, z with comparisons); pointer is the condition's.  Required when the
 * "select" row of bc->kind's table says so; otherwise an absent selector
 * selects every particle.  In 2-D the box spans all z.  Returns 0 or -1 with
 * every problem in err.  A kind's parse hook when "select" is its only key. */
int tlsph_selector_parse(const json_t *obj, struct tlsph_scene *s, struct tlsph_bc *bc,
                         const char *pointer, struct tlsph_errors *err);

/* The same for any owner of a selector: obj's "select" into sel, P the
 * owner's pointer; an absent selector is an error when required, else it
 * selects every particle.  The expression in sel is freed with the scene. */
int tlsph_selector_read(const json_t *obj, int required, struct tlsph_scene *s,
                        struct tlsph_selector *sel, const char *P, struct tlsph_errors *err);

/* Whether the scene gave any test (an absent selector selects everything). */
int tlsph_selector_given(const struct tlsph_selector *sel);

/* The particles sel selects, by reference position: their indices in
 * increasing order into index (NULL: count only); returns their number. */
size_t tlsph_selector_pick(const struct tlsph_model *m, struct tlsph_selector *sel,
                           int32_t *index);

/* A kind's select hook for conditions whose group is exactly their selector's. */
size_t tlsph_selector_select(const struct tlsph_model *m, struct tlsph_bc *bc, int32_t *index);

#endif
