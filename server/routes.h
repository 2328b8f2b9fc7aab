/* The tlsphd API: OGC API - Processes 1.0 style resources over the jobs
 * service, the queue, results.c and study.c.  One route table and its matcher
 * in routes.c; the handlers by resource in routes_meta.c, routes_jobs.c and
 * routes_results.c (route.h is their shared interface).
 *
 * Threads (see http.h): routes run on the MHD thread with app->q (its own
 * queue handle) and only do short queue reads/writes and file opens; scene
 * validation + job insertion, HDF5 reads and study summaries run as deferred
 * tasks on the worker thread with that thread's own queue handle. */
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

/* http_config callbacks */
void troutes_admit(struct hreq *r, void *app); /* the token and the route, on the headers */
void troutes_route(struct hreq *r, void *app);
void *troutes_thread_init(void *app);  /* opens a queue handle for a helper thread */
void troutes_thread_fini(void *ctx);
int troutes_wait_ready(void *app, void *ctx, const char *id);

#endif
