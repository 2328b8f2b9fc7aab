/* The job queue on SQLite (see queue.h and docs: daemon-research.md §3).
 *
 * - One connection per handle, opened READWRITE|CREATE|NOMUTEX; WAL,
 *   synchronous=NORMAL, foreign_keys=ON, busy timeout 5 s.
 * - Schema versioned with PRAGMA user_version; migrations[] applied in order in
 *   one BEGIN IMMEDIATE transaction; a newer database is refused.
 * - Every statement is prepared once (struct tq caches them) and every value is
 *   bound; the only SQL text assembled at run time is the tq_list variants,
 *   built from constant fragments.
 * - Every write runs inside BEGIN IMMEDIATE ... COMMIT (ROLLBACK on error), and
 *   every statement is stepped to completion and reset so no read snapshot is
 *   left open (it would block WAL checkpoints). */
#include "queue.h"

#include <sqlite3.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ------------------------------------------------------------------ schema */

struct migration {
    int version;
    const char *sql;
};

static const struct migration migrations[] = {
    {1,
     "CREATE TABLE jobs("
     " id TEXT PRIMARY KEY NOT NULL,"
     " process TEXT NOT NULL CHECK(process IN ('run','study')),"
     " study_id TEXT REFERENCES jobs(id) ON DELETE CASCADE," /* NULL = none */
     " seq INTEGER NOT NULL DEFAULT -1,"
     " status TEXT NOT NULL CHECK(status IN"
     "  ('accepted','running','successful','failed','dismissed')),"
     " outcome TEXT NOT NULL DEFAULT '',"
     " message TEXT,"
     " input TEXT NOT NULL,"
     " params TEXT,"
     " cost TEXT,"
     " progress REAL NOT NULL DEFAULT 0,"
     " sim_time REAL NOT NULL DEFAULT 0,"
     " end_time REAL NOT NULL DEFAULT 0,"
     " step INTEGER NOT NULL DEFAULT 0,"
     " eta REAL NOT NULL DEFAULT -1,"
     " created REAL NOT NULL,"
     " started REAL NOT NULL DEFAULT 0,"
     " finished REAL NOT NULL DEFAULT 0,"
     " attempts INTEGER NOT NULL DEFAULT 0,"
     " pid INTEGER NOT NULL DEFAULT 0,"
     " cancel_requested INTEGER NOT NULL DEFAULT 0,"
     " threads INTEGER NOT NULL DEFAULT 0,"
     " wall_limit REAL NOT NULL DEFAULT 0);"
     "CREATE INDEX jobs_status ON jobs(status, created);"
     "CREATE INDEX jobs_study ON jobs(study_id, seq);"
     "CREATE INDEX jobs_created ON jobs(created);"},
};
#define N_MIGRATIONS (sizeof migrations / sizeof migrations[0])
#define SCHEMA_VERSION (migrations[N_MIGRATIONS - 1].version)

/* Column order read by read_job(). */
#define JOB_COLS                                                                          \
    "id, process, study_id, seq, status, outcome, message, input, params, cost, progress, " \
    "sim_time, end_time, step, eta, created, started, finished, attempts, pid, "           \
    "cancel_requested, threads, wall_limit"

#define FINAL_SQL "('successful','failed','dismissed')"

