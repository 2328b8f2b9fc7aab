/* The result file of a run whose particle count changes (io/output/output.h,
 * docs/output.md "Changing particle counts"): a free plate is stepped and
 * written, a fibre is split with the crack's facets up to it (crack/split.h,
 * the library call: no crack driver yet), it is stepped and written again, a
 * second fibre is split, and so on; every step passes the stability contract.
 * The file is then read back by an independent reader, h5py under the system
 * Python (tests/engine/output_count_check.py), against the facts this test
 * writes beside it (facts.json: each frame's count, each split's parent ids,
 * masses and the halves' new ids), by a SWMR reader while the file is still
 * being written (after the second split), and, where ParaView is installed, through
 * the XDMF sidecar with ParaView's "XDMF Reader" (every frame's number of
 * points and one field's range).  References: the counts and ids are exact;
 * the halves' masses sum to the parent's to one rounding (split.h: m2 = m -
 * m1), checked to 1e-15 relative. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "crack/split.h"
#include "io/output/output.h"
#include "support/check_main.h"
#include "support/crack_plate.h"
#include "support/scene_builder.h"

/* a free plate (10 x 8 x 3 particles) opening in mode I across the row y =
 * 0.0045, which is at rest (v_y = +-5 m/s on either side), beside a block */
static const char *plate_fmt =
    "{\"dimension\":3,\"time\":{\"end\":1.0,\"max_steps\":1000,\"cfl\":0.3},"
    "\"contact\":{\"enabled\":false},\"output\":{\"frames\":10},"
    "\"discretization\":{\"hourglass\":{\"enabled\":true}},"
    "\"materials\":{\"m\":{\"density\":7800,\"youngs_modulus\":2e11,\"poisson_ratio\":0.3}},"
    "\"bodies\":[{\"name\":\"plate\",\"material\":\"m\",\"spacing\":0.001%s,"
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.010,0.008,0.003]}},"
    "\"initial_velocity\":[\"0\",\"5*tanh((y-0.0045)*1e5)\",\"0\"]},"
    "{\"name\":\"block\",\"material\":\"m\",\"spacing\":0.001,"
    "\"geometry\":{\"box\":{\"min\":[0.02,0,0],\"max\":[0.023,0.003,0.003]}}}]}";

/* The plate scene's model; extra: more keys of the plate body ("" none). */
static struct tlsph_model *plate(const char *extra)
{
    char json[2048];
    ck_assert_int_lt(snprintf(json, sizeof json, plate_fmt, extra), (int)sizeof json);
    return build_model(json);
}

#define DELTA 1e-5
#define MAXF 8
#define EVENTS 3

/* The fibre of body 0 nearest to (x, y) in the x-y plane (the plate's
 * particles stacked along z): its particles, ascending z. */
static size_t fibre_near(const struct tlsph_model *m, double x, double y, size_t *out)
{
    double d2min = INFINITY;
    for (size_t i = m->body_begin[0]; i < m->body_end[0]; i++) {
        const double dx = m->p.X[3 * i] - x, dy = m->p.X[3 * i + 1] - y;
        d2min = fmin(d2min, dx * dx + dy * dy);
    }
    size_t n = 0;
    for (size_t i = m->body_begin[0]; i < m->body_end[0]; i++) {
        const double dx = m->p.X[3 * i] - x, dy = m->p.X[3 * i + 1] - y;
        if (dx * dx + dy * dy <= d2min + 1e-18) {
            ck_assert_uint_lt(n, MAXF);
            out[n++] = i;
        }
    }
    return n;
}

/* n steps, each passing the stability contract (energy balance, det F,
 * finite values): the split run stays a sane run */
static void steps(struct tlsph_model *m, int n)
{
    struct tlsph_diagnostic d;
    for (int s = 0; s < n; s++) {
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &d) == 0, "step %ld: %s", m->step, d.message);
    }
}

/* The crack as split e leaves it: the plane y = yt from 2 mm behind the
 * first fibre to fibre e at x_e, through the thickness and beyond, as two
 * triangles (the facets the crack driver would add). */
