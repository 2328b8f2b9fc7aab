/* Unit tests of server/results.c on real result files written by tlsph-run.
 *
 * Environment: top_builddir (for tlsph-run) and top_srcdir (for examples/),
 * both default ".".  The result files go to a mkdtemp directory that is removed
 * at the end. */
#include <check.h>
#include <hdf5.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "results.h"
#include "support/check_main.h"

static char tmpdir[256];
static char h5[512];     /* the finished elastic-strip run (2-D, 400 particles) */
static char scene_long[512];
static char h5_named[512]; /* the strip with a gauge and a section (series families) */
static double end_time;

static const char *env_or(const char *name, const char *def)
{
    const char *v = getenv(name);
    return v && *v ? v : def;
}

static long obj_count(void)
{
    return (long)H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL);
}

static void sleep_ms(long ms)
{
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Runs once for the whole suite (also under CK_FORK=no). */
static void setup_files(void)
{
    if (h5[0])
        return;
    const char *src = env_or("top_srcdir", "."), *bld = env_or("top_builddir", ".");
    snprintf(tmpdir, sizeof tmpdir, "/tmp/test_results.XXXXXX");
    if (!mkdtemp(tmpdir)) {
        perror("mkdtemp");
        exit(1);
    }
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "'%s/tlsph-run' '%s/examples/elastic-strip.json' -o '%s/strip' --quiet",
             bld, src, tmpdir);
    if (system(cmd) != 0) {
        fprintf(stderr, "failed: %s\n", cmd);
        exit(1);
    }
    snprintf(h5, sizeof h5, "%s/strip/result.h5", tmpdir);

    /* the same scene, longer: for reading while the engine writes */
    char path[512];
    snprintf(path, sizeof path, "%s/examples/elastic-strip.json", src);
    json_error_t je;
    json_t *scene = json_load_file(path, 0, &je);
    if (!scene) {
        fprintf(stderr, "%s: %s\n", path, je.text);
        exit(1);
    }
    end_time = json_number_value(json_object_get(json_object_get(scene, "time"), "end"));
    json_t *t = json_object_get(scene, "time");
    json_object_set_new(t, "end", json_real(40 * end_time));
    json_t *o = json_object_get(scene, "output");
    json_object_set_new(o, "frames", json_integer(400));
    json_object_set_new(o, "series_every", json_integer(5));
    snprintf(scene_long, sizeof scene_long, "%s/long.json", tmpdir);
    if (json_dump_file(scene, scene_long, 0) != 0) {
        fprintf(stderr, "cannot write %s\n", scene_long);
        exit(1);
    }

    /* the short strip with a gauge and a section whose names use every kind of
     * character the naming rule allows (core/util/names.h) */
    json_object_set_new(t, "end", json_real(end_time / 4));
    json_object_set_new(o, "frames", json_integer(2));
    json_object_set_new(o, "gauges",
                        json_pack("[{s:s, s:[s,s], s:f}]", "name", "Strip.gauge-1", "between",
                                  "left", "right", "area", 0.01));
    json_object_set_new(o, "sections",
                        json_pack("[{s:s, s:[f,f,f], s:[f,f,f], s:f}]", "name", "_mid", "point",
                                  0.0205, 0.0, 0.0, "normal", 1.0, 0.0, 0.0, "thickness", 0.001));
    char scene_named[600];
    snprintf(scene_named, sizeof scene_named, "%s/named.json", tmpdir);
    if (json_dump_file(scene, scene_named, 0) != 0) {
        fprintf(stderr, "cannot write %s\n", scene_named);
        exit(1);
    }
    json_decref(scene);
    snprintf(cmd, sizeof cmd, "'%s/tlsph-run' '%s' -o '%s/named' --quiet", bld, scene_named,
             tmpdir);
    if (system(cmd) != 0) {
        fprintf(stderr, "failed: %s\n", cmd);
        exit(1);
    }
    snprintf(h5_named, sizeof h5_named, "%s/named/result.h5", tmpdir);
}

static void cleanup_files(void)
{
    /* the fixture runs per test in fork mode: only the process that created the
     * directory (the parent, via atexit) removes it */
}

static pid_t creator;

static void remove_tmpdir(void)
{
    if (tmpdir[0] && getpid() == creator) {
        char cmd[600];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
        if (system(cmd) != 0)
            fprintf(stderr, "could not remove %s\n", tmpdir);
    }
}

/* ------------------------------------------------------------ series */

