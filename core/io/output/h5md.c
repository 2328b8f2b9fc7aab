/* The result file: an H5MD-style HDF5 file written under SWMR (single writer,
 * multiple readers), so the daemon and h5py can read it while the run goes on.
 * Layout: core/io/output/output.h and docs/output.md.
 *
 * SWMR rules followed here (HDF5 1.10 SWMR technical note; shared notes 4.2):
 *  - the file uses the latest format (libver bounds LATEST, LATEST);
 *  - every group, dataset and attribute is created in tlsph_output_open, then
 *    H5Fstart_swmr_write; nothing is created afterwards.  The writer only
 *    extends datasets along their unlimited first axis and overwrites existing
 *    values: /cost and /diagnostics attributes are pre-created with placeholder
 *    values of fixed size (fixed-length strings, fixed-size arrays) and
 *    rewritten in place at close (tested: H5Awrite after H5Fstart_swmr_write
 *    succeeds and the closed file is plain-h5dump readable);
 *  - strings are fixed-length (SWMR cannot modify variable-length data);
 *  - all objects are closed before H5Fstart_swmr_write and the datasets
 *    reopened afterwards with our access property list, because the call resets
 *    the chunk cache of open datasets (HDFGroup/hdf5 issue #1730);
 *  - per frame: every value dataset is extended and written, then step and
 *    time, each followed by H5Dflush, so a reader that takes len(step) as the
 *    frame count only ever reads complete frames.
 *
 * Frame fields and time-series columns share one step and one time dataset per
 * family through hard links (as LAMMPS' dump h5md does); to a reader they are
 * ordinary datasets.
 *
 * Time-series rows are buffered in memory (one chunk, SERIES_CHUNK rows) and
 * written when the buffer is full, at every frame, when SERIES_MAX_AGE seconds
 * of wall time have passed since the last write, and at close. */
#ifdef HAVE_CONFIG_H
#include "config.h"
#endif
#ifndef PACKAGE_VERSION
#define PACKAGE_VERSION "0.1.0"
#endif

#include "io/output/output.h"

#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "io/fields.h"
#include "io/output/xdmf.h"
#include "util/clock.h"

#define H5_NAME "result.h5"
#define XMF_NAME "result.xmf"
#define SERIES_CHUNK 1024        /* rows per series chunk and per memory buffer */
#define SERIES_MAX_AGE 1.0       /* s of wall time before buffered rows are written */
#define XMF_MAX_AGE 2.0          /* s of wall time between rewrites of the XDMF sidecar */
#define FRAME_CHUNK_BYTES (512u * 1024u) /* target chunk size of frame values */
#define CHUNK_CACHE_BYTES (4u * 1024u * 1024u)
#define DEFLATE_LEVEL 1
/* Fixed sizes of the strings rewritten at close (truncated to fit). */
#define STATUS_LEN 32
#define QUANTITY_LEN 64
#define MESSAGE_LEN 256
#define DIAG_IDS 16

struct frame_value {
    const struct tlsph_field *f;
    hid_t value;
};

struct series_value {
    char *path;       /* of the value dataset, for reopening after SWMR starts */
    int ncomp;
    size_t offset;    /* first column of this series in a buffered row */
    hid_t value;
};

struct tlsph_output {
    hid_t file;
    size_t n;
    char *h5_path, *xmf_path;

    /* every present field, for the XDMF sidecar */
    const struct tlsph_field **present;
    size_t npresent;

    struct frame_value *frames;
    size_t nframe_fields;
    hid_t frame_step, frame_time;
    char frame_step_path[256], frame_time_path[256];
    size_t nframes;
    double *frame_times;
    size_t frame_times_cap;
    void *scratch; /* n * max ncomp * 8 bytes */

    struct series_value *series;
    size_t nseries;
    hid_t series_step, series_time;
    char series_step_path[256], series_time_path[256];
    size_t width;        /* doubles per buffered row */
    double *rows;        /* [SERIES_CHUNK][width] */
    int64_t *row_step;
    double *row_time;
    size_t nrows;
    size_t nsamples;     /* rows written to the file */
    int64_t last_step_written;
    double last_series_write;
    double last_xmf_write;    /* wall clock of the last sidecar rewrite, s */
};

/* ------------------------------------------------------------ helpers */

static herr_t first_error(unsigned n, const H5E_error2_t *e, void *data)
{
    char *buf = data;
    if (n == 0 && e->desc)
        snprintf(buf, 256, "%s (in %s)", e->desc, e->func_name ? e->func_name : "?");
    return 0;
}

/* The innermost message of HDF5's error stack, for error reports. */
static void h5_error_text(char buf[256])
{
    buf[0] = '\0';
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, first_error, buf);
    if (!buf[0])
        snprintf(buf, 256, "unknown HDF5 error");
}

static hid_t file_type(enum tlsph_field_type t)
{
    switch (t) {
    case TLSPH_FLOAT64: return H5T_IEEE_F64LE;
    case TLSPH_FLOAT32: return H5T_IEEE_F32LE;
    case TLSPH_INT64: return H5T_STD_I64LE;
    case TLSPH_INT32: return H5T_STD_I32LE;
    }
    return H5T_IEEE_F64LE;
}

static hid_t mem_type(enum tlsph_field_type t)
{
    switch (t) {
    case TLSPH_FLOAT64: return H5T_NATIVE_DOUBLE;
    case TLSPH_FLOAT32: return H5T_NATIVE_FLOAT;
    case TLSPH_INT64: return H5T_NATIVE_INT64;
    case TLSPH_INT32: return H5T_NATIVE_INT32;
    }
    return H5T_NATIVE_DOUBLE;
}

static size_t type_size(enum tlsph_field_type t)
{
    return (t == TLSPH_FLOAT32 || t == TLSPH_INT32) ? 4 : 8;
}

/* Extractors fill doubles (float types) or int64 (integer types).  Narrow them
 * in place: element i is read at byte 8i before it is written at byte 4i, and
 * writes never reach bytes not yet read, so a forward loop is safe. */
