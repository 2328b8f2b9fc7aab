/* Inside the queue module (server/queue_internal.h): the handle, the
 * prepared statements and the helpers that queue.c (schema, statements,
 * connections, rows), queue_jobs.c (inserts, reads, state changes) and
 * queue_study.c (a study's state from its children) share.  All SQL text is
 * in queue.c's statement table; the other files only bind and step. */
#ifndef TLSPHD_QUEUE_INTERNAL_H
#define TLSPHD_QUEUE_INTERNAL_H

#include <sqlite3.h>
#include <stddef.h>

#include "queue.h"

enum tqi_stmt {
    S_BEGIN,
    S_COMMIT,
    S_ROLLBACK,
    S_INSERT,
    S_GET,
    S_LOOKUP,
    S_CLAIM,
    S_SET_PID,
    S_PROGRESS,
    S_FINISH,
    S_REQUEUE,
    S_DISMISS,          /* accepted or running job -> dismissed/cancelled */
    S_CANCEL_MARK,      /* cancel_requested = 1 on one row */
    S_CANCEL_CHILDREN_ACCEPTED,
    S_CANCEL_CHILDREN_RUNNING,
    S_CANCEL_REQUESTS,
    S_DELETE,
    S_RECOVER_CANCELLED,
    S_RECOVER_REQUEUE,
    S_RECOVER_FAIL,
    S_OPEN_STUDIES,
    S_STUDY_AGG,
    S_STUDY_UPDATE,
    S_COUNTS,
    S_LIST0, /* + bitmask: 1 status, 2 study_id, 4 process */
    S_COUNT = S_LIST0 + 8
};

struct tq {
    sqlite3 *db;
    sqlite3_stmt *st[S_COUNT];
    char err[512];
};

/* Row of S_LOOKUP. */
struct tqi_lookup {
    char process[16];
    char status[16];
    char study_id[TQ_ID_LEN + 1];
    int cancel_requested;
};

/* Public entry points refuse a NULL handle (tq_last_error(NULL) explains). */
#define NEED_Q(q)      \
    do {               \
        if (!(q))      \
            return -1; \
    } while (0)

/* Unix time now, s. */
double tqi_now_seconds(void);
void tqi_set_err(struct tq *q, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* "what: " + SQLite's message. */
void tqi_set_db_err(struct tq *q, const char *what);
/* 0, or -1 with the error set when id is not a key (job_key_valid). */
int tqi_check_id(struct tq *q, const char *fn, const char *id);
/* Resets a statement and clears its bindings. */
void tqi_done_stmt(sqlite3_stmt *st);
/* Binds text, or NULL for s == NULL. */
int tqi_bind_text(sqlite3_stmt *st, int i, const char *s);
/* Steps a statement whose rows are ignored to the end: 0 or -1. */
int tqi_run_stmt(struct tq *q, sqlite3_stmt *st, const char *what);
/* The start of a write on job id: a handle, a valid id, BEGIN IMMEDIATE.
 * 0, or -1 (nothing begun). */
int tqi_begin_for(struct tq *q, const char *fn, const char *id);
/* BEGIN IMMEDIATE: 0 or -1. */
int tqi_tx_begin(struct tq *q, const char *fn);
void tqi_tx_rollback(struct tq *q);
int tqi_tx_commit(struct tq *q, const char *fn);
/* Commits when rc >= 0 (returns rc), else rolls back (-1); -1 when the commit fails. */
int tqi_tx_end(struct tq *q, const char *fn, int rc);
/* A text column into a fixed buffer: 0, or -1 when it does not fit. */
int tqi_copy_fixed(struct tq *q, char *dst, size_t size, sqlite3_stmt *st, int col,
                   const char *name);
/* A text column, malloc'ed (NULL for SQL NULL): 0 or -1. */
int tqi_copy_dyn(struct tq *q, char **dst, sqlite3_stmt *st, int col);
/* A row in JOB_COLS order: 0, or -1 (out freed and zeroed). */
int tqi_read_job(struct tq *q, sqlite3_stmt *st, struct tq_job *out);
/* 0 found, 1 not found, -1 error. */
int tqi_lookup(struct tq *q, const char *id, struct tqi_lookup *l);
/* An UPDATE ... RETURNING study_id with bindings made: 0 when a row changed
 * (study filled, "" when none), 1 when none, -1 error. */
int tqi_update_returning_study(struct tq *q, sqlite3_stmt *st, const char *what,
                               char study[TQ_ID_LEN + 1]);
/* queue_study.c: recomputes a study's row inside the caller's write
 * transaction (0, 1 no such study, -1); refresh_parent does it for the study
 * of a changed child when study is non-empty and rc is 0, and returns rc. */
int tqi_study_refresh_locked(struct tq *q, const char *study_id);
int tqi_refresh_parent(struct tq *q, const char *study, int rc);

#endif
