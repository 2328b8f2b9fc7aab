/* One field at one frame, and the list of frames (server/results_field.c),
 * see results.h. */
#include "results.h"

#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "results_h5.h"

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
    int t = h5r_object_type(f, "/particles/solid/position/step");
    if (t < 0) {
        h5r_error(err, errsize, "cannot look up", "/particles/solid/position/step");
        return -1;
    }
    if (t != OT_DATASET)
        return 0;
    int r;
    hsize_t d[3];
    hid_t ds = h5r_open_refreshed(f, "/particles/solid/position/step", &r, d, err, errsize);
    if (ds < 0)
        return -1;
    *frames = (long)d[0];
    H5Dclose(ds);
    return 0;
}

/* The particle count of frame k in a file whose count changes
 * (/particles/solid/count/value, written before the frame's step): 1 with
 * *n, 0 when the file has one count per run, -1 with err. */
static int frame_particles(hid_t f, long k, long *n, char *err, size_t errsize)
{
    static const char *path = "/particles/solid/count/value";
    const int t = h5r_object_type(f, path);
    if (t < 0) {
        h5r_error(err, errsize, "cannot look up", path);
        return -1;
    }
    if (t != OT_DATASET)
        return 0;
    int r;
    hsize_t d[3];
    hid_t ds = h5r_open_refreshed(f, path, &r, d, err, errsize);
    if (ds < 0)
        return -1;
    int rc = -1;
    int64_t v;
    hsize_t one = 1, start = (hsize_t)k;
    hid_t fs = H5Dget_space(ds), ms = H5Screate_simple(1, &one, NULL);
    if (r != 1 || (hsize_t)k >= d[0])
        errmsg_set(err, errsize, "%s holds no frame %ld", path, k);
    else if (fs < 0 || ms < 0 || H5Sselect_hyperslab(fs, H5S_SELECT_SET, &start, NULL, &one, NULL) < 0 ||
             H5Dread(ds, H5T_NATIVE_INT64, ms, fs, H5P_DEFAULT, &v) < 0)
        h5r_error(err, errsize, "cannot read", path);
    else {
        *n = (long)v;
        rc = 1;
    }
    h5r_close(&ms, H5Sclose);
    h5r_close(&fs, H5Sclose);
    h5r_close(&ds, H5Dclose);
    return rc;
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
        errmsg_set(err, errsize, TRES_NO_FIELD, name ? name : "");
        return 1;
    }
    hid_t f = h5r_open_file(h5path, err, errsize);
    if (f < 0)
        return -1;

    int rc = -1;
    hid_t d_val = -1, d_step = -1, d_time = -1, ftype = -1, fs = -1, ms = -1;
    char base[128], p_val[160], p_step[160], p_time[160];
    snprintf(base, sizeof base, "/particles/solid/%s", name);
    int t = h5r_object_type(f, base);
    if (t < 0) {
        h5r_error(err, errsize, "cannot look up", base);
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
        int a = h5r_object_type(f, p_val), b = h5r_object_type(f, p_step), c = h5r_object_type(f, p_time);
        if (a < 0 || b < 0 || c < 0) {
            h5r_error(err, errsize, "cannot look up", base);
            goto out;
        }
        if (a != OT_DATASET || b != OT_DATASET || c != OT_DATASET) {
            errmsg_set(err, errsize, "no field named \"%s\"", name);
            rc = 1;
            goto out;
        }
    } else {
        errmsg_set(err, errsize, "no field named \"%s\"", name);
        rc = 1;
        goto out;
    }

    int rs = 0, rt = 0, rv;
    hsize_t ds[3], dt[3], dv[3];
    long k = 0;
    if (is_frame) {
        d_step = h5r_open_refreshed(f, p_step, &rs, ds, err, errsize);
        if (d_step < 0)
            goto out;
        d_time = h5r_open_refreshed(f, p_time, &rt, dt, err, errsize);
        if (d_time < 0)
            goto out;
    }
    d_val = h5r_open_refreshed(f, p_val, &rv, dv, err, errsize);
    if (d_val < 0)
        goto out;

    hsize_t n_rows, ncomp;
    if (is_frame) {
        if (rs != 1 || rt != 1 || rv < 2) {
            errmsg_set(err, errsize, "field %s has an unexpected shape", name);
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
            errmsg_set(err, errsize, "no frame %ld of field %s (%ld frames)", frame, name,
                   (long)frames);
            rc = 2;
            goto out;
        }
        n_rows = dv[1];
        ncomp = rv == 3 ? dv[2] : 1;
        /* a file whose particle count changes (io/output/output.h): frame k
         * is the first count[k] particles of its row */
        long nk;
        const int c = frame_particles(f, k, &nk, err, errsize);
        if (c < 0)
            goto out;
        if (c == 1) {
            if (nk < 0 || (hsize_t)nk > n_rows) {
                errmsg_set(err, errsize, "frame %ld of field %s: count %ld outside its %llu rows",
                           k, name, nk, (unsigned long long)n_rows);
                goto out;
            }
            n_rows = (hsize_t)nk;
        }
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
            h5r_error(err, errsize, "cannot read step/time of", base);
            goto out;
        }
        out->step = (long)stepv;
        out->time = timev;
    } else {
        if (rv > 2) {
            errmsg_set(err, errsize, "field %s has an unexpected shape", name);
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
        errmsg_set(err, errsize, "field %s has %llu components", name, (unsigned long long)ncomp);
        goto out;
    }

    /* memory type: little-endian, float32 stays float32 */
    ftype = H5Dget_type(d_val);
    if (ftype < 0) {
        h5r_error(err, errsize, "cannot get the type of", p_val);
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
        errmsg_set(err, errsize, "field %s has an unsupported type", name);
        goto out;
    }

    if (h5r_read_str_attr(d_val, "units", out->units, sizeof out->units) < 0) {
        h5r_error(err, errsize, "cannot read the units of", p_val);
        goto out;
    }
    out->n_rows = (size_t)n_rows;
    out->ncomp = (int)ncomp;
    out->bytes = (size_t)n_rows * (size_t)ncomp * esize;
    out->data = malloc(out->bytes ? out->bytes : 1);
    if (!out->data) {
        errmsg_set(err, errsize, "out of memory reading field %s", name);
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
            h5r_error(err, errsize, "cannot read", p_val);
            goto out;
        }
    }
    rc = 0;
