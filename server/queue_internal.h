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
    S_INSERT_RECOVERED, /* a run rebuilt from its directory (tlsphd --recover) */
    S_GET,
    S_LOOKUP,
    S_CLAIM,
    S_CLAIM_STUDY,      /* the accepted siblings of a claimed study child (Slurm arrays) */
    S_SET_PID,
    S_SET_MESSAGE,      /* the message of a running job (the Slurm state) */
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
    int err_code; /* SQLite's extended result code of the last error, 0 for others */
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
/* One parameter value; TQI_BIND(st, TQI_TEXT(id), TQI_REAL(t), TQI_INT(n))
 * binds ?1, ?2, ?3 of st in that order (TQI_TEXT(NULL) binds SQL NULL).  The
 * designated initialisers let the compiler check each value's type. */
struct tqi_value {
    enum { TQI_V_TEXT, TQI_V_REAL, TQI_V_INT } kind;
    union {
        const char *text;
        double real;
        sqlite3_int64 integer;
    };
};
#define TQI_TEXT(s) {.kind = TQI_V_TEXT, .text = (s)}
#define TQI_REAL(x) {.kind = TQI_V_REAL, .real = (x)}
#define TQI_INT(n) {.kind = TQI_V_INT, .integer = (n)}
#define TQI_BIND(st, ...)                                                          \
    tqi_bind_values((st), (const struct tqi_value[]){__VA_ARGS__},                 \
                    sizeof((const struct tqi_value[]){__VA_ARGS__}) / sizeof(struct tqi_value))
void tqi_bind_values(sqlite3_stmt *st, const struct tqi_value *v, size_t n);
/* Ends a statement whose last step returned rc: resets it; 0 when rc is
 * SQLITE_DONE, else -1 with "what: " + SQLite's message. */
int tqi_stmt_end(struct tq *q, sqlite3_stmt *st, int rc, const char *what);
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
/* Reads the current row of st into row (0, or -1 with the error set and
 * nothing left to free); frees what such a read took.  The job row pair
 * (tqi_read_job_row, tqi_free_job_row) reads struct tq_job in JOB_COLS order. */
typedef int tqi_read_row_fn(struct tq *q, sqlite3_stmt *st, void *row);
typedef void tqi_free_row_fn(void *row);
tqi_read_row_fn tqi_read_job_row;
tqi_free_row_fn tqi_free_job_row;
/* A statement that yields at most one row, stepped to the end and reset:
 * 0 row read, 1 no row, -1 error (fn names it; row freed by free_row, if any). */
int tqi_read_one(struct tq *q, sqlite3_stmt *st, const char *fn, tqi_read_row_fn *read_row,
                 tqi_free_row_fn *free_row, void *row);
/* Every row of st, each `size` bytes, into a malloc'ed array (*rows, NULL when
 * there are none; *n rows), st reset: 0, or -1 with everything freed. */
int tqi_read_all(struct tq *q, sqlite3_stmt *st, const char *fn, size_t size,
                 tqi_read_row_fn *read_row, tqi_free_row_fn *free_row, void **rows, size_t *n);
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
