/* HDF5 datasets of the result file; see h5_dataset.h. */
#include "io/output/h5_dataset.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "io/output/h5_attr.h"

#define DEFLATE_LEVEL 1

/* One row per stored type. */
struct tlsph_h5_type tlsph_h5_type(enum tlsph_field_type t)
{
    switch (t) {
    case TLSPH_FLOAT64: break;
    case TLSPH_FLOAT32: return (struct tlsph_h5_type){H5T_IEEE_F32LE, H5T_NATIVE_FLOAT, 4};
    case TLSPH_INT64: return (struct tlsph_h5_type){H5T_STD_I64LE, H5T_NATIVE_INT64, 8};
    case TLSPH_INT32: return (struct tlsph_h5_type){H5T_STD_I32LE, H5T_NATIVE_INT32, 4};
    }
    return (struct tlsph_h5_type){H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 8};
}

struct h5_message {
    char *text;   /* the outermost message, 256 bytes */
    char sys[96]; /* the system's error text a file driver reported, if any */
};

static herr_t first_error(unsigned n, const H5E_error2_t *e, void *data)
{
    struct h5_message *m = data;
    if (!e->desc)
        return 0;
    if (n == 0)
        snprintf(m->text, 256, "%s (in %s)", e->desc, e->func_name ? e->func_name : "?");
    /* the driver's "file write failed: ..., errno = 28, error message = 'No
     * space left on device', ..." says what the outermost message does not */
    const char *s = strstr(e->desc, "error message = '");
    if (s && !m->sys[0]) {
        s += strlen("error message = '");
        const char *end = strchr(s, '\'');
        const int len = end ? (int)(end - s) : (int)strlen(s);
        snprintf(m->sys, sizeof m->sys, "%.*s", len < 95 ? len : 95, s);
    }
    return 0;
}

void tlsph_h5_stack_text(hid_t estack, char buf[256])
{
    struct h5_message m = {.text = buf};
    buf[0] = '\0';
    H5Ewalk2(estack, H5E_WALK_DOWNWARD, first_error, &m);
    if (buf[0] && m.sys[0]) {
        const size_t used = strlen(buf);
        snprintf(buf + used, 256 - used, ": %s", m.sys);
    }
}

void tlsph_h5_error_text(char buf[256])
{
    tlsph_h5_stack_text(H5E_DEFAULT, buf);
    if (!buf[0])
        snprintf(buf, 256, "unknown HDF5 error");
}

/* A chunked dataset; integer_fill != NULL: its fill value for integer file
 * types (float types keep HDF5's default, 0). */