static void grow_crack(struct tlsph_crack_surface *cs, double yt, double x_behind, double x_e)
{
    const double zlo = -0.001, zhi = 0.004;
    const double lower[3][3] = {{x_behind, yt, zlo}, {x_e, yt, zlo}, {x_e, yt, zhi}};
    const double upper[3][3] = {{x_behind, yt, zlo}, {x_e, yt, zhi}, {x_behind, yt, zhi}};
    ck_assert_int_eq(tlsph_crack_surface_add(cs, lower), TLSPH_CRACK_OK);
    ck_assert_int_eq(tlsph_crack_surface_add(cs, upper), TLSPH_CRACK_OK);
}

static void remove_dir(const char *dir)
{
    const char *names[] = {"result.h5", "result.xmf", "facts.json"};
    char path[128];
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        unlink(path);
    }
    ck_assert_int_eq(rmdir(dir), 0);
}

/* Runs the system Python's h5py check (and ParaView's, where installed) on
 * dir; live: "live" and the counts written so far, while the writer holds the
 * file (a SWMR reader). */
static int run_checker(const char *dir, const char *live)
{
    const char *py = getenv("SYSTEM_PYTHON");
    const char *top = getenv("top_srcdir");
    if (!py || !*py || strcmp(py, "no") == 0)
        py = "/usr/bin/python3";
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "'%s' '%s/tests/engine/output_count_check.py' %s '%s' %s", py,
             top ? top : ".", live ? "live" : "", dir, live ? live : "");
    return system(cmd);
}

START_TEST(changing_count_read_back)
{
    struct tlsph_model *m = plate("");
    ck_assert_int_eq(tlsph_output_count_may_change(m), 0);
    char dir[] = "/tmp/test_output_count.XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char path[128];
    snprintf(path, sizeof path, "%s/facts.json", dir);
    FILE *facts = fopen(path, "w");
    ck_assert_ptr_nonnull(facts);
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tlsph_output *o = tlsph_output_open_with(dir, m, 1, &err);
    ck_assert_msg(o != NULL, "%s", err.count ? err.items[0].message : "");
    char counts[256] = ""; /* the counts written so far, for the live reader */
    size_t len = 0;
    fprintf(facts, "{\"counts\": [%zu", m->p.n);
    ck_assert_int_eq(tlsph_output_frame(o, m), 0);
    len += (size_t)snprintf(counts + len, sizeof counts - len, "%zu", m->p.n);
    steps(m, 3);
    ck_assert_int_eq(tlsph_output_frame(o, m), 0);
    fprintf(facts, ", %zu", m->p.n);
    len += (size_t)snprintf(counts + len, sizeof counts - len, " %zu", m->p.n);
    /* each event: the parents' ids and masses (before), the halves' ids (after) */
    struct tlsph_crack_surface cs;
    ck_assert_int_eq(tlsph_crack_surface_init(&cs, 2.4 * 0.001), TLSPH_CRACK_OK);
    int64_t pid[EVENTS][MAXF], h1[EVENTS][MAXF], h2[EVENTS][MAXF];
    double pmass[EVENTS][MAXF];
    size_t kk[EVENTS];
    for (int e = 0; e < EVENTS; e++) {
        size_t parent[MAXF];
        /* the row at rest, y = 0.0045, from the left edge (lattice x = 0.0005) */
        const double xe = 0.0005 + 0.001 * e;
        const size_t k = fibre_near(m, xe, 0.0045, parent);
        ck_assert_uint_eq(k, 3);
        kk[e] = k;
        for (size_t s = 0; s < k; s++) {
            pid[e][s] = m->p.id[parent[s]];
            pmass[e][s] = m->p.mass[parent[s]];
        }
        const size_t n0 = m->p.n, at = m->body_end[0];
        const size_t first = cs.nfacets;
        grow_crack(&cs, 0.0045, e ? xe - 0.001 : xe - 0.002, xe);
        struct tlsph_split sp = {parent, k, {1, 0, 0}, {1, 0, 0}, {0, DELTA, 0}};
        ck_assert_int_eq(tlsph_split_particles(m, &sp, &cs, first, NULL, NULL, &err), 0);
        ck_assert_uint_eq(m->p.n, n0 + k);
        for (size_t s = 0; s < k; s++) {
            h1[e][s] = m->p.id[parent[s]]; /* half 1 keeps the index */
            h2[e][s] = m->p.id[at + s];    /* half 2 at the end of the body's range */
        }
        steps(m, 3);
        ck_assert_int_eq(tlsph_output_frame(o, m), 0);
        fprintf(facts, ", %zu", m->p.n);
        len += (size_t)snprintf(counts + len, sizeof counts - len, " %zu", m->p.n);
        if (e == 1) /* a reader while the run writes sees the grown frames */
            ck_assert_int_eq(run_checker(dir, counts), 0);
    }
    /* a frame of the same count again: nothing new */
    steps(m, 2);
    ck_assert_int_eq(tlsph_output_frame(o, m), 0);
    fprintf(facts, ", %zu], \"splits\": [", m->p.n);
    for (int e = 0; e < EVENTS; e++)
        for (size_t s = 0; s < kk[e]; s++)
            fprintf(facts, "%s{\"frame\": %d, \"parent\": %lld, \"mass\": %.17g, \"halves\": [%lld, %lld]}",
                    e || s ? ", " : "", e + 2, (long long)pid[e][s], pmass[e][s],
                    (long long)h1[e][s], (long long)h2[e][s]);
    fputs("]}\n", facts);
    ck_assert_int_eq(fclose(facts), 0);
    struct tlsph_cost cost = {.particles = m->p.n, .steps = m->step, .threads = 1};
    ck_assert_int_eq(tlsph_output_close(o, m, &cost, "successful", NULL), 0);
    tlsph_errors_free(&err);
    tlsph_crack_surface_release(&cs);
    ck_assert_int_eq(run_checker(dir, NULL), 0);
    remove_dir(dir);
    tlsph_model_free(m);
}
END_TEST

