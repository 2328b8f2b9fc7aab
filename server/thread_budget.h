/* The daemon's thread budget (server/thread_budget.c): the OpenMP threads of
 * the engines that run at once never add up to more than the cores.
 *
 * Why: an engine's threads meet at a barrier several times a step.  When the
 * engines of two jobs want more threads than there are cores, a thread that
 * reaches a barrier waits for a partner that the scheduler has put off the
 * core, for a time slice of milliseconds; measured on 2 cores, two 2-thread
 * runs side by side were each slower than one thread (docs/performance.md,
 * "Threads on a shared machine").  Two 1-thread jobs, in contrast, each run at
 * full speed, so on a machine running several jobs the best share is a core
 * per job, not threads per job.
 *
 * The rules (docs/deployment.md, "Threads and cores"):
 *   - cores: the config key `cores`, else the CPUs this process may run on
 *     (sched_getaffinity, so a container's or a taskset's limit counts);
 *   - threads_per_job unset: cores / max_jobs, at least 1;
 *   - threads_per_job set so that threads_per_job x max_jobs > cores: lowered
 *     to cores / max_jobs (at least 1), with a warning;
 *   - max_jobs > cores: kept, with a warning: at most `cores` engines run at
 *     once, the others wait (raise `cores` to share cores on purpose);
 *   - at run time a job starts only when a core is free and gets
 *     min(its threads, free cores) threads (tbudget_grant).
 * The Slurm executor does not use it: Slurm allots the cores of its nodes.
 *
 * Plain values, no locking: the supervisor thread alone keeps the count. */
#ifndef TLSPHD_THREAD_BUDGET_H
#define TLSPHD_THREAD_BUDGET_H

#include <stddef.h>

struct tbudget {
    int cores; /* threads that may run at once, >= 1 */
    int used;  /* threads of the running engines, 0..cores */
};

/* The CPUs this process may run on (sched_getaffinity), else the online
 * processors, at least 1. */
int tbudget_detect_cores(void);

/* Settles threads_per_job for cores and max_jobs (the rules above):
 * *threads_per_job 0 means unset.  Writes a warning (empty when none) to
 * warn; returns 1 when it wrote one, else 0. */
int tbudget_configure(int cores, int max_jobs, int *threads_per_job, char *warn, size_t warnsize);

/* Threads for a job that asks for want (< 1 counts as 1): min(want, free
 * cores), or 0 when no core is free (the job waits). */
int tbudget_grant(const struct tbudget *b, int want);
/* Books n threads as running (n from tbudget_grant) / gives them back. */
void tbudget_take(struct tbudget *b, int n);
void tbudget_give(struct tbudget *b, int n);
#endif
