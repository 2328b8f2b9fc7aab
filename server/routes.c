/* The tlsphd API: one route table and its matcher (see routes.h, route.h and
 * schemas/openapi.json).
 *
 * A request path is split into segments (an empty segment, more than
 * ROUTE_SEGMENTS_MAX of them or a path of ROUTE_PATH_MAX bytes is 404), then
 * matched against every pattern: literal segments, "{id}", "{process}" and
 * "{name}" (any one segment, kept for the handler), and a trailing "**"
 * (one or more segments).  The first row whose pattern and method match
 * handles the request (GET rows answer HEAD too).  When patterns match but no
 * method does, the answer is 405 with Allow listing the methods of every
 * matching row; when nothing matches, 404.  A bearer token is required
 * unless some public row's pattern matches the path, whatever the method. */
#include "route.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "auth.h"
#include "errmsg.h"
#include "problem.h"

struct route {
    const char *method;    /* "GET" (answers HEAD too), "POST" or "DELETE" */
    const char *pattern;
    route_handler *handler;
    bool public;           /* served without a token */
    enum route_lane lane;  /* the helper threads that run it (routes.h) */
};

/* Order matters only where patterns overlap: the first matching row wins,
 * so the catch-all under results/ comes last. */
static const struct route routes[] = {
    {"GET", "/", meta_landing, true, LANE_LIGHT},
    {"GET", "/conformance", meta_conformance, true, LANE_LIGHT},
    {"GET", "/openapi.json", meta_openapi, true, LANE_LIGHT},
    {"GET", "/healthz", meta_healthz, true, LANE_LIGHT},
    {"GET", "/schemas/{name}", meta_schema, true, LANE_LIGHT},
    {"GET", "/processes", meta_processes, false, LANE_LIGHT},
    {"GET", "/processes/{process}", meta_process, false, LANE_LIGHT},
    {"POST", "/processes/{process}/execution", job_execute, false, LANE_WRITE},
    {"GET", "/jobs", job_list, false, LANE_HEAVY},
    {"GET", "/jobs/{id}", job_get, false, LANE_LIGHT},
    {"DELETE", "/jobs/{id}", job_delete, false, LANE_WRITE},
    {"GET", "/jobs/{id}/log", result_log, false, LANE_HEAVY},
    {"GET", "/jobs/{id}/results", result_doc, false, LANE_HEAVY},
    {"GET", "/jobs/{id}/results/summary", result_summary, false, LANE_HEAVY},
    {"GET", "/jobs/{id}/results/convergence", result_convergence, false, LANE_HEAVY},
    {"GET", "/jobs/{id}/results/result.h5", result_h5, false, LANE_HEAVY},
    {"GET", "/jobs/{id}/results/result.xmf", result_xmf, false, LANE_HEAVY},
    {"GET", "/jobs/{id}/results/series", result_series_list, false, LANE_HEAVY},
    {"GET", "/jobs/{id}/results/series/**", result_series, false, LANE_HEAVY},
    {"GET", "/jobs/{id}/results/frames", result_frames, false, LANE_HEAVY},
    {"GET", "/jobs/{id}/results/fields/{name}", result_field, false, LANE_HEAVY},
    {"GET", "/jobs/{id}/results/**", result_other, false, LANE_HEAVY},
};
#define NROUTES (sizeof routes / sizeof routes[0])

/* ------------------------------------------------------------------ matcher */

/* Splits r's path into c->seg; false when it is not a path we serve. */
static bool split_path(struct route_call *c, const char *path)
{
    if (path[0] != '/' || strlen(path) >= sizeof c->path)
        return false;
    strcpy(c->path, path + 1);
    c->nseg = 0;
    if (!c->path[0])
        return true;
    for (char *p = c->path;;) {
        char *slash = strchr(p, '/');
        if (slash)
            *slash = '\0';
        if (!*p || c->nseg == ROUTE_SEGMENTS_MAX) /* "//", a trailing '/', too deep */
            return false;
        c->seg[c->nseg++] = p;
        if (!slash)
            return true;
        p = slash + 1;
    }
}

