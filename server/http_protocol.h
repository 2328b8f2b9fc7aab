/* The request checks tlsphd makes itself where libmicrohttpd 0.9.75 is
 * lenient (server/http_protocol.c).  MHD accepts, and http.c must refuse:
 *   - Content-Length together with Transfer-Encoding (MHD follows the
 *     Transfer-Encoding and keeps the connection: a request smuggled in the
 *     body would be answered) -> 400;
 *   - a Transfer-Encoding other than "chunked" (MHD reads such a body until
 *     the connection closes, so the client never gets an answer) -> 501;
 *   - Content-Length given twice, Host missing (HTTP/1.1) or given twice, a
 *     header name with white space ("Host : x") -> 400;
 *   - more than HTTP_MAX_QUERY_PARAMS query parameters -> 414 (MHD runs out
 *     of connection memory storing them and never answers).
 * What MHD answers itself before the daemon sees the request (a
 * Content-Length that is not a number, a request line or header block larger
 * than the connection's memory) keeps MHD's own HTML body: 0.9.75 has no hook
 * to replace it. */
#ifndef TLSPHD_HTTP_PROTOCOL_H
#define TLSPHD_HTTP_PROTOCOL_H

#include <stddef.h>

#include "problem.h"

struct MHD_Connection;

#define HTTP_MAX_QUERY_PARAMS 256

/* uri is the raw request target, before MHD splits its query.  Above
 * HTTP_MAX_QUERY_PARAMS parameters the query is cut off in place (MHD then
 * stores none) and the count is returned; otherwise 0. */
size_t http_protocol_trim_query(char *uri);

/* Checks the request's version and headers (all of them, duplicates
 * included).  0 when the request may go on; otherwise -1 with the status in
 * *kind and a sentence for the problem's detail. */
int http_protocol_check(struct MHD_Connection *conn, const char *version, enum problem_kind *kind,
                        char *detail, size_t size);

#endif
