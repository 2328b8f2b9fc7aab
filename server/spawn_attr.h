/* posix_spawn attributes for a helper the daemon runs (server/spawn_attr.c):
 * h5clear (result_repair.c), sbatch, squeue, scancel (slurm_cmd.c).  The
 * daemon's threads block every signal and it ignores SIGPIPE; a child would
 * inherit both through exec, so it gets an empty mask and the default
 * dispositions. */
#ifndef TLSPHD_SPAWN_ATTR_H
#define TLSPHD_SPAWN_ATTR_H

#include <spawn.h>

/* Initialises *at with an empty signal mask and default dispositions:
 * 0, or an errno value (*at is then destroyed). */
int spawn_attr_defaults(posix_spawnattr_t *at);

#endif
