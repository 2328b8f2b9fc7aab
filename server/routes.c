/* The tlsphd API, see routes.h and schemas/openapi.json. */
#include "routes.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "auth.h"
#include "errmsg.h"
#include "jobdir.h"
#include "jobs.h"
#include "problem.h"
#include "queue.h"
#include "results.h"
#include "scene/scene.h"
#include "study.h"
#include "supervisor.h"
#include "util/clock.h"

#define MAX_SEGMENTS 16
#define MAX_WAIT 60.0
#define LOG_TAIL (64 * 1024)
#define JSON_FIELD_MAX 100000
#define MAX_ITEM_LINKS 100
#define REL_RESULTS "http://www.opengis.net/def/rel/ogc/1.0/results"
#define REL_EXEC "http://www.opengis.net/def/rel/ogc/1.0/execute"
#define REL_JOBLIST "http://www.opengis.net/def/rel/ogc/1.0/job-list"
#define REL_PROCESSES "http://www.opengis.net/def/rel/ogc/1.0/processes"
#define REL_CONFORMANCE "http://www.opengis.net/def/rel/ogc/1.0/conformance"

/* ------------------------------------------------------------------ helpers */

/* jobs_dir/<id>/<file>; id already validated. */
static void job_file(char *out, size_t n, const struct tapp *a, const char *id,
                     enum jobdir_file file)
{
    if (jobdir_path(out, n, a->cfg->jobs_dir, id, file) != 0)
        out[0] = '\0';
}

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

static json_t *link_new(const char *href, const char *rel, const char *type, const char *title)
{
    json_t *l = json_object();
    json_object_set_new(l, "href", json_string(href));
    json_object_set_new(l, "rel", json_string(rel));
    if (type)
        json_object_set_new(l, "type", json_string(type));
    if (title)
        json_object_set_new(l, "title", json_string(title));
    return l;
}

static void add_link(json_t *links, const char *rel, const char *type, const char *title,
                     const char *fmt, ...) __attribute__((format(printf, 5, 6)));
