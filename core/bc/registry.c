#include <stdio.h>
#include <string.h>

#include "bc/kind.h"

/* Each defined in core/bc/<name>.c. */
extern const struct tlsph_bc_kind tlsph_bc_fixed, tlsph_bc_velocity, tlsph_bc_wall,
    tlsph_bc_symmetry, tlsph_bc_body_force, tlsph_bc_pressure;

/* One row per kind; the order is that of the names in error messages. */
static const struct tlsph_bc_kind *const kinds[] = {
    &tlsph_bc_fixed,
    &tlsph_bc_velocity,
    &tlsph_bc_wall,
    &tlsph_bc_symmetry,
    &tlsph_bc_body_force,
    &tlsph_bc_pressure,
};

#define NKINDS (sizeof kinds / sizeof *kinds)

const struct tlsph_bc_kind *tlsph_bc_find(const char *name)
{
    for (size_t i = 0; i < NKINDS; i++)
        if (strcmp(kinds[i]->name, name) == 0)
            return kinds[i];
    return NULL;
}

void tlsph_bc_names(char *buf, size_t size, int load_only, const char *quote,
                    const char *last_sep)
{
    size_t count = 0, total = 0, len = 0;
    for (size_t i = 0; i < NKINDS; i++)
        total += !load_only || kinds[i]->carries_load;
    buf[0] = '\0';
    for (size_t i = 0; i < NKINDS && len < size; i++) {
        if (load_only && !kinds[i]->carries_load)
            continue;
        const char *sep = count == 0 ? "" : count + 1 == total ? last_sep : ", ";
        const int w = snprintf(buf + len, size - len, "%s%s%s%s", sep, quote, kinds[i]->name, quote);
        len += w > 0 ? (size_t)w : 0;
        count++;
    }
}
