/* tlsphd's HTTP helper threads: the lanes that run the routes and the
 * watcher that enforces the connections' deadlines and answers long-polls
 * (see http.h and http_internal.h).
 *
 * A request whose body is complete is suspended on the MHD thread and queued
 * in its lane (http_lane_submit); a thread of that lane runs the route with
 * its own context (e.g. its own queue handle).  A task the route defers runs
 * at once on the same thread (it is already off the MHD thread); a long-poll
 * parks the request with the watcher, which resumes it when it may be
 * answered, and the route runs again in its lane.  Lanes share nothing but
 * the mutex guarding their queues: a request never waits behind one of
 * another lane. */
#include "http_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <microhttpd.h>

#include "errmsg.h"
#include "http_conns.h"
#include "util/clock.h"

#define WATCH_PERIOD_MS 200
#define LATE_LOG_PERIOD 10.0
#define HOLD_POLL_US    20000

int http_lane_submit(struct hreq *r)
{
    struct http *h = r->http;
    struct lane *l = &h->lanes[r->lane >= 0 && r->lane < h->cfg.nlanes ? r->lane : 0];
    pthread_mutex_lock(&h->mu);
    if (h->stopping) {
        pthread_mutex_unlock(&h->mu);
        return -1;
    }
    /* suspended before a lane thread can see it (that thread resumes it) */
    r->phase = PHASE_QUEUED;
    MHD_suspend_connection(r->conn);
    r->next = NULL;
    if (l->tail)
        l->tail->next = r;
    else
        l->head = r;
    l->tail = r;
    pthread_cond_signal(&l->cv);
    pthread_mutex_unlock(&h->mu);
    return 0;
}

int http_defer(struct hreq *r, void (*fn)(struct hreq *r, void *app, void *ctx))
{
    if (!r->on_lane)
        return -1; /* on the MHD thread only while shutting down */
    fn(r, r->http->cfg.app, r->ctx);
    return 0;
}

int http_wait(struct hreq *r, const char *id, double deadline)
{
    struct http *h = r->http;
    if (!r->on_lane)
        return -1;
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
    /* armed by the lane thread once the route has returned (run_route) */
    struct waiter *w = &h->waiters[h->nwait++];
    w->r = r;
    snprintf(w->id, sizeof w->id, "%s", id);
    w->deadline = deadline;
    w->armed = 0;
    r->phase = PHASE_WAITING;
    pthread_mutex_unlock(&h->mu);
    return 0;
}

/* Testing only (http_config.hold_path): holds a request of the held lane
 * while the file exists (not once the server stops); logs it once. */
static void hold_if_asked(struct http *h, const struct hreq *r)
{
    if (!h->cfg.hold_path || r->lane != h->cfg.hold_lane)
        return;
    int logged = 0;
    for (;;) {
        pthread_mutex_lock(&h->mu);
        const int stopping = h->stopping;
        pthread_mutex_unlock(&h->mu);
        if (stopping || access(h->cfg.hold_path, F_OK) != 0)
            return;
        if (!logged++)
            tlog("test_hold: holding %s %s", r->method, r->path);
        usleep(HOLD_POLL_US);
    }
}

/* Runs r's route on this lane thread; then resumes r with its reply, or arms
 * its long-poll.  r is not touched after that (the MHD thread owns it). */
static void run_route(struct http *h, struct hreq *r, void *ctx)
{
    hold_if_asked(h, r);
    r->ctx = ctx;
    r->on_lane = 1;
    r->has_reply = 0;
    r->phase = PHASE_RUNNING;
    h->cfg.route(r, h->cfg.app, ctx);
    r->on_lane = 0;
    if (r->phase == PHASE_WAITING) {
        pthread_mutex_lock(&h->mu);
        for (size_t i = 0; i < h->nwait; i++)
            if (h->waiters[i].r == r)
                h->waiters[i].armed = 1;
        pthread_cond_signal(&h->watch_cv);
        pthread_mutex_unlock(&h->mu);
        return;
    }
    if (!r->has_reply)
        http_reply_problem(r, PROBLEM_INTERNAL, "no response produced");
    r->phase = PHASE_READY;
    MHD_resume_connection(r->conn);
}

