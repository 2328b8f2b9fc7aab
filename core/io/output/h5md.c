/* The result file: an H5MD-style HDF5 file written under SWMR (single writer,
 * multiple readers), so the daemon and h5py can read it while the run goes on.
 * Layout: core/io/output/output.h and docs/output.md.
 *
 * SWMR rules followed here (HDF5 1.10 SWMR technical note; shared notes 4.2):
 *  - the file uses the latest format (libver bounds LATEST, LATEST);
 *  - every group, dataset and attribute is created in tlsph_output_open (by
 *    layout.c), then H5Fstart_swmr_write; nothing is created afterwards.  The
 *    writer only extends datasets along their unlimited axes (the first; with
 *    a changing particle count also the particle axis, output.h) and
 *    overwrites existing values: /cost and /diagnostics attributes are
 *    pre-created with placeholder values of fixed size (fixed-length strings,
 *    fixed-size arrays; records.c) and rewritten in place at close (tested:
 *    H5Awrite after H5Fstart_swmr_write succeeds and the closed file is
 *    plain-h5dump readable);
 *  - strings are fixed-length (SWMR cannot modify variable-length data);
 *  - all objects are closed before H5Fstart_swmr_write and the datasets
 *    reopened afterwards with our access property list, because the call resets
 *    the chunk cache of open datasets (HDFGroup/hdf5 issue #1730);
 *  - per frame: every value dataset is extended and written, then step and
 *    time, each followed by H5Dflush, so a reader that takes len(step) as the
 *    frame count only ever reads complete frames;
 *  - after every frame and every write of series rows, H5Fflush (commit): it
 *    also records the end of the allocated space (EOA) in the superblock,
 *    which SWMR writing otherwise leaves at its value after the layout.  A
 *    file whose writer was killed stays marked open for writing; `h5clear -s`
 *    closes the mark but cuts the file at the recorded EOA, so without the
 *    commit it would cut every frame away (measured: 27.7 MB to 100 kB).  The
 *    lossless repair, which the daemon runs, is `h5clear -s --increment=0`
 *    (EOA = end of file); docs/output.md says what a user does.
 *
 * Frame fields and time-series columns share one step and one time dataset per
 * family through hard links (as LAMMPS' dump h5md does); to a reader they are
 * ordinary datasets.
 *
 * Time-series rows are buffered in memory (one chunk, TLSPH_SERIES_CHUNK rows)
 * and written when the buffer is full, at every frame, when SERIES_MAX_AGE
 * seconds of wall time have passed since the last write, and at close. */
#include "io/output/output.h"
#include "io/output/output_internal.h"

#include <errno.h>
#include <hdf5.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/fields.h"
#include "io/output/h5_dataset.h"
#include "io/output/records.h"
#include "io/output/xdmf.h"
#include "util/clock.h"

#define H5_NAME "result.h5"
#define XMF_NAME "result.xmf"
#define SERIES_MAX_AGE 1.0       /* s of wall time before buffered rows are written */
#define XMF_MAX_AGE 2.0          /* s of wall time between rewrites of the XDMF sidecar */
#define CHUNK_CACHE_BYTES (4u * 1024u * 1024u)

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

void tlsph_output_extract(struct tlsph_output *o, const struct tlsph_field *f,
                          const struct tlsph_model *m)
{
    f->extract(m, o->scratch);
    narrow_in_place(o->scratch, o->n * (size_t)f->ncomp, f->type);
}

