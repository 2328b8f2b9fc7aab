/* The service's own resources (server/routes_meta.c): the landing page,
 * conformance, the API definition, the schemas, health, and the process
 * descriptions (OGC API - Processes 1.0). */
#include "route.h"

#include <ctype.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "problem.h"

void meta_landing(struct hreq *r, struct route_call *c)
{
    (void)c;
    json_t *o = json_pack("{s:s,s:s}", "title", "tlsphd",
                          "description", "TLSPH simulation job service (OGC API - Processes 1.0 style)");
    json_t *links = json_array();
    route_add_link(links, "self", "application/json", "this document", "/");
    route_add_link(links, "service-desc", "application/vnd.oai.openapi+json;version=3.1",
             "the API definition", "/openapi.json");
    route_add_link(links, REL_CONFORMANCE, "application/json", "conformance", "/conformance");
    route_add_link(links, REL_PROCESSES, "application/json", "processes", "/processes");
    route_add_link(links, REL_JOBLIST, "application/json", "jobs", "/jobs");
    json_object_set_new(o, "links", links);
    http_reply_json(r, 200, o);
}

void meta_conformance(struct hreq *r, struct route_call *c)
{
    (void)c;
    const char *base = "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/";
    const char *cls[] = {"core", "json", "job-list", "dismiss", "oas30"};
    json_t *arr = json_array();
    for (size_t i = 0; i < sizeof cls / sizeof cls[0]; i++) {
        char buf[128];
        snprintf(buf, sizeof buf, "%s%s", base, cls[i]);
        json_array_append_new(arr, json_string(buf));
    }
    http_reply_json(r, 200, json_pack("{s:o}", "conformsTo", arr));
}

/* A process description (full: with its inputs and outputs). */
static json_t *process_desc(const char *id, bool full)
{
    const int run = !strcmp(id, "run");
    json_t *o = json_pack("{s:s,s:s,s:s,s:s,s:[s,s],s:[s]}", "id", id, "title",
                          run ? "Run one TLSPH simulation" : "Parametric study",
                          "description",
                          run ? "Runs one scene (schemas/scene.schema.json) and stores its "
                                "results as HDF5 (H5MD layout) with an XDMF sidecar."
                              : "Runs a base scene once per point of a sweep over scene values "
                                "given by JSON pointers (product or zip) and tabulates the results.",
                          "version", "1.0.0", "jobControlOptions", "async-execute", "dismiss",
                          "outputTransmission", "reference");
    json_t *links = json_array();
    route_add_link(links, "self", "application/json", "process description", "/processes/%s", id);
    route_add_link(links, REL_EXEC, "application/json", "execute", "/processes/%s/execution", id);
    json_object_set_new(o, "links", links);
    if (full) {
        json_t *inputs = json_object();
        if (run) {
            json_object_set_new(inputs, "scene",
                                json_pack("{s:s,s:s,s:{s:s}}", "title", "scene", "description",
                                          "the scene document", "schema", "$ref",
                                          "/schemas/scene.schema.json"));
        } else {
            json_object_set_new(inputs, "base",
                                json_pack("{s:s,s:{s:s}}", "title", "base scene", "schema",
                                          "$ref", "/schemas/scene.schema.json"));
            json_object_set_new(inputs, "sweep",
                                json_pack("{s:s,s:{s:s}}", "title", "sweep", "schema", "$ref",
                                          "/schemas/study.schema.json#/properties/sweep"));
            json_object_set_new(inputs, "outputs",
                                json_pack("{s:s,s:i,s:{s:s}}", "title", "derived outputs",
                                          "minOccurs", 0, "schema", "$ref",
                                          "/schemas/study.schema.json#/properties/outputs"));
        }
        json_object_set_new(o, "inputs", inputs);
        json_t *outputs = json_object();
        if (run)
            json_object_set_new(outputs, "result",
                                json_pack("{s:s,s:{s:s,s:s}}", "title", "HDF5 result file",
                                          "schema", "type", "string", "contentMediaType",
                                          "application/x-hdf5"));
        else
            json_object_set_new(outputs, "summary",
                                json_pack("{s:s,s:{s:s}}", "title", "study summary table",
                                          "schema", "type", "object"));
        json_object_set_new(o, "outputs", outputs);
    }
    return o;
}

void meta_processes(struct hreq *r, struct route_call *c)
{
    (void)c;
    json_t *arr = json_pack("[o,o]", process_desc("run", false), process_desc("study", false));
    json_t *links = json_array();
    route_add_link(links, "self", "application/json", "processes", "/processes");
    http_reply_json(r, 200, json_pack("{s:o,s:o}", "processes", arr, "links", links));
}

void meta_process(struct hreq *r, struct route_call *c)
{
    const char *id = c->process;
    if (strcmp(id, "run") && strcmp(id, "study")) {
        http_reply_problem(r, PROBLEM_NO_SUCH_PROCESS, "known processes: run, study");
        return;
    }
    http_reply_json(r, 200, process_desc(id, true));
}

void meta_openapi(struct hreq *r, struct route_call *c)
{
    const struct tapp *a = c->app;
    if (!a->openapi) {
        http_reply_problem(r, PROBLEM_NOT_FOUND, "openapi.json is not installed");
        return;
    }
    char *b = malloc(a->openapi_len + 1);
    if (!b) {
        http_reply_problem(r, PROBLEM_INTERNAL, "out of memory");
        return;
    }
    memcpy(b, a->openapi, a->openapi_len);
    http_reply_buf(r, 200, "application/vnd.oai.openapi+json;version=3.1", b, a->openapi_len);
}

/* GET /schemas/<name>.json from the schemas directory (names: [a-z0-9._-]). */
void meta_schema(struct hreq *r, struct route_call *c)
{
    const char *name = c->name;
    const struct tapp *a = c->app;
    size_t n = strlen(name);
    int ok = n > 5 && n < 64 && !strcmp(name + n - 5, ".json") && name[0] != '.';
    for (size_t i = 0; ok && i < n; i++)
        ok = islower((unsigned char)name[i]) || isdigit((unsigned char)name[i]) ||
             name[i] == '.' || name[i] == '-' || name[i] == '_';
    char path[1200];
    int fd = -1;
    struct stat st;
    if (ok) {
        snprintf(path, sizeof path, "%s/%s", a->cfg->schemas_dir, name);
        fd = open(path, O_RDONLY | O_CLOEXEC);
    }
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        if (fd >= 0)
            close(fd);
        http_reply_problem(r, PROBLEM_NOT_FOUND, "no such schema");
        return;
    }
    http_reply_fd(r, 200, "application/schema+json", fd, 0, (uint64_t)st.st_size);
}

void meta_healthz(struct hreq *r, struct route_call *c)
{
    const struct tapp *a = c->app;
    long acc = 0, run = 0, fin = 0;
    if (tq_counts(a->q, &acc, &run, &fin) != TQ_OK) {
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "database unavailable");
        return;
    }
    http_reply_json(r, 200,
                    json_pack("{s:s,s:{s:I,s:I,s:I}}", "status", "ok", "jobs", "accepted",
                              (json_int_t)acc, "running", (json_int_t)run, "final",
                              (json_int_t)fin));
}