enum {
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

static const char *const stmt_sql[S_LIST0] = {
    [S_BEGIN] = "BEGIN IMMEDIATE",
    [S_COMMIT] = "COMMIT",
    [S_ROLLBACK] = "ROLLBACK",
    [S_INSERT] = "INSERT INTO jobs(id, process, study_id, seq, status, message, input, params,"
                 " created, threads, wall_limit, eta)"
                 " VALUES(?1, ?2, ?3, ?4, 'accepted', ?5, ?6, ?7, ?8, ?9, ?10, -1)",
    [S_GET] = "SELECT " JOB_COLS " FROM jobs WHERE id = ?1",
    [S_LOOKUP] = "SELECT process, status, study_id, cancel_requested FROM jobs WHERE id = ?1",
    [S_CLAIM] = "UPDATE jobs SET status='running', attempts=attempts+1, started=?1, outcome=''"
                " WHERE id = (SELECT id FROM jobs WHERE status='accepted' AND process='run'"
                "             ORDER BY created, rowid LIMIT 1)"
                " RETURNING " JOB_COLS,
    [S_SET_PID] = "UPDATE jobs SET pid=?2 WHERE id=?1 AND status='running' AND process='run'",
    [S_PROGRESS] = "UPDATE jobs SET progress=?2, sim_time=?3, end_time=?4, step=?5, eta=?6"
                   " WHERE id=?1 AND status='running' AND process='run' RETURNING study_id",
    [S_FINISH] = "UPDATE jobs SET status=?2, outcome=?3, message=?4, cost=COALESCE(?5, cost),"
                 " finished=?6, pid=0,"
                 " progress=CASE WHEN ?2='successful' THEN 100 ELSE progress END,"
                 " eta=CASE WHEN ?2='successful' THEN 0 ELSE eta END"
                 " WHERE id=?1 AND process='run' AND status IN ('running','accepted')"
                 " RETURNING study_id",
    [S_REQUEUE] = "UPDATE jobs SET status='accepted', outcome='', message=?2, pid=0,"
                  " cancel_requested=0, progress=0, sim_time=0, step=0, eta=-1, started=0"
                  " WHERE id=?1 AND status='running' AND process='run' RETURNING study_id",
    [S_DISMISS] = "UPDATE jobs SET status='dismissed', outcome='cancelled', message=?2,"
                  " finished=?3, pid=0"
                  " WHERE id=?1 AND process='run' AND status IN ('accepted','running')",
    [S_CANCEL_MARK] = "UPDATE jobs SET cancel_requested=1 WHERE id=?1",
    [S_CANCEL_CHILDREN_ACCEPTED] =
        "UPDATE jobs SET status='dismissed', outcome='cancelled', message=?2, finished=?3"
        " WHERE study_id=?1 AND status='accepted'",
    [S_CANCEL_CHILDREN_RUNNING] =
        "UPDATE jobs SET cancel_requested=1 WHERE study_id=?1 AND status='running'",
    [S_CANCEL_REQUESTS] = "SELECT id FROM jobs WHERE status='running' AND process='run'"
                          " AND cancel_requested=1 ORDER BY created, rowid",
    [S_DELETE] = "DELETE FROM jobs WHERE id=?1",
    [S_RECOVER_CANCELLED] =
        "UPDATE jobs SET status='dismissed', outcome='cancelled', finished=?1, pid=0,"
        " message='cancelled (the daemon restarted before the engine stopped)'"
        " WHERE status='running' AND process='run' AND cancel_requested=1",
    [S_RECOVER_REQUEUE] =
        "UPDATE jobs SET status='accepted', outcome='', pid=0, cancel_requested=0,"
        " progress=0, sim_time=0, step=0, eta=-1, started=0,"
        " message='requeued after daemon restart'"
        " WHERE status='running' AND process='run' AND attempts < ?1",
    [S_RECOVER_FAIL] =
        "UPDATE jobs SET status='failed', outcome='interrupted', finished=?1, pid=0,"
        " message='interrupted by daemon restarts (' || attempts || ' attempts)'"
        " WHERE status='running' AND process='run'",
    [S_OPEN_STUDIES] = "SELECT id FROM jobs WHERE process='study'"
                       " AND status IN ('accepted','running')",
    [S_STUDY_AGG] = "SELECT status, COUNT(*), TOTAL(progress),"
                    " MIN(CASE WHEN started > 0 THEN started END), MAX(finished)"
                    " FROM jobs WHERE study_id=?1 GROUP BY status",
    [S_STUDY_UPDATE] = "UPDATE jobs SET status=?2, outcome=?3, message=?4, progress=?5,"
                       " started=?6, finished=?7 WHERE id=?1",
    [S_COUNTS] = "SELECT TOTAL(status='accepted'), TOTAL(status='running'),"
                 " TOTAL(status IN " FINAL_SQL ") FROM jobs WHERE process='run'",
};

struct tq {
    sqlite3 *db;
    sqlite3_stmt *st[S_COUNT];
    char err[512];
};

/* ------------------------------------------------------------------ helpers */

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void set_err(struct tq *q, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void set_err(struct tq *q, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(q->err, sizeof q->err, fmt, ap);
    va_end(ap);
}

static void set_db_err(struct tq *q, const char *what)
{
    set_err(q, "%s: %s", what, sqlite3_errmsg(q->db));
}

const char *tq_last_error(struct tq *q)
{
    return q ? q->err : "no queue handle";
}

/* Public entry points refuse a NULL handle (tq_last_error(NULL) explains). */
#define NEED_Q(q)      \
    do {               \
        if (!(q))      \
            return -1; \
    } while (0)

static int check_id(struct tq *q, const char *fn, const char *id)
{
    if (job_key_valid(id))
        return 0;
    set_err(q, "%s: invalid job id (1..%d characters of [0-9A-Za-z_-])", fn, TQ_ID_LEN);
    return -1;
}

bool tq_status_final(const char *status)
{
    return status && (!strcmp(status, TQ_SUCCESSFUL) || !strcmp(status, TQ_FAILED) ||
                      !strcmp(status, TQ_DISMISSED));
}

bool tq_status_valid(const char *status)
{
    return status && (!strcmp(status, TQ_ACCEPTED) || !strcmp(status, TQ_RUNNING) ||
                      tq_status_final(status));
}

static void done_stmt(sqlite3_stmt *st)
{
    sqlite3_reset(st);
    sqlite3_clear_bindings(st);
}

static int bind_text(sqlite3_stmt *st, int i, const char *s)
{
    return s ? sqlite3_bind_text(st, i, s, -1, SQLITE_TRANSIENT) : sqlite3_bind_null(st, i);
}

/* Steps a statement that returns no rows (or whose rows are ignored) to the end. */
static int run_stmt(struct tq *q, sqlite3_stmt *st, const char *what)
{
    int rc;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW)
        ;
    if (rc != SQLITE_DONE) {
        set_db_err(q, what);
        done_stmt(st);
        return -1;
    }
    done_stmt(st);
    return 0;
}

static int tx_begin(struct tq *q, const char *fn)
{
    int rc = sqlite3_step(q->st[S_BEGIN]);
    sqlite3_reset(q->st[S_BEGIN]);
    if (rc != SQLITE_DONE) {
        set_err(q, "%s: BEGIN IMMEDIATE: %s", fn, sqlite3_errstr(rc));
        return -1;
    }
    return 0;
}

static void tx_rollback(struct tq *q)
{
    if (!sqlite3_get_autocommit(q->db)) {
        sqlite3_step(q->st[S_ROLLBACK]);
        sqlite3_reset(q->st[S_ROLLBACK]);
    }
}

static int tx_commit(struct tq *q, const char *fn)
{
    int rc = sqlite3_step(q->st[S_COMMIT]);
    sqlite3_reset(q->st[S_COMMIT]);
    if (rc != SQLITE_DONE) {
        set_err(q, "%s: COMMIT: %s", fn, sqlite3_errstr(rc));
        tx_rollback(q);
        return -1;
    }
    return 0;
}

/* Ends a transaction: commit when rc >= 0, else roll back.  Returns rc, or -1
 * when the commit fails. */
static int tx_end(struct tq *q, const char *fn, int rc)
{
    if (rc < 0) {
        tx_rollback(q);
        return -1;
    }
    if (tx_commit(q, fn) < 0)
        return -1;
    return rc;
}

static int copy_fixed(struct tq *q, char *dst, size_t size, sqlite3_stmt *st, int col,
                      const char *name)
{
    const unsigned char *t = sqlite3_column_text(st, col);
    size_t len = t ? (size_t)sqlite3_column_bytes(st, col) : 0;
    if (len >= size) {
        set_err(q, "stored %s is too long (%zu bytes)", name, len);
        return -1;
    }
    if (len)
        memcpy(dst, t, len);
    dst[len] = '\0';
    return 0;
}

static int copy_dyn(struct tq *q, char **dst, sqlite3_stmt *st, int col)
{
    *dst = NULL;
    if (sqlite3_column_type(st, col) == SQLITE_NULL)
        return 0;
    const unsigned char *t = sqlite3_column_text(st, col);
    if (!t) {
        set_err(q, "out of memory reading a column");
        return -1;
    }
    size_t len = (size_t)sqlite3_column_bytes(st, col);
    char *s = malloc(len + 1);
    if (!s) {
        set_err(q, "out of memory (%zu bytes)", len + 1);
        return -1;
    }
    memcpy(s, t, len);
    s[len] = '\0';
    *dst = s;
    return 0;
}

/* Reads a row in JOB_COLS order.  On failure out is freed and zeroed. */
static int read_job(struct tq *q, sqlite3_stmt *st, struct tq_job *out)
{
    memset(out, 0, sizeof *out);
    if (copy_fixed(q, out->id, sizeof out->id, st, 0, "id") < 0 ||
        copy_fixed(q, out->process, sizeof out->process, st, 1, "process") < 0 ||
        copy_fixed(q, out->study_id, sizeof out->study_id, st, 2, "study_id") < 0 ||
        copy_fixed(q, out->status, sizeof out->status, st, 4, "status") < 0 ||
        copy_fixed(q, out->outcome, sizeof out->outcome, st, 5, "outcome") < 0 ||
        copy_dyn(q, &out->message, st, 6) < 0 || copy_dyn(q, &out->input, st, 7) < 0 ||
        copy_dyn(q, &out->params, st, 8) < 0 || copy_dyn(q, &out->cost, st, 9) < 0) {
        tq_job_free(out);
        return -1;
    }
    out->seq = (long)sqlite3_column_int64(st, 3);
    out->progress = sqlite3_column_double(st, 10);
    out->sim_time = sqlite3_column_double(st, 11);
    out->end_time = sqlite3_column_double(st, 12);
    out->step = (long)sqlite3_column_int64(st, 13);
    out->eta = sqlite3_column_double(st, 14);
    out->created = sqlite3_column_double(st, 15);
    out->started = sqlite3_column_double(st, 16);
    out->finished = sqlite3_column_double(st, 17);
    out->attempts = sqlite3_column_int(st, 18);
    out->pid = (long)sqlite3_column_int64(st, 19);
    out->cancel_requested = sqlite3_column_int(st, 20);
    out->threads = (long)sqlite3_column_int64(st, 21);
    out->wall_limit = sqlite3_column_double(st, 22);
    return 0;
}

void tq_job_free(struct tq_job *j)
{
    if (!j)
        return;
    free(j->message);
    free(j->input);
    free(j->params);
    free(j->cost);
    memset(j, 0, sizeof *j);
}

void tq_jobs_free(struct tq_job *jobs, size_t n)
{
    for (size_t i = 0; i < n; i++)
        tq_job_free(&jobs[i]);
    free(jobs);
}

/* Row of S_LOOKUP. */
struct lookup {
    char process[16];
    char status[16];
    char study_id[TQ_ID_LEN + 1];
    int cancel_requested;
};

/* 0 found, 1 not found, -1 error. */
static int lookup(struct tq *q, const char *id, struct lookup *l)
{
    sqlite3_stmt *st = q->st[S_LOOKUP];
    memset(l, 0, sizeof *l);
    bind_text(st, 1, id);
    int rc = sqlite3_step(st);
    if (rc == SQLITE_ROW) {
        if (copy_fixed(q, l->process, sizeof l->process, st, 0, "process") < 0 ||
            copy_fixed(q, l->status, sizeof l->status, st, 1, "status") < 0 ||
            copy_fixed(q, l->study_id, sizeof l->study_id, st, 2, "study_id") < 0) {
            done_stmt(st);
            return -1;
        }
        l->cancel_requested = sqlite3_column_int(st, 3);
        rc = sqlite3_step(st);
    } else if (rc == SQLITE_DONE) {
        done_stmt(st);
        return 1;
    }
    if (rc != SQLITE_DONE) {
        set_db_err(q, "lookup");
        done_stmt(st);
        return -1;
    }
    done_stmt(st);
    return 0;
}

/* Runs an UPDATE ... RETURNING study_id with bindings already made.  Returns 0
 * when a row changed (study filled, "" when none), 1 when none, -1 error. */
static int update_returning_study(struct tq *q, sqlite3_stmt *st, const char *what,
                                  char study[TQ_ID_LEN + 1])
{
    int changed = 0;
    int rc;
    study[0] = '\0';
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        changed = 1;
        if (copy_fixed(q, study, TQ_ID_LEN + 1, st, 0, "study_id") < 0) {
            done_stmt(st);
            return -1;
        }
    }
    if (rc != SQLITE_DONE) {
        set_db_err(q, what);
        done_stmt(st);
        return -1;
    }
    done_stmt(st);
    return changed ? 0 : 1;
}

