/* The progress bar of a download, drawn on stderr only when stderr is a
 * terminal (never in pipes, logs or tests that capture it):
 *   "result.h5  [##########..........]  52%  1.6 of 3.0 MiB"
 * redrawn in place at most every 0.1 s, and erased at the end so the line
 * about the finished transfer takes its place. */
#ifndef TLSPH_CLIENT_FETCH_BAR_H
#define TLSPH_CLIENT_FETCH_BAR_H

#include <curl/curl.h>

typedef struct {
    int on;                   /* stderr is a terminal */
    const char *name;         /* shown before the bar (not copied) */
    const long *status;       /* the answer's HTTP status: draws only for 200 and 206 */
    const long long *offset;  /* bytes the file had before this transfer (resume) */
    double last_draw;         /* monotonic seconds; < 0: never drawn */
    double last_bytes;        /* the bytes last shown */
} fetch_bar;

/* Prepares the bar; status and offset are read while the transfer runs. */
void fetch_bar_init(fetch_bar *b, const char *name, const long *status, const long long *offset);
/* Has libcurl report progress to the bar (nothing when it is off).  Returns 0,
 * -1 when libcurl refuses the options. */
int fetch_bar_attach(fetch_bar *b, CURL *c);
/* Erases the bar when one was drawn. */
void fetch_bar_end(fetch_bar *b);

#endif