START_TEST(test_series_list)
{
    char err[256] = "";
    json_t *l = tres_series_list(h5, err, sizeof err);
    ck_assert_msg(l != NULL, "%s", err);
    int have_ke = 0, have_rf = 0, have_left = 0;
    for (size_t i = 0; i < json_array_size(l); i++) {
        json_t *e = json_array_get(l, i);
        const char *name = json_string_value(json_object_get(e, "name"));
        const char *units = json_string_value(json_object_get(e, "units"));
        ck_assert_ptr_nonnull(name);
        ck_assert_ptr_nonnull(units);
        ck_assert_msg(json_object_size(e) == 3, "keys of %s", name);
        if (strcmp(name, "kinetic_energy") == 0) {
            have_ke = 1;
            ck_assert_str_eq(units, "J");
            ck_assert(json_is_null(json_object_get(e, "components")));
        }
        if (strcmp(name, "groups/right/reaction_force") == 0) {
            have_rf = 1;
            ck_assert_str_eq(units, "N");
            json_t *c = json_object_get(e, "components");
            ck_assert_int_eq(json_array_size(c), 3);
            ck_assert_str_eq(json_string_value(json_array_get(c, 0)), "x");
            ck_assert_str_eq(json_string_value(json_array_get(c, 2)), "z");
        }
        if (strcmp(name, "groups/left/displacement") == 0)
            have_left = 1;
        ck_assert(strcmp(name, "groups") != 0);
    }
    ck_assert(have_ke && have_rf && have_left);
    json_decref(l);
    ck_assert_int_eq(obj_count(), 0);
}
END_TEST

/* Every family's series is listed and can be read and reduced (what a study
 * output does) under the name the list gives, whatever characters the naming
 * rule lets its item's name hold.  The daemon listed only the "groups" family
 * before issue 13 (item 4): gauges and sections could not be found. */
START_TEST(test_series_families)
{
    char err[256] = "";
    json_t *l = tres_series_list(h5_named, err, sizeof err);
    ck_assert_msg(l != NULL, "%s", err);
    const char *want[] = {"groups/right/reaction_force", "gauges/Strip.gauge-1/engineering_stress",
                          "gauges/Strip.gauge-1/engineering_strain", "sections/_mid/normal_stress",
                          NULL};
    for (int w = 0; want[w]; w++) {
        int listed = 0;
        for (size_t i = 0; i < json_array_size(l); i++)
            listed |= strcmp(json_string_value(json_object_get(json_array_get(l, i), "name")),
                             want[w]) == 0;
        ck_assert_msg(listed, "%s is not listed", want[w]);
        int nf = 0;
        json_t *one = tres_series(h5_named, want[w], &nf, err, sizeof err);
        ck_assert_msg(one != NULL, "%s: %s", want[w], err);
        ck_assert_int_gt(json_array_size(json_object_get(one, "step")), 1);
        json_decref(one);
        double fin, mx, mn;
        ck_assert_int_eq(tres_series_reduce(h5_named, want[w], 0, &fin, &mx, &mn, err, sizeof err),
                         TRES_OK);
        ck_assert(mn <= fin && fin <= mx);
    }
    for (size_t i = 0; i < json_array_size(l); i++) {
        const char *name = json_string_value(json_object_get(json_array_get(l, i), "name"));
        ck_assert_msg(tres_series_name_ok(name), "listed name %s fails the rule", name);
        ck_assert_msg(strcmp(name, "gauges") != 0 && strcmp(name, "sections") != 0,
                      "a family listed as a series: %s", name);
    }
    json_decref(l);
    ck_assert_int_eq(obj_count(), 0);
}
END_TEST

/* Length of a dataset read independently of results.c. */
static long dataset_len(const char *path, const char *dset)
{
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);
    if (f < 0)
        return -1;
    hid_t d = H5Dopen2(f, dset, H5P_DEFAULT);
    hid_t s = H5Dget_space(d);
    hsize_t dims[3] = {0, 0, 0};
    H5Sget_simple_extent_dims(s, dims, NULL);
    H5Sclose(s);
    H5Dclose(d);
    H5Fclose(f);
    return (long)dims[0];
}

