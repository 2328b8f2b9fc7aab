/* What one engine run tells the daemon, see engine_report.h. */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE /* sigabbrev_np */
#endif
#include "engine_report.h"

#include <jansson.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "errmsg.h"
#include "queue.h"
#include "run/protocol.h"

/* Errors quoted in a job's message; the rest are in the engine log. */
#define MESSAGE_ERRORS 5

void engine_report_init(struct engine_report *r, double end_time)
{
    memset(r, 0, sizeof *r);
    r->end_time = end_time;
    r->eta = -1;
}

void engine_report_free(struct engine_report *r)
{
    free(r->cost);
    free(r->diagnostic);
    free(r->errors);
    strbuf_free(&r->line);
    memset(r, 0, sizeof *r);
}

static void set_text(char **dst, char *text)
{
    free(*dst);
    *dst = text;
}

/* The errors of a final event as "pointer: detail" lines, the way the engine
 * prints them for people ("(scene)" for the whole document). */
static char *errors_text(const json_t *errors)
{
    struct strbuf b = {0};
    size_t i;
    const json_t *e;
    json_array_foreach(errors, i, e) {
        const char *pointer = json_string_value(json_object_get(e, "pointer"));
        const char *detail = json_string_value(json_object_get(e, "detail"));
        if (i == MESSAGE_ERRORS || !detail)
            break;
        strbuf_printf(&b, "%s%s: %s", b.len ? "\n" : "", pointer && *pointer ? pointer : "(scene)",
                      detail);
    }
    return b.len ? strbuf_take(&b) : (strbuf_free(&b), NULL);
}

static void take_number(const json_t *o, const char *key, double *dst)
{
    const json_t *v = json_object_get(o, key);
    if (json_is_number(v))
        *dst = json_number_value(v);
}

static void take_integer(const json_t *o, const char *key, long *dst)
{
    const json_t *v = json_object_get(o, key);
    if (json_is_integer(v))
        *dst = (long)json_integer_value(v);
}

static void take_final(struct engine_report *r, const json_t *o)
{
    r->finished = true;
    take_integer(o, "step", &r->step);
    take_number(o, "time", &r->sim_time);
    const json_t *cost = json_object_get(o, "cost");
    if (json_is_object(cost))
        set_text(&r->cost, json_dumps(cost, JSON_COMPACT));
    const char *diag = json_string_value(json_object_get(json_object_get(o, "diagnostic"), "message"));
    if (diag)
        set_text(&r->diagnostic, strdup(diag));
    const json_t *errors = json_object_get(o, "errors");
    if (json_is_array(errors))
        set_text(&r->errors, errors_text(errors));
}

/* One whole line; true when it moved the progress. */
static bool take_line(struct engine_report *r, const char *line, size_t len)
{
    json_t *o = json_loadb(line, len, 0, NULL);
    const char *ev = json_string_value(json_object_get(o, "event"));
    bool moved = false;
    if (!ev || !json_is_object(o)) {
        /* not an event: ignored (the protocol is line-oriented JSON only) */
    } else if (!strcmp(ev, TLSPH_EVENT_STARTED)) {
        take_number(o, "end_time", &r->end_time);
        moved = true;
    } else if (!strcmp(ev, TLSPH_EVENT_PROGRESS)) {
        take_number(o, "end_time", &r->end_time);
        take_number(o, "time", &r->sim_time);
        take_integer(o, "step", &r->step);
        take_number(o, "eta_seconds", &r->eta);
        moved = true;
    } else if (!strcmp(ev, TLSPH_EVENT_FINISHED)) {
        take_final(r, o); /* its step and time are the run's last: the job shows them */
        moved = true;
    }
    json_decref(o);
    return moved;
}

bool engine_report_feed(struct engine_report *r, const char *buf, size_t n)
{
    bool moved = false;
    while (n > 0) {
        const char *nl = memchr(buf, '\n', n);
        const size_t part = nl ? (size_t)(nl - buf) : n;
        if (!r->overflow) {
            const bool fits = r->line.len + part <= ENGINE_LINE_MAX;
            if (fits)
                strbuf_add(&r->line, buf, part);
            if (!fits || r->line.oom) {
                strbuf_reset(&r->line); /* the line is dropped: skip to its end */
                r->overflow = true;
            }
        }
        if (nl) {
            if (!r->overflow && r->line.len > 0)
                moved |= take_line(r, r->line.p, r->line.len);
            strbuf_reset(&r->line);
            r->overflow = false;
        }
        buf += nl ? part + 1 : part;
        n -= nl ? part + 1 : part;
    }
    return moved;
}

bool engine_report_eof(struct engine_report *r)
{
    const bool moved = !r->overflow && r->line.len > 0 && take_line(r, r->line.p, r->line.len);
    strbuf_reset(&r->line);
    r->overflow = false;
    return moved;
}

static const char *signal_name(int sig)
{
    const char *n = sigabbrev_np(sig);
    return n ? n : "?";
}

void engine_outcome(const struct engine_report *r, int wstatus, enum engine_stop why,
                    double wall_limit, struct engine_outcome *out)
{
    const bool lost = wstatus == -1;
    const int code = !lost && WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1;
    const int sig = !lost && WIFSIGNALED(wstatus) ? WTERMSIG(wstatus) : 0;
    memset(out, 0, sizeof *out);
    out->status = TQ_FAILED;
    out->outcome = "crashed";

    if (code == TLSPH_EXIT_SUCCESS) {
        out->status = TQ_SUCCESSFUL;
        out->outcome = "successful";
    } else if (why == ENGINE_STOP_CANCEL) {
        out->status = TQ_DISMISSED;
        out->outcome = "cancelled";
        out->message = strdup("cancelled");
    } else if (why == ENGINE_STOP_SHUTDOWN) {
        out->requeue = true;
    } else if (why == ENGINE_STOP_TIMEOUT) {
        out->outcome = "timed_out";
        out->message = errmsg_format("wall-clock limit of %g s exceeded", wall_limit);
    } else if (code == TLSPH_EXIT_INVALID) {
        out->outcome = "invalid";
        out->message = strdup(r->errors ? r->errors : "invalid scene");
    } else if (code == TLSPH_EXIT_UNSTABLE) {
        out->outcome = "unstable";
        out->message = strdup(r->diagnostic ? r->diagnostic : "numerically unstable");
    } else if (code == TLSPH_EXIT_IO) {
        out->outcome = "io_error";
        out->message = r->errors ? errmsg_format("I/O failure: %s", r->errors) : strdup("I/O failure");
    } else if (code == TLSPH_EXIT_CANCELLED) {
        out->status = TQ_DISMISSED;
        out->outcome = "cancelled";
        out->message = strdup("cancelled");
    } else if (lost) {
        out->message = strdup("engine ended, but its exit status was lost (reaped elsewhere)");
    } else if (sig) {
        out->message = errmsg_format("killed by signal %d (SIG%s)%s", sig, signal_name(sig),
                               sig == SIGKILL ? ": killed externally or out of memory" : "");
    } else {
        out->message = errmsg_format("engine exited with unexpected status %d (see the job log)", code);
    }
}