static void add_link(json_t *links, const char *rel, const char *type, const char *title,
                     const char *fmt, ...)
{
    char href[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(href, sizeof href, fmt, ap);
    va_end(ap);
    json_array_append_new(links, link_new(href, rel, type, title));
}

static json_t *json_parse_or_null(const char *text)
{
    if (!text || !*text)
        return NULL;
    return json_loads(text, 0, NULL);
}

static struct jobs_env jobs_env(struct tapp *a, struct tq *q)
{
    return (struct jobs_env){.q = q, .cfg = a->cfg, .sup = a->sup};
}

/* Children of a study ordered by seq. */
static int study_children(struct tapp *a, struct tq *q, const char *id, struct tq_job **out,
                          size_t *n)
{
    const struct jobs_env env = jobs_env(a, q);
    return jobs_study_children(&env, id, out, n);
}

/* statusInfo (schemas/job.schema.json).  For a study, status, progress and
 * started are aggregated from the children (the study row is refreshed by the
 * queue when a child finishes; this also reflects running children). */
static json_t *status_info(struct tapp *a, struct tq *q, const struct tq_job *j, int with_items)
{
    json_t *o = json_object();
    const int study = !strcmp(j->process, "study");
    const char *status = j->status;
    double progress = j->progress, started = j->started;
    struct tq_job *kids = NULL;
    size_t nk = 0;
    char live_message[128] = "";
    if (study && study_children(a, q, j->id, &kids, &nk) == 0 && nk > 0 && !tq_status_final(j->status)) {
        size_t nacc = 0, nfinal = 0;
        double sum = 0;
        for (size_t i = 0; i < nk; i++) {
            if (!strcmp(kids[i].status, TQ_ACCEPTED))
                nacc++;
            else if (tq_status_final(kids[i].status))
                nfinal++, sum += 100.0;
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
    json_object_set_new(o, "processID", json_string(j->process));
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
    long p = (long)floor(progress);
    if (!strcmp(status, TQ_SUCCESSFUL))
        p = 100;
    json_object_set_new(o, "progress", json_integer(p < 0 ? 0 : p > 100 ? 100 : p));
    if (j->study_id[0])
        json_object_set_new(o, "study", json_string(j->study_id));
    if (!study && (j->started > 0 || j->end_time > 0)) {
        json_t *sim = json_object();
        json_object_set_new(sim, "time", json_real(j->sim_time));
        json_object_set_new(sim, "end_time", json_real(j->end_time));
        json_object_set_new(sim, "step", json_integer(j->step));
        if (j->eta >= 0 && !tq_status_final(j->status))
            json_object_set_new(sim, "eta_seconds", json_real(j->eta));
        json_object_set_new(o, "simulation", sim);
    }
    json_t *cost = json_parse_or_null(j->cost);
    if (json_is_object(cost))
        json_object_set_new(o, "cost", cost);
    else
        json_decref(cost);
    json_t *links = json_array();
    add_link(links, "self", "application/json", "this job", "/jobs/%s", j->id);
    if (tq_status_final(status) || !strcmp(status, TQ_RUNNING))
        add_link(links, REL_RESULTS, "application/json", "results", "/jobs/%s/results", j->id);
    if (!study && strcmp(status, TQ_ACCEPTED))
        add_link(links, "log", "text/plain", "engine log", "/jobs/%s/log", j->id);
    if (j->study_id[0])
        add_link(links, "up", "application/json", "the study", "/jobs/%s", j->study_id);
    if (study) {
        add_link(links, REL_JOBLIST, "application/json", "children", "/jobs?study=%s", j->id);
        if (with_items)
            for (size_t i = 0; i < nk && i < MAX_ITEM_LINKS; i++)
                add_link(links, "item", "application/json", NULL, "/jobs/%s", kids[i].id);
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

static int accepts_json(struct hreq *r)
{
    const char *acc = http_header(r, "Accept");
    return acc && strstr(acc, "application/json") != NULL;
}

/* ------------------------------------------------------------- static pages */

static void landing(struct hreq *r)
{
    json_t *o = json_pack("{s:s,s:s}", "title", "tlsphd",
                          "description", "TLSPH simulation job service (OGC API - Processes 1.0 style)");
    json_t *links = json_array();
    add_link(links, "self", "application/json", "this document", "/");
    add_link(links, "service-desc", "application/vnd.oai.openapi+json;version=3.1",
             "the API definition", "/openapi.json");
    add_link(links, REL_CONFORMANCE, "application/json", "conformance", "/conformance");
    add_link(links, REL_PROCESSES, "application/json", "processes", "/processes");
    add_link(links, REL_JOBLIST, "application/json", "jobs", "/jobs");
    json_object_set_new(o, "links", links);
    http_reply_json(r, 200, o);
}

static void conformance(struct hreq *r)
{
    const char *base = "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/";
    const char *cls[] = {"core", "json", "job-list", "dismiss", "oas30"};
    json_t *arr = json_array();
    for (size_t i = 0; i < sizeof cls / sizeof cls[0]; i++) {
        char buf[128];
        snprintf(buf, sizeof buf, "%s%s", base, cls[i]);
        json_array_append_new(arr, json_string(buf));
    }
    http_reply_json(r, 200, json_pack("{s:o}", "conformsTo", arr));
}

static json_t *process_desc(const char *id, int full)
{
    const int run = !strcmp(id, "run");
    json_t *o = json_pack("{s:s,s:s,s:s,s:s,s:[s,s],s:[s]}", "id", id, "title",
                          run ? "Run one TLSPH simulation" : "Parametric study",
                          "description",
                          run ? "Runs one scene (schemas/scene.schema.json) and stores its "
                                "results as HDF5 (H5MD layout) with an XDMF sidecar."
                              : "Runs a base scene once per point of a sweep over scene values "
                                "given by JSON pointers (product or zip) and tabulates the results.",
                          "version", "1.0.0", "jobControlOptions", "async-execute", "dismiss",
                          "outputTransmission", "reference");
    json_t *links = json_array();
    add_link(links, "self", "application/json", "process description", "/processes/%s", id);
    add_link(links, REL_EXEC, "application/json", "execute", "/processes/%s/execution", id);
    json_object_set_new(o, "links", links);
    if (full) {
        json_t *inputs = json_object();
        if (run) {
            json_object_set_new(inputs, "scene",
                                json_pack("{s:s,s:s,s:{s:s}}", "title", "scene", "description",
                                          "the scene document", "schema", "$ref",
                                          "/schemas/scene.schema.json"));
        } else {
            json_object_set_new(inputs, "base",
                                json_pack("{s:s,s:{s:s}}", "title", "base scene", "schema",
                                          "$ref", "/schemas/scene.schema.json"));
            json_object_set_new(inputs, "sweep",
                                json_pack("{s:s,s:{s:s}}", "title", "sweep", "schema", "$ref",
                                          "/schemas/study.schema.json#/properties/sweep"));
            json_object_set_new(inputs, "outputs",
                                json_pack("{s:s,s:i,s:{s:s}}", "title", "derived outputs",
                                          "minOccurs", 0, "schema", "$ref",
                                          "/schemas/study.schema.json#/properties/outputs"));
        }
        json_object_set_new(o, "inputs", inputs);
        json_t *outputs = json_object();
        if (run)
            json_object_set_new(outputs, "result",
                                json_pack("{s:s,s:{s:s,s:s}}", "title", "HDF5 result file",
                                          "schema", "type", "string", "contentMediaType",
                                          "application/x-hdf5"));
        else
            json_object_set_new(outputs, "summary",
                                json_pack("{s:s,s:{s:s}}", "title", "study summary table",
                                          "schema", "type", "object"));
        json_object_set_new(o, "outputs", outputs);
    }
    return o;
}

static void processes(struct hreq *r)
{
    json_t *arr = json_pack("[o,o]", process_desc("run", 0), process_desc("study", 0));
    json_t *links = json_array();
    add_link(links, "self", "application/json", "processes", "/processes");
    http_reply_json(r, 200, json_pack("{s:o,s:o}", "processes", arr, "links", links));
}

static void process_one(struct hreq *r, const char *id)
{
    if (strcmp(id, "run") && strcmp(id, "study")) {
        http_reply_problem(r, PROBLEM_NO_SUCH_PROCESS, "known processes: run, study");
        return;
    }
    http_reply_json(r, 200, process_desc(id, 1));
}

static void openapi(struct hreq *r, struct tapp *a)
{
    if (!a->openapi) {
        http_reply_problem(r, PROBLEM_NOT_FOUND, "openapi.json is not installed");
        return;
    }
    char *b = malloc(a->openapi_len + 1);
    if (!b) {
        http_reply_problem(r, PROBLEM_INTERNAL, "out of memory");
        return;
    }
    memcpy(b, a->openapi, a->openapi_len);
    http_reply_buf(r, 200, "application/vnd.oai.openapi+json;version=3.1", b, a->openapi_len);
}

/* GET /schemas/<name>.json from the schemas directory (names: [a-z0-9._-]). */
static void schema_file(struct hreq *r, struct tapp *a, const char *name)
{
    size_t n = strlen(name);
    int ok = n > 5 && n < 64 && !strcmp(name + n - 5, ".json") && name[0] != '.';
    for (size_t i = 0; ok && i < n; i++)
        ok = islower((unsigned char)name[i]) || isdigit((unsigned char)name[i]) ||
             name[i] == '.' || name[i] == '-' || name[i] == '_';
    char path[1200];
    int fd = -1;
    struct stat st;
    if (ok) {
        snprintf(path, sizeof path, "%s/%s", a->cfg->schemas_dir, name);
        fd = open(path, O_RDONLY | O_CLOEXEC);
    }
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        if (fd >= 0)
            close(fd);
        http_reply_problem(r, PROBLEM_NOT_FOUND, "no such schema");
        return;
    }
    http_reply_fd(r, 200, "application/schema+json", fd, 0, (uint64_t)st.st_size);
}

static void healthz(struct hreq *r, struct tapp *a)
{
    long acc = 0, run = 0, fin = 0;
    if (tq_counts(a->q, &acc, &run, &fin) != 0) {
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "database unavailable");
        return;
    }
    http_reply_json(r, 200,
                    json_pack("{s:s,s:{s:I,s:I,s:I}}", "status", "ok", "jobs", "accepted",
                              (json_int_t)acc, "running", (json_int_t)run, "final",
                              (json_int_t)fin));
}

/* ------------------------------------------------------------------ submit */

/* Body → JSON object; replies 400/422 and returns NULL on failure. */
static json_t *parse_body(struct hreq *r, const char *const *allowed_inputs, json_t **inputs)
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
            if (strcmp(k, "inputs")) { /* schemas/execute.schema.json */
                if (!prob)
                    prob = problem_new(PROBLEM_VALIDATION, "unknown member", r->path);
                char p[300];
                tlsph_pointer_join(p, sizeof p, "", k);
                problem_add_error(prob, p, "unknown member (accepted: inputs)");
            }
        }
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

static void reply_created(struct hreq *r, struct tapp *a, struct tq *q, const char *id)
{
    struct tq_job j;
    if (tq_get(q, id, &j) != 0) {
        http_reply_problem(r, PROBLEM_INTERNAL, "job vanished after insertion");
        return;
    }
    http_reply_json(r, 201, status_info(a, q, &j, 0));
    tq_job_free(&j);
    char loc[64];
    snprintf(loc, sizeof loc, "/jobs/%s", id);
    http_add_header(r, "Location", loc);
    if (r->flags & 1)
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
        prob = problem_new(PROBLEM_INTERNAL, "cannot create the job directory", r->path);
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

static void submit(struct hreq *r, struct tapp *a, struct tq *q, bool study)
{
    static const char *const run_inputs[] = {"scene", NULL};
    static const char *const study_inputs[] = {"base", "sweep", "outputs", NULL};
    json_t *inputs = NULL;
    json_t *root = parse_body(r, study ? study_inputs : run_inputs, &inputs);
    if (!root)
        return;
    const struct jobs_env env = jobs_env(a, q);
    struct jobs_submitted sub;
    jobs_submitted_init(&sub);
    enum jobs_rc rc = study ? jobs_submit_study(&env, inputs, &sub)
                            : jobs_submit_run(&env, inputs, &sub);
    if (rc == JOBS_OK)
        reply_created(r, a, q, sub.id);
    else
        reply_not_submitted(r, rc, study, &sub);
    jobs_submitted_free(&sub);
    json_decref(root);
}

static void task_submit_run(struct hreq *r, void *app, void *ctx)
{
    submit(r, app, ctx, false);
}

static void task_submit_study(struct hreq *r, void *app, void *ctx)
{
    submit(r, app, ctx, true);
}

static void execute(struct hreq *r, const char *pid)
{
    if (strcmp(pid, "run") && strcmp(pid, "study")) {
        http_reply_problem(r, PROBLEM_NO_SUCH_PROCESS, "known processes: run, study");
        return;
    }
    if (require_json_content(r) != 0)
        return;
    const char *prefer = http_header(r, "Prefer");
    if (prefer && strstr(prefer, "respond-async"))
        r->flags |= 1;
    if (http_defer(r, !strcmp(pid, "run") ? task_submit_run : task_submit_study) != 0)
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "shutting down");
}

/* ------------------------------------------------------------------- jobs */

static int parse_long_arg(const char *s, long lo, long hi, long *out)
{
    if (!s)
        return 1;
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno || end == s || *end || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

static void list_jobs(struct hreq *r, struct tapp *a)
{
    const char *status = http_query(r, "status");
    const char *study = http_query(r, "study");
    const char *process = http_query(r, "processID");
    if (!process)
        process = http_query(r, "process");
    long limit = 100, offset = 0;
    if (status && *status && !tq_status_valid(status)) {
        http_reply_problem(r, PROBLEM_BAD_REQUEST,
                           "status must be accepted, running, successful, failed or dismissed");
        return;
    }
    if (study && *study && !job_id_valid(study)) {
        http_reply_problem(r, PROBLEM_BAD_REQUEST, "study must be a job id (32 hex digits)");
        return;
    }
    if (process && *process && strcmp(process, "run") && strcmp(process, "study")) {
        http_reply_problem(r, PROBLEM_BAD_REQUEST, "processID must be run or study");
        return;
    }
    if (parse_long_arg(http_query(r, "limit"), 1, 10000, &limit) < 0) {
        http_reply_problem(r, PROBLEM_BAD_REQUEST, "limit must be an integer in [1, 10000]");
        return;
    }
    if (parse_long_arg(http_query(r, "offset"), 0, 1L << 40, &offset) < 0) {
        http_reply_problem(r, PROBLEM_BAD_REQUEST, "offset must be a non-negative integer");
        return;
    }
    struct tq_job *jobs = NULL;
    size_t n = 0;
    if (tq_list(a->q, status, study, process, limit, offset, &jobs, &n) != 0) {
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "database busy, retry");
        http_add_header(r, "Retry-After", "1");
        return;
    }
    json_t *arr = json_array();
    for (size_t i = 0; i < n; i++)
        json_array_append_new(arr, status_info(a, a->q, &jobs[i], 0));
    tq_jobs_free(jobs, n);
    json_t *links = json_array();
    char q[256];
    snprintf(q, sizeof q, "%s%s%s%s%s%s", status && *status ? "&status=" : "",
             status && *status ? status : "", study && *study ? "&study=" : "",
             study && *study ? study : "", process && *process ? "&processID=" : "",
             process && *process ? process : "");
    add_link(links, "self", "application/json", NULL, "/jobs?limit=%ld&offset=%ld%s", limit,
             offset, q);
    if ((long)n == limit)
        add_link(links, "next", "application/json", NULL, "/jobs?limit=%ld&offset=%ld%s", limit,
                 offset + limit, q);
    http_reply_json(r, 200, json_pack("{s:o,s:o}", "jobs", arr, "links", links));
}

/* Loads a job for a route: replies 404 (or 503) and returns -1 when it cannot. */
static int load_job(struct hreq *r, struct tapp *a, struct tq *q, const char *id, struct tq_job *j)
{
    if (!job_id_valid(id)) {
        memset(j, 0, sizeof *j);
        http_reply_problem(r, PROBLEM_NO_SUCH_JOB, "no job with this id");
        return -1;
    }
    int rc = tq_get(q, id, j);
    (void)a;
    if (rc == 1) {
        http_reply_problem(r, PROBLEM_NO_SUCH_JOB, "no job with this id");
        return -1;
    }
    if (rc != 0) {
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "database busy, retry");
        http_add_header(r, "Retry-After", "1");
        return -1;
    }
    return 0;
}

static void get_job(struct hreq *r, struct tapp *a, const char *id)
{
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
    if (load_job(r, a, a->q, id, &j) != 0)
        return;
    if (!r->resumed && wait > 0 && !tq_status_final(j.status) &&
        http_wait(r, j.id, tlsph_monotonic_seconds() + wait) == 0) {
        tq_job_free(&j);
        return; /* parked; the route runs again with r->resumed */
    }
    http_reply_json(r, 200, status_info(a, a->q, &j, 1));
    tq_job_free(&j);
}

static void delete_job(struct hreq *r, struct tapp *a, const char *id)
{
    struct tq_job j;
    if (load_job(r, a, a->q, id, &j) != 0)
        return;
    if (r->resumed) { /* after waiting for the cancellation to take effect */
        http_reply_json(r, 200, status_info(a, a->q, &j, 1));
        tq_job_free(&j);
        return;
    }
    const struct jobs_env env = jobs_env(a, a->q);
    if (!tq_status_final(j.status)) {
        if (jobs_cancel(&env, j.id) != JOBS_OK) {
            tq_job_free(&j);
            http_reply_problem(r, PROBLEM_UNAVAILABLE, "database busy, retry");
            return;
        }
        tq_job_free(&j);
        if (load_job(r, a, a->q, id, &j) != 0)
            return;
        /* a running engine is stopped by the supervisor: wait for it (bounded) */
        if (!tq_status_final(j.status) &&
            http_wait(r, j.id, tlsph_monotonic_seconds() + a->cfg->kill_grace + 3.0) == 0) {
            tq_job_free(&j);
            return;
        }
        http_reply_json(r, 200, status_info(a, a->q, &j, 1));
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
    default:
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "database busy, retry");
        break;
    }
    tq_job_free(&j);
}

