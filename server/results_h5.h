/* Inside the result readers (server/results_h5.h): the HDF5 helpers that
 * results.c (time series) and results_field.c (fields and frames) share,
 * defined in results_h5.c.  Every id opened is closed on every path; HDF5's
 * own error printing is off and its failures become messages in err. */
#ifndef TLSPHD_RESULTS_H5_H
#define TLSPHD_RESULTS_H5_H

#include <hdf5.h>
#include <jansson.h>
#include <stddef.h>

/* h5r_object_type answers */
enum { OT_ABSENT = 0, OT_GROUP = 1, OT_DATASET = 2, OT_OTHER = 3 };

/* err = "HDF5: what path: <the library's message>", taken from the current
 * error stack (call right after the failing call). */
void h5r_error(char *err, size_t errsize, const char *what, const char *path);
/* Switches HDF5's own error printing off. */
void h5r_quiet(void);
/* Closes *id with fn when open, then marks it closed. */
void h5r_close(hid_t *id, herr_t (*fn)(hid_t));
/* Opens a result file read-only in SWMR mode; -1 with err. */
hid_t h5r_open_file(const char *path, char *err, size_t errsize);
/* A JSON real, or null when v is not finite. */
json_t *h5r_json_real(double v);
/* 1 when every link of the absolute path exists, 0 if not, -1 error. */
int h5r_path_exists(hid_t f, const char *path);
/* The object at path (OT_*), or -1 on error. */
int h5r_object_type(hid_t f, const char *path);
/* A string attribute into buf: 0 ok, 1 absent, -1 error. */
int h5r_read_str_attr(hid_t obj, const char *name, char *buf, size_t size);
/* Opens a dataset of rank 1..3, refreshed (SWMR), with its current dims; -1 with err. */
hid_t h5r_open_refreshed(hid_t f, const char *path, int *rank, hsize_t dims[3], char *err,
                         size_t errsize);
/* The first n rows of an open dataset into buf as mtype: 0 or -1. */
int h5r_read_rows(hid_t d, int rank, const hsize_t dims[3], hsize_t n, hid_t mtype, void *buf);

#endif
