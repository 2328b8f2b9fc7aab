/* The HTTP layer of tlsphd, see http.h. */
#include "http.h"

#include <errno.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <unistd.h>

#include <microhttpd.h>

#include "errmsg.h"
#include "http_conns.h"
#include "http_protocol.h"
#include "numtext.h"
#include "util/clock.h"

#define CONNECTION_MEMORY_LIMIT (128 * 1024)
#define WATCH_PERIOD_MS 200
#define LATE_LOG_PERIOD 10.0

enum { PHASE_NEW, PHASE_BODY, PHASE_DEFERRED, PHASE_WAITING, PHASE_DONE };

struct task {
    struct hreq *r;
    void (*fn)(struct hreq *r, void *app, void *ctx);
    struct task *next;
};

struct waiter {
    struct hreq *r;
    char id[40];
    double deadline;
};

struct http {
    struct http_config cfg;
    struct MHD_Daemon *d;
    pthread_mutex_t mu;
    pthread_cond_t work_cv, watch_cv;
    struct task *head, *tail;
    struct waiter *waiters;
    size_t nwait, capwait;
    int stopping;
    pthread_t worker, watcher;
    int worker_started, watcher_started;
    struct http_conns *conns;
    size_t late_closed;   /* connections shut past a deadline, not yet logged */
    double late_logged;   /* when that was last logged */
};

/* ------------------------------------------------------------------ replies */

static void reply_clear(struct hreply *p)
{
    free(p->ctype);
    free(p->body);
    if (p->fd >= 0)
        close(p->fd);
    for (int i = 0; i < p->nhdr; i++) {
        free(p->hname[i]);
        free(p->hvalue[i]);
    }
    memset(p, 0, sizeof *p);
    p->fd = -1;
}

static void reply_set(struct hreq *r, unsigned status, const char *ctype)
{
    /* keep headers added before the reply body was chosen */
    free(r->reply.ctype);
    free(r->reply.body);
    if (r->reply.fd >= 0)
        close(r->reply.fd);
    r->reply.body = NULL;
    r->reply.len = 0;
    r->reply.fd = -1;
    r->reply.offset = 0;
    r->reply.status = status;
    r->reply.ctype = ctype ? strdup(ctype) : NULL;
    r->has_reply = 1;
}

void http_reply_buf(struct hreq *r, unsigned status, const char *ctype, char *body, size_t len)
{
    reply_set(r, status, ctype);
    r->reply.body = body;
    r->reply.len = body ? len : 0;
}

void http_reply_text(struct hreq *r, unsigned status, const char *ctype, const char *text)
{
    char *b = strdup(text ? text : "");
    http_reply_buf(r, status, ctype, b, b ? strlen(b) : 0);
}

void http_reply_json(struct hreq *r, unsigned status, json_t *body)
{
    char *s = body ? numtext_json_dumps(body, JSON_COMPACT | JSON_ENSURE_ASCII) : NULL;
    json_decref(body);
    if (!s) {
        http_reply_text(r, 500, PROBLEM_CONTENT_TYPE,
                        "{\"type\":\"urn:tlsph:problem:internal\",\"title\":\"Internal server "
                        "error\",\"status\":500}");
        return;
    }
    size_t n = strlen(s);
    s[n] = '\0';
    http_reply_buf(r, status, "application/json", s, n);
}

void http_reply_problem_json(struct hreq *r, json_t *problem)
{
    json_int_t st = json_integer_value(json_object_get(problem, "status"));
    http_reply_json(r, st >= 400 && st < 600 ? (unsigned)st : 500, problem);
    free(r->reply.ctype);
    r->reply.ctype = strdup(PROBLEM_CONTENT_TYPE);
}

void http_reply_problem(struct hreq *r, enum problem_kind kind, const char *detail)
{
    http_reply_problem_json(r, problem_new(kind, detail, r->path));
}

void http_reply_fd(struct hreq *r, unsigned status, const char *ctype, int fd, uint64_t offset,
                   uint64_t len)
{
    reply_set(r, status, ctype);
    r->reply.fd = fd;
    r->reply.offset = offset;
    r->reply.len = (size_t)len;
}

void http_add_header(struct hreq *r, const char *name, const char *value)
{
    for (int i = 0; i < r->reply.nhdr; i++)
        if (!strcasecmp(r->reply.hname[i], name)) {
            free(r->reply.hvalue[i]);
            r->reply.hvalue[i] = strdup(value);
            return;
        }
    if (r->reply.nhdr >= HTTP_MAX_HEADERS)
        return;
    r->reply.hname[r->reply.nhdr] = strdup(name);
    r->reply.hvalue[r->reply.nhdr] = strdup(value);
    r->reply.nhdr++;
}

