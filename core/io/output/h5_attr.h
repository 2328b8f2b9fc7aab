/* HDF5 attributes as the result file writes them (core/io/output/h5md.c and
 * records.c).  Each function returns 0 or -1 (HDF5's error stack then says
 * why) and closes what it opened on every path.
 *
 * Strings are fixed-length, null-terminated ASCII: SWMR cannot rewrite
 * variable-length data, and a fixed length lets a value be rewritten in place. */
#ifndef TLSPH_H5_ATTR_H
#define TLSPH_H5_ATTR_H

#include <hdf5.h>
#include <stddef.h>
#include <stdint.h>

/* A fixed-length ASCII string type of size bytes; the caller closes it
 * (H5Tclose).  H5I_INVALID_HID on failure. */
hid_t tlsph_h5_string_type(size_t size, H5T_str_t pad);

/* Attribute name of obj with file type ftype, a scalar when count == 0, else a
 * 1-D array of count; value is in memory type mtype. */
int tlsph_h5_attr_values(hid_t obj, const char *name, hid_t ftype, hid_t mtype, size_t count,
                         const void *value);
int tlsph_h5_attr_double(hid_t obj, const char *name, double v);
int tlsph_h5_attr_int64(hid_t obj, const char *name, int64_t v);
/* A string attribute of at least size bytes, so that a later value of up to
 * size - 1 bytes can replace it (tlsph_h5_rewrite_string). */
int tlsph_h5_attr_string_sized(hid_t obj, const char *name, const char *value, size_t size);
int tlsph_h5_attr_string(hid_t obj, const char *name, const char *value);
/* The units (NULL: "1"), description and components attributes of a dataset;
 * NULL description or components are left out. */
int tlsph_h5_describe(hid_t ds, const char *units, const char *description,
                      const char *components);

/* Rewrite an existing attribute in place, as SWMR allows: same type and size.
 * A string longer than the attribute holds is truncated to fit. */
int tlsph_h5_rewrite(hid_t obj, const char *name, hid_t mtype, const void *value);
int tlsph_h5_rewrite_string(hid_t obj, const char *name, const char *value);

#endif