static void narrow_in_place(void *buf, size_t count, enum tlsph_field_type t)
{
    if (t == TLSPH_FLOAT32) {
        const double *d = buf;
        float *f = buf;
        for (size_t i = 0; i < count; i++) {
            double v = d[i];
            f[i] = (float)v;
        }
    } else if (t == TLSPH_INT32) {
        const int64_t *s = buf;
        int32_t *o = buf;
        for (size_t i = 0; i < count; i++) {
            int64_t v = s[i];
            o[i] = (int32_t)v;
        }
    }
}

static int field_present(const struct tlsph_field *f, const struct tlsph_model *m)
{
    return f->present == NULL || f->present(m);
}

/* Attributes.  Strings are fixed-length, null-terminated ASCII of at least
 * size bytes (so that a later, longer value of up to size-1 bytes fits). */
static int attr_string_sized(hid_t obj, const char *name, const char *value, size_t size)
{
    size_t len = strlen(value);
    if (size < len + 1)
        size = len + 1;
    char *buf = calloc(size, 1);
    if (!buf)
        return -1;
    memcpy(buf, value, len);
    int rc = -1;
    hid_t type = H5Tcopy(H5T_C_S1), space = H5I_INVALID_HID, attr = H5I_INVALID_HID;
    if (type < 0 || H5Tset_size(type, size) < 0 || H5Tset_strpad(type, H5T_STR_NULLTERM) < 0)
        goto done;
    if ((space = H5Screate(H5S_SCALAR)) < 0)
        goto done;
    if ((attr = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT)) < 0)
        goto done;
    if (H5Awrite(attr, type, buf) < 0)
        goto done;
    rc = 0;
done:
    if (attr >= 0)
        H5Aclose(attr);
    if (space >= 0)
        H5Sclose(space);
    if (type >= 0)
        H5Tclose(type);
    free(buf);
    return rc;
}

static int attr_string(hid_t obj, const char *name, const char *value)
{
    return attr_string_sized(obj, name, value, 0);
}

/* A numeric attribute: scalar when count == 0, else a 1-D array of count. */
static int attr_numeric(hid_t obj, const char *name, hid_t ftype, hid_t mtype, size_t count,
                        const void *value)
{
    int rc = -1;
    hsize_t dims[1] = {count};
    hid_t space = count ? H5Screate_simple(1, dims, NULL) : H5Screate(H5S_SCALAR);
    hid_t attr = H5I_INVALID_HID;
    if (space < 0)
        return -1;
    if ((attr = H5Acreate2(obj, name, ftype, space, H5P_DEFAULT, H5P_DEFAULT)) < 0)
        goto done;
    if (H5Awrite(attr, mtype, value) < 0)
        goto done;
    rc = 0;
done:
    if (attr >= 0)
        H5Aclose(attr);
    H5Sclose(space);
    return rc;
}

static int attr_double(hid_t obj, const char *name, double v)
{
    return attr_numeric(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 0, &v);
}

static int attr_int64(hid_t obj, const char *name, int64_t v)
{
    return attr_numeric(obj, name, H5T_STD_I64LE, H5T_NATIVE_INT64, 0, &v);
}

/* Rewrites an existing attribute (allowed under SWMR: same size, in place). */
static int rewrite_attr(hid_t obj, const char *name, hid_t mtype, const void *value)
{
    hid_t attr = H5Aopen(obj, name, H5P_DEFAULT);
    if (attr < 0)
        return -1;
    int rc = H5Awrite(attr, mtype, value) < 0 ? -1 : 0;
    if (H5Aclose(attr) < 0)
        rc = -1;
    return rc;
}

static int rewrite_string(hid_t obj, const char *name, const char *value)
{
    hid_t attr = H5Aopen(obj, name, H5P_DEFAULT);
    if (attr < 0)
        return -1;
    int rc = -1;
    char *buf = NULL;
    hid_t type = H5Aget_type(attr);
    size_t size = type >= 0 ? H5Tget_size(type) : 0;
    if (size > 0 && (buf = calloc(size, 1)) != NULL) {
        size_t len = strlen(value);
        memcpy(buf, value, len < size - 1 ? len : size - 1);
        rc = H5Awrite(attr, type, buf) < 0 ? -1 : 0;
    }
    free(buf);
    if (type >= 0)
        H5Tclose(type);
    if (H5Aclose(attr) < 0)
        rc = -1;
    return rc;
}

/* The units / description / components attributes of a dataset. */
static int describe(hid_t ds, const char *units, const char *description,
                    const char *components)
{
    if (attr_string(ds, "units", units ? units : "1") < 0)
        return -1;
    if (description && attr_string(ds, "description", description) < 0)
        return -1;
    if (components && attr_string(ds, "components", components) < 0)
        return -1;
    return 0;
}

/* A scalar fixed-length string dataset (no size limit, unlike compact attributes). */
static int string_dataset(hid_t loc, const char *name, const char *text, const char *description)
{
    int rc = -1;
    size_t len = strlen(text);
    hid_t type = H5Tcopy(H5T_C_S1), space = H5I_INVALID_HID, ds = H5I_INVALID_HID;
    if (type < 0 || H5Tset_size(type, len ? len : 1) < 0 ||
        H5Tset_strpad(type, H5T_STR_NULLPAD) < 0)
        goto done;
    if ((space = H5Screate(H5S_SCALAR)) < 0)
        goto done;
    if ((ds = H5Dcreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT)) < 0)
        goto done;
    if (H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, len ? text : " ") < 0)
        goto done;
    if (attr_string(ds, "description", description) < 0)
        goto done;
    rc = 0;
done:
    if (ds >= 0)
        H5Dclose(ds);
    if (space >= 0)
        H5Sclose(space);
    if (type >= 0)
        H5Tclose(type);
    return rc;
}

static hid_t make_group(hid_t loc, const char *name)
{
    return H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
}