START_TEST(test_series_json)
{
    char err[256] = "";
    int nf = -1;
    long T = dataset_len(h5, "/observables/kinetic_energy/step");
    ck_assert_int_gt(T, 10);

    json_t *s = tres_series(h5, "kinetic_energy", &nf, err, sizeof err);
    ck_assert_msg(s != NULL, "%s", err);
    ck_assert_int_eq(nf, 0);
    ck_assert_str_eq(json_string_value(json_object_get(s, "name")), "kinetic_energy");
    ck_assert_str_eq(json_string_value(json_object_get(s, "units")), "J");
    json_t *step = json_object_get(s, "step"), *time = json_object_get(s, "time"),
           *value = json_object_get(s, "value");
    ck_assert_int_eq(json_array_size(step), T);
    ck_assert_int_eq(json_array_size(time), T);
    ck_assert_int_eq(json_array_size(value), T);
    for (long i = 1; i < T; i++) {
        ck_assert_int_gt(json_integer_value(json_array_get(step, i)),
                         json_integer_value(json_array_get(step, i - 1)));
        ck_assert(json_real_value(json_array_get(time, i)) >
                  json_real_value(json_array_get(time, i - 1)));
        ck_assert(json_is_real(json_array_get(value, i)));
        ck_assert(json_real_value(json_array_get(value, i)) >= 0);
    }
    double tl = json_real_value(json_array_get(time, T - 1));
    ck_assert_msg(fabs(tl - end_time) <= 1e-9 * end_time, "last time %g, end %g", tl, end_time);
    json_decref(s);

    s = tres_series(h5, "groups/right/reaction_force", &nf, err, sizeof err);
    ck_assert_msg(s != NULL, "%s", err);
    value = json_object_get(s, "value");
    ck_assert_int_eq(json_array_size(value), T);
    for (long i = 0; i < T; i++)
        ck_assert_int_eq(json_array_size(json_array_get(value, i)), 3);
    ck_assert_int_eq(json_array_size(json_object_get(s, "components")), 3);
    json_decref(s);
    ck_assert_int_eq(obj_count(), 0);
}
END_TEST

