/* Strength (deviatoric response) models.  One file per model, one row per model
 * in material/strength/registry.c; the scene names a row: "strength": {"type": name, ...}.
 *
 * A plastic model is nothing but its flow-stress law sigma_y(eps_p, epsdot_p, T)
 * and the derivatives the return mapping needs; the J2 radial return
 * (material/strength/j2_return.c) and the elastic predictor (material_point.c) are shared
 * by every law.  The elastic model has no flow law: no plastic state is
 * allocated and no return mapping runs for its particles.
 *
 * A new flow law provides, in its own file, a descriptor tlsph_strength_<name>
 * with every member below (flow non-NULL; check only where its parse is
 * tlsph_strength_parse and its parameters have relations to check), and one
 * row ROW(<name>) in registry.c's FLOW_LAWS (which also makes the lists of
 * accepted names).
 * Nothing outside this folder names a model, except the scene parser's
 * default (tlsph_strength_elastic).
 *
 * Stress convention: symmetric tensors are stored as 6 components in the order
 * xx xy xz yy yz zz.  The deviatoric response is computed in the unrotated frame
 * (rotation R of the polar decomposition F = R U), see core/material/material_point.h. */
#ifndef TLSPH_STRENGTH_H
#define TLSPH_STRENGTH_H

#include <jansson.h>

#include "util/errors.h"
#include "scene/scene.h"

/* The flow stress and its partial derivatives at one state. */
struct tlsph_flow {
    double stress;        /* sigma_y, Pa (Cauchy von Mises stress at yield) */
    double d_strain;      /* d sigma_y / d eps_p, Pa (may be +inf at eps_p = 0, e.g. n < 1) */
    double d_rate;        /* d sigma_y / d epsdot_p, Pa s */
    double d_temperature; /* d sigma_y / d T, Pa/K */
};

struct tlsph_key_table; /* core/scene/keys.h */

struct tlsph_strength_model {
    const char *name;   /* as written in the scene: "strength": {"type": name, ...} */
    const struct tlsph_key_table *keys; /* its parameters: what parse reads (core/scene/keys.h) */
    const char *module; /* "strength:<name>", for the run's list of active modules */
    /* Reads the model's parameters from obj (its "type" key is already checked)
     * into m->strength_params / m->strength_terms, reporting unknown keys and bad
     * values.  m's elastic constants and its thermal block are already parsed,
     * and m->strength is this model.  Returns 0 or -1.  A law whose parameters
     * are its key table, plus the relations of check, uses
     * tlsph_strength_parse (parse_util.h). */
    int (*parse)(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err);
    /* For tlsph_strength_parse: the relations between the law's parameters
     * that its key table cannot state (K eps_0^n below E, sigma_s not below
     * sigma_0), checked once every key has read cleanly; reports each one that
     * fails under pointer.  Returns 0 or -1.  NULL: none. */
    int (*check)(const struct tlsph_material *m, const char *pointer, struct tlsph_errors *err);
    /* Flow stress at equivalent plastic strain eps_p >= 0 (1), plastic strain
     * rate >= 0 (1/s) and temperature T (K; only read when the material's
     * TLSPH_FLOW_THERMAL term is on).  NULL for the elastic model. */
    void (*flow)(const struct tlsph_material *m, double eps_p, double rate, double T,
                 struct tlsph_flow *out);
};

const struct tlsph_strength_model *tlsph_strength_find(const char *name);
/* Comma-separated list of names, for error messages. */
const char *tlsph_strength_names(void);
/* The same, only the models with a flow law. */
const char *tlsph_strength_plastic_names(void);
/* Does this material flow plastically (has a flow law)? */
static inline int tlsph_material_is_plastic(const struct tlsph_material *m)
{
    return m->strength->flow != 0;
}

/* The model without a flow law, the default when a material names no strength
 * (core/scene/parse.c). */
extern const struct tlsph_strength_model tlsph_strength_elastic;

#endif
