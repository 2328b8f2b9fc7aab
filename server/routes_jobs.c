/* Jobs as resources (server/routes_jobs.c): execute a process (submit a run
 * or a study), the job list, one job's statusInfo (with long-poll), and
 * DELETE (cancel, then remove).  The work is the jobs service's (jobs.h);
 * this file reads requests and writes answers. */
#include "route.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "errmsg.h"
#include "problem.h"
#include "util/clock.h"

#define MAX_WAIT 60.0       /* s, longest long-poll */
#define MAX_ITEM_LINKS 100  /* item links of a study's children */

static void rfc3339(json_t *obj, const char *key, double t)
{
    if (t <= 0)
        return;
    char buf[40];
    time_t s = (time_t)t;
    struct tm tm;
    gmtime_r(&s, &tm);
    strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    json_object_set_new(obj, key, json_string(buf));
}

/* statusInfo (schemas/job.schema.json).  For a study, status, progress and
 * started are aggregated from the children (the study row is refreshed by the
 * queue when a child finishes; this also reflects running children). */
static json_t *status_info(const struct tapp *a, struct tq *q, const struct tq_job *j,
                           bool with_items)
{
    json_t *o = json_object();
    const int study = !strcmp(j->process, "study");
    const char *status = j->status;
    double progress = j->progress, started = j->started;
    struct tq_job *kids = NULL;
    size_t nk = 0;
    char live_message[128] = "";
    const struct jobs_env env = route_jobs_env(a, q);
    if (study && jobs_study_children(&env, j->id, &kids, &nk) == 0 && nk > 0 &&
        !tq_status_final(j->status)) {
        size_t nacc = 0, nfinal = 0;
        double sum = 0;
        for (size_t i = 0; i < nk; i++) {
            /* the queue's rule (queue_study.c): a child that ran to its end
             * counts 100, a running or dismissed one the progress it reached */
            if (!strcmp(kids[i].status, TQ_ACCEPTED))
                nacc++;
            else if (!strcmp(kids[i].status, TQ_SUCCESSFUL) || !strcmp(kids[i].status, TQ_FAILED))
                nfinal++, sum += 100.0;
            else if (tq_status_final(kids[i].status))
                nfinal++, sum += kids[i].progress;
            else
                sum += kids[i].progress;
            if (kids[i].started > 0 && (started <= 0 || kids[i].started < started))
                started = kids[i].started;
        }
        status = nacc == nk ? TQ_ACCEPTED : TQ_RUNNING;
        if (nfinal == nk)
            status = j->status; /* the queue refreshes it with the last child */
        progress = sum / (double)nk;
        /* the stored message is refreshed only when a child finishes */
        snprintf(live_message, sizeof live_message, "%zu of %zu children finished, %zu running",
                 nfinal, nk, nk - nacc - nfinal);
    }
    json_object_set_new(o, "type", json_string("process"));
    json_object_set_new(o, "processID", json_string(route_process_id(j)));
    json_object_set_new(o, "jobID", json_string(j->id));
    json_object_set_new(o, "status", json_string(status));
    if (live_message[0])
        json_object_set_new(o, "message", json_string(live_message));
    else if (j->message && *j->message)
        json_object_set_new(o, "message", json_string(j->message));
    if (j->outcome[0])
        json_object_set_new(o, "outcome", json_string(j->outcome));
    rfc3339(o, "created", j->created);
    rfc3339(o, "started", started);
    rfc3339(o, "finished", j->finished);
    /* when the status last changed: the latest of these (progress is in
     * "progress" and "simulation"); for a study, also its children's starts */
    double updated = j->created;
    if (started > updated)
        updated = started;
    if (j->finished > updated)
        updated = j->finished;
    rfc3339(o, "updated", updated);
    long p = (long)floor(progress);
    if (!strcmp(status, TQ_SUCCESSFUL))
        p = 100;
    json_object_set_new(o, "progress", json_integer(p < 0 ? 0 : p > 100 ? 100 : p));
    if (j->study_id[0])
        json_object_set_new(o, "study", json_string(j->study_id));
    if (study)
        json_object_set_new(o, "children", json_integer((json_int_t)nk));
    if (!study && (j->started > 0 || j->end_time > 0)) {
        json_t *sim = json_object();
        json_object_set_new(sim, "time", json_real(j->sim_time));
        json_object_set_new(sim, "end_time", json_real(j->end_time));
        json_object_set_new(sim, "step", json_integer(j->step));
        if (j->eta >= 0 && !tq_status_final(j->status))
            json_object_set_new(sim, "eta_seconds", json_real(j->eta));
        json_object_set_new(o, "simulation", sim);
    }
    json_t *cost = route_json_or_null(j->cost);
    if (json_is_object(cost))
        json_object_set_new(o, "cost", cost);
    else
        json_decref(cost);
    json_t *links = json_array();
    route_add_link(links, "self", "application/json", "this job", "/jobs/%s", j->id);
    /* OGC 1.0: the results (the map of outputs) exist once the job succeeded;
     * a run's series, frames and fields can be read from its start on */
    if (!strcmp(status, TQ_SUCCESSFUL))
        route_add_link(links, REL_RESULTS, "application/json", "results", "/jobs/%s/results", j->id);
    if (!study && strcmp(status, TQ_ACCEPTED)) {
        route_add_link(links, "log", "text/plain", "engine log", "/jobs/%s/log", j->id);
        route_add_link(links, "series", "application/json", "time series",
                       "/jobs/%s/results/series", j->id);
        route_add_link(links, "frames", "application/json", "field frames",
                       "/jobs/%s/results/frames", j->id);
        route_add_link(links, "fields", "application/octet-stream",
                       "one field at one frame: /results/fields/{field}?frame=k",
                       "/jobs/%s/results/fields/position?frame=-1", j->id);
        if (tq_status_final(status)) {
            route_add_link(links, "enclosure", "application/x-hdf5",
                           "result file (HDF5, H5MD layout; partial when the job failed)",
                           "/jobs/%s/results/result.h5", j->id);
            route_add_link(links, "alternate", "text/xml", "XDMF sidecar for ParaView",
                           "/jobs/%s/results/result.xmf", j->id);
        }
    }
    if (study && strcmp(status, TQ_ACCEPTED))
        route_add_link(links, "summary", "application/json", "summary table",
                       "/jobs/%s/results/summary", j->id);
    if (j->study_id[0])
        route_add_link(links, "up", "application/json", "the study", "/jobs/%s", j->study_id);
    if (study) {
        route_add_link(links, REL_JOBLIST, "application/json", "children", "/jobs?study=%s", j->id);
        if (with_items)
            for (size_t i = 0; i < nk && i < MAX_ITEM_LINKS; i++)
                route_add_link(links, "item", "application/json", NULL, "/jobs/%s", kids[i].id);
    }
    json_object_set_new(o, "links", links);
    tq_jobs_free(kids, nk);
    return o;
}