/* Creates an extendible dataset of rank 1..3 with an unlimited first axis. */
static hid_t extendible(hid_t loc, const char *name, hid_t ftype, int rank, const hsize_t *tail,
                        const hsize_t *chunk, int compress)
{
    hsize_t dims[3] = {0, 0, 0}, maxdims[3] = {H5S_UNLIMITED, 0, 0};
    for (int r = 1; r < rank; r++)
        dims[r] = maxdims[r] = tail[r - 1];
    hid_t space = H5Screate_simple(rank, dims, maxdims);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    hid_t ds = H5I_INVALID_HID;
    if (space < 0 || dcpl < 0)
        goto done;
    if (H5Pset_chunk(dcpl, rank, chunk) < 0)
        goto done;
    if (compress && (H5Pset_shuffle(dcpl) < 0 || H5Pset_deflate(dcpl, DEFLATE_LEVEL) < 0))
        goto done;
    ds = H5Dcreate2(loc, name, ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
done:
    if (dcpl >= 0)
        H5Pclose(dcpl);
    if (space >= 0)
        H5Sclose(space);
    return ds;
}

/* Particles per chunk of a field with ncomp components of elsize bytes. */
static hsize_t particles_per_chunk(size_t n, int ncomp, size_t elsize)
{
    size_t per = FRAME_CHUNK_BYTES / ((size_t)ncomp * elsize);
    if (per < 1)
        per = 1;
    if (per >= n)
        return (hsize_t)n;
    /* Equal chunks, so the last one is not mostly padding (uncompressed
     * datasets store whole chunks). */
    size_t nchunks = (n + per - 1) / per;
    return (hsize_t)((n + nchunks - 1) / nchunks);
}

/* ------------------------------------------------------------ creation */

static int write_reference_field(struct tlsph_output *o, hid_t solid, const struct tlsph_field *f,
                                 const struct tlsph_model *m)
{
    int rc = -1;
    int rank = f->ncomp > 1 ? 2 : 1;
    hsize_t dims[2] = {o->n, (hsize_t)f->ncomp};
    hsize_t chunk[2] = {particles_per_chunk(o->n, f->ncomp, type_size(f->type)),
                        (hsize_t)f->ncomp};
    hid_t space = H5Screate_simple(rank, dims, NULL);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE), ds = H5I_INVALID_HID;
    if (space < 0 || dcpl < 0)
        goto done;
    if (H5Pset_chunk(dcpl, rank, chunk) < 0 || H5Pset_shuffle(dcpl) < 0 ||
        H5Pset_deflate(dcpl, DEFLATE_LEVEL) < 0)
        goto done;
    ds = H5Dcreate2(solid, f->name, file_type(f->type), space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    if (ds < 0)
        goto done;
    f->extract(m, o->scratch);
    narrow_in_place(o->scratch, o->n * (size_t)f->ncomp, f->type);
    if (H5Dwrite(ds, mem_type(f->type), H5S_ALL, H5S_ALL, H5P_DEFAULT, o->scratch) < 0)
        goto done;
    if (describe(ds, f->units, f->description, f->components) < 0)
        goto done;
    rc = 0;
done:
    if (ds >= 0)
        H5Dclose(ds);
    if (dcpl >= 0)
        H5Pclose(dcpl);
    if (space >= 0)
        H5Sclose(space);
    return rc;
}

/* step and time of a family (frames or series): created once in group g, and
 * hard-linked into the other groups of the family. */
static int step_time(hid_t g, char *step_path, char *time_path, hsize_t chunk_rows,
                     const char *group_path)
{
    if (step_path[0]) {
        if (H5Lcreate_hard(g, step_path, g, "step", H5P_DEFAULT, H5P_DEFAULT) < 0 ||
            H5Lcreate_hard(g, time_path, g, "time", H5P_DEFAULT, H5P_DEFAULT) < 0)
            return -1;
        return 0;
    }
    hsize_t chunk[1] = {chunk_rows};
    hid_t s = extendible(g, "step", H5T_STD_I64LE, 1, NULL, chunk, 0);
    hid_t t = extendible(g, "time", H5T_IEEE_F64LE, 1, NULL, chunk, 0);
    int rc = -1;
    if (s < 0 || t < 0)
        goto done;
    if (attr_string(s, "description", "time step index of each sample") < 0 ||
        describe(t, "s", "simulated time of each sample", NULL) < 0)
        goto done;
    snprintf(step_path, 256, "%s/step", group_path);
    snprintf(time_path, 256, "%s/time", group_path);
    rc = 0;
done:
    if (s >= 0)
        H5Dclose(s);
    if (t >= 0)
        H5Dclose(t);
    return rc;
}

static int create_frame_field(struct tlsph_output *o, hid_t solid, const struct tlsph_field *f)
{
    char path[256];
    snprintf(path, sizeof path, "/particles/solid/%s", f->name);
    hid_t g = make_group(solid, f->name);
    if (g < 0)
        return -1;
    int rc = -1;
    hsize_t tail[2] = {o->n, (hsize_t)f->ncomp};
    hsize_t chunk[3] = {1, particles_per_chunk(o->n, f->ncomp, type_size(f->type)),
                        (hsize_t)f->ncomp};
    int compress = f->type != TLSPH_FLOAT64; /* float64 positions barely compress */
    hid_t v = extendible(g, "value", file_type(f->type), f->ncomp > 1 ? 3 : 2, tail, chunk,
                         compress);
    if (v < 0)
        goto done;
    if (describe(v, f->units, f->description, f->components) < 0)
        goto done;
    if (step_time(g, o->frame_step_path, o->frame_time_path, 1024, path) < 0)
        goto done;
    o->frames[o->nframe_fields++] = (struct frame_value){f, H5I_INVALID_HID};
    rc = 0;
done:
    if (v >= 0)
        H5Dclose(v);
    H5Gclose(g);
    return rc;
}

/* One series column in group parent (path parent_path). */
static int create_series(struct tlsph_output *o, hid_t parent, const char *parent_path,
                         const struct tlsph_series_column *c, size_t offset)
{
    char path[512];
    if ((size_t)snprintf(path, sizeof path, "%s/%s", parent_path, c->name) >= sizeof path)
        return -1;
    hid_t g = make_group(parent, c->name);
    if (g < 0)
        return -1;
    int rc = -1;
    hsize_t tail[1] = {(hsize_t)c->ncomp};
    hsize_t chunk[2] = {SERIES_CHUNK, (hsize_t)c->ncomp};
    hid_t v = extendible(g, "value", H5T_IEEE_F64LE, c->ncomp > 1 ? 2 : 1, tail, chunk, 0);
    struct series_value *s = &o->series[o->nseries];
    if (v < 0)
        goto done;
    if (describe(v, c->units, c->description, c->ncomp == 3 ? "x y z" : NULL) < 0)
        goto done;
    if (step_time(g, o->series_step_path, o->series_time_path, SERIES_CHUNK, path) < 0)
        goto done;
    size_t len = strlen(path) + sizeof "/value";
    if (!(s->path = malloc(len)))
        goto done;
    snprintf(s->path, len, "%s/value", path);
    s->ncomp = c->ncomp;
    s->offset = offset;
    s->value = H5I_INVALID_HID;
    o->nseries++;
    rc = 0;
done:
    if (v >= 0)
        H5Dclose(v);
    H5Gclose(g);
    return rc;
}

/* HDF5 link names cannot contain '/', and "." names the group itself. */
static void link_name(char *out, size_t size, const char *name)
{
    snprintf(out, size, "%s", name[0] ? name : "_");
    for (char *p = out; *p; p++)
        if (*p == '/')
            *p = '_';
    if (strcmp(out, ".") == 0)
        snprintf(out, size, "_");
}

static int create_metadata(hid_t file, const struct tlsph_model *m)
{
    int rc = -1;
    hid_t h5md = H5I_INVALID_HID, sub = H5I_INVALID_HID, par = H5I_INVALID_HID;
    char *modules = NULL;
    json_t *arr = NULL;
    const int version[2] = {1, 1};

    if ((h5md = make_group(file, "h5md")) < 0)
        goto done;
    if (attr_numeric(h5md, "version", H5T_STD_I32LE, H5T_NATIVE_INT, 2, version) < 0)
        goto done;
    if ((sub = make_group(h5md, "creator")) < 0 || attr_string(sub, "name", "tlsph") < 0 ||
        attr_string(sub, "version", PACKAGE_VERSION) < 0)
        goto done;
    H5Gclose(sub);
    if ((sub = make_group(h5md, "author")) < 0 || attr_string(sub, "name", "tlsph") < 0)
        goto done;
    H5Gclose(sub);
    sub = H5I_INVALID_HID;

    if ((par = make_group(file, "parameters")) < 0)
        goto done;
    if (!(arr = json_array()))
        goto done;
    for (int i = 0; i < m->nmodules; i++)
        if (json_array_append_new(arr, json_string(m->modules[i] ? m->modules[i] : "")) < 0)
            goto done;
    if (!(modules = json_dumps(arr, JSON_COMPACT)))
        goto done;
    if (string_dataset(par, "scene", m->scene.json_text ? m->scene.json_text : "{}",
                       "the scene as submitted (JSON)") < 0 ||
        string_dataset(par, "modules", modules, "active modules (JSON array of names)") < 0)
        goto done;
    /* setup statistics: how well the discretisation resolves every particle */
    if (attr_int64(par, "dimension", m->scene.dimension) < 0 ||
        attr_string(par, "engine_version", PACKAGE_VERSION) < 0 ||
        attr_string(par, "units_system", "SI") < 0 ||
        attr_int64(par, "particles", (int64_t)m->p.n) < 0 ||
        attr_int64(par, "pairs", (int64_t)m->pairs.npairs) < 0 ||
        attr_int64(par, "deficient_supports", (int64_t)m->deficient_supports) < 0 ||
        attr_int64(par, "isolated_particles", (int64_t)m->isolated) < 0 ||
        attr_double(par, "max_L_condition", m->max_L_condition) < 0 ||
        attr_double(par, "initial_time_step", m->dt) < 0)
        goto done;
    rc = 0;
done:
    free(modules);
    json_decref(arr);
    if (sub >= 0)
        H5Gclose(sub);
    if (par >= 0)
        H5Gclose(par);
    if (h5md >= 0)
        H5Gclose(h5md);
    return rc;
}

/* /cost and /diagnostics with placeholder values, rewritten at close. */
static int create_records(hid_t file, const struct tlsph_model *m)
{
    int rc = -1;
    hid_t g = H5I_INVALID_HID;
    int64_t ids[DIAG_IDS];
    for (int i = 0; i < DIAG_IDS; i++)
        ids[i] = -1;

    if ((g = make_group(file, "cost")) < 0)
        goto done;
    if (attr_int64(g, "particles", (int64_t)m->p.n) < 0 ||
        attr_int64(g, "pairs", (int64_t)m->pairs.npairs) < 0 || attr_int64(g, "steps", -1) < 0 ||
        attr_double(g, "wall_seconds", NAN) < 0 ||
        attr_double(g, "particle_steps_per_second", NAN) < 0 ||
        attr_int64(g, "peak_memory_bytes", -1) < 0 || attr_double(g, "bytes_per_particle", NAN) < 0)
        goto done;
    H5Gclose(g);

    if ((g = make_group(file, "diagnostics")) < 0)
        goto done;
    if (attr_string_sized(g, "status", "running", STATUS_LEN) < 0 ||
        attr_int64(g, "step", -1) < 0 || attr_double(g, "time", NAN) < 0 ||
        attr_string_sized(g, "quantity", "", QUANTITY_LEN) < 0 ||
        attr_double(g, "value", NAN) < 0 || attr_double(g, "limit", NAN) < 0 ||
        attr_int64(g, "nids", 0) < 0 ||
        attr_numeric(g, "ids", H5T_STD_I64LE, H5T_NATIVE_INT64, DIAG_IDS, ids) < 0 ||
        attr_string_sized(g, "message", "", MESSAGE_LEN) < 0)
        goto done;
    rc = 0;
done:
    if (g >= 0)
        H5Gclose(g);
    return rc;
}

static int create_particles(struct tlsph_output *o, const struct tlsph_model *m)
{
    int rc = -1;
    hid_t parts = H5I_INVALID_HID, solid = H5I_INVALID_HID, box = H5I_INVALID_HID;
    hid_t strtype = H5I_INVALID_HID, space = H5I_INVALID_HID, attr = H5I_INVALID_HID;
    const char boundary[3][5] = {"none", "none", "none"};
    hsize_t three[1] = {3};

    if ((parts = make_group(o->file, "particles")) < 0 || (solid = make_group(parts, "solid")) < 0)
        goto done;
    /* H5MD requires a box; particles are not in a periodic domain. */
    if ((box = make_group(solid, "box")) < 0 || attr_int64(box, "dimension", 3) < 0)
        goto done;
    if ((strtype = H5Tcopy(H5T_C_S1)) < 0 || H5Tset_size(strtype, 5) < 0 ||
        (space = H5Screate_simple(1, three, NULL)) < 0 ||
        (attr = H5Acreate2(box, "boundary", strtype, space, H5P_DEFAULT, H5P_DEFAULT)) < 0 ||
        H5Awrite(attr, strtype, boundary) < 0)
        goto done;

    for (size_t i = 0; i < o->npresent; i++) {
        const struct tlsph_field *f = o->present[i];
        int r = f->kind == TLSPH_FIELD_REFERENCE ? write_reference_field(o, solid, f, m)
                                                  : create_frame_field(o, solid, f);
        if (r < 0)
            goto done;
    }
    rc = 0;
done:
    if (attr >= 0)
        H5Aclose(attr);
    if (space >= 0)
        H5Sclose(space);
    if (strtype >= 0)
        H5Tclose(strtype);
    if (box >= 0)
        H5Gclose(box);
    if (solid >= 0)
        H5Gclose(solid);
    if (parts >= 0)
        H5Gclose(parts);
    return rc;
}

/* /observables/<family>/<item>/<column> for every item with series and every
 * present column; the family's group only when it has an item or is "always". */
static int create_family(struct tlsph_output *o, const struct tlsph_model *m, hid_t obs,
                         const struct tlsph_series_family *f, size_t *offset)
{
    int rc = -1;
    hid_t fam = H5I_INVALID_HID, g = H5I_INVALID_HID;
    if (f->always && (fam = make_group(obs, f->name)) < 0)
        goto done;
    for (size_t k = 0; k < f->count(m); k++) {
        const char *item = f->item(m, k);
        if (!item)
            continue;
        if (fam < 0 && (fam = make_group(obs, f->name)) < 0)
            goto done;
        char name[TLSPH_NAME_MAX + 8], path[TLSPH_NAME_MAX + 64];
        link_name(name, sizeof name, item);
        snprintf(path, sizeof path, "/observables/%s/%s", f->name, name);
        if ((g = make_group(fam, name)) < 0)
            goto done;
        for (size_t c = 0; c < f->ncolumns; c++) {
            if (!tlsph_series_present(&f->columns[c], m))
                continue;
            if (create_series(o, g, path, &f->columns[c], *offset) < 0)
                goto done;
            *offset += (size_t)f->columns[c].ncomp;
        }
        H5Gclose(g);
        g = H5I_INVALID_HID;
    }
    rc = 0;
done:
    if (g >= 0)
        H5Gclose(g);
    if (fam >= 0)
        H5Gclose(fam);
    return rc;
}

static int create_observables(struct tlsph_output *o, const struct tlsph_model *m)
{
    int rc = -1;
    hid_t obs = H5I_INVALID_HID;
    size_t offset = 0;

    if ((obs = make_group(o->file, "observables")) < 0)
        goto done;
    for (size_t c = 0; c < tlsph_nglobal_series; c++) {
        if (!tlsph_series_present(&tlsph_global_series[c], m))
            continue;
        if (create_series(o, obs, "/observables", &tlsph_global_series[c], offset) < 0)
            goto done;
        offset += (size_t)tlsph_global_series[c].ncomp;
    }
    for (size_t f = 0; f < TLSPH_NFAMILIES; f++)
        if (create_family(o, m, obs, &tlsph_series_families[f], &offset) < 0)
            goto done;
    rc = 0;
done:
    if (obs >= 0)
        H5Gclose(obs);
    return rc;
}

/* After H5Fstart_swmr_write: open the datasets we write, with our chunk cache. */
static int reopen_datasets(struct tlsph_output *o)
{
    int rc = -1;
    hid_t dapl = H5Pcreate(H5P_DATASET_ACCESS);
    if (dapl < 0)
        return -1;
    if (H5Pset_chunk_cache(dapl, H5D_CHUNK_CACHE_NSLOTS_DEFAULT, CHUNK_CACHE_BYTES, 1.0) < 0)
        goto done;
    for (size_t i = 0; i < o->nframe_fields; i++) {
        char path[256];
        snprintf(path, sizeof path, "/particles/solid/%s/value", o->frames[i].f->name);
        if ((o->frames[i].value = H5Dopen2(o->file, path, dapl)) < 0)
            goto done;
    }
    for (size_t i = 0; i < o->nseries; i++)
        if ((o->series[i].value = H5Dopen2(o->file, o->series[i].path, dapl)) < 0)
            goto done;
    if (o->nframe_fields &&
        ((o->frame_step = H5Dopen2(o->file, o->frame_step_path, dapl)) < 0 ||
         (o->frame_time = H5Dopen2(o->file, o->frame_time_path, dapl)) < 0))
        goto done;
    if (o->nseries &&
        ((o->series_step = H5Dopen2(o->file, o->series_step_path, dapl)) < 0 ||
         (o->series_time = H5Dopen2(o->file, o->series_time_path, dapl)) < 0))
        goto done;
    rc = 0;
done:
    H5Pclose(dapl);
    return rc;
}

static void free_output(struct tlsph_output *o)
{
    if (!o)
        return;
    int failed = 0;
    for (size_t i = 0; i < o->nframe_fields; i++)
        if (o->frames[i].value >= 0)
            failed |= H5Dclose(o->frames[i].value) < 0;
    for (size_t i = 0; i < o->nseries; i++) {
        if (o->series[i].value >= 0)
            failed |= H5Dclose(o->series[i].value) < 0;
        free(o->series[i].path);
    }
    hid_t ids[4] = {o->frame_step, o->frame_time, o->series_step, o->series_time};
    for (int i = 0; i < 4; i++)
        if (ids[i] >= 0)
            failed |= H5Dclose(ids[i]) < 0;
    if (o->file >= 0)
        failed |= H5Fclose(o->file) < 0;
    (void)failed;
    free(o->frames);
    free(o->series);
    free(o->present);
    free(o->frame_times);
    free(o->scratch);
    free(o->rows);
    free(o->row_step);
    free(o->row_time);
    free(o->h5_path);
    free(o->xmf_path);
    free(o);
}

static char *join_path(const char *dir, const char *name)
{
    size_t len = strlen(dir) + strlen(name) + 2;
    char *p = malloc(len);
    if (p)
        snprintf(p, len, "%s/%s", dir, name);
    return p;
}

struct tlsph_output *tlsph_output_open(const char *dir, const struct tlsph_model *m,
                                       struct tlsph_errors *err)
{
    char h5err[256];
    struct tlsph_output *o = calloc(1, sizeof *o);
    hid_t fapl = H5I_INVALID_HID;
    if (!o) {
        tlsph_errors_add(err, "", "output: out of memory");
        return NULL;
    }
    o->file = o->frame_step = o->frame_time = o->series_step = o->series_time = H5I_INVALID_HID;
    o->n = m->p.n;

    /* HDF5 prints its error stack to stderr by default; library code must not
     * print.  The setting is process-wide (HDF5 keeps one default stack), which
     * suits this engine: every HDF5 call is checked and reported through err
     * or a return value, with the message taken from the stack (h5_error_text). */
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);

    if (o->n == 0) {
        tlsph_errors_add(err, "", "output: the model has no particles");
        goto fail;
    }
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        tlsph_errors_add(err, "", "output: cannot create directory %s: %s", dir, strerror(errno));
        goto fail;
    }

    /* The tables, sized once. */
    int maxcomp = 1;
    o->present = malloc(tlsph_nfields * sizeof *o->present);
    o->frames = malloc((tlsph_nfields ? tlsph_nfields : 1) * sizeof *o->frames);
    size_t maxseries = tlsph_nglobal_series;
    o->width = tlsph_global_series_width(m);
    for (size_t fi = 0; fi < TLSPH_NFAMILIES; fi++) {
        const struct tlsph_series_family *f = &tlsph_series_families[fi];
        const size_t w = tlsph_family_width(f, m);
        for (size_t k = 0; k < f->count(m); k++)
            if (f->item(m, k)) {
                maxseries += f->ncolumns;
                o->width += w;
            }
    }
    o->series = calloc(maxseries ? maxseries : 1, sizeof *o->series);
    o->rows = malloc(SERIES_CHUNK * (o->width ? o->width : 1) * sizeof *o->rows);
    o->row_step = malloc(SERIES_CHUNK * sizeof *o->row_step);
    o->row_time = malloc(SERIES_CHUNK * sizeof *o->row_time);
    o->frame_times_cap = m->scene.frames > 0 ? (size_t)m->scene.frames + 2 : 16;
    o->frame_times = malloc(o->frame_times_cap * sizeof *o->frame_times);
    o->h5_path = join_path(dir, H5_NAME);
    o->xmf_path = join_path(dir, XMF_NAME);
    if (!o->present || !o->frames || !o->series || !o->rows || !o->row_step || !o->row_time ||
        !o->frame_times || !o->h5_path || !o->xmf_path) {
        tlsph_errors_add(err, "", "output: out of memory");
        goto fail;
    }
    for (size_t i = 0; i < tlsph_nfields; i++) {
        if (!field_present(&tlsph_fields[i], m))
            continue;
        o->present[o->npresent++] = &tlsph_fields[i];
        if (tlsph_fields[i].ncomp > maxcomp)
            maxcomp = tlsph_fields[i].ncomp;
    }
    if (!(o->scratch = malloc(o->n * (size_t)maxcomp * 8))) {
        tlsph_errors_add(err, "", "output: out of memory (%zu particles)", o->n);
        goto fail;
    }

    if ((fapl = H5Pcreate(H5P_FILE_ACCESS)) < 0 ||
        H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST) < 0 ||
        H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG) < 0) {
        h5_error_text(h5err);
        tlsph_errors_add(err, "", "output: HDF5 setup failed: %s", h5err);
        goto fail;
    }
    if ((o->file = H5Fcreate(o->h5_path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl)) < 0) {
        h5_error_text(h5err);
        tlsph_errors_add(err, "", "output: cannot create %s: %s", o->h5_path, h5err);
        goto fail;
    }
    if (create_metadata(o->file, m) < 0 || create_particles(o, m) < 0 ||
        create_observables(o, m) < 0 || create_records(o->file, m) < 0) {
        h5_error_text(h5err);
        tlsph_errors_add(err, "", "output: cannot lay out %s: %s", o->h5_path, h5err);
        goto fail;
    }
    if (H5Fstart_swmr_write(o->file) < 0 || reopen_datasets(o) < 0) {
        h5_error_text(h5err);
        tlsph_errors_add(err, "", "output: cannot start SWMR writing of %s: %s", o->h5_path,
                         h5err);
        goto fail;
    }
    H5Pclose(fapl);
    fapl = H5I_INVALID_HID;
    o->last_series_write = tlsph_monotonic_seconds();
    if (tlsph_xdmf_write(o->xmf_path, H5_NAME, o->n, 0, o->frame_times, o->present,
                         o->npresent) < 0) {
        tlsph_errors_add(err, "", "output: cannot write %s: %s", o->xmf_path, strerror(errno));
        goto fail;
    }
    return o;