/* ----------------------------------------------------------------- results */

static void results_doc(struct hreq *r, const struct tq_job *j)
{
    json_t *o = json_object();
    json_object_set_new(o, "jobID", json_string(j->id));
    json_object_set_new(o, "status", json_string(j->status));
    json_t *links = json_array();
    add_link(links, "self", "application/json", "this document", "/jobs/%s/results", j->id);
    add_link(links, "up", "application/json", "the job", "/jobs/%s", j->id);
    if (!strcmp(j->process, "study")) {
        add_link(links, "summary", "application/json", "summary table",
                 "/jobs/%s/results/summary", j->id);
        add_link(links, "summary", "text/csv", "summary table (CSV)",
                 "/jobs/%s/results/summary?format=csv", j->id);
        add_link(links, REL_JOBLIST, "application/json", "children", "/jobs?study=%s", j->id);
    } else {
        add_link(links, "enclosure", "application/x-hdf5", "result file (HDF5, H5MD layout)",
                 "/jobs/%s/results/result.h5", j->id);
        add_link(links, "alternate", "text/xml", "XDMF sidecar for ParaView",
                 "/jobs/%s/results/result.xmf", j->id);
        add_link(links, "series", "application/json", "time series", "/jobs/%s/results/series",
                 j->id);
        add_link(links, "frames", "application/json", "field frames", "/jobs/%s/results/frames",
                 j->id);
        add_link(links, "fields", "application/octet-stream",
                 "one field at one frame: /results/fields/{field}?frame=k",
                 "/jobs/%s/results/fields/position?frame=-1", j->id);
        add_link(links, "log", "text/plain", "engine log", "/jobs/%s/log", j->id);
    }
    json_object_set_new(o, "links", links);
    http_reply_json(r, 200, o);
}