static void *lane_main(void *arg)
{
    struct lane *l = arg;
    struct http *h = l->h;
    void *ctx = h->cfg.thread_init ? h->cfg.thread_init(h->cfg.app) : NULL;
    pthread_mutex_lock(&h->mu);
    for (;;) {
        while (!l->head && !h->stopping)
            pthread_cond_wait(&l->cv, &h->mu);
        struct hreq *r = l->head;
        if (!r)
            break; /* stopping and drained */
        l->head = r->next;
        if (!l->head)
            l->tail = NULL;
        pthread_mutex_unlock(&h->mu);
        run_route(h, r, ctx);
        pthread_mutex_lock(&h->mu);
    }
    pthread_mutex_unlock(&h->mu);
    if (h->cfg.thread_fini)
        h->cfg.thread_fini(ctx);
    return NULL;
}

/* Shuts the connections past their deadlines (http_conns.h); says so in the
 * log at most every LATE_LOG_PERIOD s, so that an attack does not flood it.
 * Caller holds h->mu. */
static void enforce_deadlines(struct http *h, double now)
{
    h->late_closed += http_conns_enforce(h->conns, now);
    if (h->late_closed && now - h->late_logged >= LATE_LOG_PERIOD) {
        tlog("closed %zu slow connection(s): headers or body not complete within "
             "header_timeout %d s / body_timeout %d s, or waiting longest for their headers "
             "when connections ran short",
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
            int go = w->armed && (h->stopping || now >= w->deadline);
            if (w->armed && !go && h->cfg.wait_ready)
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
        if (h->watch_stop && h->nwait == 0)
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

int http_threads_start(struct http *h)
{
    for (int k = 0; k < h->cfg.nlanes; k++) {
        h->lanes[k].h = h;
        pthread_cond_init(&h->lanes[k].cv, NULL);
    }
    pthread_cond_init(&h->watch_cv, NULL);
    for (int k = 0; k < h->cfg.nlanes; k++)
        for (int i = 0; i < h->cfg.lane_threads[k]; i++) {
            if (h->nlane_threads == HTTP_MAX_THREADS ||
                pthread_create(&h->threads[h->nlane_threads], NULL, lane_main, &h->lanes[k]) != 0) {
                tlog("cannot start the HTTP server's threads");
                http_threads_stop(h);
                return -1;
            }
            h->nlane_threads++;
        }
    if (pthread_create(&h->threads[h->nlane_threads], NULL, watcher_main, h) != 0) {
        tlog("cannot start the HTTP server's watcher thread");
        http_threads_stop(h);
        return -1;
    }
    h->watcher_started = 1;
    return 0;
}

void http_threads_stop(struct http *h)
{
    pthread_mutex_lock(&h->mu);
    h->stopping = 1;
    for (int k = 0; k < h->cfg.nlanes; k++)
        pthread_cond_broadcast(&h->lanes[k].cv);
    pthread_cond_broadcast(&h->watch_cv);
    pthread_mutex_unlock(&h->mu);
    for (int i = 0; i < h->nlane_threads; i++)
        pthread_join(h->threads[i], NULL); /* runs what was queued, resuming each */
    /* only now: a route that ran while the lanes drained may have parked its request */
    pthread_mutex_lock(&h->mu);
    h->watch_stop = 1;
    pthread_cond_broadcast(&h->watch_cv);
    pthread_mutex_unlock(&h->mu);
    if (h->watcher_started)
        pthread_join(h->threads[h->nlane_threads], NULL); /* resumes every long-poll */
    for (int k = 0; k < h->cfg.nlanes; k++)
        pthread_cond_destroy(&h->lanes[k].cv);
    pthread_cond_destroy(&h->watch_cv);
    h->nlane_threads = 0;
    h->watcher_started = 0;
}
