/* Job commands: submit, status, wait, cancel, list. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "commands.h"
#include "exitcodes.h"
#include "http.h"
#include "jobfmt.h"
#include "urls.h"
#include "util/clock.h"

int job_poll(const settings *s, const char *id, double wait_s, json_t **out)
{
    char path[128];
    if (wait_s > 60)
        wait_s = 60;
    if (wait_s > 0)
        snprintf(path, sizeof path, "/jobs/%s?wait=%.1f", id, wait_s);
    else
        snprintf(path, sizeof path, "/jobs/%s", id);
    int rc = http_json(s, "GET", path, NULL, HTTP_TIMEOUT + (long)ceil(wait_s), out);
    if (rc == RC_OK && !json_is_object(*out)) {
        fprintf(stderr, "tlsph: unexpected answer for job %s\n", id);
        json_decref(*out);
        *out = NULL;
        rc = RC_NETWORK;
    }
    return rc;
}

/* Submits {"inputs": wrap} to /processes/PROC/execution and prints the job id. */
int submit_job(const settings *s, const char *process, json_t *inputs)
{
    json_t *body = json_pack("{s:o}", "inputs", inputs), *ans = NULL;
    if (!body) {
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    char path[64];
    snprintf(path, sizeof path, "/processes/%s/execution", process);
    int rc = http_json(s, "POST", path, body, HTTP_TIMEOUT, &ans);
    json_decref(body);
    if (rc != RC_OK)
        return rc;
    const char *id = json_string_value(json_object_get(ans, "jobID"));
    if (!id || !id_valid(id)) {
        fprintf(stderr, "tlsph: the server did not answer a job id\n");
        rc = RC_NETWORK;
    } else {
        printf("%s\n", id);
    }
    json_decref(ans);
    return rc;
}

int cmd_submit(const settings *s, int argc, char **argv)
{
    return submit_file(s, argc, argv, "submit", "SCENE.json", "run", "scene");
}

int cmd_status(const settings *s, int argc, char **argv)
{
    const char *id;
    int as_json = 0;
    int rc = id_args(argv[0], "job", argc, argv, "--json", &as_json, &id);
    if (rc != RC_OK)
        return rc;
    json_t *info;
    if ((rc = job_poll(s, id, 0, &info)) != RC_OK)
        return rc;
    if (as_json) {
        if (json_dumpf(info, stdout, JSON_INDENT(2)) != 0)
            rc = RC_IO;
        putchar('\n');
    } else {
        job_print_summary(stdout, info);
    }
    json_decref(info);
    return rc;
}

int cmd_wait(const settings *s, int argc, char **argv)
{
    const char *id = NULL;
    double timeout = 0;
    int rc;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--timeout") == 0 && i + 1 < argc) {
            char *end;
            errno = 0;
            timeout = strtod(argv[++i], &end);
            if (*end || errno || !(timeout > 0) || !isfinite(timeout))
                return usage_error("wait", "--timeout needs a positive number of seconds", argv[i]);
        } else if ((rc = take_id("wait", "job", argv[i], &id)) != RC_OK) {
            return rc;
        }
    }
    if ((rc = need_id("wait", "job", id)) != RC_OK)
        return rc;
    double deadline = timeout > 0 ? tlsph_monotonic_seconds() + timeout : 0;
    for (;;) {
        double w = 30;
        if (deadline) {
            double left = deadline - tlsph_monotonic_seconds();
            if (left <= 0) {
                fprintf(stderr, "tlsph: job %s is not final after %g s\n", id, timeout);
                return RC_TIMEOUT;
            }
            if (left < w)
                w = left;
        }
        double t0 = tlsph_monotonic_seconds();
        json_t *info;
        if ((rc = job_poll(s, id, w, &info)) != RC_OK)
            return rc;
        const char *st = job_status(info);
        if (job_is_final(st)) {
            job_print_final_line(stdout, info);
            rc = job_exit_code(st);
            json_decref(info);
            return rc;
        }
        json_decref(info);
        if (tlsph_monotonic_seconds() - t0 < 0.2) { /* a server that does not long-poll: do not spin */
            struct timespec ts = {0, 500000000L};
            nanosleep(&ts, NULL);
        }
    }
}

