/* The tlsphd API: OGC API - Processes 1.0 style resources over the jobs
 * service, the queue, results.c and study.c.  One route table and its matcher
 * in routes.c; the handlers by resource in routes_meta.c, routes_jobs.c and
 * routes_results.c (route.h is their shared interface).
 *
 * Threads (see http.h): every route runs on a thread of its lane (the route
 * table's lane column: light reads, writes, heavy reads), with that thread's
 * own queue handle as c->app->q; a deferred task runs on the same thread. */
#ifndef TLSPHD_ROUTES_H
#define TLSPHD_ROUTES_H

#include <stddef.h>

#include "config.h"
#include "http.h"

struct tq;
struct tsup;

struct tapp {
    const struct tcfg *cfg;
    struct tq *q;      /* the MHD thread's queue handle */
    struct tsup *sup;  /* for tsup_wake */
    char *openapi;     /* openapi.json text (NULL: 404) */
    size_t openapi_len;
};

/* The lanes requests run in (http_config.lane_threads): a request never
 * waits behind one of another lane. */
enum route_lane {
    LANE_LIGHT, /* health, status, the API's descriptions: short reads */
    LANE_WRITE, /* submissions (scene validation) and cancel/remove */
    LANE_HEAVY, /* job lists and result reads (HDF5, summaries) */
    LANE_COUNT
};

/* http_config callbacks */
void troutes_admit(struct hreq *r, void *app); /* the token and the route, on the headers */
/* ctx: the lane thread's queue handle (troutes_thread_init); NULL: use app's */
void troutes_route(struct hreq *r, void *app, void *ctx);
void *troutes_thread_init(void *app);  /* opens a queue handle for a helper thread */
void troutes_thread_fini(void *ctx);
int troutes_wait_ready(void *app, void *ctx, const char *id);

#endif
