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
 *    values of fixed size (fixed-length strings, fixed-size arrays; records.c) and
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
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/fields.h"
#include "io/output/h5_attr.h"
#include "io/output/h5_dataset.h"
#include "io/output/records.h"
#include "io/output/xdmf.h"
#include "util/clock.h"

#define H5_NAME "result.h5"
#define XMF_NAME "result.xmf"
#define SERIES_CHUNK 1024        /* rows per series chunk and per memory buffer */
#define FRAME_STEP_CHUNK 1024    /* rows per chunk of the frames' step and time */
#define SERIES_MAX_AGE 1.0       /* s of wall time before buffered rows are written */
#define XMF_MAX_AGE 2.0          /* s of wall time between rewrites of the XDMF sidecar */
#define FRAME_CHUNK_BYTES (512u * 1024u) /* target chunk size of frame values */
#define CHUNK_CACHE_BYTES (4u * 1024u * 1024u)
#define GROUP_PATH_MAX 256

/* The step and time datasets of a family of elements (the frame fields, or
 * the series columns): created in the family's first group, hard-linked into
 * the others. */
struct timeline {
    char group[GROUP_PATH_MAX]; /* of the group that holds them; "" until created */
    hid_t step, time;           /* open once SWMR writing has started */
};

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
    struct timeline frame_timeline;
    size_t nframes;
    double *frame_times;
    size_t frame_times_cap;
    void *scratch; /* n * max ncomp * 8 bytes */

    struct series_value *series;
    size_t nseries;
    struct timeline series_timeline;
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

/* The values of field f, in its file type's memory layout, into o->scratch. */
static void extract_field(struct tlsph_output *o, const struct tlsph_field *f,
                          const struct tlsph_model *m)
{
    f->extract(m, o->scratch);
    narrow_in_place(o->scratch, o->n * (size_t)f->ncomp, f->type);
}

static int field_present(const struct tlsph_field *f, const struct tlsph_model *m)
{
    return f->present == NULL || f->present(m);
}