/* ------------------------------------------------------------------ open/close */

static int exec_sql(sqlite3 *db, const char *sql, char *err, size_t errsize)
{
    char *msg = NULL;
    if (sqlite3_exec(db, sql, NULL, NULL, &msg) != SQLITE_OK) {
        snprintf(err, errsize, "%s: %s", sql, msg ? msg : sqlite3_errmsg(db));
        sqlite3_free(msg);
        return -1;
    }
    return 0;
}

/* Single-value pragma read into text (buf) or integer (*val). */
static int pragma_query(sqlite3 *db, const char *sql, char *buf, size_t bufsize, long *val,
                        char *err, size_t errsize)
{
    sqlite3_stmt *st = NULL;
    if (sqlite3_prepare_v2(db, sql, -1, &st, NULL) != SQLITE_OK) {
        snprintf(err, errsize, "%s: %s", sql, sqlite3_errmsg(db));
        return -1;
    }
    int rc = sqlite3_step(st);
    if (rc == SQLITE_ROW) {
        if (buf) {
            const unsigned char *t = sqlite3_column_text(st, 0);
            snprintf(buf, bufsize, "%s", t ? (const char *)t : "");
        }
        if (val)
            *val = (long)sqlite3_column_int64(st, 0);
        while ((rc = sqlite3_step(st)) == SQLITE_ROW)
            ;
    }
    if (rc != SQLITE_DONE) {
        snprintf(err, errsize, "%s: %s", sql, sqlite3_errmsg(db));
        sqlite3_finalize(st);
        return -1;
    }
    sqlite3_finalize(st);
    return 0;
}

