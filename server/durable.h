/* Files that survive a crash (server/durable.c): the data is written to a
 * temporary file beside the target, synced, renamed over the target, and the
 * directory synced, so that after a crash a reader finds either the whole
 * new file or none.  The job directories' scene.json (jobdir.c) and the
 * intent files (intent.c) are written this way. */
#ifndef TLSPHD_DURABLE_H
#define TLSPHD_DURABLE_H

#include <stddef.h>

/* Writes len bytes of data to path, in directory dir; tmpl is the temporary
 * file's path in dir, ending in "XXXXXX.tmp" (mkostemps fills in the X; it
 * is modified).  0, or -1 with err (nothing is left at tmpl). */
int durable_write(const char *dir, char *tmpl, const char *path, const char *data, size_t len,
                  char *err, size_t errsize);

#endif
