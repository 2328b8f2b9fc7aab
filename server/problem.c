/* RFC 9457 problem details, see problem.h. */
#include "problem.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

#define OGC_EXC "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/"

static const struct {
    unsigned status;
    const char *type;
    const char *title;
} kinds[PROBLEM_KIND_COUNT] = {
    [PROBLEM_BAD_REQUEST] = {400, "urn:tlsph:problem:bad-request", "Bad request"},
    [PROBLEM_BAD_JSON] = {400, "urn:tlsph:problem:bad-json", "Request body is not valid JSON"},
    [PROBLEM_UNAUTHORIZED] = {401, "urn:tlsph:problem:unauthorized",
                              "Missing or invalid bearer token"},
    [PROBLEM_NOT_FOUND] = {404, "urn:tlsph:problem:not-found", "Not found"},
    [PROBLEM_NO_SUCH_JOB] = {404, OGC_EXC "no-such-job", "No such job"},
    [PROBLEM_NO_SUCH_PROCESS] = {404, OGC_EXC "no-such-process", "No such process"},
    [PROBLEM_NO_SUCH_RESULT] = {404, "urn:tlsph:problem:no-such-result", "No such result"},
    [PROBLEM_METHOD] = {405, "urn:tlsph:problem:method-not-allowed", "Method not allowed"},
    [PROBLEM_NOT_ACCEPTABLE] = {406, "urn:tlsph:problem:not-acceptable", "Not acceptable"},
    [PROBLEM_RESULT_NOT_READY] = {404, OGC_EXC "result-not-ready", "Result not ready"},
    [PROBLEM_CONFLICT] = {409, "urn:tlsph:problem:conflict", "Conflict"},
    [PROBLEM_TOO_LARGE] = {413, "urn:tlsph:problem:payload-too-large", "Request body too large"},
    [PROBLEM_URI_TOO_LONG] = {414, "urn:tlsph:problem:uri-too-long", "URI too long"},
    [PROBLEM_OUTPUT_QUOTA] = {413, "urn:tlsph:problem:output-quota",
                              "Estimated result file above the quota"},
    [PROBLEM_MEDIA_TYPE] = {415, "urn:tlsph:problem:unsupported-media-type",
                            "Unsupported media type"},
    [PROBLEM_RANGE] = {416, "urn:tlsph:problem:range-not-satisfiable", "Range not satisfiable"},
    [PROBLEM_VALIDATION] = {422, "urn:tlsph:problem:validation", "Request failed validation"},
    [PROBLEM_NOT_IMPLEMENTED] = {501, "urn:tlsph:problem:not-implemented", "Not implemented"},
    [PROBLEM_INTERNAL] = {500, "urn:tlsph:problem:internal", "Internal server error"},
    [PROBLEM_UNAVAILABLE] = {503, "urn:tlsph:problem:unavailable", "Service unavailable"},
    [PROBLEM_NO_STORAGE] = {507, "urn:tlsph:problem:insufficient-storage", "Insufficient storage"},
};

enum problem_kind problem_of_errno(int err)
{
    switch (err) {
    case ENOSPC:
    case EDQUOT:
    case EFBIG:
    case EROFS:
        return PROBLEM_NO_STORAGE;
    case EIO:
    case EMFILE:
    case ENFILE:
    case ENOMEM:
    case EAGAIN:
    case EBUSY:
    case EINTR:
    case ENOBUFS:
    case ETXTBSY:
    case ESTALE:
        return PROBLEM_UNAVAILABLE;
    case ENOENT:
    case ENOTDIR:
    case ELOOP:
        return PROBLEM_NOT_FOUND;
    default:
        return PROBLEM_INTERNAL;
    }
}

unsigned problem_status(enum problem_kind kind)
{
    return (unsigned)kind < PROBLEM_KIND_COUNT ? kinds[kind].status : 500;
}

json_t *problem_new(enum problem_kind kind, const char *detail, const char *instance)
{
    if ((unsigned)kind >= PROBLEM_KIND_COUNT)
        kind = PROBLEM_INTERNAL;
    json_t *p = json_object();
    if (!p)
        return NULL;
    json_object_set_new(p, "type", json_string(kinds[kind].type));
    json_object_set_new(p, "title", json_string(kinds[kind].title));
    json_object_set_new(p, "status", json_integer(kinds[kind].status));
    json_object_set_new(p, "detail", json_string(detail && *detail ? detail : kinds[kind].title));
    /* json_string rejects invalid UTF-8 (a hostile path): fall back to a placeholder */
    if (instance) {
        json_t *s = json_string(instance);
        json_object_set_new(p, "instance", s ? s : json_string("(invalid)"));
    }
    return p;
}

void problem_add_error(json_t *problem, const char *pointer, const char *detail)
{
    json_t *arr = json_object_get(problem, "errors");
    if (!arr) {
        arr = json_array();
        json_object_set_new(problem, "errors", arr);
    }
    char buf[1024];
    snprintf(buf, sizeof buf, "#%s", pointer);
    json_t *e = json_object();
    json_t *ps = json_string(buf);
    json_object_set_new(e, "pointer", ps ? ps : json_string("#"));
    json_t *ds = json_string(detail ? detail : "");
    json_object_set_new(e, "detail", ds ? ds : json_string("invalid"));
    json_array_append_new(arr, e);
}

void problem_add_errors(json_t *problem, const char *prefix, const struct tlsph_errors *errs)
{
    char buf[1024];
    for (size_t i = 0; i < errs->count; i++) {
        snprintf(buf, sizeof buf, "%s%s", prefix ? prefix : "",
                 errs->items[i].pointer ? errs->items[i].pointer : "");
        problem_add_error(problem, buf, errs->items[i].message);
    }
    if (errs->out_of_memory)
        problem_add_error(problem, prefix ? prefix : "", "more errors (out of memory)");
}
