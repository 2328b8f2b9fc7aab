/* Study commands: study submit | status | table. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "exitcodes.h"
#include "http.h"
#include "jobfmt.h"

static int study_status(const settings *s, int argc, char **argv)
{
    const char *id;
    int rc = id_args("study status", "study", argc, argv, NULL, NULL, &id);
    if (rc != RC_OK)
        return rc;
    json_t *info, *kids;
    if ((rc = job_poll(s, id, 0, &info)) != RC_OK)
        return rc;
    job_print_summary(stdout, info);
    json_decref(info);
    char path[128];
    snprintf(path, sizeof path, "/jobs?study=%s&limit=10000", id);
    if ((rc = http_json(s, "GET", path, NULL, HTTP_TIMEOUT, &kids)) != RC_OK)
        return rc;
    const char *names[] = {"accepted", "running", "successful", "failed", "dismissed"};
    int count[5] = {0};
    size_t i, total = 0;
    json_t *j;
    json_array_foreach(json_object_get(kids, "jobs"), i, j)
    {
        total++;
        for (int k = 0; k < 5; k++)
            if (strcmp(job_status(j), names[k]) == 0)
                count[k]++;
    }
    printf("children  %zu:", total);
    const char *sep = " ";
    for (int k = 0; k < 5; k++)
        if (count[k]) {
            printf("%s%d %s", sep, count[k], names[k]);
            sep = ", ";
        }
    putchar('\n');
    json_decref(kids);
    return RC_OK;
}

/* Cell text of a summary value. */
static void cell_text(char *buf, size_t n, const json_t *v)
{
    if (json_is_integer(v))
        snprintf(buf, n, "%lld", (long long)json_integer_value(v));
    else if (json_is_real(v))
        snprintf(buf, n, "%.6g", json_real_value(v));
    else if (json_is_string(v)) {
        snprintf(buf, n, "%s", json_string_value(v));
        for (char *p = buf; *p; p++)
            if ((unsigned char)*p < 0x20)
                *p = ' ';
    } else if (json_is_null(v) || !v)
        snprintf(buf, n, "-");
    else
        snprintf(buf, n, "%s", json_is_true(v) ? "true" : json_is_false(v) ? "false" : "?");
}

/* Column i of nc: numbers right-aligned to width w, text left-aligned (the
 * last column unpadded); two spaces between columns. */
static void print_table_cell(size_t i, size_t nc, int w, int right, const char *text)
{
    if (right)
        printf("%s%*s", i ? "  " : "", w, text);
    else
        printf("%s%-*s", i ? "  " : "", i + 1 < nc ? w : 0, text);
}

static int study_table(const settings *s, int argc, char **argv)
{
    const char *id;
    int csv = 0;
    int rc = id_args("study table", "study", argc, argv, "--csv", &csv, &id);
    if (rc != RC_OK)
        return rc;
    char path[128];
    snprintf(path, sizeof path, "/jobs/%s/results/summary%s", id, csv ? "?format=csv" : "");
    if (csv) {
        http_response r;
        if ((rc = http_text(s, path, &r)) != RC_OK)
            return rc;
        if (fwrite(r.body, 1, r.len, stdout) != r.len || fflush(stdout) != 0)
            rc = RC_IO;
        http_response_free(&r);
        return rc;
    }
    json_t *doc;
    if ((rc = http_json(s, "GET", path, NULL, HTTP_TIMEOUT, &doc)) != RC_OK)
        return rc;
    json_t *cols = json_object_get(doc, "columns"), *rows = json_object_get(doc, "rows");
    size_t nc = json_array_size(cols);
    int *w = calloc(nc ? nc : 1, sizeof *w), *numeric = calloc(nc ? nc : 1, sizeof *numeric);
    if (!w || !numeric) {
        free(w);
        free(numeric);
        json_decref(doc);
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    char buf[256];
    size_t i, r;
    json_t *row;
    for (i = 0; i < nc; i++) {
        cell_text(buf, sizeof buf, json_array_get(cols, i));
        w[i] = (int)strlen(buf);
    }
    json_array_foreach(rows, r, row) for (i = 0; i < nc; i++)
    {
        cell_text(buf, sizeof buf, json_array_get(row, i));
        if ((int)strlen(buf) > w[i])
            w[i] = (int)strlen(buf);
        if (json_is_number(json_array_get(row, i)))
            numeric[i] = 1;
    }
    for (i = 0; i < nc; i++) {
        cell_text(buf, sizeof buf, json_array_get(cols, i));
        print_table_cell(i, nc, w[i], numeric[i], buf);
    }
    putchar('\n');
    json_array_foreach(rows, r, row)
    {
        for (i = 0; i < nc; i++) {
            json_t *v = json_array_get(row, i);
            cell_text(buf, sizeof buf, v);
            print_table_cell(i, nc, w[i], numeric[i] && !json_is_string(v), buf);
        }
        putchar('\n');
    }
    free(w);
    free(numeric);
    json_decref(doc);
    return fflush(stdout) == 0 ? RC_OK : RC_IO;
}

int cmd_study(const settings *s, int argc, char **argv)
{
    if (argc < 2)
        return usage_error("study", "expected submit, status or table", NULL);
    const char *sub = argv[1];
    if (strcmp(sub, "submit") == 0)
        return submit_file(s, argc - 1, argv + 1, "study submit", "STUDY.json", "study", NULL);
    if (strcmp(sub, "status") == 0)
        return study_status(s, argc - 1, argv + 1);
    if (strcmp(sub, "table") == 0)
        return study_table(s, argc - 1, argv + 1);
    return usage_error("study", "unknown subcommand", sub);
}