static int migrate(sqlite3 *db, const char *path, char *err, size_t errsize)
{
    if (exec_sql(db, "BEGIN IMMEDIATE", err, errsize) < 0)
        return -1;
    long v = 0;
    if (pragma_query(db, "PRAGMA user_version", NULL, 0, &v, err, errsize) < 0)
        goto fail;
    if (v > SCHEMA_VERSION) {
        snprintf(err, errsize,
                 "%s: database schema version %ld is newer than this daemon supports (%d); "
                 "refusing to open it (use the newer tlsphd or a fresh database)",
                 path, v, SCHEMA_VERSION);
        goto fail;
    }
    for (size_t i = 0; i < N_MIGRATIONS; i++) {
        if (migrations[i].version <= v)
            continue;
        if (exec_sql(db, migrations[i].sql, err, errsize) < 0)
            goto fail;
        char sql[64];
        snprintf(sql, sizeof sql, "PRAGMA user_version = %d", migrations[i].version);
        if (exec_sql(db, sql, err, errsize) < 0)
            goto fail;
    }
    if (exec_sql(db, "COMMIT", err, errsize) < 0)
        goto fail;
    return 0;
fail:
    if (!sqlite3_get_autocommit(db))
        sqlite3_exec(db, "ROLLBACK", NULL, NULL, NULL);
    return -1;
}

static const char *const list_where[3] = {"status = ?1", "study_id = ?2", "process = ?3"};

int tq_open(const char *path, struct tq **out, char *err, size_t errsize)
{
    char dummy[8];
    if (!err || !errsize) {
        err = dummy;
        errsize = sizeof dummy;
    }
    err[0] = '\0';
    if (!out) {
        snprintf(err, errsize, "tq_open: no output handle");
        return -1;
    }
    *out = NULL;
    if (!path || !path[0]) {
        snprintf(err, errsize, "tq_open: empty database path");
        return -1;
    }
    struct tq *q = calloc(1, sizeof *q);
    if (!q) {
        snprintf(err, errsize, "tq_open: out of memory");
        return -1;
    }
    int rc = sqlite3_open_v2(path, &q->db,
                             SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX,
                             NULL);
    if (rc != SQLITE_OK) {
        snprintf(err, errsize, "%s: cannot open database: %s", path,
                 q->db ? sqlite3_errmsg(q->db) : sqlite3_errstr(rc));
        goto fail;
    }
    sqlite3_extended_result_codes(q->db, 1);
    sqlite3_busy_timeout(q->db, 5000);

    /* Refuse a newer schema before touching the file (journal mode is persistent). */
    long v = 0;
    if (pragma_query(q->db, "PRAGMA user_version", NULL, 0, &v, err, errsize) < 0)
        goto fail;
    if (v > SCHEMA_VERSION) {
        snprintf(err, errsize,
                 "%s: database schema version %ld is newer than this daemon supports (%d); "
                 "refusing to open it (use the newer tlsphd or a fresh database)",
                 path, v, SCHEMA_VERSION);
        goto fail;
    }
    char mode[32];
    if (pragma_query(q->db, "PRAGMA journal_mode=WAL", mode, sizeof mode, NULL, err, errsize) < 0)
        goto fail;
    if (strcmp(mode, "wal") != 0) {
        snprintf(err, errsize,
                 "%s: cannot switch the database to WAL mode (journal_mode is \"%s\"); "
                 "the database must be on a local filesystem",
                 path, mode);
        goto fail;
    }
    if (exec_sql(q->db, "PRAGMA synchronous=NORMAL", err, errsize) < 0 ||
        exec_sql(q->db, "PRAGMA foreign_keys=ON", err, errsize) < 0)
        goto fail;
    long fk = 0;
    if (pragma_query(q->db, "PRAGMA foreign_keys", NULL, 0, &fk, err, errsize) < 0)
        goto fail;
    if (fk != 1) {
        snprintf(err, errsize, "%s: SQLite refused to enable foreign keys", path);
        goto fail;
    }
    if (migrate(q->db, path, err, errsize) < 0)
        goto fail;

    for (int i = 0; i < S_COUNT; i++) {
        char sqlbuf[1024];
        const char *sql;
        if (i < S_LIST0) {
            sql = stmt_sql[i];
        } else {
            int mask = i - S_LIST0;
            size_t len = (size_t)snprintf(sqlbuf, sizeof sqlbuf, "SELECT " JOB_COLS " FROM jobs");
            const char *sep = " WHERE ";
            for (int b = 0; b < 3; b++)
                if (mask & (1 << b)) {
                    len += (size_t)snprintf(sqlbuf + len, sizeof sqlbuf - len, "%s%s", sep,
                                            list_where[b]);
                    sep = " AND ";
                }
            snprintf(sqlbuf + len, sizeof sqlbuf - len,
                     " ORDER BY created DESC, rowid DESC LIMIT ?4 OFFSET ?5");
            sql = sqlbuf;
        }
        if (sqlite3_prepare_v3(q->db, sql, -1, SQLITE_PREPARE_PERSISTENT, &q->st[i], NULL) !=
            SQLITE_OK) {
            snprintf(err, errsize, "tq_open: preparing \"%s\": %s", sql, sqlite3_errmsg(q->db));
            goto fail;
        }
    }
    *out = q;
    return 0;
fail:
    tq_close(q);
    return -1;
}

