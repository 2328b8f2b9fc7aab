/* RFC 9457 problem details (application/problem+json) for tlsphd (server/problem.c).
 *
 * Every error response of the daemon is one of these objects:
 *   {"type": URI, "title", "status", "detail", "instance", ["errors": [{pointer, detail}]]}
 * The type is an OGC API - Processes 1.0 exception URI where one applies
 * (no-such-job, no-such-process, result-not-ready), else urn:tlsph:problem:<slug>. */
#ifndef TLSPHD_PROBLEM_H
#define TLSPHD_PROBLEM_H

#include <jansson.h>

#include "util/errors.h"

#define PROBLEM_CONTENT_TYPE "application/problem+json"

enum problem_kind {
    PROBLEM_BAD_REQUEST,       /* 400 */
    PROBLEM_BAD_JSON,          /* 400 */
    PROBLEM_UNAUTHORIZED,      /* 401 */
    PROBLEM_NOT_FOUND,         /* 404 */
    PROBLEM_NO_SUCH_JOB,       /* 404 (OGC) */
    PROBLEM_NO_SUCH_PROCESS,   /* 404 (OGC) */
    PROBLEM_NO_SUCH_RESULT,    /* 404: unknown series / field / frame */
    PROBLEM_METHOD,            /* 405 */
    PROBLEM_NOT_ACCEPTABLE,    /* 406 */
    PROBLEM_RESULT_NOT_READY,  /* 404 (OGC type URI; OGC 1.0 asks 404) */
    PROBLEM_CONFLICT,          /* 409 */
    PROBLEM_TOO_LARGE,         /* 413 */
    PROBLEM_URI_TOO_LONG,      /* 414: too many query parameters */
    PROBLEM_OUTPUT_QUOTA,      /* 413: a job's estimated result file is above the quota */
    PROBLEM_MEDIA_TYPE,        /* 415 */
    PROBLEM_RANGE,             /* 416 */
    PROBLEM_VALIDATION,        /* 422 */
    PROBLEM_INTERNAL,          /* 500 */
    PROBLEM_NOT_IMPLEMENTED,   /* 501: a Transfer-Encoding other than chunked */
    PROBLEM_UNAVAILABLE,       /* 503 */
    PROBLEM_NO_STORAGE,        /* 507: the data directory's disk cannot take it */
    PROBLEM_KIND_COUNT
};

/* The kind for a system error met on the data directory's disk: 507 when
 * the disk cannot take what is written (ENOSPC, EDQUOT, EFBIG, EROFS), 503
 * when it or the process is failing for now (EIO, EMFILE, ENFILE, ENOMEM,
 * EAGAIN, EBUSY, ...; answered with Retry-After), 404 for a file that is not
 * there (ENOENT, ENOTDIR, ELOOP: O_NOFOLLOW met a link), 500 otherwise. */
enum problem_kind problem_of_errno(int err);

/* HTTP status of a kind. */
unsigned problem_status(enum problem_kind kind);
/* A new problem object (detail may be NULL; instance is the request path). */
json_t *problem_new(enum problem_kind kind, const char *detail, const char *instance);
/* Appends {"pointer": "#" + prefix + pointer, "detail": message} for every error
 * (prefix like "/inputs/scene"). */
void problem_add_errors(json_t *problem, const char *prefix, const struct tlsph_errors *errs);
/* Appends one {"pointer": "#" + pointer, "detail"} entry. */
void problem_add_error(json_t *problem, const char *pointer, const char *detail);

#endif
