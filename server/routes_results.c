/* A job's results as resources (server/routes_results.c): the results
 * document, the files (result.h5, result.xmf, with byte ranges and ETags),
 * time series (JSON, CSV), frames, one field at one frame (binary or JSON),
 * a study's summary table, and the engine log.  HDF5 reads and summaries run
 * as tasks on the worker thread (results.h, study.h). */
#include "route.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "convergence.h"
#include "jobdir.h"
#include "numtext.h"
#include "problem.h"
#include "results.h"
#include "study.h"

#define LOG_TAIL (64 * 1024)     /* bytes of the engine log served */
#define JSON_FIELD_MAX 100000    /* values of a field served as JSON */

/* jobs_dir/<id>/<file> ("" when the id is not valid: the open fails). */
static void job_file(char *out, size_t n, const struct tapp *a, const char *id,
                     enum jobdir_file file)
{
    if (jobdir_path(out, n, a->cfg->jobs_dir, id, file) != 0)
        out[0] = '\0';
}

/* The results of a successful job (OGC API - Processes 1.0, response
 * "document"): the map of its declared outputs, each by reference. */
static void results_doc(struct hreq *r, const struct tq_job *j)
{
    const struct output_decl *out = route_process_output(route_process_id(j));
    char href[128];
    snprintf(href, sizeof href, "/jobs/%s/results/%s", j->id, out->path);
    http_reply_json(r, 200,
                    json_pack("{s:{s:s,s:s,s:s,s:s}}", out->id, "href", href, "rel", out->rel,
                              "type", out->media_type, "title", out->title));
}

/* The status of the exception for a failed job, by what made it fail
 * (OGC 1.0 /req/core/job-results-failed: a 4xx or 5xx reflecting the
 * failure): the input's (422), the disk's (507), else the server's (500). */
static unsigned failed_status(const char *outcome)
{
    if (!strcmp(outcome, "invalid") || !strcmp(outcome, "unstable") ||
        !strcmp(outcome, "timed_out") || !strcmp(outcome, "children_failed"))
        return 422;
    if (!strcmp(outcome, "io_error"))
        return 507;
    return 500;
}

/* The results of a failed or dismissed job: an exception naming why, with
 * the job's message and links to what it left (a run's partial result file
 * and its log: docs/api.md). */
static void results_exception(struct hreq *r, const struct tq_job *j)
{
    const bool failed = !strcmp(j->status, TQ_FAILED);
    /* a study fails when some of its children did (its message counts them) */
    const char *outcome = j->outcome[0]                     ? j->outcome
                          : failed && !strcmp(j->process, "study") ? "children_failed"
                          : failed                                 ? "failed"
                                                                   : "cancelled";
    char type[96];
    snprintf(type, sizeof type, "urn:tlsph:problem:job-%s", failed ? outcome : "dismissed");
    json_t *p = json_object();
    json_object_set_new(p, "type", json_string(type));
    json_object_set_new(p, "title",
                        json_string(failed ? "The job failed: it has no results"
                                           : "The job was dismissed: it has no results"));
    json_object_set_new(p, "status", json_integer(failed ? failed_status(outcome) : 404));
    json_t *msg = json_string(j->message && *j->message ? j->message : outcome);
    json_object_set_new(p, "detail", msg ? msg : json_string(outcome));
    json_object_set_new(p, "instance", json_string(r->path));
    json_object_set_new(p, "outcome", json_string(outcome));
    json_t *links = json_array();
    route_add_link(links, "up", "application/json", "the job", "/jobs/%s", j->id);
    if (strcmp(j->process, "study")) {
        route_add_link(links, "enclosure", "application/x-hdf5",
                       "the partial result file, if the engine wrote one",
                       "/jobs/%s/results/result.h5", j->id);
        route_add_link(links, "log", "text/plain", "engine log", "/jobs/%s/log", j->id);
    } else {
        route_add_link(links, "summary", "application/json", "the children's table",
                       "/jobs/%s/results/summary", j->id);
        if (!strcmp(route_process_id(j), "convergence"))
            route_add_link(links, "convergence", "application/json",
                           "what the finished children support", "/jobs/%s/results/convergence",
                           j->id);
    }
    json_object_set_new(p, "links", links);
    http_reply_problem_json(r, p);
}

