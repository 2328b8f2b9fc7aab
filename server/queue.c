/* The job queue on SQLite (see queue.h): the schema, every SQL statement,
 * connections and the row helpers.  The operations are in queue_jobs.c and
 * queue_study.c (queue_internal.h); no SQL text lives anywhere else.
 *
 * - One connection per handle, opened READWRITE|CREATE|NOMUTEX; WAL,
 *   synchronous=NORMAL, foreign_keys=ON, busy timeout 5 s.
 * - Schema versioned with PRAGMA user_version; migrations[] applied in order in
 *   one BEGIN IMMEDIATE transaction; a newer database is refused.
 * - Every statement is prepared once (struct tq caches them) and every value is
 *   bound; the only SQL text assembled at run time is the tq_list variants
 *   and tq_list_filtered's statement, built from constant fragments.
 * - Every write runs inside BEGIN IMMEDIATE ... COMMIT (ROLLBACK on error), and
 *   every statement is stepped to completion and reset so no read snapshot is
 *   left open (it would block WAL checkpoints). */
#include "queue_internal.h"

#include <sqlite3.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "errmsg.h"
#include "strbuf.h"

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

static const char *const stmt_sql[S_LIST0] = {
    [S_BEGIN] = "BEGIN IMMEDIATE",
    [S_COMMIT] = "COMMIT",
    [S_ROLLBACK] = "ROLLBACK",
    [S_INSERT] = "INSERT INTO jobs(id, process, study_id, seq, status, message, input, params,"
                 " created, threads, wall_limit, eta)"
                 " VALUES(?1, ?2, ?3, ?4, 'accepted', ?5, ?6, ?7, ?8, ?9, ?10, -1)",
    [S_INSERT_RECOVERED] =
        "INSERT INTO jobs(id, process, status, outcome, message, input, progress, created,"
        " started, finished, attempts, threads, wall_limit, eta)"
        " VALUES(?1, 'run', ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, -1)",
    [S_GET] = "SELECT " JOB_COLS " FROM jobs WHERE id = ?1",
    [S_LOOKUP] = "SELECT process, status, study_id, cancel_requested FROM jobs WHERE id = ?1",
    [S_CLAIM] = "UPDATE jobs SET status='running', attempts=attempts+1, started=?1, outcome=''"
                " WHERE id = (SELECT id FROM jobs WHERE status='accepted' AND process='run'"
                "             ORDER BY created, rowid LIMIT 1)"
                " RETURNING " JOB_COLS,
    [S_CLAIM_STUDY] = "UPDATE jobs SET status='running', attempts=attempts+1, started=?2, outcome=''"
                      " WHERE study_id=?1 AND status='accepted' AND process='run'"
                      " RETURNING " JOB_COLS,
    [S_SET_MESSAGE] = "UPDATE jobs SET message=?2 WHERE id=?1 AND status='running' AND process='run'",
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
                 " TOTAL(status IN " FINAL_SQL ") FROM jobs WHERE process=?1",
};

/* ------------------------------------------------------------------ helpers */

double tqi_now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void tqi_set_err(struct tq *q, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(q->err, sizeof q->err, fmt, ap);
    va_end(ap);
    q->err_code = 0;
}

void tqi_set_db_err(struct tq *q, const char *what)
{
    tqi_set_err(q, "%s: %s", what, sqlite3_errmsg(q->db));
    q->err_code = sqlite3_extended_errcode(q->db);
}

bool tq_disk_full(struct tq *q)
{
    return q && (q->err_code & 0xff) == SQLITE_FULL;
}

const char *tq_last_error(struct tq *q)
{
    return q ? q->err : "no queue handle";
}