out:
    h5r_close(&ms, H5Sclose);
    h5r_close(&fs, H5Sclose);
    h5r_close(&ftype, H5Tclose);
    h5r_close(&d_val, H5Dclose);
    h5r_close(&d_time, H5Dclose);
    h5r_close(&d_step, H5Dclose);
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
            return h5r_json_real((double)v);
        }
        double v;
        memcpy(&v, b, 8);
        return h5r_json_real(v);
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
    json_object_set_new(o, "time", h5r_json_real(f->time));
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
    hid_t f = h5r_open_file(h5path, err, errsize);
    if (f < 0)
        return NULL;
    json_t *out = NULL;
    int64_t *steps = NULL;
    double *times = NULL;
    hid_t d_step = -1, d_time = -1;
    const char *ps = "/particles/solid/position/step", *pt = "/particles/solid/position/time";
    int a = h5r_object_type(f, ps), b = h5r_object_type(f, pt);
    if (a < 0 || b < 0) {
        h5r_error(err, errsize, "cannot look up", ps);
        goto done;
    }
    if (a != OT_DATASET || b != OT_DATASET) {
        out = json_array(); /* no frames (yet) */
        goto done;
    }
    int rs, rt;
    hsize_t ds[3], dt[3];
    d_step = h5r_open_refreshed(f, ps, &rs, ds, err, errsize);
    if (d_step < 0)
        goto done;
    d_time = h5r_open_refreshed(f, pt, &rt, dt, err, errsize);
    if (d_time < 0)
        goto done;
    if (rs != 1 || rt != 1) {
        errmsg_set(err, errsize, "frame step/time have an unexpected shape");
        goto done;
    }
    hsize_t n = ds[0] < dt[0] ? ds[0] : dt[0];
    steps = malloc((n ? n : 1) * sizeof *steps);
    times = malloc((n ? n : 1) * sizeof *times);
    if (!steps || !times) {
        errmsg_set(err, errsize, "out of memory");
        goto done;
    }
    if (h5r_read_rows(d_step, 1, ds, n, H5T_NATIVE_INT64, steps) < 0 ||
        h5r_read_rows(d_time, 1, dt, n, H5T_NATIVE_DOUBLE, times) < 0) {
        h5r_error(err, errsize, "cannot read", "frame step/time");
        goto done;
    }
    out = json_array();
    for (hsize_t i = 0; i < n; i++)
        json_array_append_new(out, json_pack("{s:I,s:I,s:o}", "index", (json_int_t)i, "step",
                                             (json_int_t)steps[i], "time", h5r_json_real(times[i])));
done:
    free(steps);
    free(times);
    h5r_close(&d_time, H5Dclose);
    h5r_close(&d_step, H5Dclose);
    H5Fclose(f);
    return out;
}
