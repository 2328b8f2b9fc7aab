/* Reading results for the API, see results.h: the time series here, fields
 * and frames in results_field.c, the shared HDF5 helpers in results_h5.c.
 *
 * Every public function opens the file itself (H5F_ACC_RDONLY | H5F_ACC_SWMR_READ:
 * works on a file the engine is writing in SWMR mode and on a closed file),
 * refreshes each dataset before looking at its shape, bounds row and frame
 * counts by the length of the `step` dataset (the writer's commit marker) and
 * closes every id it opened on every path.  HDF5's own error printing is
 * switched off; HDF5 failures become messages in err.
 *
 * Names from the outside are checked before they reach HDF5: series names are
 * "/"-separated segments that follow the engine's naming rule (util/names.h),
 * at most 200 characters; field names [A-Za-z0-9_] (at most 64). */
#include "results.h"

#include <hdf5.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "numtext.h"
#include "results_h5.h"
#include "strbuf.h"
#include "util/names.h"

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

    int t = h5r_object_type(f, base);
    if (t < 0) {
        h5r_error(err, errsize, "cannot look up", base);
        return -1;
    }
    if (t != OT_GROUP)
        return 1;
    int tv = h5r_object_type(f, p_value), ts = h5r_object_type(f, p_step), tt = h5r_object_type(f, p_time);
    if (tv < 0 || ts < 0 || tt < 0) {
        h5r_error(err, errsize, "cannot look up", base);
        return -1;
    }
    if (tv != OT_DATASET || ts != OT_DATASET || tt != OT_DATASET)
        return 1;

    int rc = -1, rs, rt, rv;
    hsize_t ds[3], dt[3], dv[3];
    /* step first: it is the commit marker */
    hid_t d_step = h5r_open_refreshed(f, p_step, &rs, ds, err, errsize);
    hid_t d_time = d_step >= 0 ? h5r_open_refreshed(f, p_time, &rt, dt, err, errsize) : -1;
    hid_t d_val = d_time >= 0 ? h5r_open_refreshed(f, p_value, &rv, dv, err, errsize) : -1;
    if (d_val < 0)
        goto out;
    if (rs != 1 || rt != 1 || rv > 2) {
        errmsg_set(err, errsize, "series %s has an unexpected shape", name);
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
        errmsg_set(err, errsize, "series %s has %llu components", name, (unsigned long long)dv[1]);
        goto out;
    }
    if (h5r_read_str_attr(d_val, "units", s->units, sizeof s->units) < 0 ||
        h5r_read_str_attr(d_val, "components", s->components, sizeof s->components) < 0) {
        h5r_error(err, errsize, "cannot read attributes of", p_value);
        goto out;
    }
    if (want_data) {
        size_t nc = s->ncomp ? (size_t)s->ncomp : 1;
        s->step = malloc((s->rows ? s->rows : 1) * sizeof *s->step);
        s->time = malloc((s->rows ? s->rows : 1) * sizeof *s->time);
        s->value = malloc((s->rows ? s->rows : 1) * nc * sizeof *s->value);
        if (!s->step || !s->time || !s->value) {
            errmsg_set(err, errsize, "out of memory reading series %s", name);
            goto out;
        }
        if (h5r_read_rows(d_step, 1, ds, n, H5T_NATIVE_INT64, s->step) < 0 ||
            h5r_read_rows(d_time, 1, dt, n, H5T_NATIVE_DOUBLE, s->time) < 0 ||
            h5r_read_rows(d_val, rv, dv, n, H5T_NATIVE_DOUBLE, s->value) < 0) {
            h5r_error(err, errsize, "cannot read series", name);
            goto out;
        }
    }
    rc = 0;
out:
    h5r_close(&d_val, H5Dclose);
    h5r_close(&d_time, H5Dclose);
    h5r_close(&d_step, H5Dclose);
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

/* The series of family group /observables/<family>: "<family>/<item>/<column>"
 * for every item group and every column in it. */
