/* HDF5 helpers of the result readers, see results_h5.h; and the one
 * definition of a valid result name (results.h). */
#include "results_h5.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "results.h"
#include "util/names.h"

#define SERIES_NAME_MAX 200
#define FIELD_NAME_MAX 64


/* The outermost message of the current HDF5 error stack, plus the system error
 * text a file driver reported ("error message = '...'"), if any.  Must be called
 * right after the failing call: every HDF5 API call resets the stack. */
struct h5msg {
    char text[128];
    char sys[96];
};

static herr_t h5_walk_cb(unsigned n, const H5E_error2_t *e, void *data)
{
    struct h5msg *m = data;
    if (!e || !e->desc)
        return 0;
    if (n == 0)
        snprintf(m->text, sizeof m->text, "%s", e->desc);
    const char *p = strstr(e->desc, "error message = '");
    if (p && !m->sys[0]) {
        p += strlen("error message = '");
        const char *q = strchr(p, '\'');
        int len = q ? (int)(q - p) : (int)strlen(p);
        snprintf(m->sys, sizeof m->sys, "%.*s", len, p);
    }
    return 0;
}

void h5r_error(char *err, size_t errsize, const char *what, const char *path)
{
    struct h5msg m = {"", ""};
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, h5_walk_cb, &m);
    errmsg_set(err, errsize, "HDF5: %s %s%s%s%s%s", what, path ? path : "", m.text[0] ? ": " : "",
           m.text, m.sys[0] ? ": " : "", m.sys);
    H5Eclear2(H5E_DEFAULT);
}

void h5r_quiet(void)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

void h5r_close(hid_t *id, herr_t (*fn)(hid_t))
{
    if (*id >= 0)
        fn(*id);
    *id = -1;
}

hid_t h5r_open_file(const char *path, char *err, size_t errsize)
{
    h5r_quiet();
    if (!path || !*path) {
        errmsg_set(err, errsize, "no result file");
        return -1;
    }
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    if (fapl < 0) {
        h5r_error(err, errsize, "cannot create file access list", NULL);
        return -1;
    }
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, fapl);
    if (f < 0)
        h5r_error(err, errsize, "cannot open", path); /* before H5Pclose resets the stack */
    H5Pclose(fapl);
    return f;
}

json_t *h5r_json_real(double v)
{
    return isfinite(v) ? json_real(v) : json_null();
}

/* 1 if every component of path (absolute, "/"-separated) exists as a link,
 * 0 if not, -1 on error. */
int h5r_path_exists(hid_t f, const char *path)
{
    char buf[512];
    size_t len = strlen(path);
    if (len >= sizeof buf)
        return 0;
    memcpy(buf, path, len + 1);
    for (size_t i = 1; i <= len; i++) {
        if (buf[i] == '/' || buf[i] == '\0') {
            char c = buf[i];
            buf[i] = '\0';
            htri_t e = H5Lexists(f, buf, H5P_DEFAULT);
            buf[i] = c;
            if (e < 0)
                return -1;
            if (e == 0)
                return 0;
        }
    }
    return 1;
}


/* Object type at path (OT_*), or -1 on error. */
int h5r_object_type(hid_t f, const char *path)
{
    int e = h5r_path_exists(f, path);
    if (e <= 0)
        return e < 0 ? -1 : OT_ABSENT;
    H5O_info_t info;
    if (H5Oget_info_by_name2(f, path, &info, H5O_INFO_BASIC, H5P_DEFAULT) < 0)
        return -1;
    if (info.type == H5O_TYPE_GROUP)
        return OT_GROUP;
    return info.type == H5O_TYPE_DATASET ? OT_DATASET : OT_OTHER;
}