static int require_json_content(struct hreq *r)
{
    const char *ct = http_header(r, "Content-Type");
    if (!ct) {
        http_reply_problem(r, PROBLEM_MEDIA_TYPE, "Content-Type: application/json is required");
        return -1;
    }
    while (*ct == ' ')
        ct++;
    size_t n = strlen("application/json");
    if (strncasecmp(ct, "application/json", n) != 0 || (ct[n] && ct[n] != ';' && ct[n] != ' ')) {
        http_reply_problem(r, PROBLEM_MEDIA_TYPE, "Content-Type must be application/json");
        return -1;
    }
    return 0;
}
/* Appends one validation error to *prob (made on the first). */
static void add_problem(struct hreq *r, json_t **prob, const char *pointer, const char *detail)
{
    if (!*prob)
        *prob = problem_new(PROBLEM_VALIDATION, detail, r->path);
    problem_add_error(*prob, pointer, detail);
}

/* The execute request's options besides inputs (OGC API - Processes 1.0,
 * execute.yaml): outputs may name the process's one output (output, sent by
 * reference: transmissionMode "value" is refused), response is "document"
 * or "raw" (both give the same asynchronous job; see docs/api.md), and a
 * subscriber is refused: this server does not call back (no callback
 * conformance class); poll GET /jobs/{id}?wait=S instead. */
