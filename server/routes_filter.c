/* The query of GET /jobs read into a queue filter (see route.h): the OGC API
 * - Processes 1.0 job-list parameters type, processID, status (repeated or
 * comma-separated), datetime, minDuration and maxDuration, and tlsph's
 * study. */
#include "route.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <microhttpd.h>

struct each_arg {
    const char *name;
    void (*fn)(const char *value, void *ctx);
    void *ctx;
};

static enum MHD_Result each_cb(void *cls, enum MHD_ValueKind kind, const char *key,
                               const char *value)
{
    (void)kind;
    struct each_arg *a = cls;
    if (key && !strcmp(key, a->name))
        a->fn(value ? value : "", a->ctx);
    return MHD_YES;
}

void route_query_each(struct hreq *r, const char *name, void (*fn)(const char *value, void *ctx),
                      void *ctx)
{
    struct each_arg a = {name, fn, ctx};
    MHD_get_connection_values(r->conn, MHD_GET_ARGUMENT_KIND, each_cb, &a);
}

/* ------------------------------------------------------------ list values */

/* Every comma-separated item of every value of a parameter, copied into
 * items (bad set when there are more than fit or an item is too long). */
struct items {
    char v[8][16];
    size_t n;
    bool bad;
};

static void add_items(const char *value, void *ctx)
{
    struct items *it = ctx;
    for (const char *p = value;; p++) {
        const char *e = strchr(p, ',');
        const size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len > 0) {
            bool seen = false;
            for (size_t i = 0; i < it->n; i++)
                seen |= strlen(it->v[i]) == len && !strncmp(it->v[i], p, len);
            if (!seen && (it->n == sizeof it->v / sizeof it->v[0] || len >= sizeof it->v[0]))
                it->bad = true;
            else if (!seen)
                snprintf(it->v[it->n++], sizeof it->v[0], "%.*s", (int)len, p);
        }
        if (!e)
            return;
        p = e;
    }
}

/* --------------------------------------------------------------- datetime */

/* An RFC 3339 date-time ("2026-11-25T19:00:00Z", fraction and offset
 * allowed) → Unix seconds; false when it is not one. */
static bool parse_rfc3339(const char *s, size_t len, double *out)
{
    char buf[64];
    if (len >= sizeof buf)
        return false;
    memcpy(buf, s, len);
    buf[len] = '\0';
    struct tm tm;
    memset(&tm, 0, sizeof tm);
    int consumed = 0;
    char t;
    if (sscanf(buf, "%4d-%2d-%2d%c%2d:%2d:%2d%n", &tm.tm_year, &tm.tm_mon, &tm.tm_mday, &t,
               &tm.tm_hour, &tm.tm_min, &tm.tm_sec, &consumed) != 7 ||
        (t != 'T' && t != 't') || consumed != 19)
        return false;
    if (tm.tm_mon < 1 || tm.tm_mon > 12 || tm.tm_mday < 1 || tm.tm_mday > 31 || tm.tm_hour > 23 ||
        tm.tm_min > 59 || tm.tm_sec > 60)
        return false;
    const char *p = buf + consumed;
    double frac = 0;
    if (*p == '.') {
        const char *q = ++p;
        double scale = 0.1;
        while (isdigit((unsigned char)*p)) {
            frac += (*p - '0') * scale;
            scale /= 10;
            p++;
        }
        if (p == q)
            return false;
    }
    long offset = 0;
    if (*p == 'Z' || *p == 'z') {
        p++;
    } else if (*p == '+' || *p == '-') {
        int oh, om, n = 0;
        if (sscanf(p + 1, "%2d:%2d%n", &oh, &om, &n) != 2 || n != 5 || oh > 23 || om > 59)
            return false;
        offset = (*p == '+' ? 1 : -1) * (oh * 3600L + om * 60L);
        p += 6;
    } else {
        return false;
    }
    if (*p)
        return false;
    tm.tm_year -= 1900;
    tm.tm_mon -= 1;
    const time_t t0 = timegm(&tm);
    *out = (double)t0 - (double)offset + frac;
    return true;
}

/* One end of a datetime interval: "" or ".." is open (false in *has). */
static bool parse_end(const char *s, size_t len, bool *has, double *t)
{
    *has = false;
    if (len == 0 || (len == 2 && !strncmp(s, "..", 2)))
        return true;
    *has = true;
    return parse_rfc3339(s, len, t);
}

/* datetime: an instant, or an interval "start/end" with open ends. */
static bool parse_datetime(const char *v, struct tq_filter *f)
{
    const char *slash = strchr(v, '/');
    if (!slash) {
        if (!parse_rfc3339(v, strlen(v), &f->created_min))
            return false;
        f->created_max = f->created_min;
        f->has_created_min = f->has_created_max = true;
        return true;
    }
    return parse_end(v, (size_t)(slash - v), &f->has_created_min, &f->created_min) &&
           parse_end(slash + 1, strlen(slash + 1), &f->has_created_max, &f->created_max) &&
           (!f->has_created_min || !f->has_created_max || f->created_min <= f->created_max);
}

