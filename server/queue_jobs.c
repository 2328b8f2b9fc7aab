/* The queue's job operations (server/queue_jobs.c): inserts, reads and the
 * state changes of run jobs (claim, pid, progress, finish, requeue, cancel,
 * delete, start-up recovery), each in one write transaction; see queue.h for
 * the contract and queue.c for the statements. */
#include "queue_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ insert */

static int check_job_fields(struct tq *q, const char *fn, const struct tq_job *j,
                            const char *want_process)
{
    if (!j) {
        tqi_set_err(q, "%s: no job", fn);
        return -1;
    }
    if (tqi_check_id(q, fn, j->id) < 0)
        return -1;
    if (strcmp(j->process, "run") != 0 && strcmp(j->process, "study") != 0) {
        tqi_set_err(q, "%s: process must be \"run\" or \"study\"", fn);
        return -1;
    }
    if (want_process && strcmp(j->process, want_process) != 0) {
        tqi_set_err(q, "%s: job %s must have process \"%s\"", fn, j->id, want_process);
        return -1;
    }
    if (!j->input) {
        tqi_set_err(q, "%s: job %s has no input", fn, j->id);
        return -1;
    }
    if (j->study_id[0] && tqi_check_id(q, fn, j->study_id) < 0)
        return -1;
    return 0;
}

static int insert_row(struct tq *q, const struct tq_job *j, const char *study_id, long seq,
                      double created)
{
    sqlite3_stmt *st = q->st[S_INSERT];
    TQI_BIND(st, TQI_TEXT(j->id), TQI_TEXT(j->process),
             TQI_TEXT(study_id && study_id[0] ? study_id : NULL), TQI_INT(seq),
             TQI_TEXT(j->message), TQI_TEXT(j->input), TQI_TEXT(j->params), TQI_REAL(created),
             TQI_INT(j->threads), TQI_REAL(j->wall_limit));
    char what[TQ_ID_LEN + 32];
    snprintf(what, sizeof what, "inserting job %s", j->id);
    return tqi_run_stmt(q, st, what);
}

enum tq_rc tq_insert(struct tq *q, const struct tq_job *j)
{
    NEED_Q(q);
    if (check_job_fields(q, "tq_insert", j, NULL) < 0)
        return -1;
    if (tqi_tx_begin(q, "tq_insert") < 0)
        return -1;
    int rc = insert_row(q, j, j->study_id, j->study_id[0] ? j->seq : -1, tqi_now_seconds());
    /* A child added to an existing study: the study must be one, and is refreshed. */
    if (rc == 0 && j->study_id[0] && tqi_study_refresh_locked(q, j->study_id) != 0)
        rc = -1;
    return tqi_tx_end(q, "tq_insert", rc);
}