fail:
    if (fapl >= 0)
        H5Pclose(fapl);
    free_output(o);
    return NULL;
}

/* ------------------------------------------------------------ writing */

/* Extends ds (rank 1..3, first axis unlimited) from `have` to have + rows and
 * writes rows rows of buf.  mspace NULL: buf is contiguous for the new rows;
 * else mspace is the memory selection (with as many elements). */
static int append_rows(hid_t ds, hid_t mtype, size_t have, size_t rows, hid_t mspace,
                       const void *buf)
{
    int rc = -1;
    hid_t fspace = H5Dget_space(ds), ms = H5I_INVALID_HID;
    if (fspace < 0)
        return -1;
    hsize_t dims[3], start[3] = {have, 0, 0}, count[3];
    int rank = H5Sget_simple_extent_ndims(fspace);
    if (rank < 1 || rank > 3 || H5Sget_simple_extent_dims(fspace, dims, NULL) < 0)
        goto done;
    H5Sclose(fspace);
    fspace = H5I_INVALID_HID;
    dims[0] = have + rows;
    if (H5Dset_extent(ds, dims) < 0 || (fspace = H5Dget_space(ds)) < 0)
        goto done;
    count[0] = rows;
    for (int r = 1; r < rank; r++)
        count[r] = dims[r];
    if (H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, count, NULL) < 0)
        goto done;
    if (mspace < 0 && (ms = H5Screate_simple(rank, count, NULL)) < 0)
        goto done;
    if (H5Dwrite(ds, mtype, mspace >= 0 ? mspace : ms, fspace, H5P_DEFAULT, buf) < 0)
        goto done;
    if (H5Dflush(ds) < 0)
        goto done;
    rc = 0;
