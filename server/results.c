/* Reading results for the API, see results.h.
 *
 * Every public function opens the file itself (H5F_ACC_RDONLY | H5F_ACC_SWMR_READ:
 * works on a file the engine is writing in SWMR mode and on a closed file),
 * refreshes each dataset before looking at its shape, bounds row and frame
 * counts by the length of the `step` dataset (the writer's commit marker) and
 * closes every id it opened on every path.  HDF5's own error printing is
 * switched off; HDF5 failures become messages in err.
 *
 * Names from the outside are checked before they reach HDF5: series names
 * [A-Za-z0-9_./-] (no "..", no empty or "." segment, no leading or trailing
 * "/", at most 200 characters), field names [A-Za-z0-9_] (at most 64). */
#include "results.h"

#include <hdf5.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "strbuf.h"

#define SERIES_NAME_MAX 200
#define FIELD_NAME_MAX 64

/* ------------------------------------------------------------ small helpers */

static void seterr(char *err, size_t errsize, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static void seterr(char *err, size_t errsize, const char *fmt, ...)
{
    if (!err || errsize == 0)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errsize, fmt, ap);
    va_end(ap);
}

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

static void seterr_h5(char *err, size_t errsize, const char *what, const char *path)
{
    struct h5msg m = {"", ""};
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, h5_walk_cb, &m);
    seterr(err, errsize, "HDF5: %s %s%s%s%s%s", what, path ? path : "", m.text[0] ? ": " : "",
           m.text, m.sys[0] ? ": " : "", m.sys);
    H5Eclear2(H5E_DEFAULT);
}

static void h5_quiet(void)
{
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
}

static void close_id(hid_t *id, herr_t (*fn)(hid_t))
{
    if (*id >= 0)
        fn(*id);
    *id = -1;
}

static hid_t open_file(const char *path, char *err, size_t errsize)
{
    h5_quiet();
    if (!path || !*path) {
        seterr(err, errsize, "no result file");
        return -1;
    }
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    if (fapl < 0) {
        seterr_h5(err, errsize, "cannot create file access list", NULL);
        return -1;
    }
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, fapl);
    if (f < 0)
        seterr_h5(err, errsize, "cannot open", path); /* before H5Pclose resets the stack */
    H5Pclose(fapl);
    return f;
}

static json_t *jreal(double v)
{
    return isfinite(v) ? json_real(v) : json_null();
}

/* 1 if every component of path (absolute, "/"-separated) exists as a link,
 * 0 if not, -1 on error. */
static int path_exists(hid_t f, const char *path)
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

enum { OT_ABSENT = 0, OT_GROUP = 1, OT_DATASET = 2, OT_OTHER = 3 };

/* Object type at path (OT_*), or -1 on error. */
static int object_type(hid_t f, const char *path)
{
    int e = path_exists(f, path);
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
static int read_str_attr(hid_t obj, const char *name, char *buf, size_t size)
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
    close_id(&mt, H5Tclose);
    close_id(&t, H5Tclose);
    close_id(&a, H5Aclose);
    return rc;
}

