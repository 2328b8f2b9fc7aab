/* Executors: how a claimed run is executed (server/executor.h).
 *
 * The supervisor thread (supervisor.h) owns what every executor shares: its
 * own queue handle, the final states still to be written (finals.h), the
 * free-space floor (storage.h), the wake pipe and the stop flag.  After its
 * start-up it hands the thread to one executor, chosen in the config file
 * (`executor = local | slurm`, config.h):
 *
 *   local  supervisor.c: fork + exec of tlsph-run on this machine, up to
 *          max_jobs at once, progress on a pipe (fd 3), the wait status;
 *          the only code that forks, signals and reaps engines.  The default.
 *   slurm  executor_slurm.c: every run is a Slurm batch job (sbatch), a
 *          study's children one job array; progress from a file in the job's
 *          directory on a shared file system, status from squeue and the
 *          job's exit_status file; the only code that calls the scheduler.
 *
 * Both turn the engine's report into the job's final state with the same
 * engine_outcome (engine_report.h), so a run ends with the same status,
 * outcome and message whichever executor ran it.  What differs at a daemon
 * restart: local engines die with the daemon (PR_SET_PDEATHSIG) and their
 * runs are requeued (tq_recover); Slurm jobs keep running, and the Slurm
 * executor adopts them again from their stored Slurm job ids. */
#ifndef TLSPHD_EXECUTOR_H
#define TLSPHD_EXECUTOR_H

#include <stdatomic.h>
#include <stdbool.h>

struct tq;
struct tcfg;
struct finals;

enum texec_kind { TEXEC_LOCAL, TEXEC_SLURM };

/* The kind named in the config ("local", "slurm"); TEXEC_LOCAL for NULL. */
enum texec_kind texec_kind_of(const char *name);

/* What the supervisor thread lends an executor for as long as it runs. */
struct texec_host {
    struct tq *q;              /* the supervisor thread's queue handle */
    struct finals *finals;     /* final states: finals_record, never tq_finish */
    const char *jobs_dir;      /* absolute */
    const char *engine_path;   /* absolute */
    int threads_per_job;       /* >= 1 */
    int max_attempts;
    double wall_limit;         /* s */
    int wake_rd;               /* readable when woken (a job queued, a cancel) */
    atomic_int *stop;          /* set: return from the loop */
    /* The supervisor's upkeep, called by the executor's loop every tick:
     * final states still waiting, the reserve file.  room: whether the
     * free-space floor lets a job start. */
    void (*keep_records)(void *sup, double now);
    bool (*room)(void *sup);
    void *sup;
};

#endif