static size_t count_lines(const char *s)
{
    size_t n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

START_TEST(test_series_csv)
{
    char err[256] = "";
    int nf = -1;
    long T = dataset_len(h5, "/observables/kinetic_energy/step");
    char *csv = tres_series_csv(h5, "kinetic_energy", &nf, err, sizeof err);
    ck_assert_msg(csv != NULL, "%s", err);
    ck_assert(strncmp(csv, "step,time,kinetic_energy\n", 25) == 0);
    ck_assert_int_eq(count_lines(csv), (size_t)T + 1);
    /* the last row's time is the end time, printed with %.17g */
    const char *last = csv + strlen(csv) - 1;
    while (last > csv && last[-1] != '\n')
        last--;
    long st;
    double t, v;
    ck_assert_int_eq(sscanf(last, "%ld,%lg,%lg", &st, &t, &v), 3);
    ck_assert(fabs(t - end_time) <= 1e-9 * end_time);
    free(csv);

    csv = tres_series_csv(h5, "groups/right/reaction_force", &nf, err, sizeof err);
    ck_assert_msg(csv != NULL, "%s", err);
    ck_assert(strncmp(csv, "step,time,reaction_force_x,reaction_force_y,reaction_force_z\n", 61) == 0);
    ck_assert_int_eq(count_lines(csv), (size_t)T + 1);
    free(csv);

    ck_assert_ptr_null(tres_series_csv(h5, "no_such_series", &nf, err, sizeof err));
    ck_assert_int_eq(nf, 1);
    ck_assert_int_eq(obj_count(), 0);
}
END_TEST

START_TEST(test_series_not_found)
{
    char err[256];
    int nf;
    const char *bad[] = {"../x", "/abs", "a b", "groups/../kinetic_energy", "x/", "a//b", "./x",
                         "groups/./right", "ke;rm", "", "groups", "groups/right",
                         "particles/solid/position", "kinetic_energy/value", NULL};
    for (int i = 0; bad[i]; i++) {
        nf = 0;
        err[0] = '\0';
        ck_assert_msg(tres_series(h5, bad[i], &nf, err, sizeof err) == NULL, "%s", bad[i]);
        ck_assert_msg(nf == 1, "%s: not_found %d (%s)", bad[i], nf, err);
    }
    char longname[260];
    memset(longname, 'a', 250);
    longname[250] = '\0';
    nf = 0;
    ck_assert_ptr_null(tres_series(h5, longname, &nf, err, sizeof err));
    ck_assert_int_eq(nf, 1);
    /* invalid names never touch the file: a missing file still says "not found" */
    nf = 0;
    ck_assert_ptr_null(tres_series("/nonexistent/result.h5", "../x", &nf, err, sizeof err));
    ck_assert_int_eq(nf, 1);
    /* a valid name on a missing file is an error, not "not found" */
    nf = 0;
    ck_assert_ptr_null(tres_series("/nonexistent/result.h5", "kinetic_energy", &nf, err, sizeof err));
    ck_assert_int_eq(nf, 0);
    ck_assert(strstr(err, "No such file") != NULL);

    ck_assert(tres_series_name_ok("groups/right-1/reaction_force"));
    ck_assert(tres_series_name_ok("a.b"));
    ck_assert(!tres_series_name_ok(".."));
    /* each segment follows the engine's naming rule (util/names.h) */
    ck_assert(tres_series_name_ok("a..b"));
    ck_assert(tres_series_name_ok("gauges/Strip.gauge-1/engineering_stress"));
    ck_assert(!tres_series_name_ok("groups/right end/reaction_force"));
    ck_assert(!tres_series_name_ok("groups/1st/reaction_force"));
    ck_assert(!tres_series_name_ok("groups/-x/reaction_force"));
    ck_assert(!tres_series_name_ok(NULL));
    ck_assert(tres_field_name_ok("det_F"));
    ck_assert(!tres_field_name_ok("stress/value"));
    ck_assert(!tres_field_name_ok("a.b"));
    double d;
    ck_assert_int_eq(tres_series_reduce(h5, "/abs", 0, &d, &d, &d, err, sizeof err), 1);
    ck_assert_int_eq(tres_series_reduce(h5, "nope", 0, &d, &d, &d, err, sizeof err), 1);
    ck_assert_int_eq(tres_series_reduce(h5, "kinetic_energy", 1, &d, &d, &d, err, sizeof err), 1);
    ck_assert_int_eq(tres_series_reduce(h5, "groups/right/reaction_force", 3, &d, &d, &d, err,
                                        sizeof err), 1);
    ck_assert_int_eq(tres_series_reduce("/nonexistent.h5", "kinetic_energy", 0, &d, &d, &d, err,
                                        sizeof err), -1);
    ck_assert_int_eq(obj_count(), 0);
}
END_TEST

START_TEST(test_series_reduce)
{
    char err[256] = "";
    int nf;
    json_t *s = tres_series(h5, "groups/right/reaction_force", &nf, err, sizeof err);
    ck_assert_msg(s != NULL, "%s", err);
    json_t *value = json_object_get(s, "value");
    size_t T = json_array_size(value);
    for (int c = -1; c < 3; c++) {
        double ef = NAN, emax = -INFINITY, emin = INFINITY;
        for (size_t i = 0; i < T; i++) {
            json_t *row = json_array_get(value, i);
            double v;
            if (c >= 0) {
                v = json_real_value(json_array_get(row, (size_t)c));
            } else {
                double x = json_real_value(json_array_get(row, 0)),
                       y = json_real_value(json_array_get(row, 1)),
                       z = json_real_value(json_array_get(row, 2));
                v = sqrt(x * x + y * y + z * z);
            }
            ef = v;
            emax = fmax(emax, v);
            emin = fmin(emin, v);
        }
        double f, mx, mn;
        ck_assert_int_eq(tres_series_reduce(h5, "groups/right/reaction_force", c, &f, &mx, &mn,
                                            err, sizeof err), 0);
        ck_assert_msg(f == ef && mx == emax && mn == emin, "component %d: %g %g %g vs %g %g %g", c,
                      f, mx, mn, ef, emax, emin);
        ck_assert(mn <= f && f <= mx);
    }
    json_decref(s);
    /* the right end is pulled: the x reaction ends positive and large */
    double f, mx, mn;
    ck_assert_int_eq(tres_series_reduce(h5, "groups/right/reaction_force", 0, &f, &mx, &mn, err,
                                        sizeof err), 0);
    ck_assert(f > 0 && mx >= f);
    /* scalar series, NULL outputs allowed */
    ck_assert_int_eq(tres_series_reduce(h5, "kinetic_energy", 0, NULL, &mx, NULL, err, sizeof err), 0);
    ck_assert(mx > 0);
    ck_assert_int_eq(tres_series_reduce(h5, "kinetic_energy", -1, &f, NULL, &mn, err, sizeof err), 0);
    ck_assert(mn >= 0 && f >= mn);
    ck_assert_int_eq(obj_count(), 0);
}
END_TEST

/* ------------------------------------------------------------ fields */

START_TEST(test_field_stress)
{
    char err[256] = "";
    struct tres_field f;
    long frames = dataset_len(h5, "/particles/solid/position/step");
    ck_assert_int_eq(frames, 21);
    long which[] = {0, -1, 20, -21};
    for (int i = 0; i < 4; i++) {
        int rc = tres_field(h5, "stress", which[i], &f, err, sizeof err);
        ck_assert_msg(rc == 0, "frame %ld: %d %s", which[i], rc, err);
        ck_assert_int_eq(f.n_rows, 400);
        ck_assert_int_eq(f.ncomp, 6);
        ck_assert_str_eq(f.dtype, "<f4");
        ck_assert_str_eq(f.units, "Pa");
        ck_assert_int_eq(f.bytes, 400 * 6 * 4);
        ck_assert_int_eq(f.frames, frames);
        long k = which[i] < 0 ? frames + which[i] : which[i];
        if (k == 0) {
            ck_assert(f.time == 0.0);
            ck_assert_int_eq(f.step, 0);
        } else {
            ck_assert(fabs(f.time - end_time) <= 1e-9 * end_time);
            ck_assert_int_gt(f.step, 0);
        }
        /* 2-D: the xz and yz components (indices 2 and 4) are zero; stress is finite */
        const float *v = f.data;
        int nonzero = 0;
        for (size_t p = 0; p < f.n_rows; p++) {
            ck_assert(v[p * 6 + 2] == 0.0f && v[p * 6 + 4] == 0.0f);
            for (int c = 0; c < 6; c++) {
                ck_assert(isfinite(v[p * 6 + c]));
                nonzero += v[p * 6 + c] != 0.0f;
            }
        }
        if (k > 0)
            ck_assert_int_gt(nonzero, 0);
        tres_field_free(&f);
        ck_assert_ptr_null(f.data);
    }
    ck_assert_int_eq(obj_count(), 0);
}
END_TEST

/* A file whose particle count changes (io/output/output.h: every field per
 * frame, /particles/solid/count), made by hand: frame 0 has 2 of the 3
 * columns, frame 1 all 3.  tres_field returns each frame's count of rows, ids
 * included; a count beyond the dataset is an error, not a read past it. */
static void write_dataset(hid_t f, const char *path, hid_t type, int rank, const hsize_t *dims,
                          const void *data)
{
    hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
    ck_assert(lcpl >= 0 && H5Pset_create_intermediate_group(lcpl, 1) >= 0);
    hid_t sp = H5Screate_simple(rank, dims, NULL);
    hid_t ds = H5Dcreate2(f, path, type, sp, lcpl, H5P_DEFAULT, H5P_DEFAULT);
    ck_assert(sp >= 0 && ds >= 0);
    ck_assert(H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0);
    H5Dclose(ds);
    H5Sclose(sp);
    H5Pclose(lcpl);
}

static void changing_file(const char *path, int64_t count1)
{
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    ck_assert(H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST) >= 0);
    hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    ck_assert(f >= 0);
    const int64_t step[2] = {0, 10}, count[2] = {2, count1}, ids[2][3] = {{0, 1, -1}, {0, 2, 3}};
    const double time[2] = {0.0, 1e-6};
    const double pos[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {0, 0, 0}}, {{0, 0, 0}, {1, 1, 0}, {1, -1, 0}}};
    const hsize_t d1[1] = {2}, d2[2] = {2, 3}, d3[3] = {2, 3, 3};
    const char *names[] = {"position", "id", "count"};
    for (int i = 0; i < 3; i++) {
        char p[128];
        snprintf(p, sizeof p, "/particles/solid/%s/step", names[i]);
        write_dataset(f, p, H5T_NATIVE_INT64, 1, d1, step);
        snprintf(p, sizeof p, "/particles/solid/%s/time", names[i]);
        write_dataset(f, p, H5T_NATIVE_DOUBLE, 1, d1, time);
    }
    write_dataset(f, "/particles/solid/position/value", H5T_NATIVE_DOUBLE, 3, d3, pos);
    write_dataset(f, "/particles/solid/id/value", H5T_NATIVE_INT64, 2, d2, ids);
    write_dataset(f, "/particles/solid/count/value", H5T_NATIVE_INT64, 1, d1, count);
    H5Fclose(f);
    H5Pclose(fapl);
}

