/* Executors, see executor.h. */
#include "executor.h"

#include <string.h>

enum texec_kind texec_kind_of(const char *name)
{
    return name && !strcmp(name, "slurm") ? TEXEC_SLURM : TEXEC_LOCAL;
}