/* Does pattern match c's segments?  With bind, the parameters are kept in c. */
static bool match(const char *pattern, struct route_call *c, bool bind)
{
    const char *p = pattern + 1;
    int i = 0;
    while (*p) {
        const char *end = strchr(p, '/');
        const size_t len = end ? (size_t)(end - p) : strlen(p);
        if (len == 2 && !strncmp(p, "**", 2)) {
            if (i >= c->nseg)
                return false;
            if (bind) {
                c->nrest = c->nseg - i;
                memcpy(c->rest, c->seg + i, (size_t)c->nrest * sizeof *c->rest);
            }
            return true;
        }
        if (i >= c->nseg)
            return false;
        if (p[0] == '{') {
            if (bind) {
                const char *name = p + 1;
                const size_t nlen = len - 2;
                if (nlen == 2 && !strncmp(name, "id", 2))
                    c->id = c->seg[i];
                else if (nlen == 7 && !strncmp(name, "process", 7))
                    c->process = c->seg[i];
                else
                    c->name = c->seg[i];
            }
        } else if (strlen(c->seg[i]) != len || strncmp(c->seg[i], p, len) != 0) {
            return false;
        }
        i++;
        p += len + (end ? 1 : 0);
    }
    return i == c->nseg;
}

static bool method_matches(const struct route *rt, const char *method)
{
    return !strcmp(rt->method, method) || (!strcmp(rt->method, "GET") && !strcmp(method, "HEAD"));
}

/* "GET, HEAD, DELETE": the methods of every row matching the path. */
static void allowed_methods(const bool *matched, char *out, size_t size)
{
    out[0] = '\0';
    for (size_t k = 0; k < NROUTES; k++) {
        if (!matched[k])
            continue;
        const char *m = !strcmp(routes[k].method, "GET") ? "GET, HEAD" : routes[k].method;
        if (strstr(out, m))
            continue;
        size_t n = strlen(out);
        snprintf(out + n, size - n, "%s%s", n ? ", " : "", m);
    }
}

/* The call of this request, kept in r->data (made on first use; a request
 * that comes back after a long-poll is matched afresh). */
static struct route_call *call_of(struct hreq *r, struct tapp *a)
{
    struct route_call *c = r->data;
    if (!c) {
        c = malloc(sizeof *c);
        if (!c)
            return NULL;
        r->data = c;
    }
    memset(c, 0, sizeof *c);
    c->app = a;
    return c;
}

/* Matches r against the table and checks its token: the row to run, or NULL
 * with the refusal (401, 404 or 405) set as r's reply. */
static const struct route *resolve(struct hreq *r, struct tapp *a)
{
    struct route_call *c = call_of(r, a);
    if (!c) {
        http_reply_problem(r, PROBLEM_INTERNAL, "out of memory");
        return NULL;
    }
    if (!split_path(c, r->path)) {
        http_reply_problem(r, PROBLEM_NOT_FOUND, "no such resource");
        return NULL;
    }
    bool matched[NROUTES], any = false, public = false;
    const struct route *hit = NULL;
    for (size_t k = 0; k < NROUTES; k++) {
        matched[k] = match(routes[k].pattern, c, false);
        any |= matched[k];
        public |= matched[k] && routes[k].public;
        if (matched[k] && !hit && method_matches(&routes[k], r->method))
            hit = &routes[k];
    }
    if (tauth_enabled(&a->cfg->auth) && !public &&
        !tauth_check_header(&a->cfg->auth, http_header(r, "Authorization"))) {
        http_reply_problem(r, PROBLEM_UNAUTHORIZED, "a valid bearer token is required");
        http_add_header(r, "WWW-Authenticate", "Bearer realm=\"tlsphd\"");
        return NULL;
    }
    if (!any) {
        http_reply_problem(r, PROBLEM_NOT_FOUND, "no such resource");
        return NULL;
    }
    if (!hit) {
        char allow[64];
        allowed_methods(matched, allow, sizeof allow);
        http_reply_problem(r, PROBLEM_METHOD, "method not allowed for this resource");
        http_add_header(r, "Allow", allow);
        return NULL;
    }
    return hit;
}

void troutes_admit(struct hreq *r, void *app)
{
    const struct route *hit = resolve(r, app); /* a refusal is answered before the body */
    r->lane = hit ? (int)hit->lane : LANE_LIGHT;
}

void troutes_route(struct hreq *r, void *app, void *ctx)
{
    const struct route *hit = resolve(r, app);
    if (!hit)
        return;
    struct route_call *c = r->data;
    if (ctx) { /* the handlers use c->app->q: this thread's own handle */
        c->thread_app = *(struct tapp *)app;
        c->thread_app.q = ctx;
        c->app = &c->thread_app;
    }
    match(hit->pattern, c, true);
    hit->handler(r, c);
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
    enum tq_rc rc = tq_get(ctx, id, &j);
    int ready = rc != TQ_OK || tq_status_final(j.status);
    tq_job_free(&j);
    return ready;
}