static void list_family(hid_t f, json_t *out, const char *family)
{
    char fpath[256];
    snprintf(fpath, sizeof fpath, "/observables/%s", family);
    char **items = NULL;
    size_t nitems = 0;
    if (group_names(f, fpath, &items, &nitems) < 0)
        return;
    for (size_t i = 0; i < nitems; i++) {
        char ipath[512];
        if (!tlsph_name_ok(items[i]))
            continue;
        snprintf(ipath, sizeof ipath, "%s/%s", fpath, items[i]);
        if (h5r_object_type(f, ipath) != OT_GROUP)
            continue;
        char **cols = NULL;
        size_t ncol = 0;
        if (group_names(f, ipath, &cols, &ncol) < 0)
            continue;
        for (size_t c = 0; c < ncol; c++) {
            char name[512];
            snprintf(name, sizeof name, "%s/%s/%s", family, items[i], cols[c]);
            if (tres_series_name_ok(name))
                list_add(f, out, name);
        }
        names_free(cols, ncol);
    }
    names_free(items, nitems);
}

json_t *tres_series_list(const char *h5path, char *err, size_t errsize)
{
    hid_t f = h5r_open_file(h5path, err, errsize);
    if (f < 0)
        return NULL;
    json_t *out = json_array();
    char **top = NULL;
    size_t ntop = 0;
    int t = h5r_object_type(f, "/observables");
    if (t < 0) {
        h5r_error(err, errsize, "cannot look up", "/observables");
        goto fail;
    }
    if (t != OT_GROUP)
        goto done; /* no series at all */
    if (group_names(f, "/observables", &top, &ntop) < 0) {
        h5r_error(err, errsize, "cannot list", "/observables");
        goto fail;
    }
    /* global series first, then the families (groups, gauges, sections): a
     * top-level group without a value dataset holds one group per item */
    for (size_t i = 0; i < ntop; i++)
        if (tres_series_name_ok(top[i]))
            list_add(f, out, top[i]);
    for (size_t i = 0; i < ntop; i++) {
        char path[256], value[300];
        if (!tlsph_name_ok(top[i]))
            continue;
        snprintf(path, sizeof path, "/observables/%s", top[i]);
        snprintf(value, sizeof value, "%s/value", path);
        if (h5r_object_type(f, path) == OT_GROUP && h5r_object_type(f, value) == OT_ABSENT)
            list_family(f, out, top[i]);
    }
    H5Eclear2(H5E_DEFAULT);
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

/* Opens, validates and reads series name.  0 ok, 1 not found, -1 error;
 * *not_found (when given) says whether it was 1. */
static int series_load(const char *h5path, const char *name, struct series *s, int *not_found,
                       char *err, size_t errsize)
{
    memset(s, 0, sizeof *s);
    int rc = -1;
    if (!tres_series_name_ok(name)) {
        errmsg_set(err, errsize, TRES_NO_SERIES, name ? name : "");
        rc = 1;
    } else {
        hid_t f = h5r_open_file(h5path, err, errsize);
        if (f >= 0) {
            rc = series_read(f, name, s, 1, err, errsize);
            if (rc == 1)
                errmsg_set(err, errsize, "no series named \"%s\"", name);
            H5Fclose(f);
        }
    }
    if (not_found)
        *not_found = rc == 1;
    return rc;
}

json_t *tres_series(const char *h5path, const char *name, int *not_found, char *err,
                    size_t errsize)
{
    struct series s;
    if (series_load(h5path, name, &s, not_found, err, errsize) != 0)
        return NULL;
    json_t *o = json_object(), *step = json_array(), *time = json_array(), *value = json_array();
    for (size_t i = 0; i < s.rows; i++) {
        json_array_append_new(step, json_integer((json_int_t)s.step[i]));
        json_array_append_new(time, h5r_json_real(s.time[i]));
        if (s.ncomp) {
            json_t *row = json_array();
            for (int c = 0; c < s.ncomp; c++)
                json_array_append_new(row, h5r_json_real(s.value[i * (size_t)s.ncomp + (size_t)c]));
            json_array_append_new(value, row);
        } else {
            json_array_append_new(value, h5r_json_real(s.value[i]));
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
    char text[NUMTEXT_REAL_MAX];
    if (isfinite(v))
        strbuf_printf(b, ",%s", numtext_real(text, sizeof text, v));
    else
        strbuf_printf(b, ",%s", isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf"));
}

char *tres_series_csv(const char *h5path, const char *name, int *not_found, char *err,
                      size_t errsize)
{
    struct series s;
    if (series_load(h5path, name, &s, not_found, err, errsize) != 0)
        return NULL;
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
        errmsg_set(err, errsize, "out of memory writing CSV");
    return csv;
}

enum tres_rc tres_series_column(const char *h5path, const char *name, int component,
                                double **time, double **value, size_t *n, char *err,
                                size_t errsize)
{
    *time = *value = NULL;
    *n = 0;
    struct series s;
    int rc = series_load(h5path, name, &s, NULL, err, errsize);
    if (rc != 0)
        return rc;
    int nc = s.ncomp ? s.ncomp : 1;
    if (component < -1 || component >= nc) {
        errmsg_set(err, errsize, "series %s has no component %d", name, component);
        series_free(&s);
        return TRES_NOT_FOUND;
    }
    double *v = malloc((s.rows ? s.rows : 1) * sizeof *v);
    if (!v) {
        errmsg_set(err, errsize, "out of memory reading series %s", name);
        series_free(&s);
        return TRES_ERROR;
    }
    for (size_t i = 0; i < s.rows; i++) {
        const double *row = s.value + i * (size_t)nc;
        double sum = 0;
        if (component < 0)
            for (int c = 0; c < nc; c++)
                sum += row[c] * row[c];
        v[i] = component >= 0 ? row[component] : sqrt(sum);
    }
    *time = s.time; /* handed over */
    s.time = NULL;
    *value = v;
    *n = s.rows;
    series_free(&s);
    return TRES_OK;
}

enum tres_rc tres_series_reduce(const char *h5path, const char *name, int component,
                                double *final, double *max, double *min, char *err,
                                size_t errsize)
{
    double fv = NAN, mx = NAN, mn = NAN;
    double *t, *v;
    size_t n;
    enum tres_rc rc = tres_series_column(h5path, name, component, &t, &v, &n, err, errsize);
    if (rc != TRES_OK)
        return rc;
    for (size_t i = 0; i < n; i++) {
        fv = v[i];
        if (!isnan(v[i])) {
            if (isnan(mx) || v[i] > mx)
                mx = v[i];
            if (isnan(mn) || v[i] < mn)
                mn = v[i];
        }
    }
    free(t);
    free(v);
    if (final)
        *final = fv;
    if (max)
        *max = mx;
    if (min)
        *min = mn;
    return TRES_OK;
}

enum tres_rc tres_run_status(const char *h5path, char *status, size_t size, char *err,
                             size_t errsize)
{
    hid_t f = h5r_open_file(h5path, err, errsize);
    if (f < 0)
        return TRES_ERROR;
    enum tres_rc rc = TRES_ERROR;
    hid_t g = H5Gopen2(f, "diagnostics", H5P_DEFAULT);
    if (g < 0) {
        h5r_error(err, errsize, "no /diagnostics in", h5path);
        rc = TRES_NOT_FOUND;
    } else {
        int a = h5r_read_str_attr(g, "status", status, size);
        rc = a == 0 ? TRES_OK : a == 1 ? TRES_NOT_FOUND : TRES_ERROR;
        if (a < 0)
            errmsg_set(err, errsize, "cannot read /diagnostics status of %s", h5path);
    }
    h5r_close(&g, H5Gclose);
    h5r_close(&f, H5Fclose);
    return rc;
}
