/* A study's state from its children (server/queue_study.c): counts per
 * status aggregated in SQL, written to the study's own row in the caller's
 * transaction whenever a child changes. */
#include "queue_internal.h"

#include <stdio.h>
#include <string.h>

/* ------------------------------------------------------------------ studies */

/* Recomputes the study row from its children; caller holds the write transaction.
 * 0, 1 no such study, -1 error. */
int tqi_study_refresh_locked(struct tq *q, const char *study_id)
{
    struct tqi_lookup l;
    int rc = tqi_lookup(q, study_id, &l);
    if (rc != 0)
        return rc;
    if (strcmp(l.process, "study") != 0) {
        tqi_set_err(q, "tq_study_refresh: job %s is not a study", study_id);
        return -1;
    }
    long acc = 0, run = 0, succ = 0, fail = 0, dism = 0;
    double run_progress = 0, dism_progress = 0, started = 0, finished = 0;
    sqlite3_stmt *st = q->st[S_STUDY_AGG];
    TQI_BIND(st, TQI_TEXT(study_id));
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
        else if (!strcmp(s, TQ_DISMISSED)) {
            dism += c;
            dism_progress += sqlite3_column_double(st, 2);
        }
        if (sqlite3_column_type(st, 3) != SQLITE_NULL) {
            double s0 = sqlite3_column_double(st, 3);
            if (started == 0 || s0 < started)
                started = s0;
        }
        double f0 = sqlite3_column_double(st, 4);
        if (f0 > finished)
            finished = f0;
    }
    if (tqi_stmt_end(q, st, rc, "tq_study_refresh") < 0)
        return -1;

    const long n = acc + run + succ + fail + dism;
    if (n == 0)
        return 0; /* nothing to aggregate; leave the row as it is */
    const long fin = succ + fail + dism;
    const char *status, *outcome = "";
    char msg[128];
    const char *message = msg;
    /* Work done: a child that ran to its end (successful or failed) counts
     * 100, a running or dismissed one the progress it reached; so a cancelled
     * study reports how far it got, not 100. */
    double progress = (100.0 * (double)(succ + fail) + run_progress + dism_progress) / (double)n;
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
    TQI_BIND(st, TQI_TEXT(study_id), TQI_TEXT(status), TQI_TEXT(outcome), TQI_TEXT(message),
             TQI_REAL(progress), TQI_REAL(started), TQI_REAL(finished));
    return tqi_run_stmt(q, st, "tq_study_refresh: update");
}

enum tq_rc tq_study_refresh(struct tq *q, const char *study_id)
{
    if (tqi_begin_for(q, "tq_study_refresh", study_id) < 0)
        return TQ_ERROR;
    return tqi_tx_end(q, "tq_study_refresh", tqi_study_refresh_locked(q, study_id));
}

/* Refreshes the study of a child when study is non-empty; keeps rc otherwise. */
int tqi_refresh_parent(struct tq *q, const char *study, int rc)
{
    if (rc == 0 && study[0] && tqi_study_refresh_locked(q, study) < 0)
        return -1;
    return rc;
}