static int field_present(const struct tlsph_field *f, const struct tlsph_model *m)
{
    return f->present == NULL || f->present(m);
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

static int timeline_open(struct output_timeline *tl, hid_t file, hid_t dapl)
{
    if ((tl->step = H5Dopen2(file, tl->step_path, dapl)) < 0)
        return -1;
    return (tl->time = H5Dopen2(file, tl->time_path, dapl)) < 0 ? -1 : 0;
}

/* Appends rows samples.  step is written last: a SWMR reader that counts the
 * rows of step finds time and every value at least that long (step is the
 * commit marker). */
static int timeline_append(const struct output_timeline *tl, size_t have, size_t rows,
                           const int64_t *step, const double *time)
{
    if (tlsph_h5_append_rows(tl->time, H5T_NATIVE_DOUBLE, have, rows, H5I_INVALID_HID, time) <
            0 ||
        tlsph_h5_append_rows(tl->step, H5T_NATIVE_INT64, have, rows, H5I_INVALID_HID, step) < 0)
        return -1;
    return 0;
}

/* ------------------------------------------------------------ open and close */

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
        char path[TLSPH_OUTPUT_PATH_MAX];
        snprintf(path, sizeof path, "/particles/solid/%s/value", o->frames[i].f->name);
        if ((o->frames[i].value = H5Dopen2(o->file, path, dapl)) < 0)
            goto done;
    }
    for (size_t i = 0; i < o->nseries; i++)
        if ((o->series[i].value = H5Dopen2(o->file, o->series[i].path, dapl)) < 0)
            goto done;
    if (o->changing && (o->count = H5Dopen2(o->file, "/particles/solid/count/value", dapl)) < 0)
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
    failed |= close_dataset(&o->count) < 0;
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
    free(o->frame_counts);
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
    return tlsph_xdmf_write(o->xmf_path, H5_NAME, o->changing ? o->nmax : o->n, o->nframes,
                            o->frame_times, o->frame_counts, o->present, o->npresent);
}

/* HDF5 calls this when an API call fails (H5Eset_auto2, set while the file is
 * set up): keeps the first failure's message, before clean-up calls reset the
 * stack.  Prints nothing. */
static herr_t remember_h5_error(hid_t estack, void *data)
{
    struct tlsph_output *o = data;
    if (!o->first_h5_error[0])
        tlsph_h5_stack_text(estack, o->first_h5_error);
    return 0;
}

/* Adds "output: <what> [<path>]: <HDF5's message>": the stack's, else the
 * first failure's while the file was set up. */
static void add_h5_error(const struct tlsph_output *o, struct tlsph_errors *err, const char *what,
                         const char *path)
{
    char h5err[256];
    tlsph_h5_stack_text(H5E_DEFAULT, h5err);
    if (!h5err[0] && o->first_h5_error[0])
        snprintf(h5err, sizeof h5err, "%s", o->first_h5_error);
    if (!h5err[0])
        tlsph_h5_error_text(h5err);
    tlsph_errors_add(err, "", "output: %s%s%s: %s", what, path ? " " : "", path ? path : "",
                     h5err);
}

/* A result file that could not be set up is removed, with its sidecar: it
 * would hold neither frames nor an outcome (no /diagnostics status), and
 * readers would take it for a run's result.  Frees o. */
static void discard_output(struct tlsph_output *o, int created, struct tlsph_errors *err)
{
    char *h5 = o->h5_path, *xmf = o->xmf_path;
    o->h5_path = o->xmf_path = NULL;
    free_output(o); /* closes the file first */
    if (created) {
        if (h5 && unlink(h5) != 0 && errno != ENOENT)
            tlsph_errors_add(err, "", "output: cannot remove the unfinished %s: %s", h5,
                             strerror(errno));
        if (xmf && unlink(xmf) != 0 && errno != ENOENT)
            tlsph_errors_add(err, "", "output: cannot remove the unfinished %s: %s", xmf,
                             strerror(errno));
    }
    free(h5);
    free(xmf);
}

int tlsph_output_count_may_change(const struct tlsph_model *m)
{
    return m->crack_driver != NULL;
}

struct tlsph_output *tlsph_output_open(const char *dir, const struct tlsph_model *m,
                                       struct tlsph_errors *err)
{
    return tlsph_output_open_with(dir, m, tlsph_output_count_may_change(m), err);
}

