/* Parameter checks shared by the flow-law parsers in core/material/strength/. */
#ifndef TLSPH_STRENGTH_PARSE_UTIL_H
#define TLSPH_STRENGTH_PARSE_UTIL_H

#include "scene/json_check.h"
#include "scene/scene.h"

/* A stress parameter (Pa): > 0 (>= 0 with allow_zero) and, when the material's
 * Young's modulus is valid, below it (a flow stress above E means a unit slip).
 * Returns like jc_number. */
static inline int strength_stress(const json_t *obj, const char *key, int required,
                                  int allow_zero, const struct tlsph_material *m,
                                  const char *pointer, double *out, struct tlsph_errors *err)
{
    const struct jc_range r = {0.0, 0.0, allow_zero ? JC_CLOSED : JC_OPEN, JC_NONE};
    int rc = jc_number(obj, key, required, r, "Pa", pointer, out, err);
    if (rc == 0 && m->youngs_modulus > 0.0 && *out >= m->youngs_modulus) {
        char p[TLSPH_POINTER_MAX];
        tlsph_pointer_join(p, sizeof p, pointer, key);
        tlsph_errors_add(err, p, "'%s' = %g Pa must be below the Young's modulus E = %g Pa", key,
                         *out, m->youngs_modulus);
        rc = -1;
    }
    return rc;
}

#define DIMENSIONLESS "(dimensionless)"

#endif