/* A decimal number of a byte range; a value past UINT64_MAX saturates (it
 * is only ever compared with the file's size).  NULL when there is none. */
static const char *range_number(const char *h, uint64_t *v)
{
    if (!isdigit((unsigned char)*h))
        return NULL;
    *v = 0;
    for (; isdigit((unsigned char)*h); h++) {
        const unsigned d = (unsigned)(*h - '0');
        *v = *v > (UINT64_MAX - d) / 10 ? UINT64_MAX : *v * 10 + d;
    }
    return h;
}

/* The Range header of a GET (RFC 9110 section 14) → [*off, *off + *len) of
 * size: 0 none or ignored (the whole file: another method, a unit other than
 * bytes, several ranges), 1 one satisfiable range (a last position past the
 * end is clamped to the end), -1 unsatisfiable or malformed (416). */
static int parse_range(const char *method, const char *h, uint64_t size, uint64_t *off,
                       uint64_t *len)
{
    if (!h || strcmp(method, "GET") != 0) /* range handling is defined for GET only */
        return 0;
    while (*h == ' ' || *h == '\t')
        h++;
    if (strncasecmp(h, "bytes=", 6) != 0)
        return 0; /* a range unit we do not know is ignored */
    h += 6;
    if (strchr(h, ','))
        return 0; /* multiple ranges: serve the whole file */
    uint64_t a, b;
    if (*h == '-') { /* the last n bytes */
        h = range_number(h + 1, &b);
        if (!h || *h || b == 0 || size == 0)
            return -1;
        *len = b > size ? size : b;
        *off = size - *len;
        return 1;
    }
    h = range_number(h, &a);
    if (!h || *h != '-')
        return -1;
    h++;
    if (*h == '\0') {
        b = UINT64_MAX;
    } else {
        h = range_number(h, &b);
        if (!h || *h || b < a)
            return -1;
    }
    if (a >= size)
        return -1;
    if (b >= size)
        b = size - 1;
    *off = a;
    *len = b - a + 1;
    return 1;
}

/* Does an If-None-Match value match etag?  "*" matches any current file;
 * otherwise a list of entity tags compared weakly (RFC 9110 section 13.1.2:
 * W/ prefixes are ignored). */
static bool none_match_hits(const char *inm, const char *etag)
{
    const char *tag = etag + (strncmp(etag, "W/", 2) ? 0 : 2);
    const size_t tlen = strlen(tag);
    for (const char *p = inm;;) {
        while (*p == ' ' || *p == '\t' || *p == ',')
            p++;
        if (!*p)
            return false;
        if (*p == '*')
            return true;
        if (!strncmp(p, "W/", 2))
            p += 2;
        const char *q = *p == '"' ? strchr(p + 1, '"') : NULL;
        if (!q)
            return false; /* not an entity tag: nothing after it can be trusted */
        if ((size_t)(q + 1 - p) == tlen && !strncmp(p, tag, tlen))
            return true;
        p = q + 1;
    }
}