/* Range header → [*off, *off + *len) of size; 0 none/ignored (whole file),
 * 1 satisfiable single range, -1 unsatisfiable/invalid. */
static int parse_range(const char *h, uint64_t size, uint64_t *off, uint64_t *len)
{
    if (!h)
        return 0;
    while (*h == ' ')
        h++;
    if (strncmp(h, "bytes=", 6) != 0)
        return -1;
    h += 6;
    if (strchr(h, ','))
        return 0; /* multiple ranges: serve the whole file */
    char *end;
    uint64_t a, b;
    if (*h == '-') {
        if (!isdigit((unsigned char)h[1]))
            return -1;
        errno = 0;
        uint64_t n = strtoull(h + 1, &end, 10);
        if (errno || *end || n == 0 || size == 0)
            return -1;
        if (n > size)
            n = size;
        *off = size - n;
        *len = n;
        return 1;
    }
    if (!isdigit((unsigned char)*h))
        return -1;
    errno = 0;
    a = strtoull(h, &end, 10);
    if (errno || *end != '-')
        return -1;
    h = end + 1;
    if (*h == '\0') {
        b = size ? size - 1 : 0;
    } else {
        if (!isdigit((unsigned char)*h))
            return -1;
        b = strtoull(h, &end, 10);
        if (errno || *end || b < a)
            return -1;
        if (b >= size)
            b = size ? size - 1 : 0;
    }
    if (a >= size)
        return -1;
    *off = a;
    *len = b - a + 1;
    return 1;
}