const char *http_header(struct hreq *r, const char *name)
{
    return MHD_lookup_connection_value(r->conn, MHD_HEADER_KIND, name);
}

const char *http_query(struct hreq *r, const char *name)
{
    return MHD_lookup_connection_value(r->conn, MHD_GET_ARGUMENT_KIND, name);
}

static enum MHD_Result queue_reply(struct hreq *r)
{
    struct MHD_Response *resp;
    struct hreply *p = &r->reply;
    if (!r->has_reply) {
        reply_clear(p);
        http_reply_problem(r, PROBLEM_INTERNAL, "no response produced");
    }
    if (p->fd >= 0) {
        resp = MHD_create_response_from_fd_at_offset64(p->len, p->fd, p->offset);
        if (resp)
            p->fd = -1; /* MHD owns and closes it */
    } else {
        resp = MHD_create_response_from_buffer(p->len, p->body ? p->body : (void *)"",
                                               p->body ? MHD_RESPMEM_MUST_FREE
                                                       : MHD_RESPMEM_PERSISTENT);
        if (resp)
            p->body = NULL;
    }
    if (!resp)
        return MHD_NO;
    if (p->ctype)
        MHD_add_response_header(resp, MHD_HTTP_HEADER_CONTENT_TYPE, p->ctype);
    for (int i = 0; i < p->nhdr; i++)
        if (p->hname[i] && p->hvalue[i])
            MHD_add_response_header(resp, p->hname[i], p->hvalue[i]);
    MHD_add_response_header(resp, "X-Content-Type-Options", "nosniff");
    MHD_add_response_header(resp, "Cache-Control", "no-store");
    enum MHD_Result ret = MHD_queue_response(r->conn, p->status, resp);
    MHD_destroy_response(resp);
    r->logged_status = p->status;
    r->phase = PHASE_DONE;
    return ret;
}

/* A reply before the body was read: MHD sends it and then closes the
 * connection instead of reading (and discarding) the rest of the upload. */
static enum MHD_Result refuse(struct hreq *r)
{
    http_add_header(r, MHD_HTTP_HEADER_CONNECTION, "close");
    return queue_reply(r);
}

/* ------------------------------------------------------------ helper threads */

int http_defer(struct hreq *r, void (*fn)(struct hreq *r, void *app, void *ctx))
{
    struct http *h = r->http;
    struct task *t = calloc(1, sizeof *t);
    if (!t)
        return -1;
    t->r = r;
    t->fn = fn;
    pthread_mutex_lock(&h->mu);
    if (h->stopping) {
        pthread_mutex_unlock(&h->mu);
        free(t);
        return -1;
    }
    /* suspend before the worker can see the task (it resumes after the task) */
    r->phase = PHASE_DEFERRED;
    r->has_reply = 0;
    MHD_suspend_connection(r->conn);
    if (h->tail)
        h->tail->next = t;
    else
        h->head = t;
    h->tail = t;
    pthread_cond_signal(&h->work_cv);
    pthread_mutex_unlock(&h->mu);
    return 0;
}

int http_wait(struct hreq *r, const char *id, double deadline)
{
    struct http *h = r->http;
    pthread_mutex_lock(&h->mu);
    if (h->stopping || h->nwait >= h->cfg.max_waiters) {
        pthread_mutex_unlock(&h->mu);
        return -1;
    }
    if (h->nwait == h->capwait) {
        size_t cap = h->capwait ? 2 * h->capwait : 16;
        void *p = realloc(h->waiters, cap * sizeof *h->waiters);
        if (!p) {
            pthread_mutex_unlock(&h->mu);
            return -1;
        }
        h->waiters = p;
        h->capwait = cap;
    }
    struct waiter *w = &h->waiters[h->nwait++];
    w->r = r;
    snprintf(w->id, sizeof w->id, "%s", id);
    w->deadline = deadline;
    r->phase = PHASE_WAITING;
    MHD_suspend_connection(r->conn);
    pthread_cond_signal(&h->watch_cv);
    pthread_mutex_unlock(&h->mu);
    return 0;
}