static void serve_file(struct hreq *r, const char *path, const char *ctype, const char *id,
                       const char *download_name, int ranges)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0) {
        const int e = errno;
        if (fd >= 0)
            close(fd);
        if (e == ENOENT)
            http_reply_problem(r, PROBLEM_NO_SUCH_RESULT, "the job produced no such file");
        else
            route_reply_fault(r, e, PROBLEM_NO_SUCH_RESULT, "cannot read the result file");
        return;
    }
    if (!S_ISREG(st.st_mode)) {
        close(fd);
        http_reply_problem(r, PROBLEM_NO_SUCH_RESULT, "the job produced no such file");
        return;
    }
    const uint64_t size = (uint64_t)st.st_size;
    char etag[96], buf[128];
    snprintf(etag, sizeof etag, "\"%" PRIx64 "-%lx.%lx-%.8s\"", size, (long)st.st_mtim.tv_sec,
             (long)st.st_mtim.tv_nsec, id);
    /* RFC 9110 section 13.2.2: If-None-Match before Range */
    const char *inm = http_header(r, "If-None-Match");
    if (inm && none_match_hits(inm, etag)) {
        close(fd);
        http_reply_buf(r, 304, NULL, NULL, 0);
        http_add_header(r, "ETag", etag);
        return;
    }
    uint64_t off = 0, len = size;
    int rr = 0;
    if (ranges) {
        /* If-Range compares strongly: a weak tag or a date never matches */
        const char *ifr = http_header(r, "If-Range");
        if (!ifr || !strcmp(ifr, etag))
            rr = parse_range(r->method, http_header(r, "Range"), size, &off, &len);
    }
    if (rr < 0) {
        close(fd);
        http_reply_problem(r, PROBLEM_RANGE, "the requested range is not satisfiable");
        snprintf(buf, sizeof buf, "bytes */%" PRIu64, size);
        http_add_header(r, "Content-Range", buf);
    } else {
        if (len == 0) {
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
static void serve_log(struct hreq *r, const struct tapp *a, const struct tq_job *j)
{
    char path[1200];
    job_file(path, sizeof path, a, j->id, JOBDIR_LOG);
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    struct stat st;
    if (fd < 0 && errno != ENOENT) { /* no log yet is an empty one; a failing disk is not */
        route_reply_fault(r, errno, PROBLEM_NO_SUCH_RESULT, "cannot read the engine log");
        return;
    }
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

/* A result read failed with otherwise (err: HDF5's words): when the file
 * itself cannot be opened or read, the disk is the cause and is answered as
 * one (route_reply_fault: 503 or 507, not 500); otherwise otherwise. */
static void reply_read_failure(struct hreq *r, const char *path, enum problem_kind otherwise,
                               const char *err)
{
    char probe[8];
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    const int e = fd < 0 ? errno : pread(fd, probe, sizeof probe, 0) < 0 ? errno : 0;
    if (fd >= 0)
        close(fd);
    if (e && problem_of_errno(e) != PROBLEM_INTERNAL)
        route_reply_fault(r, e, PROBLEM_NO_SUCH_RESULT, "cannot read the result file");
    else
        http_reply_problem(r, otherwise, err);
}

static void task_series_list(struct hreq *r, struct route_call *c, struct tq *q)
{
    char path[1200], err[256] = "";
    (void)q;
    job_file(path, sizeof path, c->app, c->id, JOBDIR_RESULT);
    json_t *list = tres_series_list(path, err, sizeof err);
    if (!list) {
        reply_read_failure(r, path, PROBLEM_NO_SUCH_RESULT, err);
        return;
    }
    json_t *links = json_array();
    route_add_link(links, "self", "application/json", NULL, "/jobs/%s/results/series", c->id);
    http_reply_json(r, 200, json_pack("{s:o,s:o}", "series", list, "links", links));
}

static void task_series(struct hreq *r, struct route_call *c, struct tq *q)
{
    char path[1200], err[256] = "";
    int not_found = 0;
    (void)q;
    job_file(path, sizeof path, c->app, c->id, JOBDIR_RESULT);
    if (c->format == FORMAT_CSV) {
        char *csv = tres_series_csv(path, c->series, &not_found, err, sizeof err);
        if (csv)
            http_reply_buf(r, 200, "text/csv; charset=utf-8", csv, strlen(csv));
        else if (not_found)
            http_reply_problem(r, PROBLEM_NO_SUCH_RESULT, err);
        else
            reply_read_failure(r, path, PROBLEM_INTERNAL, err);
        return;
    }
    json_t *s = tres_series(path, c->series, &not_found, err, sizeof err);
    if (s)
        http_reply_json(r, 200, s);
    else if (not_found)
        http_reply_problem(r, PROBLEM_NO_SUCH_RESULT, err);
    else
        reply_read_failure(r, path, PROBLEM_INTERNAL, err);
}

static void task_frames(struct hreq *r, struct route_call *c, struct tq *q)
{
    char path[1200], err[256] = "";
    (void)q;
    job_file(path, sizeof path, c->app, c->id, JOBDIR_RESULT);
    json_t *f = tres_frames(path, err, sizeof err);
    if (!f) {
        reply_read_failure(r, path, PROBLEM_NO_SUCH_RESULT, err);
        return;
    }
    http_reply_json(r, 200, json_pack("{s:o,s:I}", "frames", f, "count",
                                      (json_int_t)json_array_size(f)));
}

static void task_field(struct hreq *r, struct route_call *c, struct tq *q)
{
    char path[1200], err[256] = "", buf[64];
    (void)q;
    job_file(path, sizeof path, c->app, c->id, JOBDIR_RESULT);
    struct tres_field f;
    memset(&f, 0, sizeof f);
    enum tres_rc rc = tres_field(path, c->name, c->frame, &f, err, sizeof err);
    if (rc == TRES_NOT_FOUND || rc == TRES_NO_SUCH_FRAME) {
        http_reply_problem(r, PROBLEM_NO_SUCH_RESULT,
                           *err ? err : rc == TRES_NOT_FOUND ? "no such field" : "no such frame");
        return;
    }
    if (rc != TRES_OK) {
        reply_read_failure(r, path, PROBLEM_INTERNAL, err);
        return;
    }
    const size_t count = f.n_rows * (size_t)f.ncomp;
    if (c->format == FORMAT_JSON) {
        if (count > JSON_FIELD_MAX) {
            tres_field_free(&f);
            http_reply_problem(r, PROBLEM_NOT_ACCEPTABLE,
                               "field too large for JSON (more than 100000 values); "
                               "use application/octet-stream");
            return;
        }
        json_t *j = tres_field_json(&f, c->name, c->frame);
        tres_field_free(&f);
        http_reply_json(r, 200, j);
        return;
    }
    http_reply_buf(r, 200, "application/octet-stream", f.data, f.bytes);
    f.data = NULL;
    snprintf(buf, sizeof buf, "%zu,%d", f.n_rows, f.ncomp);
    http_add_header(r, "X-Shape", buf);
    http_add_header(r, "X-Dtype", f.dtype ? f.dtype : "<f4");
    long frame = c->frame < 0 ? f.frames + c->frame : c->frame;
    snprintf(buf, sizeof buf, "%ld", frame);
    http_add_header(r, "X-Frame", buf);
    http_add_header(r, "X-Time", numtext_real(buf, sizeof buf, f.time));
    snprintf(buf, sizeof buf, "%ld", f.step);
    http_add_header(r, "X-Step", buf);
    if (f.units[0])
        http_add_header(r, "X-Units", f.units);
    tres_field_free(&f);
}

/* A study's children as summary rows (the files and JSON they point to live
 * as long as the struct). */
struct kid_rows {
    struct tq_job *kids;
    size_t nk;
    struct tstudy_row *rows;
    char (*paths)[1200];
    json_t **owned;
};

static void kid_rows_free(struct kid_rows *k)
{
    if (k->owned)
        for (size_t i = 0; i < 2 * k->nk; i++)
            json_decref(k->owned[i]);
    free(k->owned);
    free(k->paths);
    free(k->rows);
    tq_jobs_free(k->kids, k->nk);
    memset(k, 0, sizeof *k);
}

/* 0, or -1 (busy or out of memory; nothing to free). */
static int kid_rows_load(const struct tapp *a, struct tq *q, const char *id, struct kid_rows *k)
{
    const struct jobs_env env = route_jobs_env(a, q);
    memset(k, 0, sizeof *k);
    if (jobs_study_children(&env, id, &k->kids, &k->nk) != 0)
        return -1;
    const size_t m = k->nk ? k->nk : 1;
    k->rows = calloc(m, sizeof *k->rows);
    k->paths = calloc(m, sizeof *k->paths);
    k->owned = calloc(2 * m, sizeof *k->owned);
    if (!k->rows || !k->paths || !k->owned) {
        kid_rows_free(k);
        return -1;
    }
    for (size_t i = 0; i < k->nk; i++) {
        job_file(k->paths[i], sizeof k->paths[i], a, k->kids[i].id, JOBDIR_RESULT);
        k->owned[2 * i] = route_json_or_null(k->kids[i].params);
        k->owned[2 * i + 1] = route_json_or_null(k->kids[i].cost);
        k->rows[i].seq = k->kids[i].seq;
        k->rows[i].job_id = k->kids[i].id;
        k->rows[i].status = k->kids[i].status;
        k->rows[i].params = k->owned[2 * i];
        k->rows[i].h5path = k->paths[i];
        k->rows[i].cost = k->owned[2 * i + 1];
    }
    return 0;
}

/* The table (JSON, or CSV with ?format=csv); steals table. */
static void reply_table(struct hreq *r, const struct route_call *c, json_t *table, const char *what)
{
    if (!table) {
        http_reply_problem(r, PROBLEM_INTERNAL, what);
    } else if (c->format == FORMAT_CSV) {
        char *csv = tstudy_summary_csv(table);
        if (csv)
            http_reply_buf(r, 200, "text/csv; charset=utf-8", csv, strlen(csv));
        else
            http_reply_problem(r, PROBLEM_INTERNAL, "cannot format the table");
        json_decref(table);
    } else {
        http_reply_json(r, 200, table);
    }
}

/* A study's table from its children: the summary, or (convergence) the
 * convergence result recomputed from the children's files and cost records
 * (JSON; ?format=csv: one row per output and run). */
static void study_table(struct hreq *r, struct route_call *c, struct tq *q, bool convergence)
{
    struct tq_job j;
    struct kid_rows k;
    if (route_load_job(r, q, c->id, &j) != 0)
        return;
    json_t *study = route_json_or_null(j.input);
    if (!study || kid_rows_load(c->app, q, j.id, &k) != 0) {
        json_decref(study);
        tq_job_free(&j);
        http_reply_problem(r, PROBLEM_INTERNAL, "cannot read the study");
        return;
    }
    json_t *table;
    if (!convergence) {
        table = tstudy_summary(study, k.rows, k.nk);
    } else {
        table = tconv_result(study, k.rows, k.nk);
        if (table && c->format == FORMAT_CSV) {
            json_t *rows = tconv_result_table(table);
            json_decref(table);
            table = rows;
        }
    }
    reply_table(r, c, table, convergence ? "cannot build the convergence result"
                                         : "cannot build the summary");
    kid_rows_free(&k);
    json_decref(study);
    tq_job_free(&j);
}

static void task_summary(struct hreq *r, struct route_call *c, struct tq *q)
{
    study_table(r, c, q, false);
}

static void task_convergence(struct hreq *r, struct route_call *c, struct tq *q)
{
    study_table(r, c, q, true);
}

/* ------------------------------------------------------------------ handlers */

/* The job behind a results route: answers 404/503 (route_load_job) or 409
 * while it is still queued, and returns -1 then. */
static int result_job(struct hreq *r, struct route_call *c, struct tq_job *j)
{
    if (route_load_job(r, c->app->q, c->id, j) != 0)
        return -1;
    if (!strcmp(j->status, TQ_ACCEPTED)) {
        http_reply_problem(r, PROBLEM_RESULT_NOT_READY, "the job has not started yet");
        tq_job_free(j);
        return -1;
    }
    return 0;
}

static bool is_study(const struct tq_job *j)
{
    return !strcmp(j->process, "study");
}

/* A run's result: answers 404 for a study and returns -1. */
static int run_result_job(struct hreq *r, struct route_call *c, struct tq_job *j)
{
    if (result_job(r, c, j) != 0)
        return -1;
    if (is_study(j)) {
        http_reply_problem(r, PROBLEM_NOT_FOUND, "a study has only results/summary");
        tq_job_free(j);
        return -1;
    }
    return 0;
}

/* 404 for a name that cannot exist, in results.c's words; bytes outside
 * printable ASCII become '?' (the detail must stay valid UTF-8). */
static void reply_no_such_name(struct hreq *r, const char *fmt, const char *name)
{
    char safe[61], detail[128];
    size_t n = 0;
    for (; name[n] && n < sizeof safe - 1; n++)
        safe[n] = name[n] >= 0x20 && name[n] < 0x7f ? name[n] : '?';
    safe[n] = '\0';
    snprintf(detail, sizeof detail, fmt, safe);
    http_reply_problem(r, PROBLEM_NO_SUCH_RESULT, detail);
}

/* ?format=json|csv; answers 400 and returns -1 for anything else. */
static int parse_format(struct hreq *r, struct route_call *c)
{
    const char *f = http_query(r, "format");
    c->format = FORMAT_JSON;
    if (!f || !strcmp(f, "json"))
        return 0;
    if (!strcmp(f, "csv")) {
        c->format = FORMAT_CSV;
        return 0;
    }
    http_reply_problem(r, PROBLEM_BAD_REQUEST, "format must be json or csv");
    return -1;
}

/* Defers task once the run has a result file (404 when a final job made
 * none, 409 before the engine created it). */
static void defer_result_task(struct hreq *r, struct route_call *c, const struct tq_job *j,
                              route_task *task)
{
    char path[1200];
    job_file(path, sizeof path, c->app, j->id, JOBDIR_RESULT);
    if (access(path, R_OK) != 0) {
        if (errno != ENOENT)
            route_reply_fault(r, errno, PROBLEM_NO_SUCH_RESULT, "cannot read the result file");
        else if (tq_status_final(j->status))
            http_reply_problem(r, PROBLEM_NO_SUCH_RESULT, "the job produced no result file");
        else
            http_reply_problem(r, PROBLEM_RESULT_NOT_READY, "no result file yet");
        return;
    }
    if (route_defer(r, c, task) != 0)
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "shutting down");
}

void result_log(struct hreq *r, struct route_call *c)
{
    struct tq_job j;
    if (route_load_job(r, c->app->q, c->id, &j) != 0)
        return;
    if (is_study(&j))
        http_reply_problem(r, PROBLEM_NOT_FOUND, "studies have no log");
    else
        serve_log(r, c->app, &j);
    tq_job_free(&j);
}

void result_doc(struct hreq *r, struct route_call *c)
{
    struct tq_job j;
    if (route_load_job(r, c->app->q, c->id, &j) != 0)
        return;
    if (!strcmp(j.status, TQ_SUCCESSFUL))
        results_doc(r, &j);
    else if (tq_status_final(j.status))
        results_exception(r, &j);
    else
        http_reply_problem(r, PROBLEM_RESULT_NOT_READY,
                           "the job is not finished: poll GET /jobs/{jobId}?wait=S; its series "
                           "and fields can be read while it runs");
    tq_job_free(&j);
}

void result_summary(struct hreq *r, struct route_call *c)
{
    struct tq_job j;
    if (result_job(r, c, &j) != 0)
        return;
    if (!is_study(&j))
        http_reply_problem(r, PROBLEM_NOT_FOUND, "no such resource");
    else if (parse_format(r, c) == 0 && route_defer(r, c, task_summary) != 0)
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "shutting down");
    tq_job_free(&j);
}

void result_convergence(struct hreq *r, struct route_call *c)
{
    struct tq_job j;
    if (result_job(r, c, &j) != 0)
        return;
    if (strcmp(route_process_id(&j), "convergence"))
        http_reply_problem(r, PROBLEM_NOT_FOUND, "only a convergence job has results/convergence");
    else if (parse_format(r, c) == 0 && route_defer(r, c, task_convergence) != 0)
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "shutting down");
    tq_job_free(&j);
}