void tq_close(struct tq *q)
{
    if (!q)
        return;
    for (int i = 0; i < S_COUNT; i++)
        sqlite3_finalize(q->st[i]);
    if (q->db)
        sqlite3_close(q->db);
    free(q);
}

/* ------------------------------------------------------------------ insert */

static int check_job_fields(struct tq *q, const char *fn, const struct tq_job *j,
                            const char *want_process)
{
    if (!j) {
        set_err(q, "%s: no job", fn);
        return -1;
    }
    if (check_id(q, fn, j->id) < 0)
        return -1;
    if (strcmp(j->process, "run") != 0 && strcmp(j->process, "study") != 0) {
        set_err(q, "%s: process must be \"run\" or \"study\"", fn);
        return -1;
    }
    if (want_process && strcmp(j->process, want_process) != 0) {
        set_err(q, "%s: job %s must have process \"%s\"", fn, j->id, want_process);
        return -1;
    }
    if (!j->input) {
        set_err(q, "%s: job %s has no input", fn, j->id);
        return -1;
    }
    if (j->study_id[0] && check_id(q, fn, j->study_id) < 0)
        return -1;
    return 0;
}

static int insert_row(struct tq *q, const struct tq_job *j, const char *study_id, long seq,
                      double created)
{
    sqlite3_stmt *st = q->st[S_INSERT];
    bind_text(st, 1, j->id);
    bind_text(st, 2, j->process);
    bind_text(st, 3, study_id && study_id[0] ? study_id : NULL);
    sqlite3_bind_int64(st, 4, seq);
    bind_text(st, 5, j->message);
    bind_text(st, 6, j->input);
    bind_text(st, 7, j->params);
    sqlite3_bind_double(st, 8, created);
    sqlite3_bind_int64(st, 9, j->threads);
    sqlite3_bind_double(st, 10, j->wall_limit);
    char what[TQ_ID_LEN + 32];
    snprintf(what, sizeof what, "inserting job %s", j->id);
    return run_stmt(q, st, what);
}

static int study_refresh_locked(struct tq *q, const char *study_id);

enum tq_rc tq_insert(struct tq *q, const struct tq_job *j)
{
    NEED_Q(q);
    if (check_job_fields(q, "tq_insert", j, NULL) < 0)
        return -1;
    if (tx_begin(q, "tq_insert") < 0)
        return -1;
    int rc = insert_row(q, j, j->study_id, j->study_id[0] ? j->seq : -1, now_seconds());
    /* A child added to an existing study: the study must be one, and is refreshed. */
    if (rc == 0 && j->study_id[0] && study_refresh_locked(q, j->study_id) != 0)
        rc = -1;
    return tx_end(q, "tq_insert", rc);
}

enum tq_rc tq_insert_study(struct tq *q, const struct tq_job *study,
                           const struct tq_job *children, size_t n)
{
    NEED_Q(q);
    if (check_job_fields(q, "tq_insert_study", study, "study") < 0)
        return -1;
    if (n == 0 || !children) {
        set_err(q, "tq_insert_study: a study needs at least one child");
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        if (check_job_fields(q, "tq_insert_study", &children[i], "run") < 0)
            return -1;
    if (tx_begin(q, "tq_insert_study") < 0)
        return -1;
    const double t = now_seconds();
    int rc = insert_row(q, study, NULL, -1, t);
    for (size_t i = 0; rc == 0 && i < n; i++)
        rc = insert_row(q, &children[i], study->id,
                        children[i].seq >= 0 ? children[i].seq : (long)i, t);
    if (rc == 0 && study_refresh_locked(q, study->id) < 0)
        rc = -1;
    return tx_end(q, "tq_insert_study", rc);
}

/* ------------------------------------------------------------------ reads */

enum tq_rc tq_get(struct tq *q, const char *id, struct tq_job *out)
{
    NEED_Q(q);
    if (!out) {
        set_err(q, "tq_get: no output");
        return -1;
    }
    memset(out, 0, sizeof *out);
    if (check_id(q, "tq_get", id) < 0)
        return -1;
    sqlite3_stmt *st = q->st[S_GET];
    bind_text(st, 1, id);
    int rc = sqlite3_step(st);
    if (rc == SQLITE_DONE) {
        done_stmt(st);
        return 1;
    }
    if (rc != SQLITE_ROW) {
        set_db_err(q, "tq_get");
        done_stmt(st);
        return -1;
    }
    if (read_job(q, st, out) < 0) {
        done_stmt(st);
        return -1;
    }
    rc = sqlite3_step(st);
    done_stmt(st);
    if (rc != SQLITE_DONE) {
        set_db_err(q, "tq_get");
        tq_job_free(out);
        return -1;
    }
    return 0;
}

enum tq_rc tq_list(struct tq *q, const char *status, const char *study_id, const char *process,
                   long limit, long offset, struct tq_job **out, size_t *n)
{
    NEED_Q(q);
    if (!out || !n) {
        set_err(q, "tq_list: no output");
        return -1;
    }
    *out = NULL;
    *n = 0;
    if (limit < 1 || limit > 10000) {
        set_err(q, "tq_list: limit must be in 1..10000 (got %ld)", limit);
        return -1;
    }
    if (offset < 0) {
        set_err(q, "tq_list: offset must be >= 0 (got %ld)", offset);
        return -1;
    }
    const char *f[3] = {status, study_id, process};
    int mask = 0;
    for (int b = 0; b < 3; b++)
        if (f[b] && f[b][0])
            mask |= 1 << b;
    sqlite3_stmt *st = q->st[S_LIST0 + mask];
    for (int b = 0; b < 3; b++)
        if (mask & (1 << b))
            bind_text(st, b + 1, f[b]);
    sqlite3_bind_int64(st, 4, limit);
    sqlite3_bind_int64(st, 5, offset);

    struct tq_job *a = NULL;
    size_t cnt = 0, cap = 0;
    int rc;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        if (cnt == cap) {
            size_t ncap = cap ? 2 * cap : 16;
            struct tq_job *na = realloc(a, ncap * sizeof *na);
            if (!na) {
                set_err(q, "tq_list: out of memory");
                goto fail;
            }
            a = na;
            cap = ncap;
        }
        if (read_job(q, st, &a[cnt]) < 0)
            goto fail;
        cnt++;
    }
    if (rc != SQLITE_DONE) {
        set_db_err(q, "tq_list");
        goto fail;
    }
    done_stmt(st);
    *out = a;
    *n = cnt;
    return 0;
fail:
    done_stmt(st);
    for (size_t i = 0; i < cnt; i++)
        tq_job_free(&a[i]);
    free(a);
    return -1;
}

