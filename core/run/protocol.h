/* The engine <-> daemon protocol: what tlsph-run tells whoever started it.
 *
 * The engine never touches the daemon's database; it speaks through two
 * channels only, both defined here and documented in docs/protocol.md:
 *   - its exit code (enum tlsph_exit), the authoritative outcome;
 *   - with --progress-fd N, one JSON object per line on descriptor N
 *     (schemas/progress.schema.json): "started" once the model exists,
 *     "progress" while it runs, and one "finished" event last, whose status
 *     names the exit code and which carries what the caller needs to explain
 *     a failure: the validation or I/O errors ({pointer, detail} pairs) or the
 *     stability diagnostic.  The human log on stderr is for people only; no
 *     program should parse it.
 * Exit code 1 (usage) and deaths by a signal come without a final event. */
#ifndef TLSPH_PROTOCOL_H
#define TLSPH_PROTOCOL_H

/* Process exit codes of tlsph-run. */
enum tlsph_exit {
    TLSPH_EXIT_SUCCESS = 0,
    TLSPH_EXIT_USAGE = 1,     /* bad command line or internal error; no final event */
    TLSPH_EXIT_INVALID = 2,   /* the scene was rejected; nothing was written */
    TLSPH_EXIT_UNSTABLE = 3,  /* the stability contract stopped the run */
    TLSPH_EXIT_IO = 4,        /* the result could not be written */
    TLSPH_EXIT_CANCELLED = 5  /* SIGTERM/SIGINT: the current frame was finished, file closed */
};

/* Event names (the "event" member of every line). */
#define TLSPH_EVENT_STARTED "started"
#define TLSPH_EVENT_PROGRESS "progress"
#define TLSPH_EVENT_FINISHED "finished"

/* The "status" member of the final event, one per exit code that has one. */
#define TLSPH_STATUS_SUCCESSFUL "successful"
#define TLSPH_STATUS_INVALID "invalid"
#define TLSPH_STATUS_UNSTABLE "unstable"
#define TLSPH_STATUS_IO_ERROR "io_error"
#define TLSPH_STATUS_CANCELLED "cancelled"

/* Largest --threads the engine accepts (the daemon's threads_per_job ceiling). */
#define TLSPH_MAX_THREADS 1024

/* Status name of an exit code, NULL for codes without a final event. */
static inline const char *tlsph_exit_status(int code)
{
    switch (code) {
    case TLSPH_EXIT_SUCCESS:
        return TLSPH_STATUS_SUCCESSFUL;
    case TLSPH_EXIT_INVALID:
        return TLSPH_STATUS_INVALID;
    case TLSPH_EXIT_UNSTABLE:
        return TLSPH_STATUS_UNSTABLE;
    case TLSPH_EXIT_IO:
        return TLSPH_STATUS_IO_ERROR;
    case TLSPH_EXIT_CANCELLED:
        return TLSPH_STATUS_CANCELLED;
    default:
        return NULL;
    }
}

#endif