/* result.h5 and result.xmf, whole or by byte range, once the job is final. */
static void result_file(struct hreq *r, struct route_call *c, enum jobdir_file file)
{
    struct tq_job j;
    if (run_result_job(r, c, &j) != 0)
        return;
    if (!tq_status_final(j.status)) {
        http_reply_problem(r, PROBLEM_RESULT_NOT_READY,
                           "the file is served once the job is final; read fields and "
                           "series while it runs");
    } else {
        const bool h5 = file == JOBDIR_RESULT;
        char name[64], path[1200];
        snprintf(name, sizeof name, "job-%.12s.%s", j.id, h5 ? "h5" : "xmf");
        job_file(path, sizeof path, c->app, j.id, file);
        serve_file(r, path, h5 ? "application/x-hdf5" : "text/xml", j.id, name, 1);
    }
    tq_job_free(&j);
}

void result_h5(struct hreq *r, struct route_call *c)
{
    result_file(r, c, JOBDIR_RESULT);
}

void result_xmf(struct hreq *r, struct route_call *c)
{
    result_file(r, c, JOBDIR_SIDECAR);
}

void result_series_list(struct hreq *r, struct route_call *c)
{
    struct tq_job j;
    if (run_result_job(r, c, &j) != 0)
        return;
    if (parse_format(r, c) == 0)
        defer_result_task(r, c, &j, task_series_list);
    tq_job_free(&j);
}