static void *worker_main(void *arg)
{
    struct http *h = arg;
    void *ctx = h->cfg.thread_init ? h->cfg.thread_init(h->cfg.app) : NULL;
    pthread_mutex_lock(&h->mu);
    for (;;) {
        while (!h->head && !h->stopping)
            pthread_cond_wait(&h->work_cv, &h->mu);
        struct task *t = h->head;
        if (!t)
            break; /* stopping and drained */
        h->head = t->next;
        if (!h->head)
            h->tail = NULL;
        pthread_mutex_unlock(&h->mu);
        t->fn(t->r, h->cfg.app, ctx);
        if (!t->r->has_reply)
            http_reply_problem(t->r, PROBLEM_INTERNAL, "task produced no response");
        MHD_resume_connection(t->r->conn);
        free(t);
        pthread_mutex_lock(&h->mu);
    }
    pthread_mutex_unlock(&h->mu);
    if (h->cfg.thread_fini)
        h->cfg.thread_fini(ctx);
    return NULL;
}

/* Shuts the connections past their deadlines (http_conns.h); says so in the
 * log at most every LATE_LOG_PERIOD s, so that an attack does not flood it. */
static void enforce_deadlines(struct http *h, double now)
{
    h->late_closed += http_conns_enforce(h->conns, now);
    if (h->late_closed && now - h->late_logged >= LATE_LOG_PERIOD) {
        tlog("closed %zu connection(s) whose headers or body were not complete within "
             "header_timeout %d s / body_timeout %d s",
             h->late_closed, h->cfg.header_timeout, h->cfg.body_timeout);
        h->late_closed = 0;
        h->late_logged = now;
    }
}

static void *watcher_main(void *arg)
{
    struct http *h = arg;
    void *ctx = h->cfg.thread_init ? h->cfg.thread_init(h->cfg.app) : NULL;
    pthread_mutex_lock(&h->mu);
    for (;;) {
        const double now = tlsph_monotonic_seconds();
        enforce_deadlines(h, now);
        for (size_t i = 0; i < h->nwait;) {
            struct waiter *w = &h->waiters[i];
            int go = h->stopping || now >= w->deadline;
            if (!go && h->cfg.wait_ready)
                go = h->cfg.wait_ready(h->cfg.app, ctx, w->id) != 0;
            if (go) {
                struct hreq *r = w->r;
                h->waiters[i] = h->waiters[--h->nwait];
                r->resumed = 1;
                MHD_resume_connection(r->conn);
            } else {
                i++;
            }
        }
        if (h->stopping)
            break;
        struct timespec ts; /* the deadlines are checked every period, waiters or not */
        clock_gettime(CLOCK_REALTIME, &ts);
        ts.tv_nsec += WATCH_PERIOD_MS * 1000000L;
        if (ts.tv_nsec >= 1000000000L) {
            ts.tv_sec++;
            ts.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&h->watch_cv, &h->mu, &ts);
    }
    pthread_mutex_unlock(&h->mu);
    if (h->cfg.thread_fini)
        h->cfg.thread_fini(ctx);
    return NULL;
}

/* -------------------------------------------------------------- MHD glue */

static struct hreq *request_new(struct http *h, struct MHD_Connection *conn)
{
    struct hreq *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    r->conn = conn;
    r->http = h;
    r->t0 = tlsph_monotonic_seconds();
    r->reply.fd = -1;
    r->phase = PHASE_NEW;
    return r;
}

/* Called by MHD with the raw request target before it splits the query: the
 * request starts here, and a query with too many parameters is cut off before
 * MHD tries to store them (http_protocol.h).  0.9.75 passes the connection's
 * own buffer, which it parses right after this call, so the cut takes. */
static void *uri_cb(void *cls, const char *uri, struct MHD_Connection *conn)
{
    struct hreq *r = request_new(cls, conn);
    if (r)
        r->query_params = http_protocol_trim_query((char *)uri);
    return r;
}

/* The checks of the request line and headers before anything else (http_protocol.h). */
static int protocol_refused(struct hreq *r, const char *version)
{
    char detail[160];
    enum problem_kind kind;
    if (r->query_params) {
        snprintf(detail, sizeof detail, "%zu query parameters; at most %d are accepted",
                 r->query_params, HTTP_MAX_QUERY_PARAMS);
        http_reply_problem(r, PROBLEM_URI_TOO_LONG, detail);
        return 1;
    }
    if (http_protocol_check(r->conn, version, &kind, detail, sizeof detail) != 0) {
        http_reply_problem(r, kind, detail);
        return 1;
    }
    return 0;
}

