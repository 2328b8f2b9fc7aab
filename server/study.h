/* Parametric studies (server/study.c): a base scene plus a sweep over any scene
 * value by JSON pointer.
 *
 * Study input (the "inputs" of POST /processes/study/execution):
 *   {"base": SCENE,
 *    "sweep": {"mode": "product" | "zip",
 *              "parameters": [{"pointer": "/bodies/0/spacing", "values": [0.002, 0.001]},
 *                             {"pointer": "/time/end", "range": {"start": 1e-4, "stop": 3e-4, "num": 3}},
 *                             ...]},
 *    "outputs": [{"name": "peak_reaction", "series": "groups/right/reaction_force",
 *                 "component": 0, "reduce": "max"}, ...]}     (optional; reduce: final|max|min)
 * Each child scene is the base with every swept pointer replaced (the pointer
 * must exist in the base, or name a new key of an existing object).  "product"
 * takes the Cartesian product (first parameter varies slowest), "zip" pairs the
 * i-th values (all lists the same length).  At most max_children children. */
#ifndef TLSPHD_STUDY_H
#define TLSPHD_STUDY_H

#include <jansson.h>
#include <stddef.h>

#include "util/errors.h"

struct tstudy_child {
    json_t *scene;  /* owned reference */
    json_t *params; /* {"/bodies/0/spacing": 0.001, ...} owned reference */
};

/* Validates the study (not the scenes; the caller validates each child scene with
 * the engine's validator) and expands it.  Errors carry pointers relative to the
 * study input ("/sweep/parameters/1/range/num").  Returns 0 with *children (array
 * of *n, free with tstudy_children_free) or -1. */
int tstudy_expand(const json_t *study, size_t max_children, struct tstudy_child **children,
                  size_t *n, struct tlsph_errors *err);
void tstudy_children_free(struct tstudy_child *c, size_t n);

/* RFC 6901 pointer helpers on jansson values. */
json_t *tstudy_pointer_get(json_t *root, const char *pointer);
/* Replaces (or adds to an existing object) the value at pointer; steals value. 0 or -1. */
int tstudy_pointer_set(json_t *root, const char *pointer, json_t *value);

/* One row of a study summary. */
struct tstudy_row {
    long seq;
    const char *job_id;
    const char *status;
    const json_t *params;   /* swept values */
    const char *h5path;     /* result file (may not exist) */
    const json_t *cost;     /* engine cost object or NULL */
};
/* Summary table: {"columns":[...], "rows":[[...], ...]} with columns
 * seq, job_id, status, <each swept pointer>, <each output name>, particles,
 * steps, wall_seconds, particle_steps_per_second.  Outputs that cannot be read
 * are null. */
json_t *tstudy_summary(const json_t *study, const struct tstudy_row *rows, size_t n);
/* The same table as CSV (malloc'ed text). */
char *tstudy_summary_csv(const json_t *summary);

#endif