START_TEST(test_field_changing_count)
{
    setup_files(); /* the temporary directory */
    char path[600], err[256];
    snprintf(path, sizeof path, "%s/changing.h5", tmpdir);
    changing_file(path, 3);
    struct tres_field f;
    ck_assert_int_eq(tres_field(path, "position", 0, &f, err, sizeof err), 0);
    ck_assert_uint_eq(f.n_rows, 2);
    ck_assert_int_eq(f.ncomp, 3);
    ck_assert_double_eq(((double *)f.data)[3], 1.0);
    tres_field_free(&f);
    ck_assert_int_eq(tres_field(path, "id", -1, &f, err, sizeof err), 0);
    ck_assert_uint_eq(f.n_rows, 3);
    ck_assert_int_eq(((int64_t *)f.data)[2], 3);
    ck_assert(f.time == 1e-6 && f.step == 10);
    tres_field_free(&f);
    changing_file(path, 4); /* a count beyond the datasets' 3 columns */
    ck_assert_int_eq(tres_field(path, "position", 1, &f, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "count 4 outside") != NULL, "%s", err);
    unlink(path);
}
END_TEST

START_TEST(test_field_kinds)
{
    char err[256] = "";
    struct tres_field f;
    ck_assert_int_eq(tres_field(h5, "position", -1, &f, err, sizeof err), 0);
    ck_assert_str_eq(f.dtype, "<f8");
    ck_assert_int_eq(f.ncomp, 3);
    ck_assert_str_eq(f.units, "m");
    ck_assert_int_eq(f.bytes, 400 * 3 * 8);
    json_t *j = tres_field_json(&f, "position", -1);
    ck_assert_int_eq(json_integer_value(json_array_get(json_object_get(j, "shape"), 0)), 400);
    ck_assert_int_eq(json_integer_value(json_array_get(json_object_get(j, "shape"), 1)), 3);
    ck_assert_int_eq(json_array_size(json_object_get(j, "data")), 400);
    json_t *row = json_array_get(json_object_get(j, "data"), 7);
    ck_assert_int_eq(json_array_size(row), 3);
    ck_assert(json_real_value(json_array_get(row, 0)) == ((double *)f.data)[7 * 3 + 0]);
    ck_assert_str_eq(json_string_value(json_object_get(j, "name")), "position");
    ck_assert_int_eq(json_integer_value(json_object_get(j, "frame")), -1);
    json_decref(j);
    tres_field_free(&f);

    ck_assert_int_eq(tres_field(h5, "pressure", 3, &f, err, sizeof err), 0);
    ck_assert_int_eq(f.ncomp, 1);
    ck_assert_str_eq(f.dtype, "<f4");
    j = tres_field_json(&f, "pressure", 3);
    ck_assert(json_is_real(json_array_get(json_object_get(j, "data"), 0)));
    json_decref(j);
    tres_field_free(&f);

    /* reference fields ignore the frame */
    ck_assert_int_eq(tres_field(h5, "id", 12345, &f, err, sizeof err), 0);
    ck_assert_str_eq(f.dtype, "<i8");
    ck_assert_int_eq(f.ncomp, 1);
    ck_assert_int_eq(f.n_rows, 400);
    ck_assert_int_eq(f.frames, 21);
    /* ids are a permutation of 0..N-1 (storage order may differ) */
    char seen[400] = {0};
    for (long i = 0; i < 400; i++) {
        long long id = ((long long *)f.data)[i];
        ck_assert(id >= 0 && id < 400 && !seen[id]);
        seen[id] = 1;
    }
    j = tres_field_json(&f, "id", 0);
    ck_assert_int_eq(json_integer_value(json_array_get(json_object_get(j, "data"), 399)),
                     ((long long *)f.data)[399]);
    json_decref(j);
    tres_field_free(&f);
    ck_assert_int_eq(tres_field(h5, "body", 0, &f, err, sizeof err), 0);
    ck_assert_str_eq(f.dtype, "<i4");
    tres_field_free(&f);
    ck_assert_int_eq(tres_field(h5, "reference_position", 0, &f, err, sizeof err), 0);
    ck_assert_str_eq(f.dtype, "<f8");
    ck_assert_int_eq(f.ncomp, 3);
    tres_field_free(&f);

    /* errors */
    ck_assert_int_eq(tres_field(h5, "stress", 21, &f, err, sizeof err), 2);
    ck_assert_int_eq(tres_field(h5, "stress", -22, &f, err, sizeof err), 2);
    ck_assert_ptr_null(f.data);
    ck_assert_int_eq(tres_field(h5, "no_such_field", 0, &f, err, sizeof err), 1);
    ck_assert_int_eq(tres_field(h5, "box", 0, &f, err, sizeof err), 1); /* a group, no value */
    ck_assert_int_eq(tres_field(h5, "../x", 0, &f, err, sizeof err), 1);
    ck_assert_int_eq(tres_field(h5, "stress/value", 0, &f, err, sizeof err), 1);
    ck_assert_int_eq(tres_field(h5, "a b", 0, &f, err, sizeof err), 1);
    ck_assert_int_eq(tres_field("/nonexistent.h5", "stress", 0, &f, err, sizeof err), -1);
    ck_assert_int_eq(tres_field("/nonexistent.h5", "../x", 0, &f, err, sizeof err), 1);
    tres_field_free(&f); /* safe after failure */
    ck_assert_int_eq(obj_count(), 0);
}
END_TEST