static void check_execute_options(struct hreq *r, const json_t *root,
                                  const struct output_decl *output, json_t **prob)
{
    const json_t *resp = json_object_get(root, "response");
    if (resp && !(json_is_string(resp) && (!strcmp(json_string_value(resp), "document") ||
                                           !strcmp(json_string_value(resp), "raw"))))
        add_problem(r, prob, "/response", "must be \"document\" or \"raw\"");
    if (json_object_get(root, "subscriber"))
        add_problem(r, prob, "/subscriber",
                    "callbacks are not supported by this server (no callback conformance "
                    "class): leave out subscriber and poll GET /jobs/{jobId}?wait=S");
    const json_t *outs = json_object_get(root, "outputs");
    if (!outs)
        return;
    if (!json_is_object(outs)) {
        add_problem(r, prob, "/outputs", "must be an object {output id: {transmissionMode}}");
        return;
    }
    const char *k;
    const json_t *v;
    char p[300], q[340], d[200];
    json_object_foreach((json_t *)outs, k, v)
    {
        tlsph_pointer_join(p, sizeof p, "/outputs", k);
        if (strcmp(k, output->id)) {
            snprintf(d, sizeof d, "unknown output (this process has one: %s)", output->id);
            add_problem(r, prob, p, d);
            continue;
        }
        if (!json_is_object(v)) {
            add_problem(r, prob, p, "must be an object");
            continue;
        }
        const json_t *mode = json_object_get(v, "transmissionMode");
        snprintf(q, sizeof q, "%s/transmissionMode", p);
        if (mode && !(json_is_string(mode) && (!strcmp(json_string_value(mode), "reference") ||
                                               !strcmp(json_string_value(mode), "value"))))
            add_problem(r, prob, q, "must be \"value\" or \"reference\"");
        else if (mode && !strcmp(json_string_value(mode), "value"))
            add_problem(r, prob, q,
                        "only \"reference\" is supported: the output is a file served at its "
                        "own URL");
        const json_t *fmt = json_object_get(v, "format");
        const json_t *mt = json_object_get(fmt, "mediaType");
        snprintf(q, sizeof q, "%s/format/mediaType", p);
        if (fmt && !json_is_object(fmt)) {
            snprintf(q, sizeof q, "%s/format", p);
            add_problem(r, prob, q, "must be an object {mediaType}");
        } else if (mt &&
                   !(json_is_string(mt) && !strcmp(json_string_value(mt), output->media_type))) {
            snprintf(d, sizeof d, "the output is %s", output->media_type);
            add_problem(r, prob, q, d);
        }
        const char *m;
        const json_t *mv;
        json_object_foreach((json_t *)v, m, mv)
        {
            if (strcmp(m, "transmissionMode") && strcmp(m, "format")) {
                tlsph_pointer_join(q, sizeof q, p, m);
                add_problem(r, prob, q, "unknown member (accepted: transmissionMode, format)");
            }
        }
    }
}

static json_t *parse_body(struct hreq *r, const char *const *allowed_inputs,
                          const struct output_decl *output, json_t **inputs)
{
    json_error_t e;
    json_t *root = json_loadb(r->body.p ? r->body.p : "", r->body.len, JSON_REJECT_DUPLICATES, &e);
    if (!root) {
        char d[300];
        snprintf(d, sizeof d, "line %d column %d: %s", e.line, e.column, e.text);
        http_reply_problem(r, PROBLEM_BAD_JSON, d);
        return NULL;
    }
    json_t *prob = NULL;
    if (!json_is_object(root)) {
        prob = problem_new(PROBLEM_VALIDATION, "the request body must be a JSON object", r->path);
        problem_add_error(prob, "", "expected an object {\"inputs\": {...}}");
    } else {
        const char *k;
        json_t *v;
        json_object_foreach(root, k, v)
        {
            if (strcmp(k, "inputs") && strcmp(k, "outputs") && strcmp(k, "response") &&
                strcmp(k, "subscriber")) { /* schemas/execute.schema.json */
                if (!prob)
                    prob = problem_new(PROBLEM_VALIDATION, "unknown member", r->path);
                char p[300];
                tlsph_pointer_join(p, sizeof p, "", k);
                problem_add_error(
                    prob, p, "unknown member (accepted: inputs, outputs, response, subscriber)");
            }
        }
        check_execute_options(r, root, output, &prob);
        json_t *in = json_object_get(root, "inputs");
        if (!json_is_object(in)) {
            if (!prob)
                prob = problem_new(PROBLEM_VALIDATION, "inputs is required", r->path);
            problem_add_error(prob, "/inputs", in ? "must be an object" : "required");
        } else {
            json_object_foreach(in, k, v)
            {
                int known = 0;
                for (size_t i = 0; allowed_inputs[i]; i++)
                    known |= !strcmp(k, allowed_inputs[i]);
                if (!known) {
                    if (!prob)
                        prob = problem_new(PROBLEM_VALIDATION, "unknown input", r->path);
                    char p[300];
                    tlsph_pointer_join(p, sizeof p, "/inputs", k);
                    problem_add_error(prob, p, "unknown input");
                }
            }
            *inputs = in;
        }
    }
    if (prob) {
        json_decref(root);
        http_reply_problem_json(r, prob);
        return NULL;
    }
    return root;
}

