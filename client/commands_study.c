/* Study commands: study submit | status | table. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "exitcodes.h"
#include "http.h"
#include "jobfmt.h"
#include "study_table.h"

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

/* The scene schema from the server, for the units of swept values; NULL (and
 * no message) when the server has none to give. */
static json_t *scene_schema(const settings *s)
{
    http_response r;
    json_t *schema = NULL;
    if (http_exchange(s, "GET", "/schemas/scene.schema.json", NULL, HTTP_TIMEOUT, &r) != RC_OK)
        return NULL;
    if (r.status == 200)
        schema = json_loadb(r.body, r.len, 0, NULL);
    http_response_free(&r);
    return schema;
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
    json_t *schema = scene_schema(s);
    if (study_table_print(stdout, stderr, doc, schema, STUDY_TABLE_WIDTH) != 0) {
        fprintf(stderr, "tlsph: out of memory\n");
        rc = RC_IO;
    }
    json_decref(schema);
    json_decref(doc);
    if (fflush(stdout) != 0)
        rc = RC_IO;
    return rc;
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
