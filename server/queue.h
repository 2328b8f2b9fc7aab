/* The job queue: the only file with SQL (server/queue.c).
 *
 * One SQLite database in WAL mode, busy timeout 5 s, foreign keys on, every write
 * in BEGIN IMMEDIATE; schema versioned with PRAGMA user_version and migrated
 * forward on open.  Each thread opens its own handle (tq_open); SQLite
 * serialises writers, WAL lets readers run beside them.  Only the daemon
 * opens the database (engine processes report over a pipe).
 *
 * Times are Unix seconds (double).  Ownership: strings in struct tq_job are
 * owned by the struct; tq_job_free releases them. */
#ifndef TLSPHD_QUEUE_H
#define TLSPHD_QUEUE_H

#include <stdbool.h>
#include <stddef.h>

#include "jobid.h"

#define TQ_ID_LEN JOB_ID_LEN

/* OGC status values */
#define TQ_ACCEPTED "accepted"
#define TQ_RUNNING "running"
#define TQ_SUCCESSFUL "successful"
#define TQ_FAILED "failed"
#define TQ_DISMISSED "dismissed"

/* successful, failed or dismissed: the job will not change any more. */
bool tq_status_final(const char *status);
/* One of the five status values above. */
bool tq_status_valid(const char *status);

struct tq_job {
    char id[TQ_ID_LEN + 1];
    char process[16];          /* "run" or "study" */
    char study_id[TQ_ID_LEN + 1]; /* parent study, "" if none */
    long seq;                  /* index of a study child (0-based), -1 otherwise */
    char status[16];           /* accepted|running|successful|failed|dismissed */
    char outcome[16];          /* "", successful|invalid|unstable|crashed|timed_out|cancelled|io_error|interrupted */
    char *message;             /* human-readable, may be NULL */
    char *input;               /* the scene JSON (run) or the study JSON (study) */
    char *params;              /* study child: JSON object {pointer: value}; NULL otherwise */
    char *cost;                /* JSON object from the engine's finished line; NULL until then */
    double progress;           /* 0..100 */
    double sim_time, end_time; /* s */
    long step;
    double eta;                /* s, -1 unknown */
    double created, started, finished; /* 0 = not yet */
    int attempts;
    long pid;                  /* engine process (group leader), 0 = none */
    int cancel_requested;
    long threads;              /* OpenMP threads for this job */
    double wall_limit;         /* s */
};

struct tq; /* opaque: one SQLite connection and its prepared statements */

/* Opens (creating and migrating) the database. Returns 0 or -1 with err filled. */
int tq_open(const char *path, struct tq **out, char *err, size_t errsize);
void tq_close(struct tq *q);
void tq_job_free(struct tq_job *j);
/* Frees an array of n jobs from tq_list and the array. */
void tq_jobs_free(struct tq_job *jobs, size_t n);
/* [added] Message of the last error on this handle ("" if none); valid until the
 * next call on the handle.  Every function below that returns -1 sets it. */
const char *tq_last_error(struct tq *q);
/* The last error on this handle was SQLite's "database or disk is full"
 * (SQLITE_FULL): the disk under the database has no room left. */
bool tq_disk_full(struct tq *q);

/* What the functions below return (errmsg.h: a named status, never a bare
 * number).  The values are fixed: older callers compare with -1, 0, 1, 2. */
enum tq_rc {
    TQ_ERROR = -1,    /* failed; tq_last_error says why (busy database, bad argument) */
    TQ_OK = 0,        /* done */
    TQ_NOT_FOUND = 1, /* no such job, or none in the state the call applies to
                       * (nothing changed; tq_claim_next: nothing queued) */
    TQ_NOT_FINAL = 2  /* tq_delete: the job or its study is still accepted or running */
};

/* Common conventions (all functions): ids are keys in the sense of
 * job_key_valid (jobid.h; new ids come from job_id_new); a tq_job filled by
 * tq_get/tq_list/tq_claim_next is fully overwritten (zeroed and
 * tq_job_free-safe when nothing is returned). */