static hid_t make_group(hid_t loc, const char *name)
{
    return H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
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

static char *join_path(const char *dir, const char *name)
{
    size_t len = strlen(dir) + strlen(name) + 2;
    char *p = malloc(len);
    if (p)
        snprintf(p, len, "%s/%s", dir, name);
    return p;
}

/* ------------------------------------------------------------ timelines */

/* The path of the timeline's dataset name ("step" or "time"). */
static void timeline_path(char out[GROUP_PATH_MAX + 8], const struct timeline *tl,
                          const char *name)
{
    snprintf(out, GROUP_PATH_MAX + 8, "%s/%s", tl->group, name);
}

/* Gives group g (at group_path) the family's step and time: links to those of
 * the family's first group, or, in that first group, new datasets of
 * chunk_rows rows per chunk. */
static int timeline_add(struct timeline *tl, hid_t g, const char *group_path, hsize_t chunk_rows)
{
    char path[GROUP_PATH_MAX + 8];
    if (tl->group[0]) {
        timeline_path(path, tl, "step");
        if (H5Lcreate_hard(g, path, g, "step", H5P_DEFAULT, H5P_DEFAULT) < 0)
            return -1;
        timeline_path(path, tl, "time");
        return H5Lcreate_hard(g, path, g, "time", H5P_DEFAULT, H5P_DEFAULT) < 0 ? -1 : 0;
    }
    if (strlen(group_path) >= sizeof tl->group)
        return -1;
    hsize_t chunk[1] = {chunk_rows};
    hid_t s = tlsph_h5_extendible(g, "step", H5T_STD_I64LE, 1, NULL, chunk, 0);
    hid_t t = tlsph_h5_extendible(g, "time", H5T_IEEE_F64LE, 1, NULL, chunk, 0);
    int rc = -1;
    if (s >= 0 && t >= 0 &&
        tlsph_h5_attr_string(s, "description", "time step index of each sample") == 0 &&
        tlsph_h5_describe(t, "s", "simulated time of each sample", NULL) == 0) {
        snprintf(tl->group, sizeof tl->group, "%s", group_path);
        rc = 0;
    }
    if (s >= 0)
        H5Dclose(s);
    if (t >= 0)
        H5Dclose(t);
    return rc;
}

static int timeline_open(struct timeline *tl, hid_t file, hid_t dapl)
{
    char path[GROUP_PATH_MAX + 8];
    timeline_path(path, tl, "step");
    if ((tl->step = H5Dopen2(file, path, dapl)) < 0)
        return -1;
    timeline_path(path, tl, "time");
    return (tl->time = H5Dopen2(file, path, dapl)) < 0 ? -1 : 0;
}

/* Appends rows samples.  step is written last: a SWMR reader that counts the
 * rows of step finds time and every value at least that long (step is the
 * commit marker). */
static int timeline_append(const struct timeline *tl, size_t have, size_t rows,
                           const int64_t *step, const double *time)
{
    if (tlsph_h5_append_rows(tl->time, H5T_NATIVE_DOUBLE, have, rows, H5I_INVALID_HID, time) <
            0 ||
        tlsph_h5_append_rows(tl->step, H5T_NATIVE_INT64, have, rows, H5I_INVALID_HID, step) < 0)
        return -1;
    return 0;
}

/* ------------------------------------------------------------ creation */

/* An H5MD time-dependent element: a group holding the value dataset (first
 * axis unlimited: one row per sample) and its family's step and time. */
struct element {
    const char *name;
    hid_t ftype;
    int rank;          /* of value, 1..3 */
    hsize_t tail[2];   /* extents of value's other axes */
    hsize_t chunk[3];
    int compress;
    const char *units, *description, *components;
};

/* Creates element e in parent (at parent_path) and writes its path to path. */
static int create_element(hid_t parent, const char *parent_path, const struct element *e,
                          struct timeline *tl, hsize_t step_chunk, char *path, size_t size)
{
    if ((size_t)snprintf(path, size, "%s/%s", parent_path, e->name) >= size)
        return -1;
    hid_t g = make_group(parent, e->name);
    if (g < 0)
        return -1;
    hid_t v = tlsph_h5_extendible(g, "value", e->ftype, e->rank, e->tail, e->chunk, e->compress);
    int rc = -1;
    if (v >= 0 && tlsph_h5_describe(v, e->units, e->description, e->components) == 0 &&
        timeline_add(tl, g, path, step_chunk) == 0)
        rc = 0;
    if (v >= 0)
        H5Dclose(v);
    H5Gclose(g);
    return rc;
}

static int write_reference_field(struct tlsph_output *o, hid_t solid, const struct tlsph_field *f,
                                 const struct tlsph_model *m)
{
    const struct tlsph_h5_type t = tlsph_h5_type(f->type);
    const hsize_t dims[2] = {o->n, (hsize_t)f->ncomp};
    const hsize_t chunk[2] = {particles_per_chunk(o->n, f->ncomp, t.size), (hsize_t)f->ncomp};
    hid_t ds = tlsph_h5_chunked(solid, f->name, t.file, f->ncomp > 1 ? 2 : 1, dims, NULL, chunk, 1);
    if (ds < 0)
        return -1;
    extract_field(o, f, m);
    int rc = -1;
    if (H5Dwrite(ds, t.mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, o->scratch) >= 0 &&
        tlsph_h5_describe(ds, f->units, f->description, f->components) == 0)
        rc = 0;
    if (H5Dclose(ds) < 0)
        rc = -1;
    return rc;
}

static int create_frame_field(struct tlsph_output *o, hid_t solid, const struct tlsph_field *f)
{
    const struct tlsph_h5_type t = tlsph_h5_type(f->type);
    const hsize_t ncomp = (hsize_t)f->ncomp;
    const struct element e = {
        .name = f->name,
        .ftype = t.file,
        .rank = f->ncomp > 1 ? 3 : 2,
        .tail = {o->n, ncomp},
        .chunk = {1, particles_per_chunk(o->n, f->ncomp, t.size), ncomp},
        .compress = f->type != TLSPH_FLOAT64, /* float64 positions barely compress */
        .units = f->units,
        .description = f->description,
        .components = f->components,
    };
    char path[GROUP_PATH_MAX];
    if (create_element(solid, "/particles/solid", &e, &o->frame_timeline, FRAME_STEP_CHUNK, path,
                       sizeof path) < 0)
        return -1;
    o->frames[o->nframe_fields++] = (struct frame_value){f, H5I_INVALID_HID};
    return 0;
}

/* One series column in group parent (path parent_path). */
static int create_series(struct tlsph_output *o, hid_t parent, const char *parent_path,
                         const struct tlsph_series_column *c, size_t offset)
{
    const hsize_t ncomp = (hsize_t)c->ncomp;
    const struct element e = {
        .name = c->name,
        .ftype = H5T_IEEE_F64LE,
        .rank = c->ncomp > 1 ? 2 : 1,
        .tail = {ncomp, 0},
        .chunk = {SERIES_CHUNK, ncomp, 0},
        .compress = 0,
        .units = c->units,
        .description = c->description,
        .components = c->ncomp == 3 ? "x y z" : NULL,
    };
    char path[512];
    if (create_element(parent, parent_path, &e, &o->series_timeline, SERIES_CHUNK, path,
                       sizeof path) < 0)
        return -1;
    struct series_value *s = &o->series[o->nseries];
    size_t len = strlen(path) + sizeof "/value";
    if (!(s->path = malloc(len)))
        return -1;
    snprintf(s->path, len, "%s/value", path);
    s->ncomp = c->ncomp;
    s->offset = offset;
    s->value = H5I_INVALID_HID;
    o->nseries++;
    return 0;
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
    if (tlsph_h5_attr_values(h5md, "version", H5T_STD_I32LE, H5T_NATIVE_INT, 2, version) < 0)
        goto done;
    if ((sub = make_group(h5md, "creator")) < 0 || tlsph_h5_attr_string(sub, "name", "tlsph") < 0 ||
        tlsph_h5_attr_string(sub, "version", PACKAGE_VERSION) < 0)
        goto done;
    H5Gclose(sub);
    if ((sub = make_group(h5md, "author")) < 0 || tlsph_h5_attr_string(sub, "name", "tlsph") < 0)
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
    if (tlsph_h5_string_dataset(par, "scene", m->scene.json_text ? m->scene.json_text : "{}",
                                "the scene as submitted (JSON)") < 0 ||
        tlsph_h5_string_dataset(par, "modules", modules,
                                "active modules (JSON array of names)") < 0)
        goto done;
    /* setup statistics: how well the discretisation resolves every particle */
    if (tlsph_h5_attr_int64(par, "dimension", m->scene.dimension) < 0 ||
        tlsph_h5_attr_string(par, "engine_version", PACKAGE_VERSION) < 0 ||
        tlsph_h5_attr_string(par, "units_system", "SI") < 0 ||
        tlsph_h5_attr_int64(par, "particles", (int64_t)m->p.n) < 0 ||
        tlsph_h5_attr_int64(par, "pairs", (int64_t)m->pairs.npairs) < 0 ||
        tlsph_h5_attr_int64(par, "deficient_supports", (int64_t)m->deficient_supports) < 0 ||
        tlsph_h5_attr_int64(par, "isolated_particles", (int64_t)m->isolated) < 0 ||
        tlsph_h5_attr_double(par, "max_L_condition", m->max_L_condition) < 0 ||
        tlsph_h5_attr_double(par, "initial_time_step", m->dt) < 0)
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

/* H5MD requires a box; particles are not in a periodic domain. */
static int create_box(hid_t solid)
{
    const char boundary[3][5] = {"none", "none", "none"};
    hid_t box = make_group(solid, "box");
    if (box < 0)
        return -1;
    hid_t strtype = tlsph_h5_string_type(sizeof boundary[0], H5T_STR_NULLTERM);
    int rc = -1;
    if (strtype >= 0 && tlsph_h5_attr_int64(box, "dimension", 3) == 0 &&
        tlsph_h5_attr_values(box, "boundary", strtype, strtype, 3, boundary) == 0)
        rc = 0;
    if (strtype >= 0)
        H5Tclose(strtype);
    H5Gclose(box);
    return rc;
}

static int create_particles(struct tlsph_output *o, const struct tlsph_model *m)
{
    int rc = -1;
    hid_t parts = H5I_INVALID_HID, solid = H5I_INVALID_HID;

    if ((parts = make_group(o->file, "particles")) < 0 || (solid = make_group(parts, "solid")) < 0)
        goto done;
    if (create_box(solid) < 0)
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
    if (solid >= 0)
        H5Gclose(solid);
    if (parts >= 0)
        H5Gclose(parts);
    return rc;
}

/* Every present column of columns[0..ncolumns-1] in group g (at path). */
static int create_columns(struct tlsph_output *o, const struct tlsph_model *m, hid_t g,
                          const char *path, const struct tlsph_series_column *columns,
                          size_t ncolumns, size_t *offset)
{
    for (size_t c = 0; c < ncolumns; c++) {
        if (!tlsph_series_present(&columns[c], m))
            continue;
        if (create_series(o, g, path, &columns[c], *offset) < 0)
            return -1;
        *offset += (size_t)columns[c].ncomp;
    }
    return 0;
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
        if (create_columns(o, m, g, path, f->columns, f->ncolumns, offset) < 0)
            goto done;
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
    size_t offset = 0;
    hid_t obs = make_group(o->file, "observables");
    if (obs < 0)
        return -1;
    int rc = create_columns(o, m, obs, "/observables", tlsph_global_series,
                            tlsph_nglobal_series, &offset);
    for (size_t f = 0; f < TLSPH_NFAMILIES && rc == 0; f++)
        rc = create_family(o, m, obs, &tlsph_series_families[f], &offset);
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
        char path[GROUP_PATH_MAX];
        snprintf(path, sizeof path, "/particles/solid/%s/value", o->frames[i].f->name);
        if ((o->frames[i].value = H5Dopen2(o->file, path, dapl)) < 0)
            goto done;
    }
    for (size_t i = 0; i < o->nseries; i++)
        if ((o->series[i].value = H5Dopen2(o->file, o->series[i].path, dapl)) < 0)
            goto done;
    if (o->nframe_fields && timeline_open(&o->frame_timeline, o->file, dapl) < 0)
        goto done;
    if (o->nseries && timeline_open(&o->series_timeline, o->file, dapl) < 0)
        goto done;
    rc = 0;
done:
    H5Pclose(dapl);
    return rc;
}

/* Closes *ds when open and marks it closed; -1 when closing fails. */
static int close_dataset(hid_t *ds)
{
    const int rc = *ds >= 0 && H5Dclose(*ds) < 0 ? -1 : 0;
    *ds = H5I_INVALID_HID;
    return rc;
}

/* Closes every dataset the writer holds open; -1 when one fails to close. */
static int close_datasets(struct tlsph_output *o)
{
    int failed = 0;
    for (size_t i = 0; i < o->nframe_fields; i++)
        failed |= close_dataset(&o->frames[i].value) < 0;
    for (size_t i = 0; i < o->nseries; i++)
        failed |= close_dataset(&o->series[i].value) < 0;
    hid_t *ids[4] = {&o->frame_timeline.step, &o->frame_timeline.time,
                     &o->series_timeline.step, &o->series_timeline.time};
    for (int i = 0; i < 4; i++)
        failed |= close_dataset(ids[i]) < 0;
    return failed ? -1 : 0;
}

/* Releases everything, ignoring HDF5 failures (tlsph_output_close checks them). */
static void free_output(struct tlsph_output *o)
{
    if (!o)
        return;
    (void)close_datasets(o);
    if (o->file >= 0)
        H5Fclose(o->file);
    for (size_t i = 0; i < o->nseries; i++)
        free(o->series[i].path);
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

/* The sidecar, listing the frames written so far. */
static int write_sidecar(const struct tlsph_output *o)
{
    return tlsph_xdmf_write(o->xmf_path, H5_NAME, o->n, o->nframes, o->frame_times, o->present,
                            o->npresent);
}

/* Adds "output: <what> [<path>]: <HDF5's message>". */
static void add_h5_error(struct tlsph_errors *err, const char *what, const char *path)
{
    char h5err[256];
    tlsph_h5_error_text(h5err);
    tlsph_errors_add(err, "", "output: %s%s%s: %s", what, path ? " " : "", path ? path : "",
                     h5err);
}

struct tlsph_output *tlsph_output_open(const char *dir, const struct tlsph_model *m,
                                       struct tlsph_errors *err)
{
    struct tlsph_output *o = calloc(1, sizeof *o);
    hid_t fapl = H5I_INVALID_HID;
    if (!o) {
        tlsph_errors_add(err, "", "output: out of memory");
        return NULL;
    }
    o->file = H5I_INVALID_HID;
    o->frame_timeline.step = o->frame_timeline.time = H5I_INVALID_HID;
    o->series_timeline.step = o->series_timeline.time = H5I_INVALID_HID;
    o->n = m->p.n;

    /* HDF5 prints its error stack to stderr by default; library code must not
     * print.  The setting is process-wide (HDF5 keeps one default stack), which
     * suits this engine: every HDF5 call is checked and reported through err
     * or a return value, with the message taken from the stack (add_h5_error). */
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
        add_h5_error(err, "HDF5 setup failed", NULL);
        goto fail;
    }
    if ((o->file = H5Fcreate(o->h5_path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl)) < 0) {
        add_h5_error(err, "cannot create", o->h5_path);
        goto fail;
    }
    if (create_metadata(o->file, m) < 0 || create_particles(o, m) < 0 ||
        create_observables(o, m) < 0 || tlsph_records_create(o->file, m) < 0) {
        add_h5_error(err, "cannot lay out", o->h5_path);
        goto fail;
    }
    if (H5Fstart_swmr_write(o->file) < 0 || reopen_datasets(o) < 0) {
        add_h5_error(err, "cannot start SWMR writing of", o->h5_path);
        goto fail;
    }
    H5Pclose(fapl);
    fapl = H5I_INVALID_HID;
    o->last_series_write = tlsph_monotonic_seconds();
    if (write_sidecar(o) < 0) {
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
        if (tlsph_h5_append_rows(s->value, H5T_NATIVE_DOUBLE, o->nsamples, o->nrows, ms,
                                 o->rows) < 0)
            goto done;
    }
    if (timeline_append(&o->series_timeline, o->nsamples, o->nrows, o->row_step, o->row_time) < 0)
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
        extract_field(o, f, m);
        if (tlsph_h5_append_rows(o->frames[i].value, tlsph_h5_type(f->type).mem, o->nframes, 1,
                                 H5I_INVALID_HID, o->scratch) < 0)
            return -1;
    }
    if (o->nframe_fields) {
        int64_t step = m->step;
        double t = m->t;
        if (timeline_append(&o->frame_timeline, o->nframes, 1, &step, &t) < 0)
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
        if (write_sidecar(o) < 0)
            return -1;
        o->last_xmf_write = tlsph_monotonic_seconds();
    }
    return 0;
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
    if (tlsph_records_write(o->file, cost, status, d) < 0)
        rc = -1;
    if (write_sidecar(o) < 0)
        rc = -1;
    /* Close the datasets, then the file, checking each (free_output ignores). */
    if (close_datasets(o) < 0)
        rc = -1;
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
