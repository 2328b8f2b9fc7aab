/* Slurm's job states and what the daemon makes of them (server/slurm_state.c).
 *
 * The states are those squeue's %T and sacct's State print (Slurm 22.05,
 * slurm.h's job_states and job_state_string).  The table says, for each,
 * whether the job still waits, runs or has ended, and how an end maps to the
 * API (queue.h's statuses and outcomes):
 *
 *   PENDING CONFIGURING REQUEUED REQUEUE_HOLD REQUEUE_FED RESV_DEL_HOLD
 *                         waiting   (status running, message "PENDING (reason)")
 *   RUNNING COMPLETING SUSPENDED STOPPED SIGNALING STAGE_OUT RESIZING
 *                         running
 *   COMPLETED FAILED      ended: the job's exit_status file decides, as the
 *                         local executor's wait status does (engine_report.h)
 *   TIMEOUT DEADLINE      failed, timed_out
 *   OUT_OF_MEMORY         failed, crashed ("killed by Slurm for memory")
 *   SPECIAL_EXIT          failed, crashed
 *   CANCELLED             dismissed, cancelled (by tlsphd or by someone else)
 *   NODE_FAIL PREEMPTED BOOT_FAIL
 *                         requeued like a run the daemon's crash interrupted,
 *                         up to max_attempts, then failed, interrupted
 *
 * A state not in the table counts as running (a newer Slurm's state must not
 * end a job), and is logged once. */
#ifndef TLSPHD_SLURM_STATE_H
#define TLSPHD_SLURM_STATE_H

#include <stdbool.h>
#include <stddef.h>

enum slurm_phase {
    SLURM_WAITING,  /* queued in Slurm */
    SLURM_RUNNING,  /* on a node */
    SLURM_ENDED,    /* the exit status file decides */
    SLURM_FAILED,   /* ended by Slurm: failed with the outcome of the row */
    SLURM_CANCELLED,
    SLURM_REQUEUE,  /* the node or the allocation went away: run it again */
    SLURM_UNKNOWN   /* not in the table */
};

struct slurm_state {
    const char *name;      /* as squeue prints it */
    enum slurm_phase phase;
    const char *outcome;   /* SLURM_FAILED: the API outcome */
    const char *meaning;   /* for the job's message */
};

/* The row of a state name (never NULL: an unknown name gets SLURM_UNKNOWN). */
const struct slurm_state *slurm_state_of(const char *name);

/* What to do with a watched run at one look, from the two witnesses of its
 * end: the exit status the batch script wrote (exit_rc, -1 none) and
 * Slurm's state (st, NULL when squeue no longer lists the job), and whether
 * the wait for the second witness has lasted long enough (waited):
 *
 *   Slurm ended it (TIMEOUT, OUT_OF_MEMORY, CANCELLED ...)  END_BY_SLURM
 *   NODE_FAIL, PREEMPTED, BOOT_FAIL                         REQUEUE
 *   the engine's own end (exit 0, 2, 3, 4), or any exit
 *     status once Slurm has ended or forgotten the job     END_BY_EXIT
 *   one witness only (exit 1, 5, a signal while Slurm still
 *     runs the job: Slurm's TIMEOUT may be on its way; or
 *     Slurm ended it and the status is not visible yet)     WAIT, then after
 *                                                          the grace END_BY_EXIT,
 *                                                          END_NO_STATUS (Slurm
 *                                                          has it) or
 *                                                          REQUEUE_GONE (it does not)
 *   otherwise                                               WATCH (waiting or running) */
enum slurm_verdict {
    SLURM_WATCH,
    SLURM_WAIT,
    SLURM_END_BY_EXIT,
    SLURM_END_BY_SLURM,
    SLURM_END_NO_STATUS,
    SLURM_REQUEUE_NODE,
    SLURM_REQUEUE_GONE
};
enum slurm_verdict slurm_verdict(int exit_rc, const struct slurm_state *st, bool waited);

/* The output format the executor asks squeue for, and one line of it. */
#define SLURM_QUEUE_FORMAT "%i|%T|%r|%N|%j"
struct slurm_queue_row {
    char id[48];      /* "123" or "123_4" (an array task) */
    char state[32];
    char reason[96];
    char nodes[96];
    char name[96];
};
/* Parses squeue's output: *rows (free) holds *n rows; lines that do not parse
 * are skipped.  0, or -1 out of memory. */
int slurm_queue_parse(const char *text, struct slurm_queue_row **rows, size_t *n);
/* The row of Slurm job id among n rows, NULL if absent. */
const struct slurm_queue_row *slurm_queue_find(const struct slurm_queue_row *rows, size_t n,
                                               const char *id);

#endif
