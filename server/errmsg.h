/* The daemon's error convention (server/errmsg.c).
 *
 * - A function that either works or not returns 0 or -1; one whose callers
 *   must tell failures apart returns a named enum (e.g. enum tq_rc,
 *   enum jobs_rc), never bare 1 / 2.
 * - The reason is one line for people: written into a caller's buffer
 *   (char *err, size_t errsize; errmsg_set) or kept on a handle
 *   (tq_last_error).  Library code in the daemon does not print.
 * - Only the top of each thread logs, with tlog: main, the supervisor thread,
 *   the HTTP layer and the route handlers (which answer a request and log
 *   what the client is not told).  One line each, "tlsphd: " first.
 * - HTTP answers are problem+json documents (problem.h), built in the routes
 *   from these statuses. */
#ifndef TLSPHD_ERRMSG_H
#define TLSPHD_ERRMSG_H

#include <stddef.h>

/* printf into err[errsize] (nothing when err is NULL or errsize is 0). */
void errmsg_set(char *err, size_t errsize, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* The same, malloc'ed (NULL when out of memory): for messages kept longer. */
char *errmsg_format(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* One log line on stderr: "tlsphd: " + the message + "\n". */
void tlog(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

#endif