static void reply_created(struct hreq *r, const struct route_call *c, struct tq *q, const char *id)
{
    struct tq_job j;
    if (tq_get(q, id, &j) != TQ_OK) {
        http_reply_problem(r, PROBLEM_INTERNAL, "job vanished after insertion");
        return;
    }
    http_reply_json(r, 201, status_info(c->app, q, &j, false));
    tq_job_free(&j);
    char loc[64];
    snprintf(loc, sizeof loc, "/jobs/%s", id);
    http_add_header(r, "Location", loc);
    if (c->respond_async)
        http_add_header(r, "Preference-Applied", "respond-async");
}

/* The answer to a submit the jobs service refused. */
static void reply_not_submitted(struct hreq *r, enum jobs_rc rc, bool study,
                                const struct jobs_submitted *sub)
{
    json_t *prob;
    switch (rc) {
    case JOBS_INVALID:
        prob = problem_new(PROBLEM_VALIDATION,
                           study ? "the study is invalid" : "the scene is invalid", r->path);
        problem_add_errors(prob, "/inputs", &sub->errors);
        break;
    case JOBS_NO_MEMORY:
        prob = problem_new(PROBLEM_INTERNAL, "out of memory", r->path);
        break;
    case JOBS_NO_DIRECTORY:
    case JOBS_NOT_QUEUED:
        if (sub->errnum && problem_of_errno(sub->errnum) != PROBLEM_INTERNAL &&
            problem_of_errno(sub->errnum) != PROBLEM_NOT_FOUND) {
            if (sub->why[0])
                tlog("%s", sub->why);
            route_reply_fault(r, sub->errnum, PROBLEM_INTERNAL,
                              "cannot write the job's files in the data directory");
            return;
        }
        prob = rc == JOBS_NOT_QUEUED
                   ? problem_new(PROBLEM_UNAVAILABLE,
                                 study ? "cannot queue the study" : "cannot queue the job", r->path)
                   : problem_new(PROBLEM_INTERNAL, "cannot create the job directory", r->path);
        break;
    case JOBS_OVER_QUOTA:
        prob = problem_new(PROBLEM_OUTPUT_QUOTA, sub->detail, r->path);
        problem_add_errors(prob, "/inputs", &sub->errors);
        break;
    case JOBS_NO_SPACE:
        prob = problem_new(PROBLEM_NO_STORAGE, sub->detail, r->path);
        break;
    default:
        prob = problem_new(PROBLEM_UNAVAILABLE,
                           study ? "cannot queue the study" : "cannot queue the job", r->path);
        break;
    }
    if (sub->why[0])
        tlog("%s", sub->why);
    http_reply_problem_json(r, prob);
}

enum process { PROCESS_RUN, PROCESS_STUDY, PROCESS_CONVERGENCE };

