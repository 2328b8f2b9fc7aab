/* Building request paths safely: job id validation and percent-encoding. */
#ifndef TLSPH_CLIENT_URLS_H
#define TLSPH_CLIENT_URLS_H

#include <stddef.h>

/* 1 when id is 32 lowercase hex digits. */
int id_valid(const char *id);
/* RC_OK, or prints an error and returns RC_USAGE. */
int id_check(const char *id);
/* Percent-encodes s, keeping unreserved characters and (if keep_slash) '/'.
 * Returns a malloc'd string or NULL on allocation failure. */
char *url_escape(const char *s, int keep_slash);
/* "/jobs/ID/results/series/NAME[?format=csv]", NAME percent-encoded keeping its
 * '/'.  Returns a malloc'd string or NULL on allocation failure. */
char *url_series_path(const char *id, const char *name, int csv);

#endif