/* A file for changing counts opened where no file can be made leaves nothing
 * allocated (the sanitizer build checks the leak).  (A file with one count
 * per run refusing a frame after a split: test_split's
 * output_refuses_a_new_count.) */
START_TEST(open_failures)
{
    /* a regular file where the directory should be: HDF5 fails to create
     * result.h5 in it after every table is allocated */
    char file[] = "/tmp/test_output_count.XXXXXX";
    const int fd = mkstemp(file);
    ck_assert_int_ge(fd, 0);
    close(fd);
    struct tlsph_model *m = plate("");
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    ck_assert_ptr_null(tlsph_output_open_with(file, m, 1, &err));
    ck_assert_uint_eq(err.count, 1);
    ck_assert_ptr_null(tlsph_output_open_with("/proc/no-such-dir/out", m, 1, &err));
    ck_assert_uint_eq(err.count, 2);
    tlsph_errors_free(&err);
    ck_assert_int_eq(unlink(file), 0);
    tlsph_model_free(m);
}
END_TEST

/* A model whose crack grows (crack_growth) gets the layout for changing counts
 * from tlsph_output_open; the same thin plate with fibres and a pre-crack but
 * no growth keeps one count per run (its file is no larger than it must be). */
START_TEST(growth_chooses_changing_count)
{
    char text[4096];
    struct tlsph_model *m = build_model(crack_plate_scene(text, sizeof text, 24.0, 20.0, 1e-6, 1));
    ck_assert_int_eq(tlsph_output_count_may_change(m), 1);
    tlsph_model_free(m);
    m = build_model(crack_plate_scene(text, sizeof text, 24.0, 20.0, 1e-6, 0));
    ck_assert_ptr_nonnull(m->fibres);
    ck_assert_int_eq(tlsph_output_count_may_change(m), 0);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("output_count", 120, changing_count_read_back, open_failures,
                 growth_chooses_changing_count)