/* Reads a string attribute (fixed or variable length) into buf; 0 ok, 1 absent, -1 error. */
int h5r_read_str_attr(hid_t obj, const char *name, char *buf, size_t size)
{
    buf[0] = '\0';
    htri_t ex = H5Aexists(obj, name);
    if (ex <= 0)
        return ex < 0 ? -1 : 1;
    int rc = -1;
    hid_t a = H5Aopen(obj, name, H5P_DEFAULT), t = -1, mt = -1;
    if (a < 0)
        goto out;
    t = H5Aget_type(a);
    if (t < 0 || H5Tget_class(t) != H5T_STRING)
        goto out;
    htri_t vl = H5Tis_variable_str(t);
    if (vl < 0)
        goto out;
    if (vl) {
        mt = H5Tcopy(H5T_C_S1);
        if (mt < 0 || H5Tset_size(mt, H5T_VARIABLE) < 0)
            goto out;
        char *s = NULL;
        if (H5Aread(a, mt, &s) < 0)
            goto out;
        snprintf(buf, size, "%s", s ? s : "");
        if (s)
            H5free_memory(s);
    } else {
        size_t n = H5Tget_size(t);
        if (n == 0 || n > 65536)
            goto out;
        char *tmp = calloc(n + 1, 1);
        if (!tmp)
            goto out;
        mt = H5Tcopy(H5T_C_S1);
        if (mt < 0 || H5Tset_size(mt, n + 1) < 0 || H5Tset_strpad(mt, H5T_STR_NULLTERM) < 0 ||
            H5Aread(a, mt, tmp) < 0) {
            free(tmp);
            goto out;
        }
        snprintf(buf, size, "%s", tmp);
        free(tmp);
    }
    rc = 0;
out:
    h5r_close(&mt, H5Tclose);
    h5r_close(&t, H5Tclose);
    h5r_close(&a, H5Aclose);
    return rc;
}

/* Opens dataset path, refreshes it and returns its rank and dims (up to 3). */
hid_t h5r_open_refreshed(hid_t f, const char *path, int *rank, hsize_t dims[3], char *err,
                            size_t errsize)
{
    hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
    if (d < 0) {
        h5r_error(err, errsize, "cannot open dataset", path);
        return -1;
    }
    if (H5Drefresh(d) < 0) {
        h5r_error(err, errsize, "cannot refresh", path);
        H5Dclose(d);
        return -1;
    }
    hid_t s = H5Dget_space(d);
    int r = s >= 0 ? H5Sget_simple_extent_ndims(s) : -1;
    if (r < 1 || r > 3) {
        if (s >= 0)
            H5Sclose(s);
        if (r < 0)
            h5r_error(err, errsize, "cannot get the shape of", path);
        else
            errmsg_set(err, errsize, "dataset %s has unexpected rank %d", path, r);
        H5Dclose(d);
        return -1;
    }
    dims[0] = dims[1] = dims[2] = 1;
    H5Sget_simple_extent_dims(s, dims, NULL);
    H5Sclose(s);
    *rank = r;
    return d;
}

/* Reads rows [0, n) of dataset d (rank >= 1, row shape given by dims[1..]) as mem type. */
int h5r_read_rows(hid_t d, int rank, const hsize_t dims[3], hsize_t n, hid_t mtype, void *buf)
{
    if (n == 0)
        return 0;
    hsize_t start[3] = {0, 0, 0}, count[3] = {n, dims[1], dims[2]};
    hid_t fs = H5Dget_space(d);
    if (fs < 0)
        return -1;
    hid_t ms = H5Screate_simple(rank, count, NULL);
    int rc = -1;
    if (ms >= 0 && H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) >= 0 &&
        H5Dread(d, mtype, ms, fs, H5P_DEFAULT, buf) >= 0)
        rc = 0;
    if (ms >= 0)
        H5Sclose(ms);
    H5Sclose(fs);
    return rc;
}

/* ------------------------------------------------------------ names */

int tres_series_name_ok(const char *name)
{
    if (!name || strnlen(name, SERIES_NAME_MAX + 1) > SERIES_NAME_MAX)
        return 0;
    /* segments between '/', each a name by the engine's rule (util/names.h): no
     * empty, "." or ".." segment can pass */
    for (const char *seg = name;;) {
        const char *slash = strchr(seg, '/');
        const size_t len = slash ? (size_t)(slash - seg) : strlen(seg);
        if (!tlsph_name_ok_n(seg, len))
            return 0;
        if (!slash)
            return 1;
        seg = slash + 1;
    }
}

int tres_field_name_ok(const char *name)
{
    if (!name || !*name || strlen(name) > FIELD_NAME_MAX)
        return 0;
    for (const char *p = name; *p; p++) {
        char c = *p;
        if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
              c == '_'))
            return 0;
    }
    return 1;
}
