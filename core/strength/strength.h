/* Strength (deviatoric response) models.  One file per model, one row per model
 * in strength/registry.c; the scene names a row: "strength": {"type": name, ...}.
 *
 * Stress convention: symmetric tensors are stored as 6 components in the order
 * xx xy xz yy yz zz.  The deviatoric response is computed in the unrotated frame
 * (rotation R of the polar decomposition F = R U), see core/constitutive.c. */
#ifndef TLSPH_STRENGTH_H
#define TLSPH_STRENGTH_H

#include <jansson.h>

#include "../errors.h"
#include "../scene.h"

struct tlsph_strength_model {
    const char *name;
    int (*parse)(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err);
    /* Deviatoric Kirchhoff stress (Pa) from the deviatoric Hencky strain (1),
     * both in the unrotated frame. */
    void (*deviatoric)(const struct tlsph_material *m, const double eps_dev[6], double tau_dev[6]);
};

const struct tlsph_strength_model *tlsph_strength_find(const char *name);
const char *tlsph_strength_names(void);

extern const struct tlsph_strength_model tlsph_strength_elastic;

#endif