static void serve_file(struct hreq *r, const char *path, const char *ctype, const char *id,
                       const char *download_name, int ranges)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        if (fd >= 0)
            close(fd);
        http_reply_problem(r, PROBLEM_NO_SUCH_RESULT, "the job produced no such file");
        return;
    }
    const uint64_t size = (uint64_t)st.st_size;
    char etag[96], buf[128];
    snprintf(etag, sizeof etag, "\"%" PRIx64 "-%lx.%lx-%.8s\"", size, (long)st.st_mtim.tv_sec,
             (long)st.st_mtim.tv_nsec, id);
    uint64_t off = 0, len = size;
    int rr = 0;
    if (ranges) {
        const char *ifr = http_header(r, "If-Range");
        rr = (ifr && strcmp(ifr, etag)) ? 0 : parse_range(http_header(r, "Range"), size, &off, &len);
    }
    if (rr < 0) {
        close(fd);
        http_reply_problem(r, PROBLEM_RANGE, "the requested range is not satisfiable");
        snprintf(buf, sizeof buf, "bytes */%" PRIu64, size);
        http_add_header(r, "Content-Range", buf);
    } else {
        const char *inm = http_header(r, "If-None-Match");
        if (inm && !strcmp(inm, etag) && rr == 0) {
            close(fd);
            http_reply_buf(r, 304, NULL, NULL, 0);
        } else if (len == 0) {
            close(fd);
            http_reply_buf(r, 200, ctype, NULL, 0);
        } else {
            http_reply_fd(r, rr ? 206 : 200, ctype, fd, off, len);
        }
        if (rr > 0) {
            snprintf(buf, sizeof buf, "bytes %" PRIu64 "-%" PRIu64 "/%" PRIu64, off, off + len - 1,
                     size);
            http_add_header(r, "Content-Range", buf);
        }
    }
    http_add_header(r, "ETag", etag);
    if (ranges)
        http_add_header(r, "Accept-Ranges", "bytes");
    if (download_name && rr >= 0) {
        snprintf(buf, sizeof buf, "attachment; filename=\"%s\"", download_name);
        http_add_header(r, "Content-Disposition", buf);
    }
}

/* The tail of the engine log. */
static void serve_log(struct hreq *r, struct tapp *a, const struct tq_job *j)
{
    char path[1200];
    job_file(path, sizeof path, a, j->id, JOBDIR_LOG);
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        if (fd >= 0)
            close(fd);
        http_reply_text(r, 200, "text/plain; charset=utf-8", "");
        return;
    }
    uint64_t size = (uint64_t)st.st_size;
    uint64_t off = size > LOG_TAIL ? size - LOG_TAIL : 0;
    if (size == off) {
        close(fd);
        http_reply_text(r, 200, "text/plain; charset=utf-8", "");
        return;
    }
    http_reply_fd(r, 200, "text/plain; charset=utf-8", fd, off, size - off);
}

static void h5_path(char *out, size_t n, struct tapp *a, const char *id)
{
    job_file(out, n, a, id, JOBDIR_RESULT);
}

