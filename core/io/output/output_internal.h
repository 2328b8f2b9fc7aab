/* Internal interface between the files of the result-file writer: h5md.c
 * (open, frames, series, close) and layout.c (every group, dataset and
 * attribute, created before SWMR writing starts).  Not part of the engine's
 * API: the engine sees only core/io/output/output.h. */
#ifndef TLSPH_OUTPUT_INTERNAL_H
#define TLSPH_OUTPUT_INTERNAL_H

#include <hdf5.h>
#include <stdint.h>

#include "io/fields.h"
#include "io/output/output.h"

#define TLSPH_SERIES_CHUNK 1024   /* rows per series chunk and per memory buffer */
#define TLSPH_OUTPUT_PATH_MAX 256 /* bytes of a frame field's or timeline's path */

/* The step and time datasets of a family of elements (the frame fields, or
 * the series columns): created in the family's first group, hard-linked into
 * the others, as LAMMPS' dump h5md does. */
struct output_timeline {
    char step_path[TLSPH_OUTPUT_PATH_MAX], time_path[TLSPH_OUTPUT_PATH_MAX]; /* "" until created */
    hid_t step, time; /* open once SWMR writing has started */
};

struct output_frame_value {
    const struct tlsph_field *f;
    hid_t value;
};

struct output_series_value {
    char *path;       /* of the value dataset, for reopening after SWMR starts */
    int ncomp;
    size_t offset;    /* first column of this series in a buffered row */
    hid_t value;
};

struct tlsph_output {
    hid_t file;
    size_t n;            /* particles of the model at the last frame (at open before) */
    /* The layout for changing counts (output.h): every field per frame and
     * /particles/solid/count; nmax is the particle extent of the value
     * datasets (the largest count so far), frame_counts each frame's count. */
    int changing;
    size_t nmax;
    size_t *frame_counts; /* [frame_times_cap]; NULL with one count */
    hid_t count;          /* /particles/solid/count/value, open after SWMR starts */
    size_t scratch_n;     /* particles o->scratch holds (maxcomp values each) */
    int maxcomp;
    char *h5_path, *xmf_path;
    /* the first HDF5 failure while the file is set up (tlsph_output_open): the
     * error stack of a failing call is gone once its clean-up calls ran */
    char first_h5_error[256];

    /* every present field, for the XDMF sidecar */
    const struct tlsph_field **present;
    size_t npresent;

    struct output_frame_value *frames;
    size_t nframe_fields;
    struct output_timeline frame_timeline;
    size_t nframes;
    double *frame_times;
    size_t frame_times_cap;
    void *scratch; /* n * max ncomp * 8 bytes */

    struct output_series_value *series;
    size_t nseries;
    struct output_timeline series_timeline;
    size_t width;        /* doubles per buffered row */
    double *rows;        /* [TLSPH_SERIES_CHUNK][width] */
    int64_t *row_step;
    double *row_time;
    size_t nrows;
    size_t nsamples;     /* rows written to the file */
    int64_t last_step_written;
    double last_series_write;
    double last_xmf_write;    /* wall clock of the last sidecar rewrite, s */

    struct tlsph_output_refusal refusal; /* the last value refused (finite.c) */
};

/* layout.c: creates everything in o->file (open, nothing created yet): /h5md,
 * /parameters, /particles (writing the reference fields, filling o->frames),
 * /observables (filling o->series), /cost and /diagnostics.  The frame and
 * series value datasets and the timelines stay closed.  Returns 0 or -1. */
int tlsph_output_layout(struct tlsph_output *o, const struct tlsph_model *m);

/* h5md.c: the values of field f into o->scratch, in the memory layout of its
 * file type. */
void tlsph_output_extract(struct tlsph_output *o, const struct tlsph_field *f,
                          const struct tlsph_model *m);

/* finite.c: the guard that keeps every dataset finite (output.h).  Each returns
 * 0 when every value may be stored, else fills o->refusal and returns
 * TLSPH_OUTPUT_REFUSED.  frame_field: f's values in o->scratch, as extracted;
 * series_row: one buffered row of o->width doubles. */
int tlsph_output_check_frame_field(struct tlsph_output *o, const struct tlsph_field *f,
                                   const struct tlsph_model *m);
int tlsph_output_check_series_row(struct tlsph_output *o, const double *row);

#endif
