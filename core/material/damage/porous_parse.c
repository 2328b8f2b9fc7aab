/* Reading and checking the parameters of the Gurson family (porous.h,
 * porous_keys.h): what one key cannot check alone. */
#include <string.h>

#include "material/damage/porous.h"
#include "material/damage/porous_keys.h"

const struct tlsph_key_choice tlsph_porous_criteria[] = {
    {"void_fraction", POROUS_FRACTURE_VOID_FRACTION},
    {"plastic_strain", POROUS_FRACTURE_PLASTIC_STRAIN},
    {NULL, 0},
};

int tlsph_porous_check(const struct tlsph_material *m, const char *pointer,
                       struct tlsph_errors *err)
{
    const double *g = m->damage.params;
    int bad = 0;
    if (!(g[POR_F0] < g[POR_FP])) {
        tlsph_key_error(err, pointer, "initial_void_fraction",
                        "initial void fraction %g must be below the fracture void fraction %g",
                        g[POR_F0], g[POR_FP]);
        bad = 1;
    }
    if (g[POR_FC] < 1.0) { /* a model with coalescence (eq. 45) */
        if (!(g[POR_F0] < g[POR_FC])) {
            tlsph_key_error(err, pointer, "initial_void_fraction",
                            "initial void fraction %g must be below the critical void "
                            "fraction %g",
                            g[POR_F0], g[POR_FC]);
            bad = 1;
        }
        if (!(g[POR_FC] < g[POR_FF])) {
            tlsph_key_error(err, pointer, "failure_void_fraction",
                            "failure void fraction %g must exceed the critical void fraction %g",
                            g[POR_FF], g[POR_FC]);
            bad = 1;
        }
        if (!(g[POR_FC] < 1.0 / g[POR_Q1])) {
            tlsph_key_error(err, pointer, "critical_void_fraction",
                            "critical void fraction %g must be below 1/q1 = %g (where f* "
                            "ends, eq. 45)",
                            g[POR_FC], 1.0 / g[POR_Q1]);
            bad = 1;
        }
    }
    if (g[POR_SHEAR] == POROUS_SHEAR_SWITCHED && !(g[POR_T1] < g[POR_T2])) {
        tlsph_key_error(err, pointer, "high_triaxiality",
                        "high triaxiality T2 = %g must exceed the low triaxiality T1 = %g "
                        "(eq. 54)",
                        g[POR_T2], g[POR_T1]);
        bad = 1;
    }
    return bad ? -1 : 0;
}

int tlsph_porous_parse(const json_t *obj, struct tlsph_material *m, const char *pointer,
                       const struct tlsph_key_table *table, int shear, struct tlsph_errors *err)
{
    double *g = m->damage.params;
    /* what a row has no key for: Gurson's surface, f* = f, no shear, no nucleation */
    for (int k = 0; k < POR_COUNT; k++)
        g[k] = 0.0;
    g[POR_Q1] = g[POR_Q2] = g[POR_Q3] = 1.0;
    g[POR_FC] = g[POR_FF] = 1.0;
    const struct tlsph_key_target to = {.base = g, .terms = &m->damage.terms};
    int bad = tlsph_keys_read(obj, table, pointer, &to, err) != 0;
    /* the choice was stored as an int in its double's slot (keys.h) */
    int criterion;
    memcpy(&criterion, &g[POR_CRITERION], sizeof criterion);
    g[POR_CRITERION] = criterion;
    g[POR_SHEAR] = shear;
    if (!bad)
        bad = tlsph_porous_check(m, pointer, err) != 0;
    if (tlsph_damage_refuse_evolution(
            obj, pointer, "a porous model: its damage comes from the void fraction", err) != 0)
        bad = 1;
    return bad ? -1 : 0;
}