START_TEST(test_frames)
{
    char err[256] = "";
    json_t *fr = tres_frames(h5, err, sizeof err);
    ck_assert_msg(fr != NULL, "%s", err);
    ck_assert_int_eq(json_array_size(fr), 21);
    for (size_t i = 0; i < 21; i++) {
        json_t *e = json_array_get(fr, i);
        ck_assert_int_eq(json_integer_value(json_object_get(e, "index")), i);
        if (i)
            ck_assert(json_real_value(json_object_get(e, "time")) >
                      json_real_value(json_object_get(json_array_get(fr, i - 1), "time")));
    }
    double tl = json_real_value(json_object_get(json_array_get(fr, 20), "time"));
    ck_assert(fabs(tl - end_time) <= 1e-9 * end_time);
    json_decref(fr);
    ck_assert_ptr_null(tres_frames("/nonexistent.h5", err, sizeof err));
    ck_assert_int_eq(obj_count(), 0);
}
END_TEST

static long rss_kb(void)
{
    FILE *fp = fopen("/proc/self/status", "r");
    char line[256];
    long kb = -1;
    while (fp && fgets(line, sizeof line, fp))
        if (sscanf(line, "VmRSS: %ld", &kb) == 1)
            break;
    if (fp)
        fclose(fp);
    return kb;
}