done:
    if (ms >= 0)
        H5Sclose(ms);
    if (fspace >= 0)
        H5Sclose(fspace);
    return rc;
}

static int flush_series(struct tlsph_output *o)
{
    if (o->nrows == 0)
        return 0;
    int rc = -1;
    hsize_t mdims[2] = {o->nrows, o->width};
    hid_t ms = H5Screate_simple(2, mdims, NULL);
    if (ms < 0)
        return -1;
    for (size_t i = 0; i < o->nseries; i++) {
        const struct series_value *s = &o->series[i];
        hsize_t start[2] = {0, s->offset}, count[2] = {o->nrows, (hsize_t)s->ncomp};
        if (H5Sselect_hyperslab(ms, H5S_SELECT_SET, start, NULL, count, NULL) < 0)
            goto done;
        if (append_rows(s->value, H5T_NATIVE_DOUBLE, o->nsamples, o->nrows, ms, o->rows) < 0)
            goto done;
    }
    /* step last, as for frames: it marks the rows as complete for SWMR readers */
    if (append_rows(o->series_time, H5T_NATIVE_DOUBLE, o->nsamples, o->nrows, H5I_INVALID_HID,
                    o->row_time) < 0 ||
        append_rows(o->series_step, H5T_NATIVE_INT64, o->nsamples, o->nrows, H5I_INVALID_HID,
                    o->row_step) < 0)
        goto done;
    o->nsamples += o->nrows;
    o->last_step_written = o->row_step[o->nrows - 1];
    o->nrows = 0;
    o->last_series_write = tlsph_monotonic_seconds();
    rc = 0;
done:
    H5Sclose(ms);
    return rc;
}