int tqi_check_id(struct tq *q, const char *fn, const char *id)
{
    if (job_key_valid(id))
        return 0;
    tqi_set_err(q, "%s: invalid job id (1..%d characters of [0-9A-Za-z_-])", fn, TQ_ID_LEN);
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

void tqi_done_stmt(sqlite3_stmt *st)
{
    sqlite3_reset(st);
    sqlite3_clear_bindings(st);
}

int tqi_bind_text(sqlite3_stmt *st, int i, const char *s)
{
    return s ? sqlite3_bind_text(st, i, s, -1, SQLITE_TRANSIENT) : sqlite3_bind_null(st, i);
}

void tqi_bind_values(sqlite3_stmt *st, const struct tqi_value *v, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        const int at = (int)i + 1;
        switch (v[i].kind) {
        case TQI_V_TEXT:
            tqi_bind_text(st, at, v[i].text);
            break;
        case TQI_V_REAL:
            sqlite3_bind_double(st, at, v[i].real);
            break;
        case TQI_V_INT:
            sqlite3_bind_int64(st, at, v[i].integer);
            break;
        }
    }
}

int tqi_stmt_end(struct tq *q, sqlite3_stmt *st, int rc, const char *what)
{
    if (rc != SQLITE_DONE)
        tqi_set_db_err(q, what); /* before the reset, while the message is the step's */
    tqi_done_stmt(st);
    return rc == SQLITE_DONE ? 0 : -1;
}

/* Steps a statement that returns no rows (or whose rows are ignored) to the end. */
int tqi_run_stmt(struct tq *q, sqlite3_stmt *st, const char *what)
{
    int rc;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW)
        ;
    return tqi_stmt_end(q, st, rc, what);
}

int tqi_tx_begin(struct tq *q, const char *fn)
{
    int rc = sqlite3_step(q->st[S_BEGIN]);
    sqlite3_reset(q->st[S_BEGIN]);
    if (rc != SQLITE_DONE) {
        tqi_set_err(q, "%s: BEGIN IMMEDIATE: %s", fn, sqlite3_errstr(rc));
        q->err_code = rc;
        return -1;
    }
    return 0;
}

int tqi_begin_for(struct tq *q, const char *fn, const char *id)
{
    if (!q || tqi_check_id(q, fn, id) < 0)
        return -1;
    return tqi_tx_begin(q, fn);
}

void tqi_tx_rollback(struct tq *q)
{
    if (!sqlite3_get_autocommit(q->db)) {
        sqlite3_step(q->st[S_ROLLBACK]);
        sqlite3_reset(q->st[S_ROLLBACK]);
    }
}

int tqi_tx_commit(struct tq *q, const char *fn)
{
    int rc = sqlite3_step(q->st[S_COMMIT]);
    sqlite3_reset(q->st[S_COMMIT]);
    if (rc != SQLITE_DONE) {
        tqi_set_err(q, "%s: COMMIT: %s", fn, sqlite3_errstr(rc));
        q->err_code = rc;
        tqi_tx_rollback(q);
        return -1;
    }
    return 0;
}

/* Ends a transaction: commit when rc >= 0, else roll back.  Returns rc, or -1
 * when the commit fails. */
int tqi_tx_end(struct tq *q, const char *fn, int rc)
{
    if (rc < 0) {
        tqi_tx_rollback(q);
        return -1;
    }
    if (tqi_tx_commit(q, fn) < 0)
        return -1;
    return rc;
}

int tqi_copy_fixed(struct tq *q, char *dst, size_t size, sqlite3_stmt *st, int col,
                      const char *name)
{
    const unsigned char *t = sqlite3_column_text(st, col);
    size_t len = t ? (size_t)sqlite3_column_bytes(st, col) : 0;
    if (len >= size) {
        tqi_set_err(q, "stored %s is too long (%zu bytes)", name, len);
        return -1;
    }
    if (len)
        memcpy(dst, t, len);
    dst[len] = '\0';
    return 0;
}