static enum MHD_Result access_cb(void *cls, struct MHD_Connection *conn, const char *url,
                                 const char *method, const char *version,
                                 const char *upload_data, size_t *upload_data_size,
                                 void **con_cls)
{
    struct http *h = cls;
    struct hreq *r = *con_cls;
    if (!r && !(r = *con_cls = request_new(h, conn)))
        return MHD_NO;
    if (r->phase == PHASE_NEW) {
        snprintf(r->method, sizeof r->method, "%s", method);
        r->path = strdup(url ? url : "/");
        if (!r->path)
            return MHD_NO;
        r->phase = PHASE_BODY;
        http_conn_headers_in(conn);
        if (protocol_refused(r, version))
            return refuse(r);
        if (h->cfg.admit)
            h->cfg.admit(r, h->cfg.app);
        if (r->has_reply)
            return refuse(r);
        const char *cl = MHD_lookup_connection_value(conn, MHD_HEADER_KIND,
                                                     MHD_HTTP_HEADER_CONTENT_LENGTH);
        if (cl) {
            char *end;
            errno = 0;
            unsigned long long n = strtoull(cl, &end, 10);
            if (errno || end == cl || n > h->cfg.body_limit) {
                r->too_big = 1;
                http_reply_problem(r, PROBLEM_TOO_LARGE, "request body exceeds the limit");
                return refuse(r);
            }
        }
        return MHD_YES;
    }
    if (r->phase == PHASE_BODY && *upload_data_size > 0) {
        size_t n = *upload_data_size;
        *upload_data_size = 0;
        if (r->too_big || r->body.len + n > h->cfg.body_limit) {
            r->too_big = 1;
            return MHD_YES; /* count and drop; answer 413 at the end */
        }
        strbuf_add(&r->body, upload_data, n);
        if (r->body.oom)
            return MHD_NO;
        return MHD_YES;
    }
    if (r->phase == PHASE_DONE) {
        *upload_data_size = 0; /* answered early (413): drop the rest */
        return MHD_YES;
    }
    if (r->phase == PHASE_DEFERRED) /* resumed by the worker: reply is ready */
        return queue_reply(r);
    /* body complete, or re-entry after a long-poll */
    if (r->too_big) {
        http_reply_problem(r, PROBLEM_TOO_LARGE, "request body exceeds the limit");
        return queue_reply(r);
    }
    http_conn_complete(conn);
    r->phase = PHASE_BODY;
    r->has_reply = 0;
    h->cfg.route(r, h->cfg.app);
    if (r->phase == PHASE_DEFERRED || r->phase == PHASE_WAITING)
        return MHD_YES; /* suspended */
    return queue_reply(r);
}

static void log_line(const struct hreq *r)
{
    char ts[32], path[256];
    struct timespec now;
    struct tm tm;
    clock_gettime(CLOCK_REALTIME, &now);
    gmtime_r(&now.tv_sec, &tm);
    strftime(ts, sizeof ts, "%Y-%m-%dT%H:%M:%S", &tm);
    size_t i = 0;
    for (const char *s = r->path; s && *s && i + 1 < sizeof path; s++)
        path[i++] = (*s >= 0x20 && *s < 0x7f) ? *s : '?';
    path[i] = '\0';
    fprintf(stderr, "%s.%03ldZ tlsphd: %s %s %u %.1fms\n", ts, now.tv_nsec / 1000000L,
            r->method[0] ? r->method : "-", i ? path : "-", r->logged_status, 1e3 * (tlsph_monotonic_seconds() - r->t0));
}

static void completed_cb(void *cls, struct MHD_Connection *conn, void **con_cls,
                         enum MHD_RequestTerminationCode toe)
{
    (void)cls;
    (void)toe;
    http_conn_answered(conn);
    struct hreq *r = *con_cls;
    if (!r)
        return;
    log_line(r);
    reply_clear(&r->reply);
    free(r->path);
    strbuf_free(&r->body);
    free(r->data);
    free(r);
    *con_cls = NULL;
}

