/* The naming rule at validation: every name that becomes part of an HDF5 path
 * or an API series name (materials, bodies, boundary conditions, gauges,
 * sections; the TLSPH_KEY_NAME rows of the key tables) is checked here against
 * the one rule the daemon also uses (util/names.h). */
#include "scene/keys.h"
#include "util/names.h"

int tlsph_scene_check_name(const char *name, const char *what, const char *pointer,
                           struct tlsph_errors *err)
{
    if (tlsph_name_ok(name))
        return 0;
    tlsph_errors_add(err, pointer,
                     "%s '%.80s' does not follow the naming rule: " TLSPH_NAME_RULE
                     " (names become groups of the result file and series of the API)",
                     what, name);
    return -1;
}
