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

#include "output_size.h"
#include "problem.h"
#include "storage.h"
#include "supervisor.h"

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
    /* not oas30: the API definition is OpenAPI 3.1 (OGC 1.0 defines no class for it) */
    const char *cls[] = {"core", "json", "job-list", "dismiss"};
    json_t *arr = json_array();
    for (size_t i = 0; i < sizeof cls / sizeof cls[0]; i++) {
        char buf[128];
        snprintf(buf, sizeof buf, "%s%s", base, cls[i]);
        json_array_append_new(arr, json_string(buf));
    }
    http_reply_json(r, 200, json_pack("{s:o}", "conformsTo", arr));
}

const struct output_decl *route_process_output(const char *process)
{
    static const struct output_decl run = {"result", "HDF5 result file (H5MD layout)",
                                           "application/x-hdf5", "result.h5", "enclosure"};
    static const struct output_decl study = {"summary", "study summary table", "application/json",
                                             "summary", "summary"};
    static const struct output_decl conv = {"convergence",
                                            "convergence result: order, Richardson limit, GCI, "
                                            "cost model, prediction",
                                            "application/json", "convergence", "convergence"};
    return !strcmp(process, "run")           ? &run
           : !strcmp(process, "study")       ? &study
           : !strcmp(process, "convergence") ? &conv
                                             : NULL;
}

const char *route_process_id(const struct tq_job *j)
{
    /* the stored study of a convergence job has a top-level "convergence"
     * object; in compact JSON `convergence":{` cannot occur inside a string
     * (a quote there is escaped) and no scene key takes that name with an
     * object value */
    if (!strcmp(j->process, "study") && j->input && strstr(j->input, "\"convergence\":{"))
        return "convergence";
    return j->process;
}

static json_t *input_ref(const char *title, const char *ref, int optional)
{
    json_t *o = json_pack("{s:s,s:{s:s}}", "title", title, "schema", "$ref", ref);
    if (o && optional)
        json_object_set_new(o, "minOccurs", json_integer(0));
    return o;
}

/* A process description (full: with its inputs and outputs). */
static json_t *process_desc(const char *id, bool full)
{
    const int run = !strcmp(id, "run"), conv = !strcmp(id, "convergence");
    json_t *o = json_pack("{s:s,s:s,s:s,s:s,s:[s,s],s:[s]}", "id", id, "title",
                          run ? "Run one TLSPH simulation"
                          : conv ? "Convergence study with error estimates and cost prediction"
                                 : "Parametric study",
                          "description",
                          run ? "Runs one scene (schemas/scene.schema.json) and stores its "
                                "results as HDF5 (H5MD layout) with an XDMF sidecar."
                          : conv
                              ? "Runs a base scene at a ladder of particle spacings (constant "
                                "ratio) as a study and reports, per output, the observed order, "
                                "the Richardson-extrapolated value, each resolution's error "
                                "estimate and GCI (Roache, Fs = 1.25), flags for oscillatory or "
                                "non-asymptotic convergence, the measured cost of each run, a "
                                "fitted cost model wall = c h^-q and, with a target, the "
                                "predicted spacing, particles, wall time and memory."
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
            json_object_set_new(inputs, "threads",
                                input_ref("OpenMP threads",
                                          "/schemas/execute.schema.json#/$defs/run/properties/"
                                          "inputs/properties/threads",
                                          1));
        } else if (conv) {
            const char *c = "/schemas/study.schema.json#/$defs/convergence/properties/";
            char ref[128];
            json_object_set_new(inputs, "base", input_ref("base scene", "/schemas/scene.schema.json", 0));
            snprintf(ref, sizeof ref, "%sladder", c);
            json_object_set_new(inputs, "ladder", input_ref("resolution ladder", ref, 0));
            snprintf(ref, sizeof ref, "%soutputs", c);
            json_object_set_new(inputs, "outputs", input_ref("outputs of interest", ref, 0));
            snprintf(ref, sizeof ref, "%starget", c);
            json_object_set_new(inputs, "target", input_ref("target accuracy", ref, 1));
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
            json_object_set_new(inputs, "max_parallel",
                                json_pack("{s:s,s:i,s:{s:s}}", "title", "children at once",
                                          "minOccurs", 0, "schema", "$ref",
                                          "/schemas/study.schema.json#/properties/max_parallel"));
        }
        json_object_set_new(o, "inputs", inputs);
        json_t *outputs = json_object();
        const struct output_decl *out = route_process_output(id);
        if (run)
            json_object_set_new(outputs, out->id,
                                json_pack("{s:s,s:{s:s,s:s}}", "title", out->title, "schema",
                                          "type", "string", "contentMediaType", out->media_type));
        else
            json_object_set_new(outputs, out->id,
                                json_pack("{s:s,s:{s:s,s:s}}", "title", out->title, "schema",
                                          "type", "object", "contentMediaType", out->media_type));
        json_object_set_new(o, "outputs", outputs);
    }
    return o;
}