static void submit(struct hreq *r, const struct route_call *c, struct tq *q, enum process pr)
{
    static const char *const run_inputs[] = {"scene", "threads", NULL};
    static const char *const study_inputs[] = {"base", "sweep", "outputs", "max_parallel", NULL};
    static const char *const conv_inputs[] = {"base", "ladder", "outputs", "target", NULL};
    static const char *const names[] = {"run", "study", "convergence"};
    const char *const *allowed =
        pr == PROCESS_RUN ? run_inputs : pr == PROCESS_STUDY ? study_inputs : conv_inputs;
    json_t *inputs = NULL;
    json_t *root = parse_body(r, allowed, route_process_output(names[pr]), &inputs);
    if (!root)
        return;
    const struct jobs_env env = route_jobs_env(c->app, q);
    struct jobs_submitted sub;
    jobs_submitted_init(&sub);
    enum jobs_rc rc = pr == PROCESS_RUN     ? jobs_submit_run(&env, inputs, &sub)
                      : pr == PROCESS_STUDY ? jobs_submit_study(&env, inputs, &sub)
                                            : jobs_submit_convergence(&env, inputs, &sub);
    if (rc == JOBS_OK)
        reply_created(r, c, q, sub.id);
    else
        reply_not_submitted(r, rc, pr != PROCESS_RUN, &sub);
    jobs_submitted_free(&sub);
    json_decref(root);
}

static void task_submit_run(struct hreq *r, struct route_call *c, struct tq *q)
{
    submit(r, c, q, PROCESS_RUN);
}

static void task_submit_study(struct hreq *r, struct route_call *c, struct tq *q)
{
    submit(r, c, q, PROCESS_STUDY);
}

static void task_submit_convergence(struct hreq *r, struct route_call *c, struct tq *q)
{
    submit(r, c, q, PROCESS_CONVERGENCE);
}

void job_execute(struct hreq *r, struct route_call *c)
{
    const char *pid = c->process;
    route_task *task = !strcmp(pid, "run")           ? task_submit_run
                       : !strcmp(pid, "study")       ? task_submit_study
                       : !strcmp(pid, "convergence") ? task_submit_convergence
                                                     : NULL;
    if (!task) {
        http_reply_problem(r, PROBLEM_NO_SUCH_PROCESS, ROUTE_KNOWN_PROCESSES);
        return;
    }
    if (require_json_content(r) != 0)
        return;
    const char *prefer = http_header(r, "Prefer");
    if (prefer && strstr(prefer, "respond-async"))
        c->respond_async = true;
    if (route_defer(r, c, task) != 0)
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "shutting down");
}

void job_list(struct hreq *r, struct route_call *c)
{
    const struct tapp *a = c->app;
    long limit = 100, offset = 0;
    struct tq_filter f;
    bool none;
    char detail[256];
    if (route_job_filter(r, &f, &none, detail, sizeof detail) != 0) {
        http_reply_problem(r, PROBLEM_BAD_REQUEST, detail);
        return;
    }
    if (route_query_long(http_query(r, "limit"), 1, TQ_LIST_MAX, &limit) < 0) {
        http_reply_problem(r, PROBLEM_BAD_REQUEST, "limit must be an integer in [1, 10000]");
        return;
    }
    if (route_query_long(http_query(r, "offset"), 0, 1L << 40, &offset) < 0) {
        http_reply_problem(r, PROBLEM_BAD_REQUEST, "offset must be a non-negative integer");
        return;
    }
    struct tq_job *jobs = NULL;
    size_t n = 0;
    if (!none && tq_list_filtered(a->q, &f, limit, offset, &jobs, &n) != TQ_OK) {
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "database busy, retry");
        http_add_header(r, "Retry-After", "1");
        return;
    }
    /* a full page links to a next one only when that one is not empty */
    bool more = false;
    if ((long)n == limit) {
        struct tq_job *peek = NULL;
        size_t np = 0;
        more = tq_list_filtered(a->q, &f, 1, offset + limit, &peek, &np) != TQ_OK || np > 0;
        tq_jobs_free(peek, np);
    }
    json_t *arr = json_array();
    for (size_t i = 0; i < n; i++)
        json_array_append_new(arr, status_info(a, a->q, &jobs[i], false));
    tq_jobs_free(jobs, n);
    json_t *links = json_array();
    char q[600];
    route_job_filter_query(r, &f, q, sizeof q);
    route_add_link(links, "self", "application/json", NULL, "/jobs?limit=%ld&offset=%ld%s", limit,
                   offset, q);
    if (more)
        route_add_link(links, "next", "application/json", NULL, "/jobs?limit=%ld&offset=%ld%s",
                       limit, offset + limit, q);
    http_reply_json(r, 200, json_pack("{s:o,s:o}", "jobs", arr, "links", links));
}