static int hexdigit(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

/* Percent-decoding of paths and query values, in place, like MHD's default
 * except that "%00" stays literal: a NUL must not silently cut a path short. */
static size_t unescape_cb(void *cls, struct MHD_Connection *c, char *s)
{
    (void)cls;
    (void)c;
    char *w = s;
    for (const char *r = s; *r;) {
        int hi, lo;
        if (r[0] == '%' && (hi = hexdigit(r[1])) >= 0 && (lo = hexdigit(r[2])) >= 0 &&
            (hi | lo) != 0) {
            *w++ = (char)(hi << 4 | lo);
            r += 3;
        } else {
            *w++ = *r++;
        }
    }
    *w = '\0';
    return (size_t)(w - s);
}

struct http *http_start(const struct http_config *cfg)
{
    struct http *h = calloc(1, sizeof *h);
    if (!h)
        return NULL;
    h->cfg = *cfg;
    if (!h->cfg.max_waiters)
        h->cfg.max_waiters = 128;
    h->conns = http_conns_new(cfg->header_timeout, cfg->body_timeout, cfg->connection_timeout);
    if (!h->conns) {
        free(h);
        return NULL;
    }
    pthread_mutex_init(&h->mu, NULL);
    pthread_cond_init(&h->work_cv, NULL);
    pthread_cond_init(&h->watch_cv, NULL);
    if (pthread_create(&h->worker, NULL, worker_main, h) != 0)
        goto fail;
    h->worker_started = 1;
    if (pthread_create(&h->watcher, NULL, watcher_main, h) != 0)
        goto fail;
    h->watcher_started = 1;
    unsigned flags = MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_EPOLL |
                     MHD_ALLOW_SUSPEND_RESUME | MHD_USE_ITC | MHD_USE_ERROR_LOG;
    if (cfg->addr->sa_family == AF_INET6)
        flags |= MHD_USE_IPv6;
    h->d = MHD_start_daemon(
        flags, 0, NULL, NULL, access_cb, h, MHD_OPTION_LISTEN_SOCKET, (MHD_socket)cfg->listen_fd,
        MHD_OPTION_CONNECTION_LIMIT, (unsigned)cfg->connection_limit,
        MHD_OPTION_PER_IP_CONNECTION_LIMIT, (unsigned)cfg->per_ip_limit,
        MHD_OPTION_CONNECTION_TIMEOUT, (unsigned)cfg->connection_timeout,
        MHD_OPTION_CONNECTION_MEMORY_LIMIT, (size_t)CONNECTION_MEMORY_LIMIT,
        MHD_OPTION_NOTIFY_COMPLETED, completed_cb, h, MHD_OPTION_URI_LOG_CALLBACK, uri_cb, h,
        MHD_OPTION_NOTIFY_CONNECTION, http_conns_notify, h->conns,
        MHD_OPTION_UNESCAPE_CALLBACK, unescape_cb,
        NULL, MHD_OPTION_END);
    if (!h->d) {
        tlog("cannot start the HTTP server (libmicrohttpd refused the listening socket)");
        goto fail;
    }
    return h;
fail:
    pthread_mutex_lock(&h->mu);
    h->stopping = 1;
    pthread_cond_broadcast(&h->work_cv);
    pthread_cond_broadcast(&h->watch_cv);
    pthread_mutex_unlock(&h->mu);
    if (h->worker_started)
        pthread_join(h->worker, NULL);
    if (h->watcher_started)
        pthread_join(h->watcher, NULL);
    http_conns_free(h->conns);
    free(h);
    return NULL;
}

void http_quiesce(struct http *h)
{
    MHD_socket fd = MHD_quiesce_daemon(h->d);
    if (fd != MHD_INVALID_SOCKET)
        close(fd);
}

void http_stop(struct http *h)
{
    pthread_mutex_lock(&h->mu);
    h->stopping = 1;
    pthread_cond_broadcast(&h->work_cv);
    pthread_cond_broadcast(&h->watch_cv);
    pthread_mutex_unlock(&h->mu);
    pthread_join(h->worker, NULL);  /* drains deferred tasks, resuming each */
    pthread_join(h->watcher, NULL); /* resumes every long-poll */
    /* let resumed connections send their replies (bounded) */
    for (int i = 0; i < 40; i++) {
        const union MHD_DaemonInfo *info =
            MHD_get_daemon_info(h->d, MHD_DAEMON_INFO_CURRENT_CONNECTIONS);
        if (!info || info->num_connections == 0)
            break;
        usleep(50000);
    }
    MHD_stop_daemon(h->d);
    http_conns_free(h->conns);
    free(h->waiters);
    pthread_mutex_destroy(&h->mu);
    pthread_cond_destroy(&h->work_cv);
    pthread_cond_destroy(&h->watch_cv);
    free(h);
}
