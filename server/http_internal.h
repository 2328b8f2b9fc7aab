/* Inside tlsphd's HTTP layer: the server's state, shared by http.c (the MHD
 * glue and the replies) and http_threads.c (the lanes and the watcher). */
#ifndef TLSPHD_HTTP_INTERNAL_H
#define TLSPHD_HTTP_INTERNAL_H

#include <pthread.h>

#include "http.h"

struct MHD_Daemon;

/* A request's way through the layer. */
enum {
    PHASE_NEW,     /* created (URI seen), headers not yet looked at */
    PHASE_BODY,    /* headers admitted, body being read */
    PHASE_QUEUED,  /* suspended, waiting in its lane */
    PHASE_RUNNING, /* its route runs on a lane thread */
    PHASE_READY,   /* its reply is set; resumed to have it queued on the MHD thread */
    PHASE_WAITING, /* parked for a long-poll (the watcher resumes it) */
    PHASE_DONE     /* reply queued */
};

struct waiter {
    struct hreq *r;
    char id[40];
    double deadline;
    int armed; /* its lane thread has let go of the request: the watcher may resume it */
};

struct lane {
    struct http *h;
    struct hreq *head, *tail; /* requests waiting for a thread of this lane */
    pthread_cond_t cv;
};

struct http {
    struct http_config cfg;
    struct MHD_Daemon *d;
    pthread_mutex_t mu; /* guards the lanes' queues, the waiters and the flags below */
    struct lane lanes[HTTP_MAX_LANES];
    pthread_t threads[HTTP_MAX_THREADS + 1]; /* the lanes' threads, then the watcher */
    int nlane_threads, watcher_started;
    pthread_cond_t watch_cv;
    struct waiter *waiters;
    size_t nwait, capwait;
    int stopping;   /* no new lane work; parked requests are answered */
    int watch_stop; /* the watcher ends (set once the lanes are drained) */
    struct http_conns *conns;
    size_t late_closed; /* connections shut past a deadline, not yet logged */
    double late_logged; /* when that was last logged */
};

/* http_threads.c */

/* Starts the lanes' threads and the watcher: 0, or -1 (logged; the started
 * ones stopped again). */
int http_threads_start(struct http *h);
/* Runs what the lanes still hold, answers every parked request, joins. */
void http_threads_stop(struct http *h);
/* MHD thread: suspends r and queues its route in lane r->lane.  -1 when
 * stopping (the caller runs the route itself). */
int http_lane_submit(struct hreq *r);

#endif
