/* Per-connection deadlines, see http_conns.h. */
#include "http_conns.h"

#include <pthread.h>
#include <stdlib.h>
#include <sys/socket.h>

#include "util/clock.h"

enum conn_state { CONN_HEADERS, CONN_BODY, CONN_COMPLETE };

struct http_conn {
    struct http_conn *prev, *next;
    struct http_conns *owner;
    MHD_socket fd;
    enum conn_state state;
    double header_deadline, body_deadline;
    int shut; /* shut down already */
};

struct http_conns {
    pthread_mutex_t mu;
    struct http_conn *head;
    size_t open;     /* connections in the list not shut down yet */
    size_t max_open; /* 0: no reserve */
    double header_timeout, body_timeout, keepalive;
};

struct http_conns *http_conns_new(double header_timeout, double body_timeout, double keepalive,
                                  size_t max_open)
{
    struct http_conns *cs = calloc(1, sizeof *cs);
    if (!cs)
        return NULL;
    cs->max_open = max_open;
    pthread_mutex_init(&cs->mu, NULL);
    cs->header_timeout = header_timeout;
    cs->body_timeout = body_timeout;
    cs->keepalive = keepalive;
    return cs;
}

void http_conns_free(struct http_conns *cs)
{
    if (!cs)
        return;
    while (cs->head) { /* none after MHD_stop_daemon; be safe */
        struct http_conn *n = cs->head->next;
        free(cs->head);
        cs->head = n;
    }
    pthread_mutex_destroy(&cs->mu);
    free(cs);
}

/* Caller holds cs->mu. */
static void set_deadlines(struct http_conn *k, double start)
{
    k->state = CONN_HEADERS;
    k->header_deadline = start + k->owner->header_timeout;
    const double body = k->owner->body_timeout;
    k->body_deadline = start + (body > k->owner->header_timeout ? body : k->owner->header_timeout);
}

void http_conns_notify(void *cls, struct MHD_Connection *c, void **socket_context,
                       enum MHD_ConnectionNotificationCode code)
{
    struct http_conns *cs = cls;
    if (code == MHD_CONNECTION_NOTIFY_STARTED) {
        const union MHD_ConnectionInfo *fd =
            MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD);
        struct http_conn *k = fd ? calloc(1, sizeof *k) : NULL;
        *socket_context = k;
        if (!k)
            return; /* this connection goes without deadlines (MHD's idle timeout only) */
        k->owner = cs;
        k->fd = fd->connect_fd;
        pthread_mutex_lock(&cs->mu);
        set_deadlines(k, tlsph_monotonic_seconds());
        k->next = cs->head;
        if (cs->head)
            cs->head->prev = k;
        cs->head = k;
        cs->open++;
        pthread_mutex_unlock(&cs->mu);
    } else if (code == MHD_CONNECTION_NOTIFY_CLOSED) {
        struct http_conn *k = *socket_context;
        if (!k)
            return;
        /* before MHD closes the socket: no shutdown can reach a reused fd */
        pthread_mutex_lock(&cs->mu);
        if (k->prev)
            k->prev->next = k->next;
        else
            cs->head = k->next;
        if (k->next)
            k->next->prev = k->prev;
        if (!k->shut)
            cs->open--;
        pthread_mutex_unlock(&cs->mu);
        free(k);
        *socket_context = NULL;
    }
}

static struct http_conn *conn_of(struct MHD_Connection *c)
{
    const union MHD_ConnectionInfo *i =
        MHD_get_connection_info(c, MHD_CONNECTION_INFO_SOCKET_CONTEXT);
    return i ? i->socket_context : NULL;
}

static void set_state(struct MHD_Connection *c, enum conn_state state)
{
    struct http_conn *k = conn_of(c);
    if (!k)
        return;
    pthread_mutex_lock(&k->owner->mu);
    if (state == CONN_HEADERS)
        set_deadlines(k, tlsph_monotonic_seconds() + k->owner->keepalive);
    else
        k->state = state;
    pthread_mutex_unlock(&k->owner->mu);
}

void http_conn_headers_in(struct MHD_Connection *c)
{
    set_state(c, CONN_BODY);
}

void http_conn_complete(struct MHD_Connection *c)
{
    set_state(c, CONN_COMPLETE);
}

void http_conn_answered(struct MHD_Connection *c)
{
    set_state(c, CONN_HEADERS);
}

/* Caller holds cs->mu. */
static void shut(struct http_conns *cs, struct http_conn *k)
{
    shutdown(k->fd, SHUT_RDWR);
    k->shut = 1;
    cs->open--;
}

/* The connection waiting longest for its headers (caller holds cs->mu). */
static struct http_conn *oldest_waiting(struct http_conns *cs)
{
    struct http_conn *old = NULL;
    for (struct http_conn *k = cs->head; k; k = k->next)
        if (!k->shut && k->state == CONN_HEADERS &&
            (!old || k->header_deadline < old->header_deadline))
            old = k;
    return old;
}

size_t http_conns_enforce(struct http_conns *cs, double now)
{
    size_t n = 0;
    pthread_mutex_lock(&cs->mu);
    for (struct http_conn *k = cs->head; k; k = k->next) {
        const int late = (k->state == CONN_HEADERS && now > k->header_deadline) ||
                         (k->state == CONN_BODY && now > k->body_deadline);
        if (late && !k->shut) {
            shut(cs, k);
            n++;
        }
    }
    struct http_conn *k;
    while (cs->max_open && cs->open > cs->max_open && (k = oldest_waiting(cs))) {
        shut(cs, k);
        n++;
    }
    pthread_mutex_unlock(&cs->mu);
    return n;
}