static hid_t create_chunked(hid_t loc, const char *name, hid_t ftype, int rank,
                            const hsize_t *dims, const hsize_t *maxdims, const hsize_t *chunk,
                            int compress, const int64_t *integer_fill)
{
    hid_t space = H5Screate_simple(rank, dims, maxdims);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    hid_t ds = H5I_INVALID_HID;
    if (space < 0 || dcpl < 0)
        goto done;
    if (H5Pset_chunk(dcpl, rank, chunk) < 0)
        goto done;
    if (integer_fill && H5Tget_class(ftype) == H5T_INTEGER &&
        H5Pset_fill_value(dcpl, H5T_NATIVE_INT64, integer_fill) < 0)
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

hid_t tlsph_h5_chunked(hid_t loc, const char *name, hid_t ftype, int rank, const hsize_t *dims,
                       const hsize_t *maxdims, const hsize_t *chunk, int compress)
{
    return create_chunked(loc, name, ftype, rank, dims, maxdims, chunk, compress, NULL);
}

hid_t tlsph_h5_extendible(hid_t loc, const char *name, hid_t ftype, int rank, const hsize_t *tail,
                          const hsize_t *chunk, int compress)
{
    hsize_t dims[3] = {0, 0, 0}, maxdims[3] = {H5S_UNLIMITED, 0, 0};
    for (int r = 1; r < rank; r++)
        dims[r] = maxdims[r] = tail[r - 1];
    return tlsph_h5_chunked(loc, name, ftype, rank, dims, maxdims, chunk, compress);
}

hid_t tlsph_h5_frames_dataset(hid_t loc, const char *name, hid_t ftype, int ncomp, size_t n0,
                              size_t nchunk, int compress)
{
    const hsize_t dims[3] = {0, n0, (hsize_t)ncomp};
    const hsize_t maxdims[3] = {H5S_UNLIMITED, H5S_UNLIMITED, (hsize_t)ncomp};
    const hsize_t chunk[3] = {1, nchunk, (hsize_t)ncomp};
    const int64_t none = -1; /* integer fields: no particle (ids and bodies are >= 0) */
    return create_chunked(loc, name, ftype, ncomp > 1 ? 3 : 2, dims, maxdims, chunk, compress,
                          &none);
}

int tlsph_h5_string_dataset(hid_t loc, const char *name, const char *text,
                            const char *description)
{
    int rc = -1;
    size_t len = strlen(text);
    /* HDF5 has no zero-length fixed strings: an empty text is stored as " " */
    hid_t type = tlsph_h5_string_type(len ? len : 1, H5T_STR_NULLPAD);
    hid_t space = H5Screate(H5S_SCALAR), ds = H5I_INVALID_HID;
    if (type < 0 || space < 0)
        goto done;
    if ((ds = H5Dcreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT)) < 0)
        goto done;
    if (H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, len ? text : " ") < 0)
        goto done;
    rc = tlsph_h5_attr_string(ds, "description", description);
done:
    if (ds >= 0)
        H5Dclose(ds);
    if (space >= 0)
        H5Sclose(space);
    if (type >= 0)
        H5Tclose(type);
    return rc;
}

/* Extends ds (rank 1..3) to dims and writes the block start .. start + count
 * of buf (memory selection mspace, or contiguous when H5I_INVALID_HID), then
 * flushes ds. */
static int extend_and_write(hid_t ds, hid_t mtype, int rank, const hsize_t *dims,
                            const hsize_t *start, const hsize_t *count, hid_t mspace,
                            const void *buf)
{
    int rc = -1;
    hid_t fspace = H5I_INVALID_HID, ms = H5I_INVALID_HID;
    if (H5Dset_extent(ds, dims) < 0 || (fspace = H5Dget_space(ds)) < 0)
        goto done;
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

/* The rank (lo..3) and current extent of ds; the rank, or -1. */
static int extent(hid_t ds, int lo, hsize_t dims[3])
{
    hid_t fspace = H5Dget_space(ds);
    if (fspace < 0)
        return -1;
    int rank = H5Sget_simple_extent_ndims(fspace);
    if (rank < lo || rank > 3 || H5Sget_simple_extent_dims(fspace, dims, NULL) < 0)
        rank = -1;
    H5Sclose(fspace);
    return rank;
}

int tlsph_h5_append_rows(hid_t ds, hid_t mtype, size_t have, size_t rows, hid_t mspace,
                         const void *buf)
{
    hsize_t dims[3], start[3] = {have, 0, 0}, count[3];
    const int rank = extent(ds, 1, dims);
    if (rank < 0)
        return -1;
    dims[0] = have + rows;
    count[0] = rows;
    for (int r = 1; r < rank; r++)
        count[r] = dims[r];
    return extend_and_write(ds, mtype, rank, dims, start, count, mspace, buf);
}

int tlsph_h5_append_frame(hid_t ds, hid_t mtype, size_t have, size_t n, const void *buf)
{
    hsize_t dims[3], start[3] = {have, 0, 0}, count[3] = {1, n, 0};
    const int rank = extent(ds, 2, dims);
    if (rank < 0)
        return -1;
    dims[0] = have + 1;
    if (dims[1] < n)
        dims[1] = n;
    if (rank == 3)
        count[2] = dims[2];
    return extend_and_write(ds, mtype, rank, dims, start, count, H5I_INVALID_HID, buf);
}
