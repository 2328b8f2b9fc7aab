/* The jobs service (server/jobs.c): submitting a run or a study, cancelling
 * and removing jobs, with no HTTP in sight (the routes translate its answers
 * into status codes and problem documents; a test or a tool can call it
 * directly).
 *
 * Submitting validates everything first and collects every problem (the
 * engine's scene validator, the daemon's particle limit, the study's sweep,
 * every child scene), estimates each job's result file (output_size.h)
 * against the per-job quota and the free space above the floor (storage.h),
 * then issues ids, writes them to an intent file (intent.h: a crash from here
 * on leaves nothing behind at the next start), creates each job's directory
 * before its row (the supervisor never claims a job without its scene),
 * inserts the rows in one transaction, removes the directories again if the
 * insert fails, removes the intent file and wakes the supervisor.  Removing
 * is crash-safe the same way.
 *
 * Threads: each call uses the caller's queue handle (env->q). */
#ifndef TLSPHD_JOBS_H
#define TLSPHD_JOBS_H

#include <stddef.h>

#include <jansson.h>

#include "config.h"
#include "jobid.h"
#include "queue.h"
#include "util/errors.h"

struct tsup;

struct jobs_env {
    struct tq *q;            /* the calling thread's queue handle */
    const struct tcfg *cfg;  /* jobs_dir, max_particles, max_children, per-job defaults */
    struct tsup *sup;        /* woken after a submit or a cancel; NULL: nobody to wake */
};

enum jobs_rc {
    JOBS_OK,
    JOBS_INVALID,      /* refused: the error list says why, pointers relative to the inputs */
    JOBS_NO_MEMORY,
    JOBS_NO_DIRECTORY, /* a job directory could not be made */
    JOBS_NOT_QUEUED,   /* the queue did not take the rows (tq_last_error says why) */
    JOBS_NO_SUCH_JOB,
    JOBS_NOT_FINAL,    /* the job, or its study, is still accepted or running */
    JOBS_STUDY_CHILD,  /* a study's child goes only with its study (its summary row) */
    JOBS_BUSY,         /* the database did not answer in time */
    JOBS_OVER_QUOTA,   /* a job's estimated result file is above max_output_mb (errors, detail) */
    JOBS_NO_SPACE      /* the data directory's disk cannot take it (detail) */
};

/* Most errors reported for one study (the rest are left out). */
#define JOBS_MAX_REPORTED_ERRORS 50

/* What a submit produced. */
struct jobs_submitted {
    char id[JOB_ID_LEN + 1];    /* JOBS_OK: the new job (a study: the study) */
    struct tlsph_errors errors; /* JOBS_INVALID, JOBS_OVER_QUOTA: every problem, pointers
                                 * relative to the inputs */
    char detail[512];           /* JOBS_OVER_QUOTA, JOBS_NO_SPACE: for the client, with the
                                 * estimate */
    double output_bytes;        /* the estimated result files, B (all children of a study) */
    char why[256];              /* other failures: one line for the log */
    int errnum;                 /* JOBS_NO_DIRECTORY, JOBS_NOT_QUEUED: the system error of a
                                 * failed file write (errno), 0 when none */
};
void jobs_submitted_init(struct jobs_submitted *s);
void jobs_submitted_free(struct jobs_submitted *s);

/* A run: inputs = {"scene": SCENE}.  The scene gets the daemon's particle
 * limit when it sets none (inputs is modified). */
enum jobs_rc jobs_submit_run(const struct jobs_env *env, json_t *inputs, struct jobs_submitted *out);
/* A study: inputs = {"base", "sweep", "outputs"} (study.h); its children are
 * queued with it. */
enum jobs_rc jobs_submit_study(const struct jobs_env *env, json_t *inputs,
                               struct jobs_submitted *out);
/* A convergence study: inputs = {"base", "ladder", "outputs", "target"}
 * (convergence.h); stored as a study whose input also holds the request. */
enum jobs_rc jobs_submit_convergence(const struct jobs_env *env, json_t *inputs,
                                     struct jobs_submitted *out);
/* Asks for job id (a study: each child) to stop: JOBS_OK (also for a job that
 * is final or unknown: nothing to do), JOBS_NO_SPACE (the disk is full even
 * after the reserve was freed) or JOBS_BUSY.  Cancelling and removing free
 * the reserve (storage.h) when the disk refuses their write. */
enum jobs_rc jobs_cancel(const struct jobs_env *env, const char *id);
/* Removes a final job, its files and, for a study, its children's files:
 * JOBS_OK, JOBS_NO_SUCH_JOB, JOBS_NOT_FINAL, JOBS_STUDY_CHILD (a child alone
 * is never removed: its study's summary and message count it), JOBS_NO_SPACE
 * or JOBS_BUSY. */
enum jobs_rc jobs_remove(const struct jobs_env *env, const struct tq_job *job);
/* The children of study id ordered by seq (at most max_children + 1); free
 * with tq_jobs_free.  0 or -1 (busy). */
int jobs_study_children(const struct jobs_env *env, const char *id, struct tq_job **out,
                        size_t *n);

#endif