void meta_processes(struct hreq *r, struct route_call *c)
{
    (void)c;
    json_t *arr = json_pack("[o,o,o]", process_desc("run", false), process_desc("study", false),
                            process_desc("convergence", false));
    json_t *links = json_array();
    route_add_link(links, "self", "application/json", "processes", "/processes");
    http_reply_json(r, 200, json_pack("{s:o,s:o}", "processes", arr, "links", links));
}

void meta_process(struct hreq *r, struct route_call *c)
{
    const char *id = c->process;
    if (!route_process_output(id)) {
        http_reply_problem(r, PROBLEM_NO_SUCH_PROCESS, ROUTE_KNOWN_PROCESSES);
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

/* {"accepted", "running", "final"} of one process, or NULL. */
static json_t *counts_of(struct tq *q, const char *process)
{
    long acc = 0, run = 0, fin = 0;
    if (tq_counts_of(q, process, &acc, &run, &fin) != TQ_OK)
        return NULL;
    return json_pack("{s:I,s:I,s:I}", "accepted", (json_int_t)acc, "running", (json_int_t)run,
                     "final", (json_int_t)fin);
}

/* What keeps the service from doing all its work (storage.h, finals.h): one
 * sentence each, for people. */
static json_t *problems_of(const struct tapp *a, json_t *disk)
{
    const struct tcfg *cfg = a->cfg;
    json_t *problems = json_array();
    char fr[32], fl[32], why[300], text[600];
    const int64_t free_bytes = storage_free_bytes(cfg);
    const uint64_t floor_bytes = storage_floor_bytes(cfg);
    const bool held = storage_reserve_held(cfg);
    json_object_set_new(disk, "free_bytes",
                        free_bytes >= 0 ? json_integer((json_int_t)free_bytes) : json_null());
    json_object_set_new(disk, "floor_bytes", json_integer((json_int_t)floor_bytes));
    json_object_set_new(disk, "reserve_held", json_boolean(held));
    if (free_bytes >= 0 && (uint64_t)free_bytes < floor_bytes) {
        snprintf(text, sizeof text,
                 "the data directory has %s free, below the floor of %s (min_free_mb): new jobs "
                 "are refused (507) and queued jobs wait",
                 output_size_text(fr, sizeof fr, (double)free_bytes),
                 output_size_text(fl, sizeof fl, (double)floor_bytes));
        json_array_append_new(problems, json_string(text));
    }
    if (!held)
        json_array_append_new(problems,
                              json_string("the reserve file was freed to record jobs on a full "
                                          "disk; it is allocated again once the space is back"));
    const size_t waiting = tsup_unrecorded(a->sup, why, sizeof why);
    if (waiting > 0) {
        snprintf(text, sizeof text,
                 "%zu finished job(s) wait for their final state to be recorded (retried every "
                 "second): %s",
                 waiting, why);
        json_array_append_new(problems, json_string(text));
    }
    return problems;
}

/* 200 "ok", or 200 "degraded" with the problems; 503 when the database
 * cannot be read. */
void meta_healthz(struct hreq *r, struct route_call *c)
{
    const struct tapp *a = c->app;
    json_t *runs = counts_of(a->q, "run"), *studies = counts_of(a->q, "study");
    if (!runs || !studies) {
        json_decref(runs);
        json_decref(studies);
        http_reply_problem(r, PROBLEM_UNAVAILABLE, "database unavailable");
        return;
    }
    json_t *disk = json_object();
    json_t *problems = problems_of(a, disk);
    const bool ok = json_array_size(problems) == 0;
    http_reply_json(r, 200,
                    json_pack("{s:s,s:o,s:o,s:o,s:o}", "status", ok ? "ok" : "degraded", "jobs",
                              runs, "studies", studies, "disk", disk, "problems", problems));
}