/* Open/read 1000 times: no id stays open after any call, memory stays flat. */
START_TEST(test_no_leaks)
{
    char err[256];
    long rss0 = 0;
    for (int i = 0; i < 1000; i++) {
        if (i == 100)
            rss0 = rss_kb();
        int nf;
        struct tres_field f;
        switch (i % 5) {
        case 0: {
            json_t *j = tres_series(h5, "groups/left/reaction_force", &nf, err, sizeof err);
            ck_assert_ptr_nonnull(j);
            json_decref(j);
            break;
        }
        case 1:
            ck_assert_int_eq(tres_field(h5, "stress", i % 21, &f, err, sizeof err), 0);
            tres_field_free(&f);
            break;
        case 2: {
            json_t *j = tres_series_list(h5, err, sizeof err);
            ck_assert_ptr_nonnull(j);
            json_decref(j);
            ck_assert_int_eq(tres_field(h5, "stress", 99, &f, err, sizeof err), 2);
            break;
        }
        case 3: {
            double a, b, c;
            ck_assert_int_eq(tres_series_reduce(h5, "kinetic_energy", 0, &a, &b, &c, err, sizeof err), 0);
            ck_assert_int_eq(tres_field(h5, "nope", 0, &f, err, sizeof err), 1);
            ck_assert_ptr_null(tres_series(h5, "nope", &nf, err, sizeof err));
            break;
        }
        default: {
            json_t *j = tres_frames(h5, err, sizeof err);
            ck_assert_ptr_nonnull(j);
            json_decref(j);
            ck_assert_int_eq(tres_field(h5, "id", 0, &f, err, sizeof err), 0);
            tres_field_free(&f);
            ck_assert_int_eq(tres_field("/nonexistent.h5", "id", 0, &f, err, sizeof err), -1);
            break;
        }
        }
        ck_assert_msg(obj_count() == 0, "iteration %d: %ld ids open", i, obj_count());
    }
    long rss1 = rss_kb();
    /* valgrind and AddressSanitizer (its quarantine keeps freed blocks) inflate
     * RSS; there LeakSanitizer/memcheck check leaks instead, so only check
     * outside them. */
#if defined(__SANITIZE_ADDRESS__)
    const int sanitized = 1;
#else
    const int sanitized = 0;
#endif
    const char *pre = getenv("LD_PRELOAD");
    if (!sanitized && !(pre && strstr(pre, "vgpreload")) && rss0 > 0)
        ck_assert_msg(rss1 - rss0 < 4096, "RSS grew from %ld to %ld kB", rss0, rss1);
}
END_TEST

/* ------------------------------------------------------------ live reading */