int tlsph_output_series(struct tlsph_output *o, const struct tlsph_model *m)
{
    if (o->nseries == 0)
        return 0;
    /* One sample per step: a second sample at the step just sampled replaces the
     * buffered row (or is dropped if that row is already in the file), so series
     * steps and times stay strictly increasing. */
    size_t slot = o->nrows;
    if (o->nrows > 0 && o->row_step[o->nrows - 1] == m->step)
        slot = o->nrows - 1;
    else if (o->nrows == 0 && o->nsamples > 0 && o->last_step_written == m->step)
        return 0;
    double *row = o->rows + slot * o->width;
    size_t off = tlsph_global_series_width(m);
    tlsph_global_series_values(m, row);
    for (size_t fi = 0; fi < TLSPH_NFAMILIES; fi++) {
        const struct tlsph_series_family *f = &tlsph_series_families[fi];
        const size_t w = tlsph_family_width(f, m);
        for (size_t k = 0; k < f->count(m); k++)
            if (f->item(m, k)) {
                f->values(m, k, row + off);
                off += w;
            }
    }
    o->row_step[slot] = m->step;
    o->row_time[slot] = m->t;
    o->nrows = slot + 1;
    if (o->nrows == SERIES_CHUNK || tlsph_monotonic_seconds() - o->last_series_write >= SERIES_MAX_AGE)
        return flush_series(o);
    return 0;
}

