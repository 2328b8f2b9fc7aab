/* libcurl wrapper: JSON requests, problem+json errors, resumable downloads. */
#ifndef TLSPH_CLIENT_HTTP_H
#define TLSPH_CLIENT_HTTP_H

#include <jansson.h>
#include <stddef.h>

#include "settings.h"

#define HTTP_MAX_BODY ((size_t)64 << 20) /* cap for in-memory responses */
#define HTTP_TIMEOUT 60L                 /* total seconds for an ordinary request */

typedef struct {
    long status;           /* HTTP status code */
    char *body;            /* NUL-terminated, possibly with embedded NULs */
    size_t len;
    char content_type[128];
} http_response;

/* Once per process. */
int http_global_init(void);
void http_global_cleanup(void);

/* One exchange: METHOD base-URL+path (path starts with '/'), optional JSON body.
 * Returns RC_OK when a response arrived (any status) or an RC_* after printing why not. */
int http_exchange(const settings *s, const char *method, const char *path, const char *json_body,
                  long timeout_s, http_response *r);
void http_response_free(http_response *r);

/* Prints the error of a non-2xx response (problem details) and returns its RC_* code. */
int http_report_error(const settings *s, const http_response *r);

/* A JSON request: 2xx responses are decoded into *out (caller json_decref's).
 * body may be NULL.  Returns an RC_* code; errors are printed. */
int http_json(const settings *s, const char *method, const char *path, const json_t *body,
              long timeout_s, json_t **out);

/* GET of a text resource (any 2xx body). */
int http_text(const settings *s, const char *path, http_response *r);

/* Downloads path into dest via dest.part, resuming a partial file with a Range
 * request (If-Range with the ETag remembered in dest.part.etag).  Prints a line
 * about the transfer to stderr.  Returns an RC_* code. */
int http_download(const settings *s, const char *path, const char *dest);

#endif
