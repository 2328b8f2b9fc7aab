/* The supervisor: the only file that forks, signals and reaps (server/supervisor.c).
 *
 * One thread claims accepted jobs from the queue (up to max_jobs at once) and
 * runs each as a child process: fork + exec of the engine CLI
 *   tlsph-run JOBDIR/scene.json -o JOBDIR --progress-fd 3 --threads N
 * (N = the job's threads within the thread budget, thread_budget.h)
 * in its own process group, with PR_SET_PDEATHSIG(SIGKILL) (so a dying daemon
 * takes its engines along), rlimits (address space, core dumps off, open files),
 * stdout+stderr to JOBDIR/log.txt (for people only), and a wall-clock limit.
 * It hands the progress lines from fd 3 to engine_report.h, which keeps the
 * progress (written to the queue) and the final event, and turns the exit
 * status into the job's final state (docs/protocol.md).
 * Cancellation: SIGTERM to the process group, SIGKILL after a grace period.
 * A final state the queue cannot take (a full disk) is kept and written
 * again until it is (finals.h).  While the data directory's free space is
 * below its floor no job is claimed, and the reserve file is allocated again
 * once the space is back (storage.h).
 *
 * Job directories: jobdir.h.
 *
 * This is the local executor and the thread every executor runs on
 * (executor.h): with slurm set in the configuration, the thread hands its
 * loop to executor_slurm.h after the same start-up, and tsup_wake,
 * tsup_unrecorded and tsup_stop work the same (a stop leaves the Slurm jobs
 * running for the next daemon instead of requeueing them). */
#ifndef TLSPHD_SUPERVISOR_H
#define TLSPHD_SUPERVISOR_H

#include <stddef.h>

struct tcfg;

struct tsup_config {
    const char *db_path;       /* SQLite file (the supervisor opens its own handle) */
    const char *engine_path;   /* tlsph-run */
    const char *jobs_dir;      /* one directory per job underneath */
    int max_jobs;              /* concurrent engine processes, >= 1 */
    int threads_per_job;       /* OpenMP threads per engine, >= 1 */
    int cores;                 /* the thread budget: the running engines' threads never
                                * add up to more (thread_budget.h); 0: max_jobs x
                                * threads_per_job, i.e. no budget beyond max_jobs */
    double wall_limit;         /* default wall-clock limit per job, s */
    double kill_grace;         /* s between SIGTERM and SIGKILL */
    long memory_limit_mb;      /* RLIMIT_AS per engine, 0 = none */
    int max_attempts;          /* requeue limit after daemon crashes */
    const struct tcfg *storage; /* the data directory's floor and reserve (storage.h);
                                 * NULL: not watched.  Must outlive the supervisor */
    const struct tcfg *slurm;  /* non-NULL: the Slurm executor with these settings
                                * (executor.h); NULL: local engines.  Must outlive it */
};

struct tsup; /* opaque */

/* Starts the supervisor thread. Returns 0 or -1 with err. */
int tsup_start(const struct tsup_config *cfg, struct tsup **out, char *err, size_t errsize);
/* Wakes the supervisor (new job queued, cancel requested). Async-signal-unsafe; thread-safe. */
void tsup_wake(struct tsup *s);
/* How many finished jobs wait for their final state to be recorded, and why
 * the last write failed (finals.h).  Any thread. */
size_t tsup_unrecorded(struct tsup *s, char *why, size_t size);
/* Stops: running engines get SIGTERM (then SIGKILL after the grace period) and
 * their jobs are requeued so the next daemon runs them again; joins the thread. */
void tsup_stop(struct tsup *s);
#endif
