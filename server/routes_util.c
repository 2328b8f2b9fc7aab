/* Helpers shared by the route handlers, see route.h. */
#include "route.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "problem.h"

static void run_task(struct hreq *r, void *app, void *ctx)
{
    (void)app;
    struct route_call *c = r->data;
    c->task(r, c, ctx);
}

int route_defer(struct hreq *r, struct route_call *c, route_task *task)
{
    c->task = task;
    return http_defer(r, run_task);
}

struct jobs_env route_jobs_env(const struct tapp *a, struct tq *q)
{
    return (struct jobs_env){.q = q, .cfg = a->cfg, .sup = a->sup};
}

int route_load_job(struct hreq *r, struct tq *q, const char *id, struct tq_job *j)
{
    if (!job_id_valid(id)) {
        memset(j, 0, sizeof *j);
        http_reply_problem(r, PROBLEM_NO_SUCH_JOB, "no job with this id");
        return -1;
    }
    switch (tq_get(q, id, j)) {
    case TQ_OK:
        return 0;
    case TQ_NOT_FOUND:
        http_reply_problem(r, PROBLEM_NO_SUCH_JOB, "no job with this id");
        return -1;
    default:
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "database busy, retry");
        http_add_header(r, "Retry-After", "1");
        return -1;
    }
}

void route_add_link(json_t *links, const char *rel, const char *type, const char *title,
                    const char *fmt, ...)
{
    char href[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(href, sizeof href, fmt, ap);
    va_end(ap);
    json_t *l = json_object();
    json_object_set_new(l, "href", json_string(href));
    json_object_set_new(l, "rel", json_string(rel));
    if (type)
        json_object_set_new(l, "type", json_string(type));
    if (title)
        json_object_set_new(l, "title", json_string(title));
    json_array_append_new(links, l);
}

int route_query_long(const char *s, long lo, long hi, long *out)
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

void route_reply_fault(struct hreq *r, int err, enum problem_kind missing, const char *what)
{
    enum problem_kind kind = problem_of_errno(err);
    char detail[256];
    snprintf(detail, sizeof detail, "%s: %s", what, strerror(err));
    http_reply_problem(r, kind == PROBLEM_NOT_FOUND ? missing : kind, detail);
    if (kind == PROBLEM_UNAVAILABLE)
        http_add_header(r, "Retry-After", "5");
}

json_t *route_json_or_null(const char *text)
{
    if (!text || !*text)
        return NULL;
    return json_loads(text, 0, NULL);
}