enum tq_rc tq_insert_study(struct tq *q, const struct tq_job *study,
                           const struct tq_job *children, size_t n)
{
    NEED_Q(q);
    if (check_job_fields(q, "tq_insert_study", study, "study") < 0)
        return -1;
    if (n == 0 || !children) {
        tqi_set_err(q, "tq_insert_study: a study needs at least one child");
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        if (check_job_fields(q, "tq_insert_study", &children[i], "run") < 0)
            return -1;
    if (tqi_tx_begin(q, "tq_insert_study") < 0)
        return -1;
    const double t = tqi_now_seconds();
    int rc = insert_row(q, study, NULL, -1, t);
    for (size_t i = 0; rc == 0 && i < n; i++)
        rc = insert_row(q, &children[i], study->id,
                        children[i].seq >= 0 ? children[i].seq : (long)i, t);
    if (rc == 0 && tqi_study_refresh_locked(q, study->id) < 0)
        rc = -1;
    return tqi_tx_end(q, "tq_insert_study", rc);
}

enum tq_rc tq_insert_recovered(struct tq *q, const struct tq_job *j)
{
    NEED_Q(q);
    if (check_job_fields(q, "tq_insert_recovered", j, "run") < 0)
        return -1;
    if (!tq_status_valid(j->status)) {
        tqi_set_err(q, "tq_insert_recovered: job %s has no valid status", j->id);
        return -1;
    }
    if (tqi_tx_begin(q, "tq_insert_recovered") < 0)
        return -1;
    sqlite3_stmt *st = q->st[S_INSERT_RECOVERED];
    TQI_BIND(st, TQI_TEXT(j->id), TQI_TEXT(j->status), TQI_TEXT(j->outcome), TQI_TEXT(j->message),
             TQI_TEXT(j->input), TQI_REAL(j->progress), TQI_REAL(j->created),
             TQI_REAL(j->started), TQI_REAL(j->finished), TQI_INT(j->attempts),
             TQI_INT(j->threads), TQI_REAL(j->wall_limit));
    return tqi_tx_end(q, "tq_insert_recovered", tqi_run_stmt(q, st, "tq_insert_recovered"));
}

/* ------------------------------------------------------------------ reads */

enum tq_rc tq_has_row(struct tq *q, const char *id)
{
    NEED_Q(q);
    if (tqi_check_id(q, "tq_has_row", id) < 0)
        return -1;
    struct tqi_lookup l;
    return tqi_lookup(q, id, &l);
}

enum tq_rc tq_get(struct tq *q, const char *id, struct tq_job *out)
{
    NEED_Q(q);
    if (!out) {
        tqi_set_err(q, "tq_get: no output");
        return -1;
    }
    memset(out, 0, sizeof *out);
    if (tqi_check_id(q, "tq_get", id) < 0)
        return -1;
    sqlite3_stmt *st = q->st[S_GET];
    TQI_BIND(st, TQI_TEXT(id));
    return tqi_read_one(q, st, "tq_get", tqi_read_job_row, tqi_free_job_row, out);
}

enum tq_rc tq_list(struct tq *q, const char *status, const char *study_id, const char *process,
                   long limit, long offset, struct tq_job **out, size_t *n)
{
    NEED_Q(q);
    if (!out || !n) {
        tqi_set_err(q, "tq_list: no output");
        return -1;
    }
    *out = NULL;
    *n = 0;
    if (limit < 1 || limit > TQ_LIST_MAX) {
        tqi_set_err(q, "tq_list: limit must be in 1..%d (got %ld)", TQ_LIST_MAX, limit);
        return -1;
    }
    if (offset < 0) {
        tqi_set_err(q, "tq_list: offset must be >= 0 (got %ld)", offset);
        return -1;
    }
    const char *f[3] = {status, study_id, process};
    int mask = 0;
    for (int b = 0; b < 3; b++)
        if (f[b] && f[b][0])
            mask |= 1 << b;
    /* The variant for this mask numbers its parameters ?1..?5 but uses only
     * the filters it has, so they are bound by position, not in sequence. */
    sqlite3_stmt *st = q->st[S_LIST0 + mask];
    for (int b = 0; b < 3; b++)
        if (mask & (1 << b))
            tqi_bind_text(st, b + 1, f[b]);
    sqlite3_bind_int64(st, 4, limit);
    sqlite3_bind_int64(st, 5, offset);
    void *rows;
    if (tqi_read_all(q, st, "tq_list", sizeof **out, tqi_read_job_row, tqi_free_job_row, &rows,
                     n) < 0)
        return -1;
    *out = rows;
    return 0;
}

static int read_id_row(struct tq *q, sqlite3_stmt *st, void *row)
{
    return tqi_copy_fixed(q, row, TQ_ID_LEN + 1, st, 0, "id");
}

/* The ids in column 0 of every row of st: 0, or -1 (*ids untouched). */
static int read_ids(struct tq *q, sqlite3_stmt *st, const char *fn, char (**ids)[TQ_ID_LEN + 1],
                    size_t *n)
{
    void *rows;
    if (tqi_read_all(q, st, fn, sizeof **ids, read_id_row, NULL, &rows, n) < 0)
        return -1;
    *ids = rows;
    return 0;
}

enum tq_rc tq_cancel_requests(struct tq *q, char (**ids)[TQ_ID_LEN + 1], size_t *n)
{
    NEED_Q(q);
    if (!ids || !n) {
        tqi_set_err(q, "tq_cancel_requests: no output");
        return -1;
    }
    *ids = NULL;
    return read_ids(q, q->st[S_CANCEL_REQUESTS], "tq_cancel_requests", ids, n);
}

enum tq_rc tq_counts(struct tq *q, long *accepted, long *running, long *final)
{
    return tq_counts_of(q, "run", accepted, running, final);
}

enum tq_rc tq_counts_of(struct tq *q, const char *process, long *accepted, long *running,
                        long *final)
{
    NEED_Q(q);
    sqlite3_stmt *st = q->st[S_COUNTS];
    TQI_BIND(st, TQI_TEXT(process));
    int rc = sqlite3_step(st);
    if (rc != SQLITE_ROW) {
        tqi_set_db_err(q, "tq_counts");
        tqi_done_stmt(st);
        return -1;
    }
    if (accepted)
        *accepted = (long)sqlite3_column_int64(st, 0);
    if (running)
        *running = (long)sqlite3_column_int64(st, 1);
    if (final)
        *final = (long)sqlite3_column_int64(st, 2);
    tqi_done_stmt(st);
    return 0;
}

/* ------------------------------------------------------------------ state changes */

enum tq_rc tq_claim_next(struct tq *q, struct tq_job *out)
{
    NEED_Q(q);
    if (!out) {
        tqi_set_err(q, "tq_claim_next: no output");
        return -1;
    }
    memset(out, 0, sizeof *out);
    if (tqi_tx_begin(q, "tq_claim_next") < 0)
        return -1;
    sqlite3_stmt *st = q->st[S_CLAIM];
    TQI_BIND(st, TQI_REAL(tqi_now_seconds()));
    int ret = tqi_read_one(q, st, "tq_claim_next", tqi_read_job_row, tqi_free_job_row, out);
    if (ret == 0)
        ret = tqi_refresh_parent(q, out->study_id, 0);
    ret = tqi_tx_end(q, "tq_claim_next", ret);
    if (ret != 0)
        tq_job_free(out);
    return ret;
}

enum tq_rc tq_claim_siblings(struct tq *q, const char *study_id, struct tq_job **out, size_t *n)
{
    if (!out || !n) {
        if (q)
            tqi_set_err(q, "tq_claim_siblings: no output");
        return TQ_ERROR;
    }
    *out = NULL;
    *n = 0;
    if (tqi_begin_for(q, "tq_claim_siblings", study_id) < 0)
        return TQ_ERROR;
    sqlite3_stmt *st = q->st[S_CLAIM_STUDY];
    TQI_BIND(st, TQI_TEXT(study_id), TQI_REAL(tqi_now_seconds()));
    void *rows = NULL;
    int rc = tqi_read_all(q, st, "tq_claim_siblings", sizeof **out, tqi_read_job_row,
                          tqi_free_job_row, &rows, n);
    if (rc == 0 && *n > 0)
        rc = tqi_refresh_parent(q, study_id, 0);
    rc = tqi_tx_end(q, "tq_claim_siblings", rc);
    if (rc != 0) {
        tq_jobs_free(rows, *n);
        *n = 0;
        return TQ_ERROR;
    }
    *out = rows;
    return TQ_OK;
}

/* One column of a running run job: statement which with ?1 = id, ?2 = v.
 * TQ_OK, TQ_NOT_FOUND (not a running run), TQ_ERROR. */
static enum tq_rc set_on_running(struct tq *q, const char *fn, enum tqi_stmt which, const char *id,
                                 struct tqi_value v)
{
    if (tqi_begin_for(q, fn, id) < 0)
        return TQ_ERROR;
    sqlite3_stmt *st = q->st[which];
    const struct tqi_value values[2] = {TQI_TEXT(id), v};
    tqi_bind_values(st, values, 2);
    int rc = tqi_run_stmt(q, st, fn);
    if (rc == 0 && sqlite3_changes(q->db) == 0)
        rc = 1;
    return tqi_tx_end(q, fn, rc);
}

enum tq_rc tq_set_message(struct tq *q, const char *id, const char *message)
{
    return set_on_running(q, "tq_set_message", S_SET_MESSAGE, id,
                          (struct tqi_value)TQI_TEXT(message));
}

enum tq_rc tq_set_pid(struct tq *q, const char *id, long pid)
{
    return set_on_running(q, "tq_set_pid", S_SET_PID, id, (struct tqi_value)TQI_INT(pid));
}

enum tq_rc tq_update_progress(struct tq *q, const char *id, double progress, double sim_time,
                              double end_time, long step, double eta)
{
    if (!(progress >= 0)) /* also NaN */
        progress = 0;
    if (progress > 100)
        progress = 100;
    if (tqi_begin_for(q, "tq_update_progress", id) < 0)
        return TQ_ERROR;
    sqlite3_stmt *st = q->st[S_PROGRESS];
    TQI_BIND(st, TQI_TEXT(id), TQI_REAL(progress), TQI_REAL(sim_time), TQI_REAL(end_time),
             TQI_INT(step), TQI_REAL(eta));
    char study[TQ_ID_LEN + 1];
    int rc = tqi_update_returning_study(q, st, "tq_update_progress", study);
    return tqi_tx_end(q, "tq_update_progress", tqi_refresh_parent(q, study, rc));
}

enum tq_rc tq_finish(struct tq *q, const char *id, const char *status, const char *outcome,
                     const char *message, const char *cost_json)
{
    NEED_Q(q);
    if (tqi_check_id(q, "tq_finish", id) < 0)
        return -1;
    if (!status || !tq_status_final(status)) {
        tqi_set_err(q, "tq_finish: status must be successful, failed or dismissed");
        return -1;
    }
    if (!outcome)
        outcome = "";
    if (strlen(outcome) >= sizeof ((struct tq_job *)0)->outcome) {
        tqi_set_err(q, "tq_finish: outcome \"%.32s\" is too long", outcome);
        return -1;
    }
    if (tqi_tx_begin(q, "tq_finish") < 0)
        return -1;
    sqlite3_stmt *st = q->st[S_FINISH];
    TQI_BIND(st, TQI_TEXT(id), TQI_TEXT(status), TQI_TEXT(outcome), TQI_TEXT(message),
             TQI_TEXT(cost_json), TQI_REAL(tqi_now_seconds()));
    char study[TQ_ID_LEN + 1];
    int rc = tqi_update_returning_study(q, st, "tq_finish", study);
    return tqi_tx_end(q, "tq_finish", tqi_refresh_parent(q, study, rc));
}

enum tq_rc tq_requeue(struct tq *q, const char *id, const char *message)
{
    if (tqi_begin_for(q, "tq_requeue", id) < 0)
        return TQ_ERROR;
    struct tqi_lookup l;
    int rc = tqi_lookup(q, id, &l);
    char study[TQ_ID_LEN + 1] = "";
    if (rc == 0 && (strcmp(l.status, TQ_RUNNING) != 0 || strcmp(l.process, "run") != 0))
        rc = 1;
    if (rc == 0 && l.cancel_requested) {
        /* A cancel was pending: honour it instead of running the job again. */
        sqlite3_stmt *st = q->st[S_DISMISS];
        TQI_BIND(st, TQI_TEXT(id), TQI_TEXT("cancelled (stopped before it finished)"),
                 TQI_REAL(tqi_now_seconds()));
        rc = tqi_run_stmt(q, st, "tq_requeue");
        snprintf(study, sizeof study, "%s", l.study_id);
    } else if (rc == 0) {
        sqlite3_stmt *st = q->st[S_REQUEUE];
        TQI_BIND(st, TQI_TEXT(id), TQI_TEXT(message));
        rc = tqi_update_returning_study(q, st, "tq_requeue", study);
    }
    return tqi_tx_end(q, "tq_requeue", tqi_refresh_parent(q, study, rc));
}

enum tq_rc tq_request_cancel(struct tq *q, const char *id)
{
    if (tqi_begin_for(q, "tq_request_cancel", id) < 0)
        return TQ_ERROR;
    struct tqi_lookup l;
    int rc = tqi_lookup(q, id, &l);
    const double t = tqi_now_seconds();
    if (rc != 0 || tq_status_final(l.status))
        return tqi_tx_end(q, "tq_request_cancel", rc);
    sqlite3_stmt *st;
    if (!strcmp(l.process, "study")) {
        st = q->st[S_CANCEL_MARK];
        TQI_BIND(st, TQI_TEXT(id));
        rc = tqi_run_stmt(q, st, "tq_request_cancel: study");
        if (rc == 0) {
            st = q->st[S_CANCEL_CHILDREN_ACCEPTED];
            TQI_BIND(st, TQI_TEXT(id), TQI_TEXT("cancelled before it started"), TQI_REAL(t));
            rc = tqi_run_stmt(q, st, "tq_request_cancel: children");
        }
        if (rc == 0) {
            st = q->st[S_CANCEL_CHILDREN_RUNNING];
            TQI_BIND(st, TQI_TEXT(id));
            rc = tqi_run_stmt(q, st, "tq_request_cancel: children");
        }
        if (rc == 0)
            rc = tqi_study_refresh_locked(q, id);
        return tqi_tx_end(q, "tq_request_cancel", rc < 0 ? -1 : 0);
    }
    if (!strcmp(l.status, TQ_ACCEPTED)) {
        st = q->st[S_DISMISS];
        TQI_BIND(st, TQI_TEXT(id), TQI_TEXT("cancelled before it started"), TQI_REAL(t));
        rc = tqi_run_stmt(q, st, "tq_request_cancel");
    } else {
        st = q->st[S_CANCEL_MARK];
        TQI_BIND(st, TQI_TEXT(id));
        rc = tqi_run_stmt(q, st, "tq_request_cancel");
    }
    return tqi_tx_end(q, "tq_request_cancel", tqi_refresh_parent(q, l.study_id, rc));
}

enum tq_rc tq_delete(struct tq *q, const char *id)
{
    if (tqi_begin_for(q, "tq_delete", id) < 0)
        return TQ_ERROR;
    struct tqi_lookup l;
    int rc = tqi_lookup(q, id, &l);
    if (rc == 0 && !tq_status_final(l.status))
        rc = 2;
    if (rc == 0 && l.study_id[0]) {
        struct tqi_lookup parent;
        int prc = tqi_lookup(q, l.study_id, &parent);
        if (prc < 0)
            rc = -1;
        else if (prc == 0 && !tq_status_final(parent.status))
            rc = 2;
    }
    if (rc == 0) {
        sqlite3_stmt *st = q->st[S_DELETE];
        TQI_BIND(st, TQI_TEXT(id));
        rc = tqi_run_stmt(q, st, "tq_delete");
    }
    return tqi_tx_end(q, "tq_delete", rc);
}

/* One recovery statement, bound: 0, or -1; adds the rows it changed to *touched. */
static int run_counted(struct tq *q, sqlite3_stmt *st, long *touched)
{
    if (tqi_run_stmt(q, st, "tq_recover") < 0)
        return -1;
    *touched += sqlite3_changes(q->db);
    return 0;
}

int tq_recover(struct tq *q, int max_attempts)
{
    NEED_Q(q);
    if (tqi_tx_begin(q, "tq_recover") < 0)
        return -1;
    const double t = tqi_now_seconds();
    long touched = 0;
    sqlite3_stmt *st = q->st[S_RECOVER_CANCELLED];
    TQI_BIND(st, TQI_REAL(t));
    int rc = run_counted(q, st, &touched);
    if (rc == 0) {
        st = q->st[S_RECOVER_REQUEUE];
        TQI_BIND(st, TQI_INT(max_attempts));
        rc = run_counted(q, st, &touched);
    }
    if (rc == 0) {
        st = q->st[S_RECOVER_FAIL];
        TQI_BIND(st, TQI_REAL(t));
        rc = run_counted(q, st, &touched);
    }
    /* Refresh every unfinished study (self-healing after a crash mid-way). */
    char (*ids)[TQ_ID_LEN + 1] = NULL;
    size_t cnt = 0;
    if (rc == 0)
        rc = read_ids(q, q->st[S_OPEN_STUDIES], "tq_recover", &ids, &cnt);
    for (size_t i = 0; rc == 0 && i < cnt; i++)
        if (tqi_study_refresh_locked(q, ids[i]) < 0)
            rc = -1;
    free(ids);
    if (tqi_tx_end(q, "tq_recover", rc) < 0)
        return -1;
    return touched > 2147483647L ? 2147483647 : (int)touched;
}