int tlsph_output_frame(struct tlsph_output *o, const struct tlsph_model *m)
{
    for (size_t i = 0; i < o->nframe_fields; i++) {
        const struct tlsph_field *f = o->frames[i].f;
        f->extract(m, o->scratch);
        narrow_in_place(o->scratch, o->n * (size_t)f->ncomp, f->type);
        if (append_rows(o->frames[i].value, mem_type(f->type), o->nframes, 1, H5I_INVALID_HID,
                        o->scratch) < 0)
            return -1;
    }
    if (o->nframe_fields) {
        int64_t step = m->step;
        double t = m->t;
        /* step is written last: a SWMR reader that counts rows of step finds
         * time and every value at least that long (step is the commit marker). */
        if (append_rows(o->frame_time, H5T_NATIVE_DOUBLE, o->nframes, 1, H5I_INVALID_HID, &t) <
                0 ||
            append_rows(o->frame_step, H5T_NATIVE_INT64, o->nframes, 1, H5I_INVALID_HID,
                        &step) < 0)
            return -1;
    }
    if (o->nframes == o->frame_times_cap) {
        size_t cap = 2 * o->frame_times_cap;
        double *t = realloc(o->frame_times, cap * sizeof *t);
        if (!t)
            return -1;
        o->frame_times = t;
        o->frame_times_cap = cap;
    }
    o->frame_times[o->nframes++] = m->t;
    if (flush_series(o) < 0)
        return -1;
    /* The sidecar lists every frame, so rewriting it after each one costs
     * O(frames^2) bytes over a run; ParaView cannot open the HDF5 file before
     * the writer closes it anyway.  Rewrite it at most every XMF_MAX_AGE seconds
     * (so a killed run still leaves a recent one) and always at close. */
    if (tlsph_monotonic_seconds() - o->last_xmf_write >= XMF_MAX_AGE) {
        if (tlsph_xdmf_write(o->xmf_path, H5_NAME, o->n, o->nframes, o->frame_times, o->present,
                             o->npresent) < 0)
            return -1;
        o->last_xmf_write = tlsph_monotonic_seconds();
    }
    return 0;
}

