/* watch: live progress of a job through long-polls of GET /jobs/ID?wait=1.
 * On a terminal one line is redrawn; otherwise one plain line per change (at most
 * about one per second) and the final status line.  Exit code per final status. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "commands.h"
#include "exitcodes.h"
#include "http.h"
#include "jobfmt.h"
#include "util/clock.h"

#define BAR_WIDTH 20

/* Formats the progress line (without newline) into buf. */
static double realtime_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* local_start: monotonic time at which this watch saw the job start running (-1 if it
 * was already running: then the server's "started", which has 1 s resolution). */
static void progress_line(char *buf, size_t n, const json_t *info, int bar, double local_start)
{
    const char *st = job_status(info);
    json_t *prog = json_object_get(info, "progress");
    json_t *sim = json_object_get(info, "simulation");
    double pct = json_is_number(prog) ? json_number_value(prog) : 0;
    double t = json_number_value(json_object_get(sim, "time"));
    double te = json_number_value(json_object_get(sim, "end_time"));
    json_t *eta_j = json_object_get(sim, "eta_seconds");
    if (pct < 0)
        pct = 0;
    if (pct > 100)
        pct = 100;
    size_t k = 0;
#define ADD(...)                                                                               \
    do {                                                                                       \
        if (k < n) {                                                                           \
            int w_ = snprintf(buf + k, n - k, __VA_ARGS__);                                    \
            if (w_ > 0)                                                                        \
                k += (size_t)w_;                                                               \
        }                                                                                      \
    } while (0)
    if (bar) {
        int fill = (int)(pct / 100.0 * BAR_WIDTH + 0.5);
        ADD("[");
        for (int i = 0; i < BAR_WIDTH; i++)
            ADD("%c", i < fill ? '#' : '.');
        ADD("] ");
    } else {
        ADD("%s ", st);
    }
    ADD("%3.0f%%", pct);
    if (strcmp(st, "accepted") == 0) {
        ADD("  queued");
        return;
    }
    if (json_is_object(sim) && te > 0)
        ADD("  t=%.3g/%.3g s", t, te);
    double started = job_parse_time(json_string_value(json_object_get(info, "started")));
    double finished = job_parse_time(json_string_value(json_object_get(info, "finished")));
    double elapsed = -1;
    if (local_start >= 0 && !job_is_final(st))
        elapsed = tlsph_monotonic_seconds() - local_start;
    else if (started > 0)
        elapsed = (finished > 0 ? finished : realtime_now()) - started;
    if (elapsed < 0)
        elapsed = 0;
    if (elapsed >= 0)
        ADD("  elapsed %.1f s", elapsed);
    if (!job_is_final(st)) {
        double eta = -1;
        if (json_is_number(eta_j))
            eta = json_number_value(eta_j);
        else if (elapsed > 0 && t > 0 && te > t)
            eta = elapsed * (te - t) / t;
        if (eta >= 0 && isfinite(eta))
            ADD("  ETA %.1f s", eta);
    }
    if (!bar && strcmp(st, "running") != 0 && json_is_integer(json_object_get(sim, "step")))
        ADD("  step %lld", (long long)json_integer_value(json_object_get(sim, "step")));
#undef ADD
}

int cmd_watch(const settings *s, int argc, char **argv)
{
    const char *id;
    int rc = id_args("watch", "job", argc, argv, NULL, NULL, &id);
    if (rc != RC_OK)
        return rc;
    int tty = isatty(STDOUT_FILENO);
    char last[256] = "", line[256];
    double last_print = -10, local_start = -1;
    int seen_accepted = 0;
    for (;;) {
        double t0 = tlsph_monotonic_seconds();
        json_t *info;
        if ((rc = job_poll(s, id, 1.0, &info)) != RC_OK) {
            if (tty)
                putchar('\n');
            return rc;
        }
        const char *st = job_status(info);
        int final = job_is_final(st);
        if (strcmp(st, "accepted") == 0)
            seen_accepted = 1;
        else if (seen_accepted && local_start < 0 && strcmp(st, "running") == 0)
            local_start = tlsph_monotonic_seconds();
        progress_line(line, sizeof line, info, tty, local_start);
        if (tty) {
            printf("\r%s\033[K", line);
            if (final)
                putchar('\n');
            fflush(stdout);
        } else {
            /* plain lines: only changes, at most about one per second */
            int changed = strcmp(line, last) != 0;
            if (changed && !final && tlsph_monotonic_seconds() - last_print >= 0.9) {
                printf("%s\n", line);
                fflush(stdout);
                snprintf(last, sizeof last, "%s", line);
                last_print = tlsph_monotonic_seconds();
            }
        }
        if (final) {
            job_print_final_line(stdout, info);
            fflush(stdout);
            rc = job_exit_code(st);
            json_decref(info);
            return rc;
        }
        json_decref(info);
        double dt = tlsph_monotonic_seconds() - t0;
        if (dt < 0.9) { /* answered early (no long-poll): keep about one request per second */
            double sl = 0.9 - dt;
            struct timespec ts = {(time_t)sl, (long)((sl - floor(sl)) * 1e9)};
            nanosleep(&ts, NULL);
        }
    }
}
