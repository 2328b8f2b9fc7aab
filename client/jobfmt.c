/* Formatting of statusInfo documents for people (status, wait, watch, list). */
#include "jobfmt.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "exitcodes.h"

const char *job_status(const json_t *info)
{
    const char *s = json_string_value(json_object_get(info, "status"));
    return s ? s : "";
}

int job_is_final(const char *s)
{
    return strcmp(s, "successful") == 0 || strcmp(s, "failed") == 0 || strcmp(s, "dismissed") == 0;
}

int job_exit_code(const char *s)
{
    if (strcmp(s, "successful") == 0)
        return RC_OK;
    if (strcmp(s, "dismissed") == 0)
        return RC_DISMISSED;
    return RC_FAILED;
}

void print_safe(FILE *f, const char *s)
{
    for (; s && *s; s++) {
        unsigned char c = (unsigned char)*s;
        fputc(c < 0x20 || c == 0x7f ? ' ' : c, f);
    }
}

double job_parse_time(const char *s)
{
    if (!s)
        return -1;
    struct tm tm;
    memset(&tm, 0, sizeof tm);
    int n = 0;
    if (sscanf(s, "%4d-%2d-%2d%*1[Tt]%2d:%2d:%2d%n", &tm.tm_year, &tm.tm_mon, &tm.tm_mday, &tm.tm_hour,
               &tm.tm_min, &tm.tm_sec, &n) != 6)
        return -1;
    tm.tm_year -= 1900;
    tm.tm_mon -= 1;
    double t = (double)timegm(&tm);
    const char *p = s + n;
    if (*p == '.') {
        char *end;
        t += strtod(p, &end);
        p = end;
    }
    int oh, om;
    if ((*p == '+' || *p == '-') && sscanf(p + 1, "%2d:%2d", &oh, &om) == 2)
        t -= (*p == '+' ? 1 : -1) * (oh * 3600.0 + om * 60.0);
    return t;
}

static void human_bytes(char *buf, size_t n, double b)
{
    const char *u[] = {"B", "KiB", "MiB", "GiB", "TiB"};
    int i = 0;
    while (b >= 1024 && i < 4) {
        b /= 1024;
        i++;
    }
    snprintf(buf, n, "%.3g %s", b, u[i]);
}

/* "STATUS (outcome OUTCOME)": the outcome only where it says more than the status. */
static void print_status(FILE *f, const json_t *info)
{
    const char *outcome = json_string_value(json_object_get(info, "outcome"));
    print_safe(f, job_status(info));
    if (outcome && strcmp(outcome, job_status(info)) != 0) {
        fputs(" (outcome ", f);
        print_safe(f, outcome);
        fputc(')', f);
    }
}

/* One summary row "LABEL     value", label in a 9-wide column; none without a value. */
static void print_row(FILE *f, const char *label, const char *value)
{
    if (!value)
        return;
    fprintf(f, "%-9s ", label);
    print_safe(f, value);
    fputc('\n', f);
}

void job_print_summary(FILE *f, const json_t *info)
{
    const char *id = json_string_value(json_object_get(info, "jobID"));
    const char *proc = json_string_value(json_object_get(info, "processID"));
    json_t *prog = json_object_get(info, "progress");

    fputs("job       ", f);
    print_safe(f, id ? id : "?");
    if (proc) {
        fputs(" (", f);
        print_safe(f, proc);
        fputc(')', f);
    }
    fputs("\nstatus    ", f);
    print_status(f, info);
    if (json_is_number(prog))
        fprintf(f, ", %.0f%%", json_number_value(prog));
    fputc('\n', f);
    print_row(f, "message", json_string_value(json_object_get(info, "message")));
    print_row(f, "study", json_string_value(json_object_get(info, "study")));
    json_t *sim = json_object_get(info, "simulation");
    if (json_is_object(sim)) {
        json_t *t = json_object_get(sim, "time"), *te = json_object_get(sim, "end_time");
        json_t *st = json_object_get(sim, "step"), *eta = json_object_get(sim, "eta_seconds");
        fputs("simulated", f);
        if (json_is_number(t))
            fprintf(f, " t=%.4g", json_number_value(t));
        if (json_is_number(te))
            fprintf(f, "/%.4g", json_number_value(te));
        fputs(" s", f);
        if (json_is_integer(st))
            fprintf(f, ", step %lld", (long long)json_integer_value(st));
        if (json_is_number(eta) && !job_is_final(job_status(info)))
            fprintf(f, ", ETA %.1f s", json_number_value(eta));
        fputc('\n', f);
    }
    const char *keys[] = {"created", "started", "finished"};
    for (int i = 0; i < 3; i++)
        print_row(f, keys[i], json_string_value(json_object_get(info, keys[i])));
    json_t *cost = json_object_get(info, "cost");
    if (json_is_object(cost)) {
        json_t *p = json_object_get(cost, "particles"), *s = json_object_get(cost, "steps");
        json_t *w = json_object_get(cost, "wall_seconds");
        json_t *r = json_object_get(cost, "particle_steps_per_second");
        json_t *m = json_object_get(cost, "peak_memory_bytes");
        fputs("cost     ", f);
        if (json_is_integer(p))
            fprintf(f, " %lld particles,", (long long)json_integer_value(p));
        if (json_is_integer(s))
            fprintf(f, " %lld steps,", (long long)json_integer_value(s));
        if (json_is_number(w))
            fprintf(f, " %.3g s wall,", json_number_value(w));
        if (json_is_number(r))
            fprintf(f, " %.3g particle-steps/s,", json_number_value(r));
        if (json_is_number(m)) {
            char b[32];
            human_bytes(b, sizeof b, json_number_value(m));
            fprintf(f, " peak memory %s", b);
        }
        fputc('\n', f);
    }
}

void job_print_final_line(FILE *f, const json_t *info)
{
    const char *id = json_string_value(json_object_get(info, "jobID"));
    const char *msg = json_string_value(json_object_get(info, "message"));
    print_safe(f, id ? id : "?");
    fputc(' ', f);
    print_status(f, info);
    if (msg) {
        fputs(": ", f);
        print_safe(f, msg);
    }
    fputc('\n', f);
}
