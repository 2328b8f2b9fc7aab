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
#include "http_internal.h"
#include "http_protocol.h"
#include "numtext.h"
#include "util/clock.h"

#define CONNECTION_MEMORY_LIMIT (128 * 1024)

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
    if (r->phase == PHASE_READY) /* resumed by its lane thread: the reply is set */
        return queue_reply(r);
    /* body complete (PHASE_BODY), or resumed after a long-poll (PHASE_WAITING) */
    if (r->too_big) {
        http_reply_problem(r, PROBLEM_TOO_LARGE, "request body exceeds the limit");
        return queue_reply(r);
    }
    if (r->phase == PHASE_BODY)
        http_conn_complete(conn);
    if (http_lane_submit(r) == 0)
        return MHD_YES; /* suspended until its lane thread resumes it */
    /* shutting down: answer here (a route cannot defer or wait now) */
    r->has_reply = 0;
    h->cfg.route(r, h->cfg.app, NULL);
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
            r->method[0] ? r->method : "-", i ? path : "-", r->logged_status,
            1e3 * (tlsph_monotonic_seconds() - r->t0));
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
    /* a reserve of an eighth of the connections (http_conns.h) */
    const size_t limit = (size_t)cfg->connection_limit, reserve = limit / 8 ? limit / 8 : 1;
    h->conns = http_conns_new(cfg->header_timeout, cfg->body_timeout, cfg->connection_timeout,
                              limit > reserve ? limit - reserve : 0);
    if (!h->conns) {
        free(h);
        return NULL;
    }
    pthread_mutex_init(&h->mu, NULL);
    if (http_threads_start(h) != 0) {
        pthread_mutex_destroy(&h->mu);
        http_conns_free(h->conns);
        free(h);
        return NULL;
    }
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
    http_threads_stop(h);
    pthread_mutex_destroy(&h->mu);
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
    http_threads_stop(h); /* runs what the lanes hold and answers every long-poll */
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
    free(h);
}
