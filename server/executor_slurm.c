/* The Slurm executor, see executor_slurm.h.  Everything here runs on the
 * supervisor thread; the runs it watches are in sx.jobs. */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include "executor_slurm.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <jansson.h>

#include "config.h"
#include "engine_report.h"
#include "errmsg.h"
#include "executor.h"
#include "finals.h"
#include "jobdir.h"
#include "queue.h"
#include "result_repair.h"
#include "slurm_cmd.h"
#include "slurm_record.h"
#include "slurm_resources.h"
#include "slurm_state.h"
#include "slurm_submit.h"
#include "util/clock.h"

#define TICK_MS 200            /* the loop's poll timeout */
#define SQUEUE_TIMEOUT 30.0    /* s */
#define SCANCEL_TIMEOUT 30.0   /* s */
#define SUBMIT_BACKOFF 30.0    /* s without claims after sbatch refused */
#define END_GRACE 30.0         /* s to wait for the other witness of an end
                                * (the exit status over NFS, Slurm's state) */

struct sjob {
    char id[JOB_ID_LEN + 1];
    char slurm[SLURM_ID_MAX];  /* "123" or "123_4"; "" unknown (found by its exit status) */
    char state[32];            /* Slurm's state at the last look, "" none yet */
    char message[320];         /* the message written last */
    off_t offset;              /* bytes of progress.jsonl read */
    struct engine_report report;
    bool pending;              /* progress not yet written */
    bool cancel_sent;
    double t_wait;             /* monotonic time a wait for a second witness began, 0 none */
    double wall_limit;
    int attempts;
    long mem_mb;               /* asked of Slurm, 0 unknown (adopted) */
    long time_min;
};

struct sx {
    const struct texec_host *h;
    const struct tcfg *cfg;
    struct sjob *jobs;
    size_t n, cap;
    char uid[32];
    char h5clear[PATH_MAX];
    double t_poll, t_backoff;
    bool squeue_failing;
};

/* The wait status a shell's exit code stands for (128 + n: killed by signal n). */
static int wait_status_of(int rc)
{
    return rc > 128 && rc < 128 + 65 ? rc - 128 : (rc & 0xff) << 8;
}

static int job_file(const struct sx *x, const char *id, enum jobdir_file f, char *buf, size_t size)
{
    return jobdir_path(buf, size, x->h->jobs_dir, id, f);
}

/* ------------------------------------------------------------------ progress */

static void flush_progress(struct sx *x, struct sjob *j)
{
    if (!j->pending)
        return;
    const struct engine_report *r = &j->report;
    double p = r->end_time > 0 ? 100.0 * r->sim_time / r->end_time : 0.0;
    p = p < 0 ? 0 : p > 100 ? 100 : p;
    if (tq_update_progress(x->h->q, j->id, p, r->sim_time, r->end_time, r->step, r->eta) == TQ_ERROR)
        tlog("slurm: job %s: cannot update progress: %s", j->id, tq_last_error(x->h->q));
    j->pending = false;
}

/* Reads what the engine appended to progress.jsonl since the last read. */
static void read_progress(struct sx *x, struct sjob *j)
{
    char path[PATH_MAX], buf[8192];
    if (job_file(x, j->id, JOBDIR_PROGRESS, path, sizeof path) < 0)
        return;
    const int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return;
    for (;;) {
        const ssize_t n = pread(fd, buf, sizeof buf, j->offset);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        j->offset += n;
        j->pending |= engine_report_feed(&j->report, buf, (size_t)n);
    }
    close(fd);
}

static void set_message(struct sx *x, struct sjob *j, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void set_message(struct sx *x, struct sjob *j, const char *fmt, ...)
{
    char m[sizeof j->message];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(m, sizeof m, fmt, ap);
    va_end(ap);
    if (!strcmp(m, j->message))
        return;
    if (tq_set_message(x->h->q, j->id, m) == TQ_ERROR)
        tlog("slurm: job %s: cannot set its message: %s", j->id, tq_last_error(x->h->q));
    else
        snprintf(j->message, sizeof j->message, "%s", m);
}

/* ------------------------------------------------------------------ the set */

static struct sjob *track(struct sx *x, const char *id, const char *slurm, int attempts,
                          double wall_limit, double end_time)
{
    if (x->n == x->cap) {
        const size_t cap = x->cap ? 2 * x->cap : 64;
        struct sjob *a = realloc(x->jobs, cap * sizeof *a);
        if (!a)
            return NULL;
        x->jobs = a;
        x->cap = cap;
    }
    struct sjob *j = &x->jobs[x->n++];
    memset(j, 0, sizeof *j);
    snprintf(j->id, sizeof j->id, "%s", id);
    snprintf(j->slurm, sizeof j->slurm, "%s", slurm);
    j->attempts = attempts;
    j->wall_limit = wall_limit;
    engine_report_init(&j->report, end_time);
    return j;
}

static void untrack(struct sx *x, struct sjob *j)
{
    engine_report_free(&j->report);
    *j = x->jobs[--x->n];
}

/* Runs id again, or fails it when it has had its attempts. */
static void requeue_or_fail(struct sx *x, const char *id, int attempts, const char *why);

/* The same for a watched run, which is forgotten. */
static void requeue_watched(struct sx *x, struct sjob *j, const char *why)
{
    const int attempts = j->attempts;
    char id[JOB_ID_LEN + 1];
    snprintf(id, sizeof id, "%s", j->id);
    untrack(x, j);
    requeue_or_fail(x, id, attempts, why);
}

static void requeue_or_fail(struct sx *x, const char *id, int attempts, const char *why)
{
    if (attempts >= x->h->max_attempts) {
        char m[512];
        snprintf(m, sizeof m, "%s; not run again after %d attempts", why, attempts);
        finals_record(x->h->finals, x->h->q, id, TQ_FAILED, "interrupted", m, NULL);
        return;
    }
    char m[512];
    snprintf(m, sizeof m, "%s; requeued (attempt %d of %d)", why, attempts, x->h->max_attempts);
    tlog("slurm: job %s: %s", id, m);
    if (tq_requeue(x->h->q, id, m) == TQ_ERROR)
        tlog("slurm: job %s: cannot requeue: %s", id, tq_last_error(x->h->q));
}

/* Ends a watched run (and forgets it): status etc. as finals_record. */
static void end_job(struct sx *x, struct sjob *j, const char *status, const char *outcome,
                    char *message)
{
    read_progress(x, j);
    if (engine_report_eof(&j->report))
        j->pending = true;
    struct engine_report *r = &j->report;
    if (!strcmp(status, TQ_SUCCESSFUL)) {
        r->sim_time = r->end_time > 0 ? r->end_time : r->sim_time;
        r->eta = 0;
        j->pending = true;
    }
    flush_progress(x, j);
    char rmsg[512];
    const enum result_repair_rc rr = result_repair_job(x->h5clear, x->h->jobs_dir, j->id, rmsg, sizeof rmsg);
    if (rr != RESULT_NOTHING_TO_DO)
        tlog("slurm: job %s: result.h5 left open by the engine%s: %s", j->id,
             rr == RESULT_REPAIRED ? "" : ", not repaired", rmsg);
    finals_record(x->h->finals, x->h->q, j->id, status, outcome, message, r->cost);
    free(message);
    untrack(x, j);
}

/* The run ended by the engine's exit status rc. */
static void end_by_exit(struct sx *x, struct sjob *j, int rc)
{
    read_progress(x, j);
    engine_report_eof(&j->report);
    struct engine_outcome out;
    engine_outcome(&j->report, wait_status_of(rc),
                   j->cancel_sent ? ENGINE_STOP_CANCEL : ENGINE_NOT_STOPPED, j->wall_limit, &out);
    end_job(x, j, out.status, out.outcome, out.message);
}

/* The run ended by Slurm (state st). */
static void end_by_slurm(struct sx *x, struct sjob *j, const struct slurm_state *st)
{
    char limit[64] = "";
    if (!strcmp(st->name, "TIMEOUT"))
        snprintf(limit, sizeof limit, " (--time=%ld min)", j->time_min);
    else if (!strcmp(st->name, "OUT_OF_MEMORY") && j->mem_mb > 0)
        snprintf(limit, sizeof limit, " (--mem=%ldM)", j->mem_mb);
    if (st->phase == SLURM_CANCELLED) {
        end_job(x, j, TQ_DISMISSED, "cancelled",
                errmsg_format(j->cancel_sent ? "cancelled (Slurm job %s: CANCELLED)"
                                             : "Slurm job %s: CANCELLED, not through tlsphd",
                              j->slurm));
        return;
    }
    end_job(x, j, TQ_FAILED, st->outcome,
            errmsg_format("Slurm job %s: %s: %s%s", j->slurm, st->name, st->meaning,
                          j->time_min || j->mem_mb ? limit : ""));
}

/* ------------------------------------------------------------------ Slurm */

/* The user's jobs in Slurm, all states: 0, or -1 (squeue failed; logged once). */
static int query_queue(struct sx *x, struct slurm_queue_row **rows, size_t *n)
{
    char *argv[] = {(char *)"squeue", (char *)"--noheader", (char *)"--array",
                    (char *)"--states=all", (char *)"--user", x->uid,
                    (char *)"--format=" SLURM_QUEUE_FORMAT, NULL};
    struct slurm_cmd_result r;
    const int st = slurm_cmd_run(argv, NULL, SQUEUE_TIMEOUT, &r);
    int rc = -1;
    if (st == 0) {
        rc = slurm_queue_parse(r.out.p, rows, n);
        if (x->squeue_failing)
            tlog("slurm: squeue answers again");
        x->squeue_failing = false;
    } else if (!x->squeue_failing) {
        char why[300];
        tlog("slurm: squeue failed: %s (the runs keep their state until it answers)",
             slurm_cmd_why(&r, why, sizeof why));
        x->squeue_failing = true;
    }
    slurm_cmd_free(&r);
    return rc;
}

#define SCANCEL_BATCH 100 /* Slurm ids per scancel call */

/* One scancel for the runs js[0..n) (a cancelled study's children go
 * together); a failure is tried again at the next poll. */
static void send_cancels(struct sjob **js, size_t n)
{
    char *argv[SCANCEL_BATCH + 2];
    size_t k = 0;
    argv[k++] = (char *)"scancel";
    for (size_t i = 0; i < n; i++)
        argv[k++] = js[i]->slurm;
    argv[k] = NULL;
    struct slurm_cmd_result r;
    const bool ok = slurm_cmd_run(argv, NULL, SCANCEL_TIMEOUT, &r) == 0;
    char why[300];
    if (!ok)
        slurm_cmd_why(&r, why, sizeof why);
    for (size_t i = 0; i < n; i++) {
        if (ok)
            tlog("slurm: job %s: scancel %s", js[i]->id, js[i]->slurm);
        else
            tlog("slurm: job %s: scancel %s failed: %s", js[i]->id, js[i]->slurm, why);
        js[i]->cancel_sent = ok;
    }
    slurm_cmd_free(&r);
}

static void check_cancels(struct sx *x)
{
    char (*ids)[TQ_ID_LEN + 1] = NULL;
    size_t n = 0;
    if (x->n == 0 || tq_cancel_requests(x->h->q, &ids, &n) == TQ_ERROR)
        return;
    struct sjob *batch[SCANCEL_BATCH];
    size_t nb = 0;
    for (size_t k = 0; k < n; k++)
        for (size_t i = 0; i < x->n; i++) {
            struct sjob *j = &x->jobs[i];
            if (j->cancel_sent || strcmp(j->id, ids[k]) != 0)
                continue;
            if (!j->slurm[0]) {
                j->cancel_sent = true; /* no Slurm id: its exit status ends it */
                continue;
            }
            batch[nb++] = j;
            if (nb == SCANCEL_BATCH) {
                send_cancels(batch, nb);
                nb = 0;
            }
        }
    if (nb > 0)
        send_cancels(batch, nb);
    free(ids);
}

/* One look at a watched run; true when it ended (and is gone from the set). */
static bool look_at(struct sx *x, struct sjob *j, const struct slurm_queue_row *row, double now)
{
    read_progress(x, j);
    flush_progress(x, j);
    const int rc = slurm_exit_read(x->h->jobs_dir, j->id);
    const struct slurm_state *st = row ? slurm_state_of(row->state) : NULL;
    if (row)
        snprintf(j->state, sizeof j->state, "%s", row->state);
    const bool waited = j->t_wait > 0 && now - j->t_wait >= END_GRACE;
    char why[200];
    switch (slurm_verdict(rc, st, waited)) {
    case SLURM_WATCH:
        j->t_wait = 0;
        if (st && st->phase == SLURM_WAITING)
            set_message(x, j, "Slurm job %s: %s (%s)", j->slurm, row->state, row->reason);
        else if (row)
            set_message(x, j, "Slurm job %s: %s on %s", j->slurm, row->state, row->nodes);
        return false;
    case SLURM_WAIT: /* one witness of the end: a little time for the other */
        if (j->t_wait == 0)
            j->t_wait = now;
        return false;
    case SLURM_END_BY_EXIT:
        end_by_exit(x, j, rc);
        return true;
    case SLURM_END_BY_SLURM:
        end_by_slurm(x, j, st);
        return true;
    case SLURM_END_NO_STATUS:
        end_job(x, j, TQ_FAILED, "crashed",
                errmsg_format("Slurm job %s: %s and left no exit status: the batch script did "
                              "not finish (see the job's log.txt and %s/.slurm/)",
                              j->slurm, row->state, x->h->jobs_dir));
        return true;
    case SLURM_REQUEUE_NODE:
        snprintf(why, sizeof why, "Slurm job %s: %s: %s", j->slurm, st->name, st->meaning);
        requeue_watched(x, j, why);
        return true;
    case SLURM_REQUEUE_GONE:
        snprintf(why, sizeof why, "Slurm job %s is gone from the queue and left no exit status",
                 j->slurm);
        requeue_watched(x, j, why);
        return true;
    }
    return false;
}

static void poll_all(struct sx *x, double now)
{
    x->t_poll = now;
    check_cancels(x);
    struct slurm_queue_row *rows = NULL;
    size_t nrows = 0;
    if (query_queue(x, &rows, &nrows) < 0) {
        for (size_t i = 0; i < x->n; i++) {
            read_progress(x, &x->jobs[i]);
            flush_progress(x, &x->jobs[i]);
        }
        return;
    }
    for (size_t i = 0; i < x->n;) {
        struct sjob *j = &x->jobs[i];
        const struct slurm_queue_row *row = j->slurm[0] ? slurm_queue_find(rows, nrows, j->slurm) : NULL;
        if (!look_at(x, j, row, now))
            i++; /* else the last one moved into slot i */
    }
    free(rows);
}

/* ------------------------------------------------------------------ submission */

/* The study's max_parallel (its request), else slurm_array_limit. */
static long array_limit(struct sx *x, const char *study_id)
{
    struct tq_job s;
    long limit = x->cfg->slurm_array_limit;
    if (tq_get(x->h->q, study_id, &s) == TQ_OK && s.input) {
        json_t *doc = json_loads(s.input, 0, NULL);
        json_t *mp = json_object_get(doc, "max_parallel");
        if (json_is_integer(mp) && json_integer_value(mp) > 0)
            limit = (long)json_integer_value(mp);
        json_decref(doc);
    }
    tq_job_free(&s);
    return limit;
}

/* Prepares one claimed run: clears its outputs and sizes it.  False when it
 * cannot run (finished as failed here). */
static bool prepare(struct sx *x, const struct tq_job *j, struct slurm_resources *res)
{
    char err[400];
    if (jobdir_clear_outputs(x->h->jobs_dir, j->id) < 0) {
        finals_record(x->h->finals, x->h->q, j->id, TQ_FAILED, "io_error",
                      "cannot remove the outputs of an earlier attempt", NULL);
        return false;
    }
    const long threads = j->threads > 0 ? j->threads : x->h->threads_per_job;
    const double wall = j->wall_limit > 0 ? j->wall_limit : x->h->wall_limit;
    if (slurm_resources_of(j->input ? j->input : "", x->cfg, threads, wall, res, err, sizeof err) < 0) {
        finals_record(x->h->finals, x->h->q, j->id, TQ_FAILED, "invalid", err, NULL);
        return false;
    }
    return true;
}

/* Submits the claimed runs js[0..n) as one Slurm job (array when study). */
static void submit(struct sx *x, struct tq_job *js, size_t n, bool array)
{
    const char **ids = calloc(n, sizeof *ids);
    struct tq_job **ok = calloc(n, sizeof *ok);
    if (!ids || !ok) {
        for (size_t i = 0; i < n; i++)
            requeue_or_fail(x, js[i].id, js[i].attempts, "out of memory at submission");
        free(ids);
        free(ok);
        return;
    }
    struct slurm_resources res = {0}, one;
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (prepare(x, &js[i], &one)) {
            slurm_resources_max(&res, &one);
            ok[m] = &js[i];
            ids[m++] = js[i].id;
        }
    char name[SLURM_NAME_MAX], err[400], task[SLURM_TASK_MAX], slurm[SLURM_ID_MAX], sid[32];
    if (m > 0)
        snprintf(name, sizeof name, "tlsph-%s-%d", ok[0]->id, ok[0]->attempts);
    size_t recorded = 0;
    for (; recorded < m; recorded++) {
        snprintf(task, sizeof task, array ? "%zu" : "-", recorded);
        if (slurm_record_write(x->h->jobs_dir, ids[recorded], name, task, "-", err, sizeof err) < 0)
            break;
    }
    int rc = -1;
    if (m > 0 && recorded == m) {
        const struct slurm_submission sub = {
            .name = name, .jobs_dir = x->h->jobs_dir, .engine = x->h->engine_path,
            .ids = ids, .n = m, .array = array,
            .array_limit = array && ok[0]->study_id[0] ? array_limit(x, ok[0]->study_id) : 0,
            .res = res, .cfg = x->cfg};
        rc = slurm_submit(&sub, sid, sizeof sid, err, sizeof err);
    } else if (m > 0) {
        char why[sizeof err];
        snprintf(why, sizeof why, "%s", err);
        errmsg_set(err, sizeof err, "cannot write the slurm_job record: %s", why);
    }
    if (rc < 0 && m > 0) {
        tlog("slurm: %s (%zu run(s) requeued; no submission for %g s)", err, m, SUBMIT_BACKOFF);
        x->t_backoff = tlsph_monotonic_seconds();
        for (size_t i = 0; i < m; i++)
            requeue_or_fail(x, ok[i]->id, ok[i]->attempts, err);
    }
    for (size_t i = 0; rc == 0 && i < m; i++) {
        snprintf(task, sizeof task, array ? "%zu" : "-", i);
        if (array)
            snprintf(slurm, sizeof slurm, "%s_%zu", sid, i);
        else
            snprintf(slurm, sizeof slurm, "%s", sid);
        /* the id is also found by name if this write is lost (a crash) */
        if (slurm_record_write(x->h->jobs_dir, ids[i], name, task, slurm, err, sizeof err) < 0)
            tlog("slurm: job %s: %s", ids[i], err);
        struct sjob *j = track(x, ids[i], slurm, ok[i]->attempts,
                               ok[i]->wall_limit > 0 ? ok[i]->wall_limit : x->h->wall_limit,
                               ok[i]->end_time);
        if (!j) {
            tlog("slurm: job %s: out of memory; it is adopted again at the next start", ids[i]);
            continue;
        }
        j->mem_mb = res.mem_mb;
        j->time_min = res.time_min;
        set_message(x, j, "Slurm job %s: submitted", slurm);
    }
    if (rc == 0)
        tlog("slurm: submitted %s as Slurm job %s (%zu run(s), %ld cpus, %ld MiB, %ld min)", name,
             sid, m, res.cpus, res.mem_mb, res.time_min);
    free(ids);
    free(ok);
}

/* Whether a refused sbatch holds submissions back. */
static bool backing_off(const struct sx *x)
{
    return x->t_backoff > 0 && tlsph_monotonic_seconds() - x->t_backoff < SUBMIT_BACKOFF;
}

static void claim_and_submit(struct sx *x)
{
    if (x->h->room && !x->h->room(x->h->sup))
        return;
    while (!atomic_load(x->h->stop) && !backing_off(x)) {
        struct tq_job first;
        memset(&first, 0, sizeof first);
        if (tq_claim_next(x->h->q, &first) != TQ_OK)
            return;
        if (!first.study_id[0]) {
            submit(x, &first, 1, false);
            tq_job_free(&first);
            continue;
        }
        struct tq_job *rest = NULL;
        size_t nrest = 0;
        if (tq_claim_siblings(x->h->q, first.study_id, &rest, &nrest) == TQ_ERROR)
            tlog("slurm: study %s: cannot claim its other children: %s", first.study_id,
                 tq_last_error(x->h->q));
        struct tq_job *all = calloc(nrest + 1, sizeof *all);
        if (!all) {
            requeue_or_fail(x, first.id, first.attempts, "out of memory at submission");
            for (size_t i = 0; i < nrest; i++)
                requeue_or_fail(x, rest[i].id, rest[i].attempts, "out of memory at submission");
        } else {
            all[0] = first; /* moved: the array owns the strings now */
            memset(&first, 0, sizeof first);
            for (size_t i = 0; i < nrest; i++)
                all[i + 1] = rest[i];
            free(rest);
            rest = NULL;
            submit(x, all, nrest + 1, true);
            tq_jobs_free(all, nrest + 1);
            nrest = 0;
        }
        tq_jobs_free(rest, nrest);
        tq_job_free(&first);
    }
}

/* ------------------------------------------------------------------ adoption */

/* The Slurm id of task of submission name in rows, "" when Slurm has none. */
static void find_by_name(const struct slurm_queue_row *rows, size_t n, const char *name,
                         const char *task, char *slurm, size_t size)
{
    slurm[0] = '\0';
    for (size_t i = 0; i < n; i++) {
        if (strcmp(rows[i].name, name) != 0)
            continue;
        const char *us = strchr(rows[i].id, '_');
        if (!strcmp(task, "-") && !us) {
            snprintf(slurm, size, "%s", rows[i].id);
            return;
        }
        if (us && !strcmp(us + 1, task)) {
            snprintf(slurm, size, "%s", rows[i].id);
            return;
        }
    }
}

/* Every run the queue has as running: watched again, or requeued when it
 * never reached Slurm (executor_slurm.h, "restart"). */
static void adopt(struct sx *x)
{
    struct tq_job *js = NULL;
    size_t n = 0;
    if (tq_list(x->h->q, TQ_RUNNING, NULL, "run", TQ_LIST_MAX, 0, &js, &n) == TQ_ERROR) {
        tlog("slurm: cannot list the running jobs: %s", tq_last_error(x->h->q));
        return;
    }
    struct slurm_queue_row *rows = NULL;
    size_t nrows = 0;
    const bool have_queue = n > 0 && query_queue(x, &rows, &nrows) == 0;
    long adopted = 0, requeued = 0;
    for (size_t i = 0; i < n; i++) {
        const struct tq_job *j = &js[i];
        char name[SLURM_NAME_MAX] = "", task[SLURM_TASK_MAX] = "", slurm[SLURM_ID_MAX] = "";
        const int r = slurm_record_read(x->h->jobs_dir, j->id, name, task, slurm);
        bool found = false;
        if (r > 0 && !strcmp(slurm, "-")) {
            if (!have_queue) {
                tlog("slurm: job %s: squeue does not answer; its submission is looked up at the "
                     "next start", j->id);
                continue; /* stays running, unwatched: never submitted twice */
            }
            find_by_name(rows, nrows, name, task, slurm, sizeof slurm);
            found = slurm[0] != '\0';
            if (!found && slurm_exit_read(x->h->jobs_dir, j->id) < 0) {
                requeue_or_fail(x, j->id, j->attempts,
                                "the daemon stopped while it was being submitted, before Slurm "
                                "had it");
                requeued++;
                continue;
            }
        } else if (r <= 0) {
            if (r < 0)
                tlog("slurm: job %s: its slurm_job record is unreadable", j->id);
            requeue_or_fail(x, j->id, j->attempts,
                            "the daemon stopped before it was submitted to Slurm");
            requeued++;
            continue;
        }
        if (found) {
            char err[300];
            if (slurm_record_write(x->h->jobs_dir, j->id, name, task, slurm, err, sizeof err) < 0)
                tlog("slurm: job %s: %s", j->id, err);
        }
        struct sjob *w = track(x, j->id, slurm, j->attempts,
                               j->wall_limit > 0 ? j->wall_limit : x->h->wall_limit, j->end_time);
        if (!w) {
            tlog("slurm: out of memory adopting job %s", j->id);
            continue;
        }
        w->time_min = (long)(w->wall_limit / 60.0 + 0.999);
        snprintf(w->message, sizeof w->message, "%s", j->message ? j->message : "");
        w->cancel_sent = false;
        adopted++;
    }
    if (adopted || requeued)
        tlog("slurm: adopted %ld run(s) from Slurm, requeued %ld that had not reached it", adopted,
             requeued);
    free(rows);
    tq_jobs_free(js, n);
}

/* ------------------------------------------------------------------ loop */

static void drain_wake(int fd)
{
    char buf[64];
    while (read(fd, buf, sizeof buf) > 0)
        ;
}

void texec_slurm_run(const struct texec_host *h, const struct tcfg *cfg)
{
    struct sx x = {.h = h, .cfg = cfg};
    snprintf(x.uid, sizeof x.uid, "%ld", (long)geteuid());
    if (result_repair_find_tool(x.h5clear, sizeof x.h5clear) < 0)
        x.h5clear[0] = '\0';
    tlog("slurm: executor slurm (jobs in %s, partition %s, poll %g s)", h->jobs_dir,
         cfg->slurm_partition[0] ? cfg->slurm_partition : "default", cfg->slurm_poll);
    adopt(&x);
    bool want_claim = true;
    double last_claim = 0;
    while (!atomic_load(h->stop)) {
        double now = tlsph_monotonic_seconds();
        if (want_claim || now - last_claim >= cfg->slurm_poll) {
            claim_and_submit(&x);
            want_claim = false;
            last_claim = now;
        }
        struct pollfd pfd = {.fd = h->wake_rd, .events = POLLIN};
        const int pr = poll(&pfd, 1, TICK_MS);
        if (pr > 0) {
            drain_wake(h->wake_rd);
            want_claim = true;
            check_cancels(&x);
        }
        now = tlsph_monotonic_seconds();
        if (h->keep_records)
            h->keep_records(h->sup, now);
        if (x.n > 0 && now - x.t_poll >= cfg->slurm_poll)
            poll_all(&x, now);
    }
    /* the Slurm jobs go on: the next daemon adopts them */
    for (size_t i = 0; i < x.n; i++) {
        flush_progress(&x, &x.jobs[i]);
        engine_report_free(&x.jobs[i].report);
    }
    if (x.n > 0)
        tlog("slurm: stopping; %zu run(s) stay with Slurm for the next daemon", x.n);
    free(x.jobs);
}
