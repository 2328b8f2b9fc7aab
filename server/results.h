/* Reading results for the API (server/results.c): time series and one field
 * at one frame from a job's result.h5, opened with H5F_ACC_SWMR_READ so this
 * works while the engine is still writing and after it has finished.
 * Frames and rows are bounded by the length of the `step` dataset (the
 * writer's commit marker, see docs/output.md). */
#ifndef TLSPHD_RESULTS_H
#define TLSPHD_RESULTS_H

#include <stddef.h>
#include <jansson.h>

/* What tres_field and tres_series_reduce return (errmsg.h). */
enum tres_rc {
    TRES_ERROR = -1,       /* err says why */
    TRES_OK = 0,
    TRES_NOT_FOUND = 1,    /* no such series or field */
    TRES_NO_SUCH_FRAME = 2 /* tres_field: the frame is out of range */
};

/* Names of the available series: "kinetic_energy", ..., "groups/<bc>/reaction_force".
 * Returns a JSON array of {"name","units","components"} or NULL with err. */
json_t *tres_series_list(const char *h5path, char *err, size_t errsize);
/* One series: {"name","units","components":[..] or null,"step":[...],"time":[...],
 * "value":[...] or [[x,y,z],...]}.  Returns NULL with err; *not_found set when the
 * name does not exist (as opposed to a read error). */
json_t *tres_series(const char *h5path, const char *name, int *not_found, char *err,
                    size_t errsize);
/* The same as CSV text: header "step,time,<name>[_x,_y,_z]" then rows (malloc'ed). */
char *tres_series_csv(const char *h5path, const char *name, int *not_found, char *err,
                      size_t errsize);

struct tres_field {
    void *data;        /* little-endian values, n_rows * ncomp elements (malloc'ed) */
    size_t bytes;
    size_t n_rows;     /* particles */
    int ncomp;         /* 1, 3 or 6 */
    const char *dtype; /* numpy-style: "<f4", "<f8", "<i8", "<i4" */
    char units[32];
    long frames;       /* frames available */
    double time;       /* s, time of the frame */
    long step;
};
/* Field `name` (a frame field) at frame k (negative: from the end, -1 = last);
 * reference fields (id, volume, ...) ignore frame. */
enum tres_rc tres_field(const char *h5path, const char *name, long frame,
                        struct tres_field *out, char *err, size_t errsize);
void tres_field_free(struct tres_field *f);
/* The field as JSON {"name","units","frame","time","shape":[N,C],"data":[...]} (small N). */
json_t *tres_field_json(const struct tres_field *f, const char *name, long frame);
/* Frames: [{"index","step","time"}]. */
json_t *tres_frames(const char *h5path, char *err, size_t errsize);
/* Final value (last row), max and min of a scalar series or of component c of a
 * vector series (c = -1 for the magnitude): TRES_OK, TRES_NOT_FOUND, TRES_ERROR. */
enum tres_rc tres_series_reduce(const char *h5path, const char *name, int component,
                                double *final, double *max, double *min, char *err,
                                size_t errsize);

/* Time (s) and one scalar column of a series (component c of a vector series,
 * -1 the magnitude), each a malloc'ed array of *n values the caller frees:
 * TRES_OK, TRES_NOT_FOUND (no such series or component), TRES_ERROR. */
enum tres_rc tres_series_column(const char *h5path, const char *name, int component,
                                double **time, double **value, size_t *n, char *err,
                                size_t errsize);

/* The run's outcome as the file records it (/diagnostics status:
 * "running" while it writes, or after its process died; then "successful",
 * "unstable", "cancelled" or "io_error"): TRES_OK, TRES_NOT_FOUND (no
 * attribute), TRES_ERROR (the file cannot be read). */
enum tres_rc tres_run_status(const char *h5path, char *status, size_t size, char *err,
                             size_t errsize);

/* The one definition of a valid result name, checked before any HDF5 path is
 * built (1 ok, 0 rejected); the routes refuse other names up front with the
 * same words (TRES_NO_SERIES, TRES_NO_FIELD, printf formats of the name).
 * Series: at most 200 characters, segments separated by "/", each segment a
 * name by the engine's naming rule (util/names.h: what the engine accepts for
 * the bodies, conditions, gauges and sections it writes series for), so every
 * series the engine can write can be named here.  Field: [A-Za-z0-9_], at
 * most 64. */
#define TRES_NO_SERIES "no series named \"%.60s\""
#define TRES_NO_FIELD "no field named \"%.60s\""
int tres_series_name_ok(const char *name);
int tres_field_name_ok(const char *name);

#endif