static int write_records(struct tlsph_output *o, const struct tlsph_cost *cost,
                         const char *status, const struct tlsph_diagnostic *d)
{
    int rc = -1;
    hid_t g = H5I_INVALID_HID;
    if (cost) {
        int64_t particles = (int64_t)cost->particles, pairs = (int64_t)cost->pairs,
                steps = cost->steps, peak = (int64_t)cost->peak_memory_bytes;
        if ((g = H5Gopen2(o->file, "/cost", H5P_DEFAULT)) < 0)
            goto done;
        if (rewrite_attr(g, "particles", H5T_NATIVE_INT64, &particles) < 0 ||
            rewrite_attr(g, "pairs", H5T_NATIVE_INT64, &pairs) < 0 ||
            rewrite_attr(g, "steps", H5T_NATIVE_INT64, &steps) < 0 ||
            rewrite_attr(g, "wall_seconds", H5T_NATIVE_DOUBLE, &cost->wall_seconds) < 0 ||
            rewrite_attr(g, "particle_steps_per_second", H5T_NATIVE_DOUBLE,
                         &cost->particle_steps_per_second) < 0 ||
            rewrite_attr(g, "peak_memory_bytes", H5T_NATIVE_INT64, &peak) < 0 ||
            rewrite_attr(g, "bytes_per_particle", H5T_NATIVE_DOUBLE,
                         &cost->bytes_per_particle) < 0)
            goto done;
        H5Gclose(g);
        g = H5I_INVALID_HID;
    }
    if ((g = H5Gopen2(o->file, "/diagnostics", H5P_DEFAULT)) < 0)
        goto done;
    if (rewrite_string(g, "status", status ? status : "unknown") < 0)
        goto done;
    if (d) {
        int64_t step = d->step, nids = (int64_t)(d->nids < DIAG_IDS ? d->nids : DIAG_IDS);
        int64_t ids[DIAG_IDS];
        for (int i = 0; i < DIAG_IDS; i++)
            ids[i] = i < nids ? d->ids[i] : -1;
        if (rewrite_attr(g, "step", H5T_NATIVE_INT64, &step) < 0 ||
            rewrite_attr(g, "time", H5T_NATIVE_DOUBLE, &d->time) < 0 ||
            rewrite_string(g, "quantity", d->quantity) < 0 ||
            rewrite_attr(g, "value", H5T_NATIVE_DOUBLE, &d->value) < 0 ||
            rewrite_attr(g, "limit", H5T_NATIVE_DOUBLE, &d->limit) < 0 ||
            rewrite_attr(g, "nids", H5T_NATIVE_INT64, &nids) < 0 ||
            rewrite_attr(g, "ids", H5T_NATIVE_INT64, ids) < 0 ||
            rewrite_string(g, "message", d->message) < 0)
            goto done;
    }
    rc = 0;
done:
    if (g >= 0)
        H5Gclose(g);
    return rc;
}

int tlsph_output_close(struct tlsph_output *o, const struct tlsph_model *m,
                       const struct tlsph_cost *cost, const char *status,
                       const struct tlsph_diagnostic *d)
{
    (void)m;
    if (!o)
        return -1;
    int rc = 0;
    if (flush_series(o) < 0)
        rc = -1;
    if (write_records(o, cost, status, d) < 0)
        rc = -1;
    if (tlsph_xdmf_write(o->xmf_path, H5_NAME, o->n, o->nframes, o->frame_times, o->present,
                         o->npresent) < 0)
        rc = -1;
    /* Close the datasets, then the file, checking each (free_output ignores). */
    for (size_t i = 0; i < o->nframe_fields; i++) {
        if (H5Dclose(o->frames[i].value) < 0)
            rc = -1;
        o->frames[i].value = H5I_INVALID_HID;
    }
    for (size_t i = 0; i < o->nseries; i++) {
        if (H5Dclose(o->series[i].value) < 0)
            rc = -1;
        o->series[i].value = H5I_INVALID_HID;
    }
    hid_t *ids[4] = {&o->frame_step, &o->frame_time, &o->series_step, &o->series_time};
    for (int i = 0; i < 4; i++) {
        if (*ids[i] >= 0 && H5Dclose(*ids[i]) < 0)
            rc = -1;
        *ids[i] = H5I_INVALID_HID;
    }
    if (H5Fclose(o->file) < 0)
        rc = -1;
    o->file = H5I_INVALID_HID;
    free_output(o);
    return rc;
}

void tlsph_output_abort(struct tlsph_output *o)
{
    free_output(o);
}