struct tlsph_output *tlsph_output_open_with(const char *dir, const struct tlsph_model *m,
                                            int changing_count, struct tlsph_errors *err)
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
    o->count = H5I_INVALID_HID;
    o->n = o->nmax = m->p.n;
    o->changing = changing_count != 0;

    /* HDF5 prints its error stack to stderr by default; library code must not
     * print.  The setting is process-wide (HDF5 keeps one default stack), which
     * suits this engine: every HDF5 call is checked and reported through err
     * or a return value, with the message taken from the stack (add_h5_error).
     * While the file is set up, failures are remembered instead of printed
     * (remember_h5_error); afterwards nothing is called. */
    H5Eset_auto2(H5E_DEFAULT, remember_h5_error, o);
    int created = 0;

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
    o->rows = malloc(TLSPH_SERIES_CHUNK * (o->width ? o->width : 1) * sizeof *o->rows);
    o->row_step = malloc(TLSPH_SERIES_CHUNK * sizeof *o->row_step);
    o->row_time = malloc(TLSPH_SERIES_CHUNK * sizeof *o->row_time);
    o->frame_times_cap = m->scene.frames > 0 ? (size_t)m->scene.frames + 2 : 16;
    o->frame_times = malloc(o->frame_times_cap * sizeof *o->frame_times);
    o->h5_path = join_path(dir, H5_NAME);
    o->xmf_path = join_path(dir, XMF_NAME);
    if (o->changing)
        o->frame_counts = malloc(o->frame_times_cap * sizeof *o->frame_counts);
    if (!o->present || !o->frames || !o->series || !o->rows || !o->row_step || !o->row_time ||
        !o->frame_times || !o->h5_path || !o->xmf_path || (o->changing && !o->frame_counts)) {
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
    o->maxcomp = maxcomp;
    o->scratch_n = o->n;
    if (!(o->scratch = malloc(o->n * (size_t)maxcomp * 8))) {
        tlsph_errors_add(err, "", "output: out of memory (%zu particles)", o->n);
        goto fail;
    }

    if ((fapl = H5Pcreate(H5P_FILE_ACCESS)) < 0 ||
        H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST) < 0 ||
        H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG) < 0) {
        add_h5_error(o, err, "HDF5 setup failed", NULL);
        goto fail;
    }
    if ((o->file = H5Fcreate(o->h5_path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl)) < 0) {
        add_h5_error(o, err, "cannot create", o->h5_path);
        goto fail;
    }
    created = 1;
    if (tlsph_output_layout(o, m) < 0) {
        add_h5_error(o, err, "cannot lay out", o->h5_path);
        goto fail;
    }
    if (H5Fstart_swmr_write(o->file) < 0 || reopen_datasets(o) < 0) {
        add_h5_error(o, err, "cannot start SWMR writing of", o->h5_path);
        goto fail;
    }
    H5Pclose(fapl);
    fapl = H5I_INVALID_HID;
    o->last_series_write = tlsph_monotonic_seconds();
    if (write_sidecar(o) < 0) {
        tlsph_errors_add(err, "", "output: cannot write %s: %s", o->xmf_path, strerror(errno));
        goto fail;
    }
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    return o;
fail:
    if (fapl >= 0)
        H5Pclose(fapl);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* o is about to go */
    discard_output(o, created, err);
    return NULL;
}

/* ------------------------------------------------------------ writing */

/* Makes what was written so far the file's recorded content (see the SWMR
 * rules above). */
static int commit(struct tlsph_output *o)
{
    return H5Fflush(o->file, H5F_SCOPE_LOCAL) < 0 ? -1 : 0;
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
        const struct output_series_value *s = &o->series[i];
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
    /* Computed in the first free row (nrows < TLSPH_SERIES_CHUNK: a full buffer
     * is written at once), so a refused sample leaves the buffer as it was. */
    double *row = o->rows + o->nrows * o->width;
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
    if (tlsph_output_check_series_row(o, row) != 0)
        return TLSPH_OUTPUT_REFUSED;
    if (slot != o->nrows)
        memcpy(o->rows + slot * o->width, row, o->width * sizeof *row);
    o->row_step[slot] = m->step;
    o->row_time[slot] = m->t;
    o->nrows = slot + 1;
    if (o->nrows == TLSPH_SERIES_CHUNK || tlsph_monotonic_seconds() - o->last_series_write >= SERIES_MAX_AGE)
        return flush_series(o) < 0 || commit(o) < 0 ? -1 : 0;
    return 0;
}

