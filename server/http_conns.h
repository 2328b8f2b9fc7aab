/* Absolute deadlines for every connection of tlsphd's HTTP server
 * (server/http_conns.c).
 *
 * libmicrohttpd 0.9.75 has only an idle timeout, which every header line or
 * body chunk resets: a client that dribbles a line every few seconds holds
 * its connection for ever.  Here each request gets two deadlines, both
 * counted from its start (the accept, or the answer to the previous request
 * on a kept-alive connection, plus keepalive seconds of allowed idling):
 *   - its headers must be complete within header_timeout;
 *   - its body within body_timeout.
 * Once a request is complete it has no deadline until it is answered (a
 * long-poll or a deferred task is the daemon's own wait).  A connection past
 * its deadline is shut down (shutdown(2) on its socket, from the watcher
 * thread): MHD sees the end of the stream and closes it.  The client gets no
 * answer: MHD cannot queue one before it has the request's headers.
 *
 * A reserve: when more than max_open connections are open, the oldest ones
 * still waiting for their headers (slow clients, or idle kept-alive
 * connections) are shut down first, so that a new client can still connect
 * (at connection_limit libmicrohttpd stops accepting).  A request in progress
 * is never shut for that.
 *
 * One struct http_conn per open connection, kept as MHD's socket context
 * (MHD_OPTION_NOTIFY_CONNECTION); the list is guarded by its own mutex,
 * which also orders a shutdown before MHD closes (and the kernel reuses) the
 * socket. */
#ifndef TLSPHD_HTTP_CONNS_H
#define TLSPHD_HTTP_CONNS_H

#include <stddef.h>

#include <microhttpd.h>

struct http_conns;

/* Seconds; max_open: connections kept open at most before the reserve is
 * made (0: no reserve).  NULL when out of memory. */
struct http_conns *http_conns_new(double header_timeout, double body_timeout, double keepalive,
                                  size_t max_open);
/* After MHD has stopped (every connection closed). */
void http_conns_free(struct http_conns *cs);

/* MHD_OPTION_NOTIFY_CONNECTION callback (cls: the struct http_conns). */
void http_conns_notify(void *cls, struct MHD_Connection *c, void **socket_context,
                       enum MHD_ConnectionNotificationCode code);

/* A request's progress, on the MHD thread: its headers are in (the body
 * deadline applies), it is complete (no deadline), it was answered (the next
 * request's deadlines count from now + keepalive). */
void http_conn_headers_in(struct MHD_Connection *c);
void http_conn_complete(struct MHD_Connection *c);
void http_conn_answered(struct MHD_Connection *c);

/* Shuts down the connections past a deadline at now (tlsph_monotonic_seconds),
 * then makes the reserve; returns how many.  Any thread. */
size_t http_conns_enforce(struct http_conns *cs, double now);

#endif