/* Loads a job for a route: replies 404 (or 503) and returns -1 when it cannot. */
void job_get(struct hreq *r, struct route_call *c)
{
    const struct tapp *a = c->app;
    const char *id = c->id;
    struct tq_job j;
    const char *w = http_query(r, "wait");
    double wait = 0;
    if (w) {
        char *end;
        errno = 0;
        wait = strtod(w, &end);
        if (errno || end == w || *end || !(wait >= 0) || !isfinite(wait)) {
            http_reply_problem(r, PROBLEM_BAD_REQUEST, "wait must be a number of seconds (0-60)");
            return;
        }
        if (wait > MAX_WAIT)
            wait = MAX_WAIT;
    }
    if (route_load_job(r, a->q, id, &j) != 0)
        return;
    if (!r->resumed && wait > 0 && !tq_status_final(j.status) &&
        http_wait(r, j.id, tlsph_monotonic_seconds() + wait) == 0) {
        tq_job_free(&j);
        return; /* parked; the route runs again with r->resumed */
    }
    http_reply_json(r, 200, status_info(a, a->q, &j, true));
    tq_job_free(&j);
}

void job_delete(struct hreq *r, struct route_call *c)
{
    const struct tapp *a = c->app;
    const char *id = c->id;
    struct tq_job j;
    if (route_load_job(r, a->q, id, &j) != 0)
        return;
    if (r->resumed) { /* after waiting for the cancellation to take effect */
        http_reply_json(r, 200, status_info(a, a->q, &j, true));
        tq_job_free(&j);
        return;
    }
    const struct jobs_env env = route_jobs_env(a, a->q);
    if (!tq_status_final(j.status)) {
        const enum jobs_rc rc = jobs_cancel(&env, j.id);
        if (rc != JOBS_OK) {
            tq_job_free(&j);
            if (rc == JOBS_NO_SPACE)
                http_reply_problem(r, PROBLEM_NO_STORAGE,
                                   "the data directory's disk is full: the cancellation cannot "
                                   "be recorded; free space and retry");
            else
                http_reply_problem(r, PROBLEM_UNAVAILABLE, "database busy, retry");
            return;
        }
        tq_job_free(&j);
        if (route_load_job(r, a->q, id, &j) != 0)
            return;
        /* a running engine is stopped by the supervisor: wait for it (bounded) */
        if (!tq_status_final(j.status) &&
            http_wait(r, j.id, tlsph_monotonic_seconds() + a->cfg->kill_grace + 3.0) == 0) {
            tq_job_free(&j);
            return;
        }
        http_reply_json(r, 200, status_info(a, a->q, &j, true));
        tq_job_free(&j);
        return;
    }
    /* final: remove the record and the files (a study: its children too) */
    switch (jobs_remove(&env, &j)) {
    case JOBS_OK:
        http_reply_json(r, 200, json_pack("{s:s}", "removed", j.id));
        break;
    case JOBS_NO_SUCH_JOB:
        http_reply_problem(r, PROBLEM_NO_SUCH_JOB, "no job with this id");
        break;
    case JOBS_NOT_FINAL:
        http_reply_problem(r, PROBLEM_CONFLICT,
                           "the job (or its study) is not in a final state; cancel it first");
        break;
    case JOBS_NO_SPACE:
        http_reply_problem(r, PROBLEM_NO_STORAGE,
                           "the data directory's disk is full: the removal cannot be recorded");
        break;
    case JOBS_STUDY_CHILD: {
        char detail[160];
        snprintf(detail, sizeof detail,
                 "a study's child is removed only with its study (its summary row): "
                 "DELETE /jobs/%s",
                 j.study_id);
        http_reply_problem(r, PROBLEM_CONFLICT, detail);
        break;
    }
    default:
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "database busy, retry");
        break;
    }
    tq_job_free(&j);
}
