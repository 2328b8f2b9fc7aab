/* Inside the route layer (server/route.h): what routes.c's matcher hands to
 * the handlers of routes_meta.c, routes_jobs.c and routes_results.c, and the
 * helpers they share (routes_util.c).
 *
 * A handler gets the request and a struct route_call: the matched path
 * parameters and the options it parsed from the query and the headers, each
 * in its own typed member.  The call lives in r->data (freed by http.c with
 * the request), so a task deferred with route_defer (run on the same lane thread) reads
 * the same members there. */
#ifndef TLSPHD_ROUTE_H
#define TLSPHD_ROUTE_H

#include <stdbool.h>
#include <stddef.h>

#include <jansson.h>

#include "http.h"
#include "jobs.h"
#include "queue.h"
#include "routes.h"

#define ROUTE_PATH_MAX 2048  /* longer request paths are 404 */
#define ROUTE_SEGMENTS_MAX 16

#define REL_RESULTS "http://www.opengis.net/def/rel/ogc/1.0/results"
#define REL_EXEC "http://www.opengis.net/def/rel/ogc/1.0/execute"
#define REL_JOBLIST "http://www.opengis.net/def/rel/ogc/1.0/job-list"
#define REL_PROCESSES "http://www.opengis.net/def/rel/ogc/1.0/processes"
#define REL_CONFORMANCE "http://www.opengis.net/def/rel/ogc/1.0/conformance"

enum route_format {
    FORMAT_JSON,  /* application/json (the default) */
    FORMAT_CSV,   /* ?format=csv */
    FORMAT_BINARY /* application/octet-stream (a field without Accept: application/json) */
};

struct route_call;
typedef void route_handler(struct hreq *r, struct route_call *c);
/* A deferred task, with the lane thread's queue handle. */
typedef void route_task(struct hreq *r, struct route_call *c, struct tq *q);

struct route_call {
    struct tapp *app;    /* thread_app on a lane thread: its q is that thread's */
    struct tapp thread_app;
    /* path parameters: point into path[] ("{id}", "{process}", "{name}"; NULL
     * when the route has none) and the segments matched by a trailing "**" */
    const char *id, *process, *name;
    char *rest[ROUTE_SEGMENTS_MAX];
    int nrest;
    /* what the handler parsed for its task */
    enum route_format format;
    long frame;          /* fields: ?frame= (negative: from the end) */
    char series[512];    /* series: the name, rest joined with '/' */
    bool respond_async;  /* execute: Prefer: respond-async was given */
    route_task *task;    /* set by route_defer */
    /* the request path split in place */
    char path[ROUTE_PATH_MAX];
    char *seg[ROUTE_SEGMENTS_MAX];
    int nseg;
};

/* The one output a process declares (routes_meta.c): "result" of a run (the
 * HDF5 file), "summary" of a study (its table). */
struct output_decl {
    const char *id, *title, *media_type;
    const char *path; /* under /jobs/{id}/results/ */
    const char *rel;  /* of its link in the results */
};
/* The output of process "run", "study" or "convergence" (NULL for another). */
const struct output_decl *route_process_output(const char *process);
/* The process a job was submitted to: its queue process ("run", "study"), or
 * "convergence" for a study the convergence process made. */
const char *route_process_id(const struct tq_job *j);
#define ROUTE_KNOWN_PROCESSES "known processes: run, study, convergence"

/* The handlers, by resource. */
route_handler meta_landing, meta_conformance, meta_openapi, meta_healthz, meta_schema,
    meta_processes, meta_process;
route_handler job_execute, job_list, job_get, job_delete;
route_handler result_log, result_doc, result_summary, result_h5, result_xmf, result_series_list,
    result_series, result_frames, result_field, result_other, result_convergence;

/* routes_util.c */

/* Runs task with this lane thread's queue handle; 0, or -1 when shutting down
 * (reply yourself). */
int route_defer(struct hreq *r, struct route_call *c, route_task *task);
/* The service view of this thread's queue handle. */
struct jobs_env route_jobs_env(const struct tapp *a, struct tq *q);
/* Loads job id; on failure answers 404 (bad or unknown id) or 503 and returns -1. */
int route_load_job(struct hreq *r, struct tq *q, const char *id, struct tq_job *j);
/* Appends a link object {href, rel, type, title} (type and title may be NULL). */
void route_add_link(json_t *links, const char *rel, const char *type, const char *title,
                    const char *fmt, ...) __attribute__((format(printf, 5, 6)));
/* Integer query value in [lo, hi]: 0 parsed, 1 absent (out untouched), -1 bad. */
int route_query_long(const char *s, long lo, long hi, long *out);
/* Answers a system error err met while doing `what` on the data directory
 * (problem_of_errno: 507, 503 with Retry-After, or 500; a missing file is
 * answered with missing, e.g. PROBLEM_NO_SUCH_RESULT).  The detail names
 * what failed and the system's words, never a path. */
void route_reply_fault(struct hreq *r, int err, enum problem_kind missing, const char *what);
/* routes_filter.c */

/* Calls fn with every value of query parameter name, in order (a repeated
 * parameter gives several). */
void route_query_each(struct hreq *r, const char *name, void (*fn)(const char *value, void *ctx),
                      void *ctx);
/* The job-list filter of GET /jobs's query: 0, or -1 with detail (a 400).
 * *none: the query can match no job (a type other than "process"). */
int route_job_filter(struct hreq *r, struct tq_filter *f, bool *none, char *detail, size_t size);
/* "&status=...&datetime=..." of the filter, for the list's self and next links. */
void route_job_filter_query(struct hreq *r, const struct tq_filter *f, char *out, size_t size);

/* A JSON text from the queue (NULL or "" -> NULL). */
json_t *route_json_or_null(const char *text);

#endif