static bool parse_seconds(const char *v, double *out)
{
    char *end;
    errno = 0;
    const double d = strtod(v, &end);
    if (errno || end == v || *end || !isfinite(d) || d < 0)
        return false;
    *out = d;
    return true;
}

/* ------------------------------------------------------------------- filter */

int route_job_filter(struct hreq *r, struct tq_filter *f, bool *none, char *detail, size_t size)
{
    memset(f, 0, sizeof *f);
    *none = false;
    struct items st = {.n = 0}, ty = {.n = 0}, pr = {.n = 0};
    route_query_each(r, "status", add_items, &st);
    route_query_each(r, "type", add_items, &ty);
    route_query_each(r, "processID", add_items, &pr);
    if (pr.n == 0)
        route_query_each(r, "process", add_items, &pr);
    if (st.bad || st.n > TQ_FILTER_STATUS_MAX) {
        snprintf(detail, size, "status: at most the five status values");
        return -1;
    }
    /* canonical constants: the filter outlives the parsed items */
    static const char *const names[] = {TQ_ACCEPTED, TQ_RUNNING, TQ_SUCCESSFUL, TQ_FAILED,
                                        TQ_DISMISSED};
    for (size_t i = 0; i < st.n; i++) {
        const char *known = NULL;
        for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
            if (!strcmp(st.v[i], names[k]))
                known = names[k];
        if (!known) {
            snprintf(detail, size,
                     "status must be accepted, running, successful, failed or dismissed "
                     "(repeated, or separated by commas)");
            return -1;
        }
        f->status[f->nstatus++] = known;
    }
    /* every job is of type "process" (OGC 1.0 statusInfo) */
    bool process_type = ty.n == 0;
    for (size_t i = 0; i < ty.n; i++)
        process_type |= !strcmp(ty.v[i], "process");
    *none |= !process_type;
    if (pr.bad) {
        snprintf(detail, size, "processID must be run or study");
        return -1;
    }
    bool run = false, study = false;
    for (size_t i = 0; i < pr.n; i++) {
        run |= !strcmp(pr.v[i], "run");
        study |= !strcmp(pr.v[i], "study");
        if (strcmp(pr.v[i], "run") && strcmp(pr.v[i], "study")) {
            snprintf(detail, size, "processID must be run or study");
            return -1;
        }
    }
    f->process = run && !study ? "run" : study && !run ? "study" : NULL;
    const char *sid = http_query(r, "study");
    if (sid && *sid && !job_id_valid(sid)) {
        snprintf(detail, size, "study must be a job id (32 hex digits)");
        return -1;
    }
    f->study_id = sid;
    const char *dt = http_query(r, "datetime");
    if (dt && !parse_datetime(dt, f)) {
        snprintf(detail, size,
                 "datetime must be an RFC 3339 date-time or an interval start/end "
                 "(\"..\" or empty for an open end), e.g. 2026-01-01T00:00:00Z/..");
        return -1;
    }
    const char *mind = http_query(r, "minDuration"), *maxd = http_query(r, "maxDuration");
    if (mind && !(f->has_min_duration = parse_seconds(mind, &f->min_duration))) {
        snprintf(detail, size, "minDuration must be a non-negative number of seconds");
        return -1;
    }
    if (maxd && !(f->has_max_duration = parse_seconds(maxd, &f->max_duration))) {
        snprintf(detail, size, "maxDuration must be a non-negative number of seconds");
        return -1;
    }
    return 0;
}

/* Percent-encodes what a query value may not hold as is. */
static void add_encoded(char *out, size_t size, const char *key, const char *value)
{
    size_t n = strlen(out);
    n += (size_t)snprintf(out + n, n < size ? size - n : 0, "&%s=", key);
    for (const unsigned char *p = (const unsigned char *)value; *p && n + 4 < size; p++) {
        if (isalnum(*p) || strchr("-._~:,/", *p))
            out[n++] = (char)*p;
        else
            n += (size_t)snprintf(out + n, size - n, "%%%02X", *p);
    }
    if (n < size)
        out[n] = '\0';
}

void route_job_filter_query(struct hreq *r, const struct tq_filter *f, char *out, size_t size)
{
    out[0] = '\0';
    if (f->nstatus) {
        char list[64] = "";
        for (size_t i = 0; i < f->nstatus; i++)
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? "," : "",
                     f->status[i]);
        add_encoded(out, size, "status", list);
    }
    const char *keep[] = {"type", "datetime", "minDuration", "maxDuration"};
    for (size_t i = 0; i < sizeof keep / sizeof keep[0]; i++) {
        const char *v = http_query(r, keep[i]);
        if (v)
            add_encoded(out, size, keep[i], v);
    }
    if (f->study_id && *f->study_id)
        add_encoded(out, size, "study", f->study_id);
    if (f->process)
        add_encoded(out, size, "processID", f->process);
}