START_TEST(test_read_while_writing)
{
    const char *bld = env_or("top_builddir", ".");
    char exe[512], out[512], path[600];
    snprintf(exe, sizeof exe, "%s/tlsph-run", bld);
    snprintf(out, sizeof out, "%s/live", tmpdir);
    snprintf(path, sizeof path, "%s/result.h5", out);
    pid_t pid = fork();
    ck_assert_int_ge(pid, 0);
    if (pid == 0) {
        execl(exe, exe, scene_long, "-o", out, "--quiet", "--threads", "1", (char *)NULL);
        _exit(127);
    }
    char err[256];
    int reads = 0, grew = 0, nf;
    long last_rows = -1, last_frames = -1;
    double t0 = now_s();
    int status = 0, exited = 0;
    /* Reads until it has seen the series grow twice (or the engine ended); the
     * 300 s bound only detects a hang, so a slow machine just reads longer. */
    while (!(reads >= 5 && grew >= 2) && now_s() - t0 < 300.0) {
        if (waitpid(pid, &status, WNOHANG) == pid) {
            exited = 1;
            break;
        }
        struct stat st;
        json_t *s = stat(path, &st) == 0 ? tres_series(path, "groups/right/reaction_force", &nf,
                                                       err, sizeof err)
                                         : NULL;
        ck_assert_int_eq(obj_count(), 0);
        if (!s) {
            /* the file cannot be opened before the writer has finished the layout */
            ck_assert_msg(reads == 0, "read failed after success: %s", err);
            sleep_ms(20);
            continue;
        }
        long rows = (long)json_array_size(json_object_get(s, "step"));
        ck_assert_int_eq(json_array_size(json_object_get(s, "time")), rows);
        ck_assert_int_eq(json_array_size(json_object_get(s, "value")), rows);
        for (long i = 1; i < rows; i++)
            ck_assert(json_real_value(json_array_get(json_object_get(s, "time"), (size_t)i)) >
                      json_real_value(json_array_get(json_object_get(s, "time"), (size_t)i - 1)));
        json_decref(s);
        ck_assert_int_ge(rows, last_rows);
        grew += rows > last_rows && last_rows >= 0;
        last_rows = rows;

        struct tres_field f;
        int rc = tres_field(path, "velocity", -1, &f, err, sizeof err);
        ck_assert_msg(rc == 0 || (rc == 2 && f.frames == 0), "rc %d: %s", rc, err);
        if (rc == 0) {
            ck_assert_int_ge(f.frames, last_frames);
            last_frames = f.frames;
            ck_assert_int_eq(f.n_rows, 400);
            ck_assert_str_eq(f.dtype, "<f4");
            tres_field_free(&f);
        }
        /* the raw value dataset is never shorter than the committed step */
        json_t *fr = tres_frames(path, err, sizeof err);
        ck_assert_msg(fr != NULL, "%s", err);
        ck_assert_int_ge(dataset_len(path, "/particles/solid/velocity/value"), (long)json_array_size(fr));
        json_decref(fr);
        reads++;
        ck_assert_int_eq(obj_count(), 0);
        sleep_ms(50);
    }
    if (!exited) {
        kill(pid, SIGTERM);
        ck_assert_int_eq(waitpid(pid, &status, 0), pid);
    }
    ck_assert_msg(reads >= 5, "only %d reads while running", reads);
    ck_assert_msg(grew >= 2, "the series grew only %d times", grew);
    /* after the engine has stopped (cancelled or finished), the file still reads */
    json_t *s = tres_series(path, "kinetic_energy", &nf, err, sizeof err);
    ck_assert_msg(s != NULL, "%s", err);
    ck_assert_int_ge((long)json_array_size(json_object_get(s, "step")), last_rows);
    json_decref(s);
    ck_assert_int_eq(obj_count(), 0);
}
END_TEST

static Suite *results_suite(void)
{
    Suite *s = suite_create("results");
    TCase *tc = tcase_create("finished");
    tcase_add_unchecked_fixture(tc, setup_files, cleanup_files);
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, test_series_list);
    tcase_add_test(tc, test_series_families);
    tcase_add_test(tc, test_series_json);
    tcase_add_test(tc, test_series_csv);
    tcase_add_test(tc, test_series_not_found);
    tcase_add_test(tc, test_series_reduce);
    tcase_add_test(tc, test_field_stress);
    tcase_add_test(tc, test_field_kinds);
    tcase_add_test(tc, test_field_changing_count);
    tcase_add_test(tc, test_frames);
    tcase_add_test(tc, test_no_leaks);
    suite_add_tcase(s, tc);
    TCase *live = tcase_create("live");
    tcase_add_unchecked_fixture(live, setup_files, cleanup_files);
    tcase_set_timeout(live, 600); /* a hang detector over the 300 s read loop */
    tcase_add_test(live, test_read_while_writing);
    suite_add_tcase(s, live);
    return s;
}

int main(void)
{
    creator = getpid();
    atexit(remove_tmpdir);
    return tlsph_check_run(results_suite());
}