void result_series(struct hreq *r, struct route_call *c)
{
    struct tq_job j;
    if (run_result_job(r, c, &j) != 0)
        return;
    if (parse_format(r, c) != 0)
        goto done;
    /* the name is the rest of the path: "groups/right/reaction_force" */
    c->series[0] = '\0';
    for (int i = 0; i < c->nrest; i++) {
        if (i > 0)
            strncat(c->series, "/", sizeof c->series - strlen(c->series) - 1);
        strncat(c->series, c->rest[i], sizeof c->series - strlen(c->series) - 1);
    }
    if (!tres_series_name_ok(c->series)) {
        reply_no_such_name(r, TRES_NO_SERIES, c->series);
    } else {
        defer_result_task(r, c, &j, task_series);
    }
done:
    tq_job_free(&j);
}

void result_frames(struct hreq *r, struct route_call *c)
{
    struct tq_job j;
    if (run_result_job(r, c, &j) != 0)
        return;
    defer_result_task(r, c, &j, task_frames);
    tq_job_free(&j);
}

void result_field(struct hreq *r, struct route_call *c)
{
    struct tq_job j;
    if (run_result_job(r, c, &j) != 0)
        return;
    c->frame = -1;
    if (!tres_field_name_ok(c->name)) {
        reply_no_such_name(r, TRES_NO_FIELD, c->name);
    } else if (route_query_long(http_query(r, "frame"), -1000000000L, 1000000000L, &c->frame) < 0) {
        http_reply_problem(r, PROBLEM_BAD_REQUEST,
                           "frame must be an integer (negative: from the end)");
    } else {
        const char *accept = http_header(r, "Accept");
        c->format = accept && strstr(accept, "application/json") ? FORMAT_JSON : FORMAT_BINARY;
        defer_result_task(r, c, &j, task_field);
    }
    tq_job_free(&j);
}

/* Any other path under results/: what the job has instead. */
void result_other(struct hreq *r, struct route_call *c)
{
    struct tq_job j;
    if (result_job(r, c, &j) != 0)
        return;
    http_reply_problem(r, PROBLEM_NOT_FOUND,
                       is_study(&j) ? "a study has only results/summary" : "no such resource");
    tq_job_free(&j);
}