/* The layout for changing counts: the scratch holds n particles (grown by a
 * quarter at least, as the particle arrays grow), o->n = n.  0 or -1. */
static int take_count(struct tlsph_output *o, size_t n)
{
    if (n > o->scratch_n) {
        size_t cap = o->scratch_n + o->scratch_n / 4;
        if (cap < n)
            cap = n;
        void *p = realloc(o->scratch, cap * (size_t)o->maxcomp * 8);
        if (!p)
            return -1;
        o->scratch = p;
        o->scratch_n = cap;
    }
    o->n = n;
    return 0;
}

/* Room for one more frame's time (and count). */
static int frame_room(struct tlsph_output *o)
{
    if (o->nframes < o->frame_times_cap)
        return 0;
    const size_t cap = 2 * o->frame_times_cap;
    double *t = realloc(o->frame_times, cap * sizeof *t);
    if (!t)
        return -1;
    o->frame_times = t;
    if (o->changing) {
        size_t *c = realloc(o->frame_counts, cap * sizeof *c);
        if (!c)
            return -1; /* frame_times is larger than needed: harmless */
        o->frame_counts = c;
    }
    o->frame_times_cap = cap;
    return 0;
}

int tlsph_output_frame(struct tlsph_output *o, const struct tlsph_model *m)
{
    if (m->p.n != o->n) {
        /* one count per run: the datasets' second axis is o->n */
        if (!o->changing || m->p.n == 0 || take_count(o, m->p.n) < 0)
            return -1;
    }
    if (frame_room(o) < 0)
        return -1;
    /* Every field is checked before any is written, so a refused frame leaves
     * the file as it was (the values are extracted twice: cheap next to the
     * write). */
    for (size_t i = 0; i < o->nframe_fields; i++) {
        tlsph_output_extract(o, o->frames[i].f, m);
        if (tlsph_output_check_frame_field(o, o->frames[i].f, m) != 0)
            return TLSPH_OUTPUT_REFUSED;
    }
    for (size_t i = 0; i < o->nframe_fields; i++) {
        const struct tlsph_field *f = o->frames[i].f;
        tlsph_output_extract(o, f, m);
        const hid_t mem = tlsph_h5_type(f->type).mem;
        if ((o->changing
                 ? tlsph_h5_append_frame(o->frames[i].value, mem, o->nframes, o->n, o->scratch)
                 : tlsph_h5_append_rows(o->frames[i].value, mem, o->nframes, 1, H5I_INVALID_HID,
                                        o->scratch)) < 0)
            return -1;
    }
    if (o->changing) {
        const int64_t count = (int64_t)o->n;
        if (tlsph_h5_append_rows(o->count, H5T_NATIVE_INT64, o->nframes, 1, H5I_INVALID_HID,
                                 &count) < 0)
            return -1;
        if (o->n > o->nmax)
            o->nmax = o->n;
        o->frame_counts[o->nframes] = o->n;
    }
    if (o->nframe_fields) {
        int64_t step = m->step;
        double t = m->t;
        if (timeline_append(&o->frame_timeline, o->nframes, 1, &step, &t) < 0)
            return -1;
    }
    o->frame_times[o->nframes++] = m->t;
    if (flush_series(o) < 0 || commit(o) < 0)
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

const struct tlsph_output_refusal *tlsph_output_refusal(const struct tlsph_output *o)
{
    return &o->refusal;
}

void tlsph_output_abort(struct tlsph_output *o)
{
    free_output(o);
}