/* Opens dataset path, refreshes it and returns its rank and dims (up to 3). */
static hid_t open_refreshed(hid_t f, const char *path, int *rank, hsize_t dims[3], char *err,
                            size_t errsize)
{
    hid_t d = H5Dopen2(f, path, H5P_DEFAULT);
    if (d < 0) {
        seterr_h5(err, errsize, "cannot open dataset", path);
        return -1;
    }
    if (H5Drefresh(d) < 0) {
        seterr_h5(err, errsize, "cannot refresh", path);
        H5Dclose(d);
        return -1;
    }
    hid_t s = H5Dget_space(d);
    int r = s >= 0 ? H5Sget_simple_extent_ndims(s) : -1;
    if (r < 1 || r > 3) {
        if (s >= 0)
            H5Sclose(s);
        if (r < 0)
            seterr_h5(err, errsize, "cannot get the shape of", path);
        else
            seterr(err, errsize, "dataset %s has unexpected rank %d", path, r);
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
static int read_rows(hid_t d, int rank, const hsize_t dims[3], hsize_t n, hid_t mtype, void *buf)
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
    if (!name || !*name)
        return 0;
    size_t len = strlen(name);
    if (len > SERIES_NAME_MAX || name[0] == '/' || name[len - 1] == '/' || strstr(name, ".."))
        return 0;
    for (size_t i = 0; i < len; i++) {
        char c = name[i];
        int ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                 c == '_' || c == '.' || c == '/' || c == '-';
        if (!ok)
            return 0;
        /* no empty and no "." segments */
        if (c == '/' && name[i + 1] == '/')
            return 0;
        if (c == '.' && (i == 0 || name[i - 1] == '/') && (name[i + 1] == '/' || name[i + 1] == '\0'))
            return 0;
    }
    return 1;
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

/* ------------------------------------------------------------ series */

struct series {
    size_t rows;
    int ncomp; /* 0 = scalar series ([T]), else components of [T, C] */
    int64_t *step;
    double *time;
    double *value; /* rows * max(ncomp, 1) */
    char units[32];
    char components[64];
};

static void series_free(struct series *s)
{
    free(s->step);
    free(s->time);
    free(s->value);
    memset(s, 0, sizeof *s);
}

/* Reads series `name` (already validated).  0 ok, 1 not found, -1 error. */
static int series_read(hid_t f, const char *name, struct series *s, int want_data, char *err,
                       size_t errsize)
{
    memset(s, 0, sizeof *s);
    char base[256], p_step[272], p_time[272], p_value[272];
    snprintf(base, sizeof base, "/observables/%s", name);
    snprintf(p_step, sizeof p_step, "%s/step", base);
    snprintf(p_time, sizeof p_time, "%s/time", base);
    snprintf(p_value, sizeof p_value, "%s/value", base);

    int t = object_type(f, base);
    if (t < 0) {
        seterr_h5(err, errsize, "cannot look up", base);
        return -1;
    }
    if (t != OT_GROUP)
        return 1;
    int tv = object_type(f, p_value), ts = object_type(f, p_step), tt = object_type(f, p_time);
    if (tv < 0 || ts < 0 || tt < 0) {
        seterr_h5(err, errsize, "cannot look up", base);
        return -1;
    }
    if (tv != OT_DATASET || ts != OT_DATASET || tt != OT_DATASET)
        return 1;

    int rc = -1, rs, rt, rv;
    hsize_t ds[3], dt[3], dv[3];
    /* step first: it is the commit marker */
    hid_t d_step = open_refreshed(f, p_step, &rs, ds, err, errsize);
    hid_t d_time = d_step >= 0 ? open_refreshed(f, p_time, &rt, dt, err, errsize) : -1;
    hid_t d_val = d_time >= 0 ? open_refreshed(f, p_value, &rv, dv, err, errsize) : -1;
    if (d_val < 0)
        goto out;
    if (rs != 1 || rt != 1 || rv > 2) {
        seterr(err, errsize, "series %s has an unexpected shape", name);
        goto out;
    }
    hsize_t n = ds[0];
    if (dt[0] < n)
        n = dt[0];
    if (dv[0] < n)
        n = dv[0];
    s->rows = (size_t)n;
    s->ncomp = rv == 2 ? (int)dv[1] : 0;
    if (rv == 2 && (dv[1] < 1 || dv[1] > 16)) {
        seterr(err, errsize, "series %s has %llu components", name, (unsigned long long)dv[1]);
        goto out;
    }
    if (read_str_attr(d_val, "units", s->units, sizeof s->units) < 0 ||
        read_str_attr(d_val, "components", s->components, sizeof s->components) < 0) {
        seterr_h5(err, errsize, "cannot read attributes of", p_value);
        goto out;
    }
    if (want_data) {
        size_t nc = s->ncomp ? (size_t)s->ncomp : 1;
        s->step = malloc((s->rows ? s->rows : 1) * sizeof *s->step);
        s->time = malloc((s->rows ? s->rows : 1) * sizeof *s->time);
        s->value = malloc((s->rows ? s->rows : 1) * nc * sizeof *s->value);
        if (!s->step || !s->time || !s->value) {
            seterr(err, errsize, "out of memory reading series %s", name);
            goto out;
        }
        if (read_rows(d_step, 1, ds, n, H5T_NATIVE_INT64, s->step) < 0 ||
            read_rows(d_time, 1, dt, n, H5T_NATIVE_DOUBLE, s->time) < 0 ||
            read_rows(d_val, rv, dv, n, H5T_NATIVE_DOUBLE, s->value) < 0) {
            seterr_h5(err, errsize, "cannot read series", name);
            goto out;
        }
    }
    rc = 0;
out:
    close_id(&d_val, H5Dclose);
    close_id(&d_time, H5Dclose);
    close_id(&d_step, H5Dclose);
    if (rc != 0)
        series_free(s);
    return rc;
}

/* "x y z" -> ["x","y","z"]; null for a scalar series. */
static json_t *components_json(const struct series *s)
{
    if (!s->ncomp)
        return json_null();
    json_t *a = json_array();
    char buf[64];
    snprintf(buf, sizeof buf, "%s", s->components);
    char *save = NULL;
    for (char *tok = strtok_r(buf, " ", &save); tok; tok = strtok_r(NULL, " ", &save))
        json_array_append_new(a, json_string(tok));
    if (json_array_size(a) != (size_t)s->ncomp) {
        json_array_clear(a);
        for (int c = 0; c < s->ncomp; c++) {
            char idx[16];
            snprintf(idx, sizeof idx, "%d", c);
            json_array_append_new(a, json_string(idx));
        }
    }
    return a;
}

static void list_add(hid_t f, json_t *out, const char *name)
{
    struct series s;
    char e[8];
    if (series_read(f, name, &s, 0, e, sizeof e) != 0)
        return; /* not a series (e.g. a group without value) */
    json_t *o = json_object();
    json_object_set_new(o, "name", json_string(name));
    json_object_set_new(o, "units", json_string(s.units));
    json_object_set_new(o, "components", components_json(&s));
    json_array_append_new(out, o);
    series_free(&s);
}

/* Link names of group path in creation order (falls back to name order). */
static int group_names(hid_t f, const char *path, char ***names, size_t *n)
{
    *names = NULL;
    *n = 0;
    hid_t g = H5Gopen2(f, path, H5P_DEFAULT);
    if (g < 0)
        return -1;
    H5G_info_t gi;
    if (H5Gget_info(g, &gi) < 0) {
        H5Gclose(g);
        return -1;
    }
    char **v = calloc(gi.nlinks ? gi.nlinks : 1, sizeof *v);
    if (!v) {
        H5Gclose(g);
        return -1;
    }
    H5_index_t idx = H5_INDEX_CRT_ORDER;
    for (hsize_t i = 0; i < gi.nlinks; i++) {
        ssize_t len = H5Lget_name_by_idx(g, ".", idx, H5_ITER_INC, i, NULL, 0, H5P_DEFAULT);
        if (len < 0 && idx == H5_INDEX_CRT_ORDER && i == 0) {
            H5Eclear2(H5E_DEFAULT);
            idx = H5_INDEX_NAME;
            len = H5Lget_name_by_idx(g, ".", idx, H5_ITER_INC, i, NULL, 0, H5P_DEFAULT);
        }
        if (len < 0 || len > 1024)
            continue;
        v[*n] = malloc((size_t)len + 1);
        if (!v[*n])
            continue;
        H5Lget_name_by_idx(g, ".", idx, H5_ITER_INC, i, v[*n], (size_t)len + 1, H5P_DEFAULT);
        (*n)++;
    }
    H5Gclose(g);
    *names = v;
    return 0;
}

static void names_free(char **v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(v[i]);
    free(v);
}

json_t *tres_series_list(const char *h5path, char *err, size_t errsize)
{
    hid_t f = open_file(h5path, err, errsize);
    if (f < 0)
        return NULL;
    json_t *out = json_array();
    char **top = NULL;
    size_t ntop = 0;
    int t = object_type(f, "/observables");
    if (t < 0) {
        seterr_h5(err, errsize, "cannot look up", "/observables");
        goto fail;
    }
    if (t != OT_GROUP)
        goto done; /* no series at all */
    if (group_names(f, "/observables", &top, &ntop) < 0) {
        seterr_h5(err, errsize, "cannot list", "/observables");
        goto fail;
    }
    for (size_t i = 0; i < ntop; i++) {
        if (strcmp(top[i], "groups") == 0 || !tres_series_name_ok(top[i]))
            continue;
        list_add(f, out, top[i]);
    }
    if (object_type(f, "/observables/groups") == OT_GROUP) {
        char **bcs = NULL;
        size_t nbc = 0;
        if (group_names(f, "/observables/groups", &bcs, &nbc) == 0) {
            for (size_t b = 0; b < nbc; b++) {
                char gpath[512];
                if (!tres_series_name_ok(bcs[b]) || strchr(bcs[b], '/'))
                    continue;
                snprintf(gpath, sizeof gpath, "/observables/groups/%s", bcs[b]);
                if (object_type(f, gpath) != OT_GROUP)
                    continue;
                char **cols = NULL;
                size_t ncol = 0;
                if (group_names(f, gpath, &cols, &ncol) < 0)
                    continue;
                for (size_t c = 0; c < ncol; c++) {
                    char name[512];
                    snprintf(name, sizeof name, "groups/%s/%s", bcs[b], cols[c]);
                    if (tres_series_name_ok(name))
                        list_add(f, out, name);
                }
                names_free(cols, ncol);
            }
            names_free(bcs, nbc);
        }
        H5Eclear2(H5E_DEFAULT);
    }
done:
    names_free(top, ntop);
    H5Fclose(f);
    return out;
fail:
    names_free(top, ntop);
    json_decref(out);
    H5Fclose(f);
    return NULL;
}

/* Opens, validates and reads series name.  0 ok, 1 not found, -1 error. */
static int series_load(const char *h5path, const char *name, struct series *s, char *err,
                       size_t errsize)
{
    memset(s, 0, sizeof *s);
    if (!tres_series_name_ok(name)) {
        seterr(err, errsize, TRES_NO_SERIES, name ? name : "");
        return 1;
    }
    hid_t f = open_file(h5path, err, errsize);
    if (f < 0)
        return -1;
    int rc = series_read(f, name, s, 1, err, errsize);
    if (rc == 1)
        seterr(err, errsize, "no series named \"%s\"", name);
    H5Fclose(f);
    return rc;
}

json_t *tres_series(const char *h5path, const char *name, int *not_found, char *err,
                    size_t errsize)
{
    if (not_found)
        *not_found = 0;
    struct series s;
    int rc = series_load(h5path, name, &s, err, errsize);
    if (rc != 0) {
        if (rc == 1 && not_found)
            *not_found = 1;
        return NULL;
    }
    json_t *o = json_object(), *step = json_array(), *time = json_array(), *value = json_array();
    for (size_t i = 0; i < s.rows; i++) {
        json_array_append_new(step, json_integer((json_int_t)s.step[i]));
        json_array_append_new(time, jreal(s.time[i]));
        if (s.ncomp) {
            json_t *row = json_array();
            for (int c = 0; c < s.ncomp; c++)
                json_array_append_new(row, jreal(s.value[i * (size_t)s.ncomp + (size_t)c]));
            json_array_append_new(value, row);
        } else {
            json_array_append_new(value, jreal(s.value[i]));
        }
    }
    json_object_set_new(o, "name", json_string(name));
    json_object_set_new(o, "units", json_string(s.units));
    json_object_set_new(o, "components", components_json(&s));
    json_object_set_new(o, "step", step);
    json_object_set_new(o, "time", time);
    json_object_set_new(o, "value", value);
    series_free(&s);
    return o;
}

static void sb_num(struct strbuf *b, double v)
{
    if (isfinite(v))
        strbuf_printf(b, ",%.17g", v);
    else
        strbuf_printf(b, ",%s", isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf"));
}

char *tres_series_csv(const char *h5path, const char *name, int *not_found, char *err,
                      size_t errsize)
{
    if (not_found)
        *not_found = 0;
    struct series s;
    int rc = series_load(h5path, name, &s, err, errsize);
    if (rc != 0) {
        if (rc == 1 && not_found)
            *not_found = 1;
        return NULL;
    }
    const char *col = strrchr(name, '/');
    col = col ? col + 1 : name;
    struct strbuf b = {0};
    strbuf_printf(&b, "step,time");
    if (s.ncomp) {
        json_t *comps = components_json(&s);
        for (size_t c = 0; c < json_array_size(comps); c++)
            strbuf_printf(&b, ",%s_%s", col, json_string_value(json_array_get(comps, c)));
        json_decref(comps);
    } else {
        strbuf_printf(&b, ",%s", col);
    }
    strbuf_printf(&b, "\n");
    size_t nc = s.ncomp ? (size_t)s.ncomp : 1;
    for (size_t i = 0; i < s.rows; i++) {
        strbuf_printf(&b, "%lld", (long long)s.step[i]);
        sb_num(&b, s.time[i]);
        for (size_t c = 0; c < nc; c++)
            sb_num(&b, s.value[i * nc + c]);
        strbuf_printf(&b, "\n");
    }
    series_free(&s);
    char *csv = strbuf_take(&b);
    if (!csv)
        seterr(err, errsize, "out of memory writing CSV");
    return csv;
}

enum tres_rc tres_series_reduce(const char *h5path, const char *name, int component,
                                double *final, double *max, double *min, char *err,
                                size_t errsize)
{
    double fv = NAN, mx = NAN, mn = NAN;
    struct series s;
    int rc = series_load(h5path, name, &s, err, errsize);
    if (rc != 0)
        return rc;
    int nc = s.ncomp ? s.ncomp : 1;
    if (component < -1 || component >= nc) {
        seterr(err, errsize, "series %s has no component %d", name, component);
        series_free(&s);
        return 1;
    }
    for (size_t i = 0; i < s.rows; i++) {
        const double *row = s.value + i * (size_t)nc;
        double v;
        if (component >= 0) {
            v = row[component];
        } else {
            double sum = 0;
            for (int c = 0; c < nc; c++)
                sum += row[c] * row[c];
            v = sqrt(sum);
        }
        fv = v;
        if (!isnan(v)) {
            if (isnan(mx) || v > mx)
                mx = v;
            if (isnan(mn) || v < mn)
                mn = v;
        }
    }
    series_free(&s);
    if (final)
        *final = fv;
    if (max)
        *max = mx;
    if (min)
        *min = mn;
    return 0;
}

/* ------------------------------------------------------------ fields */

static int host_is_le(void)
{
    const uint16_t one = 1;
    unsigned char c;
    memcpy(&c, &one, 1);
    return c == 1;
}

/* Reads the frame count (length of the shared frame `step`, refreshed). */
static int frame_count(hid_t f, long *frames, char *err, size_t errsize)
{
    *frames = 0;
    int t = object_type(f, "/particles/solid/position/step");
    if (t < 0) {
        seterr_h5(err, errsize, "cannot look up", "/particles/solid/position/step");
        return -1;
    }
    if (t != OT_DATASET)
        return 0;
    int r;
    hsize_t d[3];
    hid_t ds = open_refreshed(f, "/particles/solid/position/step", &r, d, err, errsize);
    if (ds < 0)
        return -1;
    *frames = (long)d[0];
    H5Dclose(ds);
    return 0;
}

void tres_field_free(struct tres_field *f)
{
    if (!f)
        return;
    free(f->data);
    f->data = NULL;
    f->bytes = 0;
}

enum tres_rc tres_field(const char *h5path, const char *name, long frame,
                        struct tres_field *out, char *err, size_t errsize)
{
    memset(out, 0, sizeof *out);
    out->dtype = "<f8";
    out->time = NAN;
    out->step = -1;
    if (!tres_field_name_ok(name)) {
        seterr(err, errsize, TRES_NO_FIELD, name ? name : "");
        return 1;
    }
    hid_t f = open_file(h5path, err, errsize);
    if (f < 0)
        return -1;

    int rc = -1;
    hid_t d_val = -1, d_step = -1, d_time = -1, ftype = -1, fs = -1, ms = -1;
    char base[128], p_val[160], p_step[160], p_time[160];
    snprintf(base, sizeof base, "/particles/solid/%s", name);
    int t = object_type(f, base);
    if (t < 0) {
        seterr_h5(err, errsize, "cannot look up", base);
        goto out;
    }
    int is_frame;
    if (t == OT_DATASET) {
        is_frame = 0;
        snprintf(p_val, sizeof p_val, "%s", base);
    } else if (t == OT_GROUP) {
        is_frame = 1;
        snprintf(p_val, sizeof p_val, "%s/value", base);
        snprintf(p_step, sizeof p_step, "%s/step", base);
        snprintf(p_time, sizeof p_time, "%s/time", base);
        int a = object_type(f, p_val), b = object_type(f, p_step), c = object_type(f, p_time);
        if (a < 0 || b < 0 || c < 0) {
            seterr_h5(err, errsize, "cannot look up", base);
            goto out;
        }
        if (a != OT_DATASET || b != OT_DATASET || c != OT_DATASET) {
            seterr(err, errsize, "no field named \"%s\"", name);
            rc = 1;
            goto out;
        }
    } else {
        seterr(err, errsize, "no field named \"%s\"", name);
        rc = 1;
        goto out;
    }

    int rs = 0, rt = 0, rv;
    hsize_t ds[3], dt[3], dv[3];
    long k = 0;
    if (is_frame) {
        d_step = open_refreshed(f, p_step, &rs, ds, err, errsize);
        if (d_step < 0)
            goto out;
        d_time = open_refreshed(f, p_time, &rt, dt, err, errsize);
        if (d_time < 0)
            goto out;
    }
    d_val = open_refreshed(f, p_val, &rv, dv, err, errsize);
    if (d_val < 0)
        goto out;

    hsize_t n_rows, ncomp;
    if (is_frame) {
        if (rs != 1 || rt != 1 || rv < 2) {
            seterr(err, errsize, "field %s has an unexpected shape", name);
            goto out;
        }
        hsize_t frames = ds[0];
        if (dt[0] < frames)
            frames = dt[0];
        if (dv[0] < frames)
            frames = dv[0];
        out->frames = (long)frames;
        k = frame < 0 ? (long)frames + frame : frame;
        if (k < 0 || (hsize_t)k >= frames) {
            seterr(err, errsize, "no frame %ld of field %s (%ld frames)", frame, name,
                   (long)frames);
            rc = 2;
            goto out;
        }
        n_rows = dv[1];
        ncomp = rv == 3 ? dv[2] : 1;
        /* step and time of the frame */
        int64_t stepv;
        double timev;
        hsize_t one = 1, start = (hsize_t)k;
        hid_t s1 = H5Dget_space(d_step), s2 = H5Dget_space(d_time), m1 = H5Screate_simple(1, &one, NULL);
        int ok = s1 >= 0 && s2 >= 0 && m1 >= 0 &&
                 H5Sselect_hyperslab(s1, H5S_SELECT_SET, &start, NULL, &one, NULL) >= 0 &&
                 H5Sselect_hyperslab(s2, H5S_SELECT_SET, &start, NULL, &one, NULL) >= 0 &&
                 H5Dread(d_step, H5T_NATIVE_INT64, m1, s1, H5P_DEFAULT, &stepv) >= 0 &&
                 H5Dread(d_time, H5T_NATIVE_DOUBLE, m1, s2, H5P_DEFAULT, &timev) >= 0;
        if (s1 >= 0)
            H5Sclose(s1);
        if (s2 >= 0)
            H5Sclose(s2);
        if (m1 >= 0)
            H5Sclose(m1);
        if (!ok) {
            seterr_h5(err, errsize, "cannot read step/time of", base);
            goto out;
        }
        out->step = (long)stepv;
        out->time = timev;
    } else {
        if (rv > 2) {
            seterr(err, errsize, "field %s has an unexpected shape", name);
            goto out;
        }
        n_rows = dv[0];
        ncomp = rv == 2 ? dv[1] : 1;
        if (frame_count(f, &out->frames, err, errsize) < 0)
            goto out;
        out->step = 0;
        out->time = 0.0; /* the reference configuration */
    }
    if (ncomp < 1 || ncomp > 16) {
        seterr(err, errsize, "field %s has %llu components", name, (unsigned long long)ncomp);
        goto out;
    }

    /* memory type: little-endian, float32 stays float32 */
    ftype = H5Dget_type(d_val);
    if (ftype < 0) {
        seterr_h5(err, errsize, "cannot get the type of", p_val);
        goto out;
    }
    H5T_class_t cls = H5Tget_class(ftype);
    size_t fsize = H5Tget_size(ftype);
    hid_t mtype;
    size_t esize;
    if (cls == H5T_FLOAT) {
        if (fsize <= 4) {
            mtype = H5T_IEEE_F32LE, esize = 4, out->dtype = "<f4";
        } else {
            mtype = H5T_IEEE_F64LE, esize = 8, out->dtype = "<f8";
        }
    } else if (cls == H5T_INTEGER) {
        H5T_sign_t sg = H5Tget_sign(ftype);
        if (fsize <= 4 && !(fsize == 4 && sg == H5T_SGN_NONE)) {
            mtype = H5T_STD_I32LE, esize = 4, out->dtype = "<i4";
        } else {
            mtype = H5T_STD_I64LE, esize = 8, out->dtype = "<i8";
        }
    } else {
        seterr(err, errsize, "field %s has an unsupported type", name);
        goto out;
    }

    if (read_str_attr(d_val, "units", out->units, sizeof out->units) < 0) {
        seterr_h5(err, errsize, "cannot read the units of", p_val);
        goto out;
    }
    out->n_rows = (size_t)n_rows;
    out->ncomp = (int)ncomp;
    out->bytes = (size_t)n_rows * (size_t)ncomp * esize;
    out->data = malloc(out->bytes ? out->bytes : 1);
    if (!out->data) {
        seterr(err, errsize, "out of memory reading field %s", name);
        goto out;
    }
    if (n_rows > 0) {
        /* frame field [F, N(, C)]: the slab [k, 0.., 0..]; reference field [N(, C)]: all */
        hsize_t start[3] = {0, 0, 0}, count[3], mdims[2] = {n_rows, ncomp};
        if (is_frame) {
            start[0] = (hsize_t)k;
            count[0] = 1, count[1] = n_rows, count[2] = ncomp;
        } else {
            count[0] = n_rows, count[1] = ncomp, count[2] = 1;
        }
        fs = H5Dget_space(d_val);
        ms = H5Screate_simple(2, mdims, NULL);
        if (fs < 0 || ms < 0 ||
            H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) < 0 ||
            H5Dread(d_val, mtype, ms, fs, H5P_DEFAULT, out->data) < 0) {
            seterr_h5(err, errsize, "cannot read", p_val);
            goto out;
        }
    }
    rc = 0;
out:
    close_id(&ms, H5Sclose);
    close_id(&fs, H5Sclose);
    close_id(&ftype, H5Tclose);
    close_id(&d_val, H5Dclose);
    close_id(&d_time, H5Dclose);
    close_id(&d_step, H5Dclose);
    H5Fclose(f);
    if (rc != 0)
        tres_field_free(out);
    return rc;
}

/* Element i of a little-endian buffer as double (or as integer for int dtypes). */
static json_t *field_elem(const struct tres_field *f, size_t i)
{
    unsigned char b[8];
    int le = host_is_le();
    size_t es = (f->dtype[2] == '4') ? 4 : 8;
    const unsigned char *src = (const unsigned char *)f->data + i * es;
    for (size_t j = 0; j < es; j++)
        b[j] = le ? src[j] : src[es - 1 - j];
    if (f->dtype[1] == 'f') {
        if (es == 4) {
            float v;
            memcpy(&v, b, 4);
            return jreal((double)v);
        }
        double v;
        memcpy(&v, b, 8);
        return jreal(v);
    }
    if (es == 4) {
        int32_t v;
        memcpy(&v, b, 4);
        return json_integer(v);
    }
    int64_t v;
    memcpy(&v, b, 8);
    return json_integer((json_int_t)v);
}

json_t *tres_field_json(const struct tres_field *f, const char *name, long frame)
{
    if (!f)
        return NULL;
    json_t *o = json_object();
    json_object_set_new(o, "name", json_string(name ? name : ""));
    json_object_set_new(o, "units", json_string(f->units));
    json_object_set_new(o, "frame", json_integer(frame));
    json_object_set_new(o, "step", json_integer(f->step));
    json_object_set_new(o, "time", jreal(f->time));
    json_object_set_new(o, "dtype", json_string(f->dtype));
    json_object_set_new(o, "shape", json_pack("[I,I]", (json_int_t)f->n_rows, (json_int_t)f->ncomp));
    json_t *data = json_array();
    size_t nc = f->ncomp > 0 ? (size_t)f->ncomp : 1;
    for (size_t i = 0; f->data && i < f->n_rows; i++) {
        if (nc == 1) {
            json_array_append_new(data, field_elem(f, i));
        } else {
            json_t *row = json_array();
            for (size_t c = 0; c < nc; c++)
                json_array_append_new(row, field_elem(f, i * nc + c));
            json_array_append_new(data, row);
        }
    }
    json_object_set_new(o, "data", data);
    return o;
}

json_t *tres_frames(const char *h5path, char *err, size_t errsize)
{
    hid_t f = open_file(h5path, err, errsize);
    if (f < 0)
        return NULL;
    json_t *out = NULL;
    int64_t *steps = NULL;
    double *times = NULL;
    hid_t d_step = -1, d_time = -1;
    const char *ps = "/particles/solid/position/step", *pt = "/particles/solid/position/time";
    int a = object_type(f, ps), b = object_type(f, pt);
    if (a < 0 || b < 0) {
        seterr_h5(err, errsize, "cannot look up", ps);
        goto done;
    }
    if (a != OT_DATASET || b != OT_DATASET) {
        out = json_array(); /* no frames (yet) */
        goto done;
    }
    int rs, rt;
    hsize_t ds[3], dt[3];
    d_step = open_refreshed(f, ps, &rs, ds, err, errsize);
    if (d_step < 0)
        goto done;
    d_time = open_refreshed(f, pt, &rt, dt, err, errsize);
    if (d_time < 0)
        goto done;
    if (rs != 1 || rt != 1) {
        seterr(err, errsize, "frame step/time have an unexpected shape");
        goto done;
    }
    hsize_t n = ds[0] < dt[0] ? ds[0] : dt[0];
    steps = malloc((n ? n : 1) * sizeof *steps);
    times = malloc((n ? n : 1) * sizeof *times);
    if (!steps || !times) {
        seterr(err, errsize, "out of memory");
        goto done;
    }
    if (read_rows(d_step, 1, ds, n, H5T_NATIVE_INT64, steps) < 0 ||
        read_rows(d_time, 1, dt, n, H5T_NATIVE_DOUBLE, times) < 0) {
        seterr_h5(err, errsize, "cannot read", "frame step/time");
        goto done;
    }
    out = json_array();
    for (hsize_t i = 0; i < n; i++)
        json_array_append_new(out, json_pack("{s:I,s:I,s:o}", "index", (json_int_t)i, "step",
                                             (json_int_t)steps[i], "time", jreal(times[i])));
done:
    free(steps);
    free(times);
    close_id(&d_time, H5Dclose);
    close_id(&d_step, H5Dclose);
    H5Fclose(f);
    return out;
}
