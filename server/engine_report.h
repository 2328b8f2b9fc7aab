/* What one engine run tells the daemon (server/engine_report.c).
 *
 * The engine speaks only through the protocol of core/run/protocol.h
 * (docs/protocol.md): JSON lines on the progress pipe and its exit code.
 * This module reads the lines (whole lines only, at most ENGINE_LINE_MAX
 * bytes each; anything else is skipped), keeps the latest progress and the
 * final event, and turns the exit status into the job's final state.  The
 * messages come from the final event (the validation or I/O errors, the
 * stability diagnostic), never from the engine's log.  No I/O, no queue:
 * the supervisor feeds it bytes and writes what it says. */
#ifndef TLSPHD_ENGINE_REPORT_H
#define TLSPHD_ENGINE_REPORT_H

#include <stdbool.h>
#include <stddef.h>

#include "strbuf.h"

#define ENGINE_LINE_MAX (256 * 1024) /* longest progress line kept, bytes */

struct engine_report {
    /* progress, from "started" and "progress" (end_time from the job until then) */
    double end_time, sim_time; /* s of simulated time */
    long step;
    double eta;                /* s of wall time, -1 unknown */
    /* the final event */
    bool finished;
    char *cost;                /* its "cost" as compact JSON text, or NULL */
    char *diagnostic;          /* the diagnostic's message (unstable), or NULL */
    char *errors;              /* "pointer: detail" lines (invalid, io_error), or NULL */
    /* line assembly */
    struct strbuf line;
    bool overflow;             /* inside an over-long line: skip to its end */
};

/* Why the daemon stopped an engine, if it did. */
enum engine_stop {
    ENGINE_NOT_STOPPED,
    ENGINE_STOP_CANCEL,   /* the user cancelled the job */
    ENGINE_STOP_TIMEOUT,  /* the wall-clock limit passed */
    ENGINE_STOP_SHUTDOWN  /* the daemon is stopping: the job runs again later */
};

/* The job's final state. */
struct engine_outcome {
    bool requeue;         /* put the job back (daemon shutdown); the rest is unset */
    const char *status;   /* TQ_SUCCESSFUL, TQ_FAILED or TQ_DISMISSED */
    const char *outcome;  /* successful|invalid|unstable|io_error|cancelled|timed_out|crashed */
    char *message;        /* for people (malloc'ed, may be NULL) */
};

void engine_report_init(struct engine_report *r, double end_time);
void engine_report_free(struct engine_report *r);
/* Feeds n bytes read from the pipe.  True when a progress, started or
 * finished event updated the progress members. */
bool engine_report_feed(struct engine_report *r, const char *buf, size_t n);
/* The pipe is closed: an unterminated last line still counts.  True when it
 * updated the progress members (as engine_report_feed). */
bool engine_report_eof(struct engine_report *r);

/* The final state from the report, the wait status (-1: lost, reaped
 * elsewhere), why the daemon stopped the engine, and the wall-clock limit that
 * applied (s).  Free out->message. */
void engine_outcome(const struct engine_report *r, int wstatus, enum engine_stop why,
                    double wall_limit, struct engine_outcome *out);

#endif
