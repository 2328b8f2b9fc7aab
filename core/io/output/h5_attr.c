/* HDF5 attributes of the result file; see h5_attr.h. */
#include "io/output/h5_attr.h"

#include <stdlib.h>
#include <string.h>

hid_t tlsph_h5_string_type(size_t size, H5T_str_t pad)
{
    hid_t type = H5Tcopy(H5T_C_S1);
    if (type >= 0 && (H5Tset_size(type, size) < 0 || H5Tset_strpad(type, pad) < 0)) {
        H5Tclose(type);
        return H5I_INVALID_HID;
    }
    return type;
}

int tlsph_h5_attr_values(hid_t obj, const char *name, hid_t ftype, hid_t mtype, size_t count,
                         const void *value)
{
    int rc = -1;
    hsize_t dims[1] = {count};
    hid_t space = count ? H5Screate_simple(1, dims, NULL) : H5Screate(H5S_SCALAR);
    hid_t attr = H5I_INVALID_HID;
    if (space < 0)
        return -1;
    if ((attr = H5Acreate2(obj, name, ftype, space, H5P_DEFAULT, H5P_DEFAULT)) >= 0)
        rc = H5Awrite(attr, mtype, value) < 0 ? -1 : 0;
    if (attr >= 0 && H5Aclose(attr) < 0)
        rc = -1;
    H5Sclose(space);
    return rc;
}

int tlsph_h5_attr_double(hid_t obj, const char *name, double v)
{
    return tlsph_h5_attr_values(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 0, &v);
}

int tlsph_h5_attr_int64(hid_t obj, const char *name, int64_t v)
{
    return tlsph_h5_attr_values(obj, name, H5T_STD_I64LE, H5T_NATIVE_INT64, 0, &v);
}

int tlsph_h5_attr_string_sized(hid_t obj, const char *name, const char *value, size_t size)
{
    size_t len = strlen(value);
    if (size < len + 1)
        size = len + 1;
    char *buf = calloc(size, 1);
    hid_t type = tlsph_h5_string_type(size, H5T_STR_NULLTERM);
    int rc = -1;
    if (buf && type >= 0) {
        memcpy(buf, value, len);
        rc = tlsph_h5_attr_values(obj, name, type, type, 0, buf);
    }
    if (type >= 0)
        H5Tclose(type);
    free(buf);
    return rc;
}

int tlsph_h5_attr_string(hid_t obj, const char *name, const char *value)
{
    return tlsph_h5_attr_string_sized(obj, name, value, 0);
}

int tlsph_h5_describe(hid_t ds, const char *units, const char *description,
                      const char *components)
{
    if (tlsph_h5_attr_string(ds, "units", units ? units : "1") < 0)
        return -1;
    if (description && tlsph_h5_attr_string(ds, "description", description) < 0)
        return -1;
    if (components && tlsph_h5_attr_string(ds, "components", components) < 0)
        return -1;
    return 0;
}

int tlsph_h5_rewrite(hid_t obj, const char *name, hid_t mtype, const void *value)
{
    hid_t attr = H5Aopen(obj, name, H5P_DEFAULT);
    if (attr < 0)
        return -1;
    int rc = H5Awrite(attr, mtype, value) < 0 ? -1 : 0;
    if (H5Aclose(attr) < 0)
        rc = -1;
    return rc;
}

int tlsph_h5_rewrite_string(hid_t obj, const char *name, const char *value)
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