int cmd_cancel(const settings *s, int argc, char **argv)
{
    const char *id;
    int remove = 0;
    int rc = id_args("cancel", "job", argc, argv, "--remove", &remove, &id);
    if (rc != RC_OK)
        return rc;
    json_t *info;
    if (!remove) {
        /* DELETE on a final job removes it with its files: only with --remove */
        if ((rc = job_poll(s, id, 0, &info)) != RC_OK)
            return rc;
        if (job_is_final(job_status(info))) {
            job_print_final_line(stdout, info);
            fprintf(stderr, "tlsph: job %s is already final; nothing to cancel "
                            "(use 'tlsph cancel --remove ID' to delete it and its files)\n", id);
            json_decref(info);
            return RC_OK;
        }
        json_decref(info);
    }
    char path[64];
    snprintf(path, sizeof path, "/jobs/%s", id);
    if ((rc = http_json(s, "DELETE", path, NULL, HTTP_TIMEOUT, &info)) != RC_OK)
        return rc;
    const char *removed = json_string_value(json_object_get(info, "removed"));
    if (removed) {
        printf("%s removed\n", removed);
    } else {
        job_print_final_line(stdout, info);
    }
    json_decref(info);
    return RC_OK;
}

static void print_cell(const char *v, int width)
{
    int n = 0;
    for (; v && *v && (width <= 0 || n < width); v++, n++)
        putchar((unsigned char)*v < 0x20 ? ' ' : *v);
    if (v && *v) /* truncated */
        fputs("…", stdout);
    for (; n < width; n++)
        putchar(' ');
}

int cmd_list(const settings *s, int argc, char **argv)
{
    const char *status = NULL, *study = NULL;
    long limit = 0;
    int as_json = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--status") == 0 && i + 1 < argc) {
            status = argv[++i];
            const char *ok[] = {"accepted", "running", "successful", "failed", "dismissed"};
            int found = 0;
            for (int k = 0; k < 5; k++)
                found |= strcmp(status, ok[k]) == 0;
            if (!found)
                return usage_error("list", "--status must be accepted, running, successful, failed or dismissed",
                                   status);
        } else if (strcmp(argv[i], "--study") == 0 && i + 1 < argc) {
            study = argv[++i];
            int rc = id_check(study);
            if (rc != RC_OK)
                return rc;
        } else if (strcmp(argv[i], "--limit") == 0 && i + 1 < argc) {
            char *end;
            errno = 0;
            limit = strtol(argv[++i], &end, 10);
            if (*end || errno || limit < 1 || limit > 10000)
                return usage_error("list", "--limit must be an integer in 1..10000", argv[i]);
        } else if (strcmp(argv[i], "--json") == 0) {
            as_json = 1;
        } else {
            return usage_error("list", "unexpected argument", argv[i]);
        }
    }
    char path[256];
    int n = snprintf(path, sizeof path, "/jobs");
    char sep = '?';
    if (status) {
        n += snprintf(path + n, sizeof path - (size_t)n, "%cstatus=%s", sep, status);
        sep = '&';
    }
    if (study) {
        n += snprintf(path + n, sizeof path - (size_t)n, "%cstudy=%s", sep, study);
        sep = '&';
    }
    if (limit)
        snprintf(path + n, sizeof path - (size_t)n, "%climit=%ld", sep, limit);
    json_t *list;
    int rc = http_json(s, "GET", path, NULL, HTTP_TIMEOUT, &list);
    if (rc != RC_OK)
        return rc;
    if (as_json) {
        if (json_dumpf(list, stdout, JSON_INDENT(2)) != 0)
            rc = RC_IO;
        putchar('\n');
        json_decref(list);
        return rc;
    }
    printf("%-32s  %-7s  %-10s  %4s  %-20s  %s\n", "JOB", "PROCESS", "STATUS", "PROG", "CREATED", "MESSAGE");
    size_t i;
    json_t *j;
    json_array_foreach(json_object_get(list, "jobs"), i, j)
    {
        json_t *prog = json_object_get(j, "progress");
        char p[16] = "-";
        if (json_is_number(prog))
            snprintf(p, sizeof p, "%.0f%%", json_number_value(prog));
        print_cell(json_string_value(json_object_get(j, "jobID")), 32);
        fputs("  ", stdout);
        print_cell(json_string_value(json_object_get(j, "processID")), 7);
        fputs("  ", stdout);
        print_cell(job_status(j), 10);
        printf("  %4s  ", p);
        print_cell(json_string_value(json_object_get(j, "created")), 20);
        fputs("  ", stdout);
        print_cell(json_string_value(json_object_get(j, "message")), 0);
        putchar('\n');
    }
    json_decref(list);
    return RC_OK;
}