enum tq_rc tq_cancel_requests(struct tq *q, char (**ids)[TQ_ID_LEN + 1], size_t *n)
{
    NEED_Q(q);
    if (!ids || !n) {
        set_err(q, "tq_cancel_requests: no output");
        return -1;
    }
    *ids = NULL;
    *n = 0;
    sqlite3_stmt *st = q->st[S_CANCEL_REQUESTS];
    char (*a)[TQ_ID_LEN + 1] = NULL;
    size_t cnt = 0, cap = 0;
    int rc;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        if (cnt == cap) {
            size_t ncap = cap ? 2 * cap : 8;
            char (*na)[TQ_ID_LEN + 1] = realloc(a, ncap * sizeof *na);
            if (!na) {
                set_err(q, "tq_cancel_requests: out of memory");
                goto fail;
            }
            a = na;
            cap = ncap;
        }
        if (copy_fixed(q, a[cnt], TQ_ID_LEN + 1, st, 0, "id") < 0)
            goto fail;
        cnt++;
    }
    if (rc != SQLITE_DONE) {
        set_db_err(q, "tq_cancel_requests");
        goto fail;
    }
    done_stmt(st);
    *ids = a;
    *n = cnt;
    return 0;
fail:
    done_stmt(st);
    free(a);
    return -1;
}

enum tq_rc tq_counts(struct tq *q, long *accepted, long *running, long *final)
{
    NEED_Q(q);
    sqlite3_stmt *st = q->st[S_COUNTS];
    int rc = sqlite3_step(st);
    if (rc != SQLITE_ROW) {
        set_db_err(q, "tq_counts");
        done_stmt(st);
        return -1;
    }
    if (accepted)
        *accepted = (long)sqlite3_column_int64(st, 0);
    if (running)
        *running = (long)sqlite3_column_int64(st, 1);
    if (final)
        *final = (long)sqlite3_column_int64(st, 2);
    done_stmt(st);
    return 0;
}

/* ------------------------------------------------------------------ studies */

/* Recomputes the study row from its children; caller holds the write transaction.
 * 0, 1 no such study, -1 error. */
static int study_refresh_locked(struct tq *q, const char *study_id)
{
    struct lookup l;
    int rc = lookup(q, study_id, &l);
    if (rc != 0)
        return rc;
    if (strcmp(l.process, "study") != 0) {
        set_err(q, "tq_study_refresh: job %s is not a study", study_id);
        return -1;
    }
    long acc = 0, run = 0, succ = 0, fail = 0, dism = 0;
    double run_progress = 0, started = 0, finished = 0;
    sqlite3_stmt *st = q->st[S_STUDY_AGG];
    bind_text(st, 1, study_id);
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        const char *s = (const char *)sqlite3_column_text(st, 0);
        long c = (long)sqlite3_column_int64(st, 1);
        if (!s)
            continue;
        if (!strcmp(s, TQ_ACCEPTED))
            acc += c;
        else if (!strcmp(s, TQ_RUNNING)) {
            run += c;
            run_progress += sqlite3_column_double(st, 2);
        } else if (!strcmp(s, TQ_SUCCESSFUL))
            succ += c;
        else if (!strcmp(s, TQ_FAILED))
            fail += c;
        else if (!strcmp(s, TQ_DISMISSED))
            dism += c;
        if (sqlite3_column_type(st, 3) != SQLITE_NULL) {
            double s0 = sqlite3_column_double(st, 3);
            if (started == 0 || s0 < started)
                started = s0;
        }
        double f0 = sqlite3_column_double(st, 4);
        if (f0 > finished)
            finished = f0;
    }
    if (rc != SQLITE_DONE) {
        set_db_err(q, "tq_study_refresh");
        done_stmt(st);
        return -1;
    }
    done_stmt(st);

    const long n = acc + run + succ + fail + dism;
    if (n == 0)
        return 0; /* nothing to aggregate; leave the row as it is */
    const long fin = succ + fail + dism;
    const char *status, *outcome = "";
    char msg[128];
    const char *message = msg;
    double progress = (100.0 * (double)fin + run_progress) / (double)n;
    if (fin == n) {
        if (succ == n) {
            status = TQ_SUCCESSFUL;
            outcome = "successful";
            progress = 100.0;
            snprintf(msg, sizeof msg, "all %ld children successful", n);
        } else if (l.cancel_requested) {
            status = TQ_DISMISSED;
            outcome = "cancelled";
            snprintf(msg, sizeof msg, "cancelled: %ld of %ld children failed/dismissed",
                     fail + dism, n);
        } else {
            status = TQ_FAILED;
            snprintf(msg, sizeof msg, "%ld of %ld children failed/dismissed", fail + dism, n);
        }
    } else {
        finished = 0;
        if (acc == n) {
            status = TQ_ACCEPTED;
            message = NULL;
            started = 0;
        } else {
            status = TQ_RUNNING;
            snprintf(msg, sizeof msg, "%ld of %ld children finished", fin, n);
        }
    }
    if (progress < 0)
        progress = 0;
    if (progress > 100)
        progress = 100;
    st = q->st[S_STUDY_UPDATE];
    bind_text(st, 1, study_id);
    bind_text(st, 2, status);
    bind_text(st, 3, outcome);
    bind_text(st, 4, message);
    sqlite3_bind_double(st, 5, progress);
    sqlite3_bind_double(st, 6, started);
    sqlite3_bind_double(st, 7, finished);
    return run_stmt(q, st, "tq_study_refresh: update");
}

