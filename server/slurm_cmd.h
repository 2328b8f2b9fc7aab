/* Running one Slurm command (server/slurm_cmd.c): sbatch, squeue, scancel.
 *
 * The Slurm executor talks to the scheduler only through its commands, never
 * slurmrestd (executor_slurm.c says why).  A command is spawned with
 * posix_spawnp (PATH decides which sbatch; SLURM_CONF in the daemon's
 * environment decides which cluster) with the signals of spawn_attr.h, its stdin fed from a string, its stdout and
 * stderr collected, and a deadline: a command that hangs (a controller that
 * does not answer) is killed and reported, so the executor's loop never
 * stalls for longer than the deadline. */
#ifndef TLSPHD_SLURM_CMD_H
#define TLSPHD_SLURM_CMD_H

#include <stddef.h>

#include "strbuf.h"

struct slurm_cmd_result {
    int status;       /* exit code, 128 + signal when killed, -1 could not run */
    struct strbuf out; /* stdout */
    struct strbuf err; /* stderr (and why it could not run) */
};

/* Runs argv (argv[0] looked up in PATH) with input on its stdin (NULL: empty)
 * for at most timeout s.  Always fills res (slurm_cmd_free); returns status. */
int slurm_cmd_run(char *const argv[], const char *input, double timeout,
                  struct slurm_cmd_result *res);
void slurm_cmd_free(struct slurm_cmd_result *res);
/* The first line of res's stderr (or stdout), for a message: into buf. */
const char *slurm_cmd_why(const struct slurm_cmd_result *res, char *buf, size_t size);

#endif
