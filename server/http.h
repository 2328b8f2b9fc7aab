/* The HTTP layer of tlsphd (server/http.c) over libmicrohttpd 0.9.75; the
 * request checks in http_protocol.h, the connections' deadlines in
 * http_conns.h.
 *
 * Threading (http_threads.c): one MHD internal polling thread (epoll) reads
 * requests, checks their headers and queues replies; it never runs a route.
 * A complete request is suspended (MHD_suspend_connection) and queued in
 * its lane (cfg.admit chose it from the headers); each lane has its own
 * threads (cfg.lane_threads), which run the route, so a request never waits
 * behind one of another lane (a status read behind a summary).  The lane
 * thread resumes the connection with the reply set, and the MHD thread
 * queues it.  The watcher thread enforces the connections' deadlines and
 * serves long-polls (GET /jobs/{id}?wait=S): parked requests are checked
 * every 200 ms with a caller-supplied predicate (on the watcher's own
 * database handle) and resumed when it says so or the deadline passes; the
 * route then runs again in its lane with r->resumed = 1.
 * Each helper thread gets a context from thread_init (e.g. its own queue handle).
 *
 * Deadlines: every request must have sent its headers within header_timeout
 * and its body within body_timeout of its start, however steadily it
 * dribbles (http_conns.h; the watcher shuts down the late ones).
 * Admission: the headers are checked (cfg.admit) before any of the body is
 * read; a refusal is answered at once with Connection: close, so a refused
 * upload costs no memory for its body.
 * Bodies: accumulated up to body_limit (Content-Length above the limit is
 * refused with 413 before the upload; chunked bodies are counted and dropped).
 * One log line per request on stderr: time, method, path, status, ms. */
#ifndef TLSPHD_HTTP_H
#define TLSPHD_HTTP_H

#include <stddef.h>
#include <stdint.h>
#include <sys/socket.h>

#include <jansson.h>

#include "problem.h"
#include "strbuf.h"

struct MHD_Connection;
struct http;

#define HTTP_MAX_HEADERS 10
#define HTTP_MAX_LANES 4
#define HTTP_MAX_THREADS 64 /* lane threads in all */

struct hreply {
    unsigned status;
    char *ctype;        /* owned */
    char *body;         /* owned, may be NULL (empty) */
    size_t len;
    int fd;             /* >= 0: file response of len bytes from offset */
    uint64_t offset;
    int nhdr;
    char *hname[HTTP_MAX_HEADERS], *hvalue[HTTP_MAX_HEADERS]; /* owned */
};

struct hreq {
    struct MHD_Connection *conn;
    struct http *http;
    char method[16];
    char *path;            /* decoded request path (owned) */
    struct strbuf body;    /* request body (NUL-terminated once non-empty) */
    int too_big;           /* body exceeded the limit */
    size_t query_params;   /* > 0: this many query parameters, too many (cut off) */
    double t0;             /* start, monotonic s */
    int resumed;           /* route re-run after a long-poll wait */
    int lane;              /* set by cfg.admit: the lane the route runs in */
    void *ctx;             /* the context of the lane thread running the route */
    int has_reply;
    struct hreply reply;
    void *data;            /* the route layer's (struct route_call), freed with free() at completion */
    /* internal */
    struct hreq *next;     /* in its lane's queue */
    int on_lane;           /* its route runs on a lane thread now */
    int phase;
    unsigned logged_status;
};

struct http_config {
    const struct sockaddr *addr; /* the address listen_fd is bound to */
    socklen_t addrlen;
    int listen_fd;         /* a bound, listening socket (the caller binds it, so that a
                            * failure can name the address); MHD closes it at stop */
    int connection_limit, per_ip_limit, connection_timeout;
    int header_timeout, body_timeout; /* s from a request's start (http_conns.h) */
    size_t body_limit;
    size_t max_waiters;
    /* testing only: requests of lane hold_lane wait while the file hold_path
     * exists (NULL: never), so that a test can hold heavy requests */
    const char *hold_path;
    int hold_lane;
    /* admission: called on the MHD thread as soon as the headers are in,
     * before any of the body is read (NULL: admit all).  A reply set here
     * (e.g. 401 for a missing token) is sent at once and the connection is
     * closed without reading the body. */
    void (*admit)(struct hreq *r, void *app);
    /* routing: called on a thread of the request's lane once the request (and
     * body) is complete, with that thread's context; must set a reply
     * (http_reply_*), may defer work (http_defer) or park (http_wait).  While
     * the server stops it may be called on the MHD thread with ctx NULL, where
     * http_defer and http_wait refuse. */
    void (*route)(struct hreq *r, void *app, void *ctx);
    int nlanes;                          /* 1..HTTP_MAX_LANES */
    int lane_threads[HTTP_MAX_LANES];    /* threads per lane (>= 1) */
    /* per helper thread context (lane threads, watcher) */
    void *(*thread_init)(void *app);
    void (*thread_fini)(void *ctx);
    /* watcher: 1 when the long-poll on job `id` may be answered now */
    int (*wait_ready)(void *app, void *ctx, const char *id);
    void *app;
};

/* Starts the MHD daemon and the helper threads. NULL on failure (logged). */
struct http *http_start(const struct http_config *cfg);
/* Stops accepting connections (MHD_quiesce_daemon). */
void http_quiesce(struct http *h);
/* Resumes every parked connection, finishes deferred tasks, stops MHD and
 * joins the helper threads. */
void http_stop(struct http *h);

/* Request accessors (the thread running the route: the request is suspended,
 * MHD does not touch its headers meanwhile). */
const char *http_header(struct hreq *r, const char *name);
const char *http_query(struct hreq *r, const char *name);

/* Replies (any thread that owns the request: the MHD thread before routing, the
 * lane thread running the route).  A later reply replaces an earlier one. */
void http_reply_buf(struct hreq *r, unsigned status, const char *ctype, char *body, size_t len);
void http_reply_text(struct hreq *r, unsigned status, const char *ctype, const char *text);
/* Steals body. */
void http_reply_json(struct hreq *r, unsigned status, json_t *body);
/* Steals problem (its "status" member gives the HTTP status). */
void http_reply_problem_json(struct hreq *r, json_t *problem);
void http_reply_problem(struct hreq *r, enum problem_kind kind, const char *detail);
/* File response: len bytes of fd from offset (fd is owned from here on). */
void http_reply_fd(struct hreq *r, unsigned status, const char *ctype, int fd, uint64_t offset,
                   uint64_t len);
void http_add_header(struct hreq *r, const char *name, const char *value);

/* Runs task with the lane thread's context (at once: a route already runs off
 * the MHD thread); the task sets the reply.  Returns 0, or -1 when shutting
 * down (the route must reply itself). */
int http_defer(struct hreq *r, void (*task)(struct hreq *r, void *app, void *ctx));
/* Parks the request until wait_ready(job id) or the deadline
 * (tlsph_monotonic_seconds); the route must return without a reply and runs
 * again when the request is resumed.  Returns 0, or -1 when it cannot wait
 * (shutdown, too many waiters). */
int http_wait(struct hreq *r, const char *id, double deadline);

#endif