enum tq_rc tq_study_refresh(struct tq *q, const char *study_id)
{
    NEED_Q(q);
    if (check_id(q, "tq_study_refresh", study_id) < 0)
        return -1;
    if (tx_begin(q, "tq_study_refresh") < 0)
        return -1;
    return tx_end(q, "tq_study_refresh", study_refresh_locked(q, study_id));
}

/* Refreshes the study of a child when study is non-empty; keeps rc otherwise. */
static int refresh_parent(struct tq *q, const char *study, int rc)
{
    if (rc == 0 && study[0] && study_refresh_locked(q, study) < 0)
        return -1;
    return rc;
}

/* ------------------------------------------------------------------ state changes */

enum tq_rc tq_claim_next(struct tq *q, struct tq_job *out)
{
    NEED_Q(q);
    if (!out) {
        set_err(q, "tq_claim_next: no output");
        return -1;
    }
    memset(out, 0, sizeof *out);
    if (tx_begin(q, "tq_claim_next") < 0)
        return -1;
    sqlite3_stmt *st = q->st[S_CLAIM];
    sqlite3_bind_double(st, 1, now_seconds());
    int rc = sqlite3_step(st), ret;
    if (rc == SQLITE_DONE) {
        ret = 1;
    } else if (rc == SQLITE_ROW) {
        ret = read_job(q, st, out);
        if (ret == 0 && (rc = sqlite3_step(st)) != SQLITE_DONE) {
            set_db_err(q, "tq_claim_next");
            ret = -1;
        }
    } else {
        set_db_err(q, "tq_claim_next");
        ret = -1;
    }
    done_stmt(st);
    if (ret == 0)
        ret = refresh_parent(q, out->study_id, 0);
    ret = tx_end(q, "tq_claim_next", ret);
    if (ret != 0)
        tq_job_free(out);
    return ret;
}

enum tq_rc tq_set_pid(struct tq *q, const char *id, long pid)
{
    NEED_Q(q);
    if (check_id(q, "tq_set_pid", id) < 0)
        return -1;
    if (tx_begin(q, "tq_set_pid") < 0)
        return -1;
    sqlite3_stmt *st = q->st[S_SET_PID];
    bind_text(st, 1, id);
    sqlite3_bind_int64(st, 2, pid);
    int rc = run_stmt(q, st, "tq_set_pid");
    if (rc == 0 && sqlite3_changes(q->db) == 0)
        rc = 1;
    return tx_end(q, "tq_set_pid", rc);
}

enum tq_rc tq_update_progress(struct tq *q, const char *id, double progress, double sim_time,
                              double end_time, long step, double eta)
{
    NEED_Q(q);
    if (check_id(q, "tq_update_progress", id) < 0)
        return -1;
    if (!(progress >= 0)) /* also NaN */
        progress = 0;
    if (progress > 100)
        progress = 100;
    if (tx_begin(q, "tq_update_progress") < 0)
        return -1;
    sqlite3_stmt *st = q->st[S_PROGRESS];
    bind_text(st, 1, id);
    sqlite3_bind_double(st, 2, progress);
    sqlite3_bind_double(st, 3, sim_time);
    sqlite3_bind_double(st, 4, end_time);
    sqlite3_bind_int64(st, 5, step);
    sqlite3_bind_double(st, 6, eta);
    char study[TQ_ID_LEN + 1];
    int rc = update_returning_study(q, st, "tq_update_progress", study);
    return tx_end(q, "tq_update_progress", refresh_parent(q, study, rc));
}

enum tq_rc tq_finish(struct tq *q, const char *id, const char *status, const char *outcome,
                     const char *message, const char *cost_json)
{
    NEED_Q(q);
    if (check_id(q, "tq_finish", id) < 0)
        return -1;
    if (!status || !tq_status_final(status)) {
        set_err(q, "tq_finish: status must be successful, failed or dismissed");
        return -1;
    }
    if (!outcome)
        outcome = "";
    if (strlen(outcome) >= sizeof ((struct tq_job *)0)->outcome) {
        set_err(q, "tq_finish: outcome \"%.32s\" is too long", outcome);
        return -1;
    }
    if (tx_begin(q, "tq_finish") < 0)
        return -1;
    sqlite3_stmt *st = q->st[S_FINISH];
    bind_text(st, 1, id);
    bind_text(st, 2, status);
    bind_text(st, 3, outcome);
    bind_text(st, 4, message);
    bind_text(st, 5, cost_json);
    sqlite3_bind_double(st, 6, now_seconds());
    char study[TQ_ID_LEN + 1];
    int rc = update_returning_study(q, st, "tq_finish", study);
    return tx_end(q, "tq_finish", refresh_parent(q, study, rc));
}

enum tq_rc tq_requeue(struct tq *q, const char *id, const char *message)
{
    NEED_Q(q);
    if (check_id(q, "tq_requeue", id) < 0)
        return -1;
    if (tx_begin(q, "tq_requeue") < 0)
        return -1;
    struct lookup l;
    int rc = lookup(q, id, &l);
    char study[TQ_ID_LEN + 1] = "";
    if (rc == 0 && (strcmp(l.status, TQ_RUNNING) != 0 || strcmp(l.process, "run") != 0))
        rc = 1;
    if (rc == 0 && l.cancel_requested) {
        /* A cancel was pending: honour it instead of running the job again. */
        sqlite3_stmt *st = q->st[S_DISMISS];
        bind_text(st, 1, id);
        bind_text(st, 2, "cancelled (stopped before it finished)");
        sqlite3_bind_double(st, 3, now_seconds());
        rc = run_stmt(q, st, "tq_requeue");
        snprintf(study, sizeof study, "%s", l.study_id);
    } else if (rc == 0) {
        sqlite3_stmt *st = q->st[S_REQUEUE];
        bind_text(st, 1, id);
        bind_text(st, 2, message);
        rc = update_returning_study(q, st, "tq_requeue", study);
    }
    return tx_end(q, "tq_requeue", refresh_parent(q, study, rc));
}

