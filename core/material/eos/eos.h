/* Equations of state: pressure from the volume ratio J = det F and the specific
 * internal energy.  One file per model, one row per model in material/eos/registry.c; the
 * scene names a row by its `name`.
 *
 * A new model provides, in its own file, a descriptor tlsph_eos_<name> with
 * every member below, and one row ROW(<name>) in registry.c's EOS_MODELS (which
 * also makes the list of accepted names).  Nothing outside this folder names a
 * model, except the scene parser's default (tlsph_eos_linear).
 *
 * Sign convention: pressure p is positive in compression; Cauchy stress
 * sigma = -p I + s. */
#ifndef TLSPH_EOS_H
#define TLSPH_EOS_H

#include <jansson.h>

#include "util/errors.h"
#include "scene/scene.h"

struct tlsph_key_table; /* core/scene/keys.h */

struct tlsph_eos_model {
    const char *name;   /* as written in the scene: "eos": {"type": name, ...} */
    const char *module; /* "eos:<name>", for the run's list of active modules */
    const struct tlsph_key_table *keys; /* its parameters: what parse reads (core/scene/keys.h) */
    /* Reads the model's parameters from obj (its "type" key is already checked)
     * into m->eos_params, reporting unknown keys and bad values. m's elastic
     * constants are already set. Returns 0 or -1. */
    int (*parse)(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err);
    /* p (Pa) and the tangent bulk modulus K_t = -J dp/dJ (Pa), used for the
     * sound speed of the time step.  J > 0 (volume ratio, 1); e in J/kg. */
    void (*pressure)(const struct tlsph_material *m, double J, double e, double *p, double *K_t);
};

const struct tlsph_eos_model *tlsph_eos_find(const char *name);
/* Comma-separated list of names, for error messages. */
const char *tlsph_eos_names(void);

/* The default when a material names no EOS (core/scene/parse.c). */
extern const struct tlsph_eos_model tlsph_eos_linear;

#endif