/* Inserts a job (id, process, input, ... as given; status accepted, created now).
 * TQ_OK or TQ_ERROR. */
enum tq_rc tq_insert(struct tq *q, const struct tq_job *j);
/* Inserts a study and its children in one transaction. */
enum tq_rc tq_insert_study(struct tq *q, const struct tq_job *study,
                           const struct tq_job *children, size_t n);
/* Inserts a run rebuilt from its job directory (tlsphd --recover) with the
 * given status, outcome, message, input, progress, created, started,
 * finished, attempts, threads and wall_limit.  TQ_OK or TQ_ERROR. */
enum tq_rc tq_insert_recovered(struct tq *q, const struct tq_job *j);
/* TQ_OK when job id has a row, TQ_NOT_FOUND, TQ_ERROR. */
enum tq_rc tq_has_row(struct tq *q, const char *id);

/* Whether the database file can be trusted, checked at start before any
 * handle is open (tq_check_file). */
enum tq_trust {
    TQ_TRUSTED,   /* it passed, or there is no file yet (a fresh start) */
    TQ_CORRUPT,   /* not a database, or PRAGMA integrity_check found damage */
    TQ_UNREADABLE /* it could not be checked (busy, I/O error, permissions) */
};
/* Opens path (never creating it), runs PRAGMA integrity_check and closes it;
 * report gets SQLite's first findings or error, one line.  integrity_check
 * rather than quick_check: it also verifies that every index matches its
 * table, and the queue reads through its indexes (the claim of the next job,
 * the lists), so a damaged index could hand out the wrong job or hide jobs;
 * and it stays short (0.6 s for 50 000 jobs, 210 MB; quick_check 0.3 s). */
enum tq_trust tq_check_file(const char *path, char *report, size_t size);
/* TQ_OK found, TQ_NOT_FOUND, TQ_ERROR. */
enum tq_rc tq_get(struct tq *q, const char *id, struct tq_job *out);
/* Most jobs one tq_list call (and one page of GET /jobs) returns. */
#define TQ_LIST_MAX 10000
/* Jobs newest first; NULL/"" filters are ignored; limit 1..TQ_LIST_MAX.
 * *out is an array of *n jobs (tq_jobs_free).  TQ_OK or TQ_ERROR. */
enum tq_rc tq_list(struct tq *q, const char *status, const char *study_id, const char *process,
                   long limit, long offset, struct tq_job **out, size_t *n);
/* The filters of GET /jobs (OGC API - Processes 1.0 job list).  Every
 * member is optional: nstatus 0, NULL/"" strings and unset bounds do not
 * filter.  A job's duration is finished - started (now - started while it
 * runs); a job that has not started has none and is left out by a duration
 * bound. */
#define TQ_FILTER_STATUS_MAX 5
struct tq_filter {
    const char *status[TQ_FILTER_STATUS_MAX]; /* any of these */
    size_t nstatus;
    const char *study_id, *process;
    bool has_created_min, has_created_max;
    double created_min, created_max; /* Unix s, inclusive */
    bool has_min_duration, has_max_duration;
    double min_duration, max_duration; /* s, inclusive */
};
/* tq_list with every filter of f (newest first, limit 1..TQ_LIST_MAX).
 * TQ_OK or TQ_ERROR. */
enum tq_rc tq_list_filtered(struct tq *q, const struct tq_filter *f, long limit, long offset,
                            struct tq_job **out, size_t *n);
/* Atomically moves the oldest accepted job (not a study parent) to running
 * (attempts+1, started = now, outcome "") and returns it: TQ_OK claimed,
 * TQ_NOT_FOUND none queued, TQ_ERROR. */
