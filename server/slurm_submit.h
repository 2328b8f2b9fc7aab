/* Handing runs to Slurm (server/slurm_submit.c): the batch script and sbatch.
 *
 * One submission is one Slurm job: a single run, or the claimed children of a
 * study as one job array (--array=0-(n-1)%limit: one scheduler entry however
 * many children).  The script, fed to sbatch on its stdin (Slurm keeps its
 * own copy, so nothing has to be left on disk for it), maps the task index
 * to the job id, and runs on the node, in the job's directory on the shared
 * file system,
 *
 *   tlsph-run DIR/scene.json -o DIR --progress-fd 3 --threads $SLURM_CPUS_PER_TASK \
 *       3>DIR/progress.jsonl >DIR/log.txt 2>&1
 *
 * so the progress stream the local executor reads from a pipe is a file that
 * the daemon reads as it grows (the engine is unchanged: fd 3 is a file), and
 * then writes the exit status to DIR/exit_status.tmp and renames it to
 * DIR/exit_status: the daemon sees the whole status or none.  A script that
 * Slurm kills (time limit, memory, cancel) writes no status; the daemon then
 * goes by Slurm's state (slurm_state.h).
 *
 * sbatch options: --parsable --job-name --output (jobs_dir/.slurm/%j.out:
 * what the script itself says, e.g. a missing directory) --chdir
 * --nodes=1 --ntasks=1 --cpus-per-task --mem --time (slurm_resources.h)
 * --no-requeue (the daemon, not Slurm, decides whether a run goes again: it
 * counts the attempts) --partition --account, then slurm_options. */
#ifndef TLSPHD_SLURM_SUBMIT_H
#define TLSPHD_SLURM_SUBMIT_H

#include <stdbool.h>
#include <stddef.h>

#include "slurm_resources.h"

struct tcfg;

struct slurm_submission {
    const char *name;            /* --job-name */
    const char *jobs_dir;        /* absolute, on the shared file system */
    const char *engine;          /* absolute path of tlsph-run on the nodes */
    const char *const *ids;      /* the job ids, task index i runs ids[i] */
    size_t n;
    bool array;                  /* a job array (even of one task) */
    long array_limit;            /* %limit, 0 = none */
    struct slurm_resources res;
    const struct tcfg *cfg;      /* partition, account, options */
};

/* The batch script (malloc'ed), NULL out of memory. */
char *slurm_script(const struct slurm_submission *s);
/* Submits: 0 with the Slurm job id in slurm_id ("123"), or -1 with err
 * (sbatch's own words). */
int slurm_submit(const struct slurm_submission *s, char *slurm_id, size_t size, char *err,
                 size_t errsize);

#endif
