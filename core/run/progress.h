/* Machine-readable progress: one JSON object per line on a file descriptor
 * (the daemon reads these).  The events, their members and the exit codes
 * they go with are defined in run/protocol.h, schemas/progress.schema.json
 * and docs/protocol.md:
 *   {"event":"started","particles":N,"pairs":P,"end_time":s,"modules":[...],...}
 *   {"event":"progress","step":k,"time":s,"end_time":s,"wall_seconds":s,"eta_seconds":s,"frames":f}
 *   {"event":"finished","status":"successful|invalid|unstable|io_error|cancelled",
 *    "step":k,"time":s,"cost":{...}         (whenever a model ran)
 *    "diagnostic":{...}                     (unstable)
 *    "errors":[{"pointer","detail"},...]}   (invalid, io_error)
 * Writes are whole lines; EINTR is retried and a closed reader is ignored, so
 * progress can never stop a run. */
#ifndef TLSPH_PROGRESS_H
#define TLSPH_PROGRESS_H

#include <jansson.h>

#include "run/protocol.h"
#include "util/errors.h"

/* Writes obj as one compact line to fd (no-op when fd < 0). Steals nothing. */
void tlsph_progress_emit(int fd, const json_t *obj);

/* A new final event {"event":"finished","status":<name of code>} with
 * "errors" from err when it holds any (err may be NULL).  The caller adds
 * step, time, cost and diagnostic where it has them.  NULL when out of memory
 * or when code has no final event (TLSPH_EXIT_USAGE). */
json_t *tlsph_progress_final(enum tlsph_exit code, const struct tlsph_errors *err);

#endif