enum tq_rc tq_claim_next(struct tq *q, struct tq_job *out);
/* The same for every other accepted child of study study_id at once (the
 * Slurm executor submits them as one job array): *out is an array of *n
 * jobs (tq_jobs_free; none: *n = 0).  TQ_OK or TQ_ERROR. */
enum tq_rc tq_claim_siblings(struct tq *q, const char *study_id, struct tq_job **out, size_t *n);
/* Sets the message of a running run job (what its executor reports about it,
 * e.g. "Slurm job 12: PENDING (Priority)"): TQ_OK, TQ_NOT_FOUND, TQ_ERROR. */
enum tq_rc tq_set_message(struct tq *q, const char *id, const char *message);
/* These two change a running run job only (else TQ_NOT_FOUND). */
enum tq_rc tq_set_pid(struct tq *q, const char *id, long pid);
enum tq_rc tq_update_progress(struct tq *q, const char *id, double progress, double sim_time,
                              double end_time, long step, double eta);
/* Final state of a run job: status successful/failed/dismissed, outcome, message, cost (may be NULL).
 * Only jobs that are running or accepted change (else TQ_NOT_FOUND); finished = now, pid = 0,
 * progress = 100 when successful; cost NULL keeps the stored cost.  A study child
 * refreshes its study in the same transaction. */
enum tq_rc tq_finish(struct tq *q, const char *id, const char *status, const char *outcome,
                     const char *message, const char *cost_json);
/* Puts a running job back in the queue (daemon restart, shutdown): status accepted,
 * pid 0, progress reset; attempts is kept.  A running job with cancel_requested
 * is dismissed (outcome cancelled) instead.  TQ_NOT_FOUND: not running. */
enum tq_rc tq_requeue(struct tq *q, const char *id, const char *message);
/* Cancel: accepted -> dismissed now (outcome cancelled); running -> cancel_requested = 1
 * (the supervisor stops it and finishes it as dismissed); final -> no change.
 * For a study, applies to every child.  TQ_OK, TQ_NOT_FOUND, TQ_ERROR. */
enum tq_rc tq_request_cancel(struct tq *q, const char *id);
/* Ids of running jobs with cancel_requested = 1 (array of *n ids, free(*ids)).
 * TQ_OK or TQ_ERROR. */
enum tq_rc tq_cancel_requests(struct tq *q, char (**ids)[TQ_ID_LEN + 1], size_t *n);
/* Removes a job in a final state (and a study's children): TQ_OK, TQ_NOT_FOUND,
 * TQ_NOT_FINAL (also for a study child whose study is not final), TQ_ERROR. */
enum tq_rc tq_delete(struct tq *q, const char *id);
/* Start-up recovery: every job left "running" by a previous daemon is requeued
 * when attempts < max_attempts, else failed with outcome "interrupted".
 * Returns the number of jobs touched, or -1. */
int tq_recover(struct tq *q, int max_attempts);
/* Study status from its children: counts per status; the study row itself is
 * updated (status, progress, started/finished) by tq_study_refresh.
 * All children final: successful if all successful, else failed ("k of n children
 * failed/dismissed"), or dismissed (outcome cancelled) if the study was cancelled.
 * All accepted: accepted.  Otherwise running.  progress = (100 * children that
 * ran to their end (successful or failed) + the progress running and dismissed
 * children reached) / n, so a cancelled study does not claim 100.  TQ_OK, TQ_NOT_FOUND, TQ_ERROR (also: not a study). */
enum tq_rc tq_study_refresh(struct tq *q, const char *study_id);
/* Number of jobs in each state (for /healthz and tests).  Counts run jobs only
 * (study children included, study parents not); any pointer may be NULL.
 * TQ_OK or TQ_ERROR. */
enum tq_rc tq_counts(struct tq *q, long *accepted, long *running, long *final);
/* The same for the jobs of one process ("run" or "study"). */
enum tq_rc tq_counts_of(struct tq *q, const char *process, long *accepted, long *running,
                        long *final);

#endif
