/* Machine-readable progress: one JSON object per line on a file descriptor
 * (the daemon reads these).  Lines:
 *   {"event":"started","particles":N,"pairs":P,"end_time":s,"modules":[...]}
 *   {"event":"progress","step":k,"time":s,"end_time":s,"wall_seconds":s,"eta_seconds":s,"frames":f}
 *   {"event":"finished","status":"successful|unstable|cancelled|io_error","step":k,"time":s,
 *    "cost":{particles,pairs,steps,wall_seconds,particle_steps_per_second,
 *            peak_memory_bytes,bytes_per_particle}, "diagnostic":{...} (unstable only)}
 * Writes are whole lines; EINTR is retried and a closed reader is ignored, so
 * progress can never stop a run. */
#ifndef TLSPH_PROGRESS_H
#define TLSPH_PROGRESS_H

#include <jansson.h>

/* Writes obj as one compact line to fd (no-op when fd < 0). Steals nothing. */
void tlsph_progress_emit(int fd, const json_t *obj);

#endif
