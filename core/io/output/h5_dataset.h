/* HDF5 datasets as the result file stores them (core/io/output/h5md.c): how
 * each field type is stored, chunked datasets, appending rows to an extendible
 * one, and the text of HDF5's last error.  Functions returning int give 0 or -1,
 * those returning hid_t an id the caller closes or H5I_INVALID_HID; on failure
 * HDF5's error stack says why (tlsph_h5_error_text), and nothing stays open. */
#ifndef TLSPH_H5_DATASET_H
#define TLSPH_H5_DATASET_H

#include <hdf5.h>
#include <stddef.h>

#include "io/fields.h"

/* How a field type is stored: the little-endian file type, the native type
 * the extractors' values are narrowed to, and its size in bytes. */
struct tlsph_h5_type {
    hid_t file, mem;
    size_t size;
};
struct tlsph_h5_type tlsph_h5_type(enum tlsph_field_type t);

/* The innermost message of HDF5's error stack (at most 255 characters);
 * "unknown HDF5 error" when the stack is empty. */
void tlsph_h5_error_text(char buf[256]);
/* The same for error stack estack; buf stays "" when it is empty. */
void tlsph_h5_stack_text(hid_t estack, char buf[256]);

/* A chunked dataset name in loc of file type ftype, rank 1..3, extent dims and
 * maximum extent maxdims (NULL: fixed at dims); compress adds shuffle and
 * deflate. */
hid_t tlsph_h5_chunked(hid_t loc, const char *name, hid_t ftype, int rank, const hsize_t *dims,
                       const hsize_t *maxdims, const hsize_t *chunk, int compress);
/* An empty chunked dataset of rank 1..3 whose first axis is unlimited; tail
 * holds the rank - 1 fixed extents of the other axes. */
hid_t tlsph_h5_extendible(hid_t loc, const char *name, hid_t ftype, int rank, const hsize_t *tail,
                          const hsize_t *chunk, int compress);
/* The value dataset of a field in a file whose particle count changes
 * (docs/output.md, "Changing particle counts"): [0, n0] or [0, n0, ncomp]
 * with both the frame and the particle axis unlimited, chunks [1, nchunk(,
 * ncomp)], fill value 0 for float types and -1 for integer types (the
 * entries past a frame's count). */
hid_t tlsph_h5_frames_dataset(hid_t loc, const char *name, hid_t ftype, int ncomp, size_t n0,
                              size_t nchunk, int compress);
/* A scalar fixed-length string dataset (no size limit, unlike compact
 * attributes) with a "description" attribute. */
int tlsph_h5_string_dataset(hid_t loc, const char *name, const char *text,
                            const char *description);
/* Extends ds (rank 1..3, first axis unlimited) from `have` to have + rows and
 * writes rows rows of buf (memory type mtype), then flushes ds.  mspace
 * H5I_INVALID_HID: buf is contiguous for the new rows; else mspace is the
 * memory selection (with as many elements). */
int tlsph_h5_append_rows(hid_t ds, hid_t mtype, size_t have, size_t rows, hid_t mspace,
                         const void *buf);

/* A dataset of tlsph_h5_frames_dataset: extends ds to have + 1 frames and
 * at least n particles and writes frame `have`'s first n particles from buf
 * (contiguous, memory type mtype), then flushes ds.  Particles past n keep
 * the fill value. */
int tlsph_h5_append_frame(hid_t ds, hid_t mtype, size_t have, size_t n, const void *buf);

#endif