static void task_series_list(struct hreq *r, void *app, void *ctx)
{
    char path[1200], err[256] = "";
    (void)ctx;
    h5_path(path, sizeof path, app, r->id);
    json_t *list = tres_series_list(path, err, sizeof err);
    if (!list) {
        http_reply_problem(r, PROBLEM_NO_SUCH_RESULT, err);
        return;
    }
    json_t *links = json_array();
    add_link(links, "self", "application/json", NULL, "/jobs/%s/results/series", r->id);
    http_reply_json(r, 200, json_pack("{s:o,s:o}", "series", list, "links", links));
}

static void task_series(struct hreq *r, void *app, void *ctx)
{
    char path[1200], err[256] = "";
    int not_found = 0;
    (void)ctx;
    h5_path(path, sizeof path, app, r->id);
    if (r->flags & 2) {
        char *csv = tres_series_csv(path, r->arg, &not_found, err, sizeof err);
        if (csv)
            http_reply_buf(r, 200, "text/csv; charset=utf-8", csv, strlen(csv));
        else
            http_reply_problem(r, not_found ? PROBLEM_NO_SUCH_RESULT : PROBLEM_INTERNAL, err);
        return;
    }
    json_t *s = tres_series(path, r->arg, &not_found, err, sizeof err);
    if (s)
        http_reply_json(r, 200, s);
    else
        http_reply_problem(r, not_found ? PROBLEM_NO_SUCH_RESULT : PROBLEM_INTERNAL, err);
}

static void task_frames(struct hreq *r, void *app, void *ctx)
{
    char path[1200], err[256] = "";
    (void)ctx;
    h5_path(path, sizeof path, app, r->id);
    json_t *f = tres_frames(path, err, sizeof err);
    if (!f) {
        http_reply_problem(r, PROBLEM_NO_SUCH_RESULT, err);
        return;
    }
    http_reply_json(r, 200, json_pack("{s:o,s:I}", "frames", f, "count",
                                      (json_int_t)json_array_size(f)));
}

static void task_field(struct hreq *r, void *app, void *ctx)
{
    char path[1200], err[256] = "", buf[64];
    (void)ctx;
    h5_path(path, sizeof path, app, r->id);
    struct tres_field f;
    memset(&f, 0, sizeof f);
    int rc = tres_field(path, r->arg, r->num, &f, err, sizeof err);
    if (rc == 1 || rc == 2) {
        http_reply_problem(r, PROBLEM_NO_SUCH_RESULT,
                           *err ? err : rc == 1 ? "no such field" : "no such frame");
        return;
    }
    if (rc != 0) {
        http_reply_problem(r, PROBLEM_INTERNAL, err);
        return;
    }
    const size_t count = f.n_rows * (size_t)f.ncomp;
    if (r->flags & 4) { /* JSON */
        if (count > JSON_FIELD_MAX) {
            tres_field_free(&f);
            http_reply_problem(r, PROBLEM_NOT_ACCEPTABLE,
                               "field too large for JSON (more than 100000 values); "
                               "use application/octet-stream");
            return;
        }
        json_t *j = tres_field_json(&f, r->arg, r->num);
        tres_field_free(&f);
        http_reply_json(r, 200, j);
        return;
    }
    http_reply_buf(r, 200, "application/octet-stream", f.data, f.bytes);
    f.data = NULL;
    snprintf(buf, sizeof buf, "%zu,%d", f.n_rows, f.ncomp);
    http_add_header(r, "X-Shape", buf);
    http_add_header(r, "X-Dtype", f.dtype ? f.dtype : "<f4");
    long frame = r->num < 0 ? f.frames + r->num : r->num;
    snprintf(buf, sizeof buf, "%ld", frame);
    http_add_header(r, "X-Frame", buf);
    snprintf(buf, sizeof buf, "%.17g", f.time);
    http_add_header(r, "X-Time", buf);
    snprintf(buf, sizeof buf, "%ld", f.step);
    http_add_header(r, "X-Step", buf);
    if (f.units[0])
        http_add_header(r, "X-Units", f.units);
    tres_field_free(&f);
}

static void task_summary(struct hreq *r, void *app, void *ctx)
{
    struct tapp *a = app;
    struct tq *q = ctx;
    struct tq_job j, *kids = NULL;
    size_t nk = 0;
    if (load_job(r, a, q, r->id, &j) != 0)
        return;
    json_t *study = json_parse_or_null(j.input);
    if (!study || study_children(a, q, j.id, &kids, &nk) != 0) {
        json_decref(study);
        tq_job_free(&j);
        http_reply_problem(r, PROBLEM_INTERNAL, "cannot read the study");
        return;
    }
    struct tstudy_row *rows = calloc(nk ? nk : 1, sizeof *rows);
    char (*paths)[1200] = calloc(nk ? nk : 1, sizeof *paths);
    json_t **owned = calloc(2 * (nk ? nk : 1), sizeof *owned);
    json_t *summary = NULL;
    if (rows && paths && owned) {
        for (size_t i = 0; i < nk; i++) {
            h5_path(paths[i], sizeof paths[i], a, kids[i].id);
            owned[2 * i] = json_parse_or_null(kids[i].params);
            owned[2 * i + 1] = json_parse_or_null(kids[i].cost);
            rows[i].seq = kids[i].seq;
            rows[i].job_id = kids[i].id;
            rows[i].status = kids[i].status;
            rows[i].params = owned[2 * i];
            rows[i].h5path = paths[i];
            rows[i].cost = owned[2 * i + 1];
        }
        summary = tstudy_summary(study, rows, nk);
    }
    if (!summary) {
        http_reply_problem(r, PROBLEM_INTERNAL, "cannot build the summary");
    } else if (r->flags & 2) {
        char *csv = tstudy_summary_csv(summary);
        if (csv)
            http_reply_buf(r, 200, "text/csv; charset=utf-8", csv, strlen(csv));
        else
            http_reply_problem(r, PROBLEM_INTERNAL, "cannot format the summary");
        json_decref(summary);
    } else {
        http_reply_json(r, 200, summary);
    }
    if (owned)
        for (size_t i = 0; i < 2 * nk; i++)
            json_decref(owned[i]);
    free(owned);
    free(paths);
    free(rows);
    tq_jobs_free(kids, nk);
    json_decref(study);
    tq_job_free(&j);
}