enum tq_rc tq_request_cancel(struct tq *q, const char *id)
{
    NEED_Q(q);
    if (check_id(q, "tq_request_cancel", id) < 0)
        return -1;
    if (tx_begin(q, "tq_request_cancel") < 0)
        return -1;
    struct lookup l;
    int rc = lookup(q, id, &l);
    const double t = now_seconds();
    if (rc != 0 || tq_status_final(l.status))
        return tx_end(q, "tq_request_cancel", rc);
    sqlite3_stmt *st;
    if (!strcmp(l.process, "study")) {
        st = q->st[S_CANCEL_MARK];
        bind_text(st, 1, id);
        rc = run_stmt(q, st, "tq_request_cancel: study");
        if (rc == 0) {
            st = q->st[S_CANCEL_CHILDREN_ACCEPTED];
            bind_text(st, 1, id);
            bind_text(st, 2, "cancelled before it started");
            sqlite3_bind_double(st, 3, t);
            rc = run_stmt(q, st, "tq_request_cancel: children");
        }
        if (rc == 0) {
            st = q->st[S_CANCEL_CHILDREN_RUNNING];
            bind_text(st, 1, id);
            rc = run_stmt(q, st, "tq_request_cancel: children");
        }
        if (rc == 0)
            rc = study_refresh_locked(q, id);
        return tx_end(q, "tq_request_cancel", rc < 0 ? -1 : 0);
    }
    if (!strcmp(l.status, TQ_ACCEPTED)) {
        st = q->st[S_DISMISS];
        bind_text(st, 1, id);
        bind_text(st, 2, "cancelled before it started");
        sqlite3_bind_double(st, 3, t);
        rc = run_stmt(q, st, "tq_request_cancel");
    } else {
        st = q->st[S_CANCEL_MARK];
        bind_text(st, 1, id);
        rc = run_stmt(q, st, "tq_request_cancel");
    }
    return tx_end(q, "tq_request_cancel", refresh_parent(q, l.study_id, rc));
}

enum tq_rc tq_delete(struct tq *q, const char *id)
{
    NEED_Q(q);
    if (check_id(q, "tq_delete", id) < 0)
        return -1;
    if (tx_begin(q, "tq_delete") < 0)
        return -1;
    struct lookup l;
    int rc = lookup(q, id, &l);
    if (rc == 0 && !tq_status_final(l.status))
        rc = 2;
    if (rc == 0 && l.study_id[0]) {
        struct lookup parent;
        int prc = lookup(q, l.study_id, &parent);
        if (prc < 0)
            rc = -1;
        else if (prc == 0 && !tq_status_final(parent.status))
            rc = 2;
    }
    if (rc == 0) {
        sqlite3_stmt *st = q->st[S_DELETE];
        bind_text(st, 1, id);
        rc = run_stmt(q, st, "tq_delete");
    }
    return tx_end(q, "tq_delete", rc);
}

int tq_recover(struct tq *q, int max_attempts)
{
    NEED_Q(q);
    if (tx_begin(q, "tq_recover") < 0)
        return -1;
    const double t = now_seconds();
    long touched = 0;
    int rc = 0;
    sqlite3_stmt *st = q->st[S_RECOVER_CANCELLED];
    sqlite3_bind_double(st, 1, t);
    if (run_stmt(q, st, "tq_recover") < 0)
        rc = -1;
    else
        touched += sqlite3_changes(q->db);
    if (rc == 0) {
        st = q->st[S_RECOVER_REQUEUE];
        sqlite3_bind_int(st, 1, max_attempts);
        if (run_stmt(q, st, "tq_recover") < 0)
            rc = -1;
        else
            touched += sqlite3_changes(q->db);
    }
    if (rc == 0) {
        st = q->st[S_RECOVER_FAIL];
        sqlite3_bind_double(st, 1, t);
        if (run_stmt(q, st, "tq_recover") < 0)
            rc = -1;
        else
            touched += sqlite3_changes(q->db);
    }
    /* Refresh every unfinished study (self-healing after a crash mid-way). */
    char (*ids)[TQ_ID_LEN + 1] = NULL;
    size_t cnt = 0, cap = 0;
    if (rc == 0) {
        int src;
        st = q->st[S_OPEN_STUDIES];
        while ((src = sqlite3_step(st)) == SQLITE_ROW) {
            if (cnt == cap) {
                size_t ncap = cap ? 2 * cap : 8;
                char (*na)[TQ_ID_LEN + 1] = realloc(ids, ncap * sizeof *na);
                if (!na) {
                    set_err(q, "tq_recover: out of memory");
                    rc = -1;
                    break;
                }
                ids = na;
                cap = ncap;
            }
            if (copy_fixed(q, ids[cnt], TQ_ID_LEN + 1, st, 0, "id") < 0) {
                rc = -1;
                break;
            }
            cnt++;
        }
        if (rc == 0 && src != SQLITE_DONE) {
            set_db_err(q, "tq_recover");
            rc = -1;
        }
        done_stmt(st);
    }
    for (size_t i = 0; rc == 0 && i < cnt; i++)
        if (study_refresh_locked(q, ids[i]) < 0)
            rc = -1;
    free(ids);
    if (tx_end(q, "tq_recover", rc) < 0)
        return -1;
    return touched > 2147483647L ? 2147483647 : (int)touched;
}