int tqi_copy_dyn(struct tq *q, char **dst, sqlite3_stmt *st, int col)
{
    *dst = NULL;
    if (sqlite3_column_type(st, col) == SQLITE_NULL)
        return 0;
    const unsigned char *t = sqlite3_column_text(st, col);
    if (!t) {
        tqi_set_err(q, "out of memory reading a column");
        return -1;
    }
    size_t len = (size_t)sqlite3_column_bytes(st, col);
    char *s = malloc(len + 1);
    if (!s) {
        tqi_set_err(q, "out of memory (%zu bytes)", len + 1);
        return -1;
    }
    memcpy(s, t, len);
    s[len] = '\0';
    *dst = s;
    return 0;
}

/* Reads a row in JOB_COLS order.  On failure out is freed and zeroed. */
int tqi_read_job(struct tq *q, sqlite3_stmt *st, struct tq_job *out)
{
    memset(out, 0, sizeof *out);
    if (tqi_copy_fixed(q, out->id, sizeof out->id, st, 0, "id") < 0 ||
        tqi_copy_fixed(q, out->process, sizeof out->process, st, 1, "process") < 0 ||
        tqi_copy_fixed(q, out->study_id, sizeof out->study_id, st, 2, "study_id") < 0 ||
        tqi_copy_fixed(q, out->status, sizeof out->status, st, 4, "status") < 0 ||
        tqi_copy_fixed(q, out->outcome, sizeof out->outcome, st, 5, "outcome") < 0 ||
        tqi_copy_dyn(q, &out->message, st, 6) < 0 || tqi_copy_dyn(q, &out->input, st, 7) < 0 ||
        tqi_copy_dyn(q, &out->params, st, 8) < 0 || tqi_copy_dyn(q, &out->cost, st, 9) < 0) {
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

int tqi_read_job_row(struct tq *q, sqlite3_stmt *st, void *row)
{
    return tqi_read_job(q, st, row);
}

void tqi_free_job_row(void *row)
{
    tq_job_free(row);
}

int tqi_read_one(struct tq *q, sqlite3_stmt *st, const char *fn, tqi_read_row_fn *read_row,
                 tqi_free_row_fn *free_row, void *row)
{
    int rc = sqlite3_step(st);
    if (rc == SQLITE_DONE) {
        tqi_done_stmt(st);
        return 1;
    }
    if (rc == SQLITE_ROW) {
        if (read_row(q, st, row) < 0) {
            tqi_done_stmt(st);
            return -1;
        }
        rc = sqlite3_step(st);
        if (rc != SQLITE_DONE && free_row)
            free_row(row);
    }
    return tqi_stmt_end(q, st, rc, fn);
}

int tqi_read_all(struct tq *q, sqlite3_stmt *st, const char *fn, size_t size,
                 tqi_read_row_fn *read_row, tqi_free_row_fn *free_row, void **rows, size_t *n)
{
    char *a = NULL;
    size_t cnt = 0, cap = 0;
    int rc;
    *rows = NULL;
    *n = 0;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        if (cnt == cap) {
            size_t ncap = cap ? 2 * cap : 16;
            char *na = realloc(a, ncap * size);
            if (!na) {
                tqi_set_err(q, "%s: out of memory", fn);
                goto fail;
            }
            a = na;
            cap = ncap;
        }
        if (read_row(q, st, a + cnt * size) < 0)
            goto fail;
        cnt++;
    }
    if (tqi_stmt_end(q, st, rc, fn) < 0)
        goto release;
    *rows = a;
    *n = cnt;
    return 0;
fail:
    tqi_done_stmt(st);
release:
    for (size_t i = 0; free_row && i < cnt; i++)
        free_row(a + i * size);
    free(a);
    return -1;
}

static int read_lookup_row(struct tq *q, sqlite3_stmt *st, void *row)
{
    struct tqi_lookup *l = row;
    if (tqi_copy_fixed(q, l->process, sizeof l->process, st, 0, "process") < 0 ||
        tqi_copy_fixed(q, l->status, sizeof l->status, st, 1, "status") < 0 ||
        tqi_copy_fixed(q, l->study_id, sizeof l->study_id, st, 2, "study_id") < 0)
        return -1;
    l->cancel_requested = sqlite3_column_int(st, 3);
    return 0;
}

/* 0 found, 1 not found, -1 error. */
int tqi_lookup(struct tq *q, const char *id, struct tqi_lookup *l)
{
    sqlite3_stmt *st = q->st[S_LOOKUP];
    memset(l, 0, sizeof *l);
    TQI_BIND(st, TQI_TEXT(id));
    return tqi_read_one(q, st, "lookup", read_lookup_row, NULL, l);
}

/* Runs an UPDATE ... RETURNING study_id with bindings already made.  Returns 0
 * when a row changed (study filled, "" when none), 1 when none, -1 error. */
int tqi_update_returning_study(struct tq *q, sqlite3_stmt *st, const char *what,
                                  char study[TQ_ID_LEN + 1])
{
    int changed = 0;
    int rc;
    study[0] = '\0';
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        changed = 1;
        if (tqi_copy_fixed(q, study, TQ_ID_LEN + 1, st, 0, "study_id") < 0) {
            tqi_done_stmt(st);
            return -1;
        }
    }
    if (tqi_stmt_end(q, st, rc, what) < 0)
        return -1;
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

/* The database's schema version into *v: 0, or -1 when it cannot be read or
 * is newer than this daemon's (which must not touch it). */
static int schema_version(sqlite3 *db, const char *path, long *v, char *err, size_t errsize)
{
    if (pragma_query(db, "PRAGMA user_version", NULL, 0, v, err, errsize) < 0)
        return -1;
    if (*v > SCHEMA_VERSION) {
        snprintf(err, errsize,
                 "%s: database schema version %ld is newer than this daemon supports (%d); "
                 "refusing to open it (use the newer tlsphd or a fresh database)",
                 path, *v, SCHEMA_VERSION);
        return -1;
    }
    return 0;
}

static int migrate(sqlite3 *db, const char *path, char *err, size_t errsize)
{
    if (exec_sql(db, "BEGIN IMMEDIATE", err, errsize) < 0)
        return -1;
    long v = 0;
    if (schema_version(db, path, &v, err, errsize) < 0)
        goto fail;
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

enum tq_rc tq_list_filtered(struct tq *q, const struct tq_filter *f, long limit, long offset,
                            struct tq_job **out, size_t *n)
{
    if (!q || !f || !out || !n || limit < 1 || limit > TQ_LIST_MAX || offset < 0 ||
        f->nstatus > TQ_FILTER_STATUS_MAX) {
        if (q)
            tqi_set_err(q, "tq_list_filtered: bad argument");
        return TQ_ERROR;
    }
    *out = NULL;
    *n = 0;
    /* Constant fragments, every value bound (parameters numbered in order). */
    char sql[1024];
    int np = 0;
    size_t len = (size_t)snprintf(sql, sizeof sql, "SELECT " JOB_COLS " FROM jobs WHERE 1");
#define ADD(text) len += (size_t)snprintf(sql + len, sizeof sql - len, "%s", text)
    if (f->nstatus) {
        ADD(" AND status IN (?");
        for (size_t i = 1; i < f->nstatus; i++)
            ADD(",?");
        ADD(")");
    }
    if (f->study_id && *f->study_id)
        ADD(" AND study_id = ?");
    if (f->process && *f->process)
        ADD(" AND process = ?");
    if (f->has_created_min)
        ADD(" AND created >= ?");
    if (f->has_created_max)
        ADD(" AND created <= ?");
    const char *duration = "(CASE WHEN finished > 0 THEN finished ELSE ? END - started)";
    if (f->has_min_duration) {
        ADD(" AND started > 0 AND ");
        ADD(duration);
        ADD(" >= ?");
    }
    if (f->has_max_duration) {
        ADD(" AND started > 0 AND ");
        ADD(duration);
        ADD(" <= ?");
    }
    ADD(" ORDER BY created DESC, rowid DESC LIMIT ? OFFSET ?");
#undef ADD
    const double now = tqi_now_seconds();
    sqlite3_stmt *st = NULL;
    if (len >= sizeof sql || sqlite3_prepare_v2(q->db, sql, -1, &st, NULL) != SQLITE_OK) {
        tqi_set_err(q, "tq_list_filtered: %s", sqlite3_errmsg(q->db));
        return TQ_ERROR;
    }
    for (size_t i = 0; i < f->nstatus; i++)
        tqi_bind_text(st, ++np, f->status[i]);
    if (f->study_id && *f->study_id)
        tqi_bind_text(st, ++np, f->study_id);
    if (f->process && *f->process)
        tqi_bind_text(st, ++np, f->process);
    if (f->has_created_min)
        sqlite3_bind_double(st, ++np, f->created_min);
    if (f->has_created_max)
        sqlite3_bind_double(st, ++np, f->created_max);
    if (f->has_min_duration) {
        sqlite3_bind_double(st, ++np, now);
        sqlite3_bind_double(st, ++np, f->min_duration);
    }
    if (f->has_max_duration) {
        sqlite3_bind_double(st, ++np, now);
        sqlite3_bind_double(st, ++np, f->max_duration);
    }
    sqlite3_bind_int64(st, ++np, limit);
    sqlite3_bind_int64(st, ++np, offset);
    void *rows;
    int rc = tqi_read_all(q, st, "tq_list_filtered", sizeof **out, tqi_read_job_row,
                          tqi_free_job_row, &rows, n);
    sqlite3_finalize(st);
    if (rc < 0)
        return TQ_ERROR;
    *out = rows;
    return TQ_OK;
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
    if (schema_version(q->db, path, &v, err, errsize) < 0)
        goto fail;
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

enum tq_trust tq_check_file(const char *path, char *report, size_t size)
{
    errmsg_set(report, size, "ok");
    sqlite3 *db = NULL;
    /* READWRITE without CREATE: a missing file is a fresh start; read-write
     * so that a WAL database can be read (its -shm index may need writing) */
    int rc = sqlite3_open_v2(path, &db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX, NULL);
    if (rc == SQLITE_CANTOPEN && access(path, F_OK) != 0) {
        sqlite3_close(db);
        return TQ_TRUSTED;
    }
    enum tq_trust trust = TQ_TRUSTED;
    sqlite3_stmt *st = NULL;
    if (rc == SQLITE_OK) {
        sqlite3_extended_result_codes(db, 1);
        sqlite3_busy_timeout(db, 5000);
        rc = sqlite3_prepare_v2(db, "PRAGMA integrity_check", -1, &st, NULL);
    }
    struct strbuf found = {0};
    int lines = 0;
    while (rc == SQLITE_OK || rc == SQLITE_ROW) {
        rc = sqlite3_step(st);
        if (rc != SQLITE_ROW)
            break;
        const char *t = (const char *)sqlite3_column_text(st, 0);
        if (t && strcmp(t, "ok") != 0 && lines++ < 3)
            strbuf_printf(&found, "%s%s", found.len ? "; " : "", t);
    }
    if (rc != SQLITE_DONE) {
        const int primary = rc & 0xff;
        trust = primary == SQLITE_CORRUPT || primary == SQLITE_NOTADB ? TQ_CORRUPT : TQ_UNREADABLE;
        errmsg_set(report, size, "%s", db ? sqlite3_errmsg(db) : sqlite3_errstr(rc));
    } else if (lines > 0) {
        trust = TQ_CORRUPT;
        errmsg_set(report, size, "%s%s", found.p ? found.p : "damaged",
                   lines > 3 ? "; ..." : "");
    }
    strbuf_free(&found);
    sqlite3_finalize(st);
    sqlite3_close(db);
    return trust;
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