static int format_csv(struct hreq *r, int *csv)
{
    const char *f = http_query(r, "format");
    *csv = 0;
    if (!f || !strcmp(f, "json"))
        return 0;
    if (!strcmp(f, "csv")) {
        *csv = 1;
        return 0;
    }
    http_reply_problem(r, PROBLEM_BAD_REQUEST, "format must be json or csv");
    return -1;
}

/* /jobs/{id}/results[/...] and /jobs/{id}/log; seg[0] = "results" or "log". */
static void job_sub(struct hreq *r, struct tapp *a, const char *id, char **seg, int nseg)
{
    struct tq_job j;
    if (load_job(r, a, a->q, id, &j) != 0)
        return;
    const int study = !strcmp(j.process, "study");
    const int final = tq_status_final(j.status), accepted = !strcmp(j.status, TQ_ACCEPTED);
    snprintf(r->id, sizeof r->id, "%s", j.id);
    char path[1200];
    int csv = 0;
    void (*task)(struct hreq *, void *, void *) = NULL;
    if (!strcmp(seg[0], "log")) {
        if (nseg != 1 || study)
            http_reply_problem(r, PROBLEM_NOT_FOUND, study ? "studies have no log" : "no such resource");
        else
            serve_log(r, a, &j);
        goto done;
    }
    if (accepted) {
        http_reply_problem(r, PROBLEM_RESULT_NOT_READY, "the job has not started yet");
        goto done;
    }
    if (nseg == 1) {
        results_doc(r, &j);
        goto done;
    }
    const char *what = seg[1];
    if (study) {
        if (strcmp(what, "summary") || nseg != 2) {
            http_reply_problem(r, PROBLEM_NOT_FOUND, "a study has only results/summary");
            goto done;
        }
        if (format_csv(r, &csv) != 0)
            goto done;
        r->flags = csv ? 2 : 0;
        task = task_summary;
    } else if (!strcmp(what, "result.h5") || !strcmp(what, "result.xmf")) {
        if (nseg != 2) {
            http_reply_problem(r, PROBLEM_NOT_FOUND, "no such resource");
        } else if (!final) {
            http_reply_problem(r, PROBLEM_RESULT_NOT_READY,
                               "the file is served once the job is final; read fields and "
                               "series while it runs");
        } else {
            const int h5 = !strcmp(what, "result.h5");
            char name[64];
            snprintf(name, sizeof name, "job-%.12s.%s", j.id, h5 ? "h5" : "xmf");
            job_file(path, sizeof path, a, j.id, h5 ? JOBDIR_RESULT : JOBDIR_SIDECAR);
            serve_file(r, path, h5 ? "application/x-hdf5" : "text/xml", j.id, name, 1);
        }
        goto done;
    } else if (!strcmp(what, "series")) {
        if (format_csv(r, &csv) != 0)
            goto done;
        if (nseg == 2) {
            task = task_series_list;
        } else {
            /* name = the remaining segments joined with '/' */
            r->arg[0] = '\0';
            for (int i = 2; i < nseg; i++) {
                if (i > 2)
                    strncat(r->arg, "/", sizeof r->arg - strlen(r->arg) - 1);
                strncat(r->arg, seg[i], sizeof r->arg - strlen(r->arg) - 1);
            }
            if (!tres_series_name_ok(r->arg)) {
                http_reply_problem(r, PROBLEM_NO_SUCH_RESULT, "no such series");
                goto done;
            }
            r->flags = csv ? 2 : 0;
            task = task_series;
        }
    } else if (!strcmp(what, "frames") && nseg == 2) {
        task = task_frames;
    } else if (!strcmp(what, "fields") && nseg == 3) {
        if (!tres_field_name_ok(seg[2])) {
            http_reply_problem(r, PROBLEM_NO_SUCH_RESULT, "no such field");
            goto done;
        }
        snprintf(r->arg, sizeof r->arg, "%s", seg[2]);
        long frame = -1;
        if (parse_long_arg(http_query(r, "frame"), -1000000000L, 1000000000L, &frame) < 0) {
            http_reply_problem(r, PROBLEM_BAD_REQUEST, "frame must be an integer (negative: from the end)");
            goto done;
        }
        r->num = frame;
        r->flags = accepts_json(r) ? 4 : 0;
        task = task_field;
    } else {
        http_reply_problem(r, PROBLEM_NOT_FOUND, "no such resource");
        goto done;
    }
    if (!study) {
        job_file(path, sizeof path, a, j.id, JOBDIR_RESULT);
        if (access(path, R_OK) != 0) {
            if (final)
                http_reply_problem(r, PROBLEM_NO_SUCH_RESULT, "the job produced no result file");
            else
                http_reply_problem(r, PROBLEM_RESULT_NOT_READY, "no result file yet");
            goto done;
        }
    }
    if (http_defer(r, task) != 0)
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "shutting down");
done:
    tq_job_free(&j);
}

/* ------------------------------------------------------------------ router */

static void method_not_allowed(struct hreq *r, const char *allow)
{
    http_reply_problem(r, PROBLEM_METHOD, "method not allowed for this resource");
    http_add_header(r, "Allow", allow);
}

static int is_get(const struct hreq *r)
{
    return !strcmp(r->method, "GET") || !strcmp(r->method, "HEAD");
}

static int public_path(char **seg, int nseg)
{
    if (nseg == 0)
        return 1;
    if (nseg == 1 && (!strcmp(seg[0], "conformance") || !strcmp(seg[0], "openapi.json") ||
                      !strcmp(seg[0], "healthz")))
        return 1;
    return nseg == 2 && !strcmp(seg[0], "schemas");
}

void troutes_route(struct hreq *r, void *app)
{
    struct tapp *a = app;
    char buf[2048];
    char *seg[MAX_SEGMENTS];
    int nseg = 0;
    const char *path = r->path;
    if (path[0] != '/' || strlen(path) >= sizeof buf) {
        http_reply_problem(r, PROBLEM_NOT_FOUND, "no such resource");
        return;
    }
    strcpy(buf, path + 1);
    if (buf[0]) {
        char *p = buf;
        for (;;) {
            char *slash = strchr(p, '/');
            if (slash)
                *slash = '\0';
            if (!*p || nseg == MAX_SEGMENTS) { /* empty segment ("//", trailing '/') */
                http_reply_problem(r, PROBLEM_NOT_FOUND, "no such resource");
                return;
            }
            seg[nseg++] = p;
            if (!slash)
                break;
            p = slash + 1;
        }
    }
    if (tauth_enabled(&a->cfg->auth) && !public_path(seg, nseg) &&
        !tauth_check_header(&a->cfg->auth, http_header(r, "Authorization"))) {
        http_reply_problem(r, PROBLEM_UNAUTHORIZED, "a valid bearer token is required");
        http_add_header(r, "WWW-Authenticate", "Bearer realm=\"tlsphd\"");
        return;
    }
    const char *allow = "GET, HEAD";
    if (nseg == 0) {
        if (!is_get(r))
            return method_not_allowed(r, allow);
        return landing(r);
    }
    if (nseg == 1 && !strcmp(seg[0], "conformance")) {
        if (!is_get(r))
            return method_not_allowed(r, allow);
        return conformance(r);
    }
    if (nseg == 1 && !strcmp(seg[0], "openapi.json")) {
        if (!is_get(r))
            return method_not_allowed(r, allow);
        return openapi(r, a);
    }
    if (nseg == 1 && !strcmp(seg[0], "healthz")) {
        if (!is_get(r))
            return method_not_allowed(r, allow);
        return healthz(r, a);
    }
    if (nseg == 2 && !strcmp(seg[0], "schemas")) {
        if (!is_get(r))
            return method_not_allowed(r, allow);
        return schema_file(r, a, seg[1]);
    }
    if (!strcmp(seg[0], "processes")) {
        if (nseg == 1) {
            if (!is_get(r))
                return method_not_allowed(r, allow);
            return processes(r);
        }
        if (nseg == 2) {
            if (!is_get(r))
                return method_not_allowed(r, allow);
            return process_one(r, seg[1]);
        }
        if (nseg == 3 && !strcmp(seg[2], "execution")) {
            if (strcmp(r->method, "POST"))
                return method_not_allowed(r, "POST");
            return execute(r, seg[1]);
        }
    } else if (!strcmp(seg[0], "jobs")) {
        if (nseg == 1) {
            if (!is_get(r))
                return method_not_allowed(r, allow);
            return list_jobs(r, a);
        }
        if (nseg == 2) {
            if (!strcmp(r->method, "DELETE"))
                return delete_job(r, a, seg[1]);
            if (!is_get(r))
                return method_not_allowed(r, "GET, HEAD, DELETE");
            return get_job(r, a, seg[1]);
        }
        if (!strcmp(seg[2], "results") || (!strcmp(seg[2], "log") && nseg == 3)) {
            if (!is_get(r))
                return method_not_allowed(r, allow);
            return job_sub(r, a, seg[1], seg + 2, nseg - 2);
        }
    }
    http_reply_problem(r, PROBLEM_NOT_FOUND, "no such resource");
}

/* ----------------------------------------------------------- helper threads */

void *troutes_thread_init(void *app)
{
    struct tapp *a = app;
    struct tq *q = NULL;
    char err[256];
    if (tq_open(a->cfg->db_path, &q, err, sizeof err) != 0) {
        tlog("helper thread cannot open the queue: %s", err);
        return NULL;
    }
    return q;
}

void troutes_thread_fini(void *ctx)
{
    if (ctx)
        tq_close(ctx);
}

int troutes_wait_ready(void *app, void *ctx, const char *id)
{
    (void)app;
    struct tq_job j;
    if (!ctx)
        return 1;
    int rc = tq_get(ctx, id, &j);
    int ready = rc != 0 || tq_status_final(j.status);
    tq_job_free(&j);
    return ready;
}
