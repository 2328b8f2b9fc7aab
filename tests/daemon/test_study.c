/* Unit tests of server/study.c: expansion, pointers, validation errors with
 * exact JSON pointers, and the summary table (with one real result file made
 * by tlsph-run; env top_builddir / top_srcdir, default "."). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "results.h"
#include "study.h"
#include "support/check_main.h"

static json_t *load(const char *text)
{
    json_error_t e;
    json_t *v = json_loads(text, JSON_REJECT_DUPLICATES, &e);
    if (!v)
        fprintf(stderr, "bad test JSON: %s: %s\n", e.text, text);
    return v;
}

static const char *env_or(const char *name, const char *def)
{
    const char *v = getenv(name);
    return v && *v ? v : def;
}

#define BASE                                                                                       \
    "{\"name\": \"s\", \"dimension\": 2, \"time\": {\"end\": 1e-4},"                               \
    " \"materials\": {\"steel\": {\"density\": 7850}},"                                            \
    " \"bodies\": [{\"name\": \"b\", \"material\": \"steel\", \"spacing\": 0.001},"                \
    "            {\"name\": \"c\", \"material\": \"steel\", \"spacing\": 0.002}],"                \
    " \"parameters\": {\"a/b\": 1, \"t~x\": 2}}"

static int has_error(const struct tlsph_errors *e, const char *pointer, const char *needle)
{
    for (size_t i = 0; i < e->count; i++)
        if (strcmp(e->items[i].pointer, pointer) == 0 &&
            (!needle || strstr(e->items[i].message, needle)))
            return 1;
    return 0;
}

static void dump_errors(const struct tlsph_errors *e)
{
    for (size_t i = 0; i < e->count; i++)
        fprintf(stderr, "  %s: %s\n", e->items[i].pointer, e->items[i].message);
}

static double num_at(json_t *root, const char *pointer)
{
    json_t *v = tstudy_pointer_get(root, pointer);
    ck_assert_msg(json_is_number(v), "%s is not a number", pointer);
    return json_number_value(v);
}

/* ------------------------------------------------------------ expansion */

START_TEST(test_product_order)
{
    json_t *study = load("{\"base\": " BASE ", \"sweep\": {\"parameters\": ["
                         "{\"pointer\": \"/bodies/0/spacing\", \"values\": [0.002, 0.001]},"
                         "{\"pointer\": \"/time/end\", \"values\": [1e-4, 2e-4, 3e-4]}]}}");
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tstudy_child *c;
    size_t n;
    int rc = tstudy_expand(study, 100, &c, &n, &err);
    if (rc)
        dump_errors(&err);
    ck_assert_int_eq(rc, 0);
    ck_assert_int_eq(err.count, 0);
    ck_assert_int_eq(n, 6);
    const double sp[] = {0.002, 0.002, 0.002, 0.001, 0.001, 0.001};
    const double te[] = {1e-4, 2e-4, 3e-4, 1e-4, 2e-4, 3e-4};
    for (size_t k = 0; k < n; k++) {
        ck_assert(num_at(c[k].scene, "/bodies/0/spacing") == sp[k]);
        ck_assert(num_at(c[k].scene, "/time/end") == te[k]);
        /* the rest of the base is untouched */
        ck_assert(num_at(c[k].scene, "/bodies/1/spacing") == 0.002);
        ck_assert_str_eq(json_string_value(tstudy_pointer_get(c[k].scene, "/name")), "s");
        ck_assert_int_eq(json_object_size(c[k].params), 2);
        ck_assert(json_number_value(json_object_get(c[k].params, "/bodies/0/spacing")) == sp[k]);
        ck_assert(json_number_value(json_object_get(c[k].params, "/time/end")) == te[k]);
    }
    /* children are deep copies: the base and the other children do not change */
    json_object_set_new(json_object_get(c[0].scene, "time"), "end", json_real(9));
    ck_assert(num_at(c[1].scene, "/time/end") == 2e-4);
    ck_assert(num_at(json_object_get(study, "base"), "/time/end") == 1e-4);
    ck_assert(num_at(json_object_get(study, "base"), "/bodies/0/spacing") == 0.001);
    tstudy_children_free(c, n);
    tlsph_errors_free(&err);
    json_decref(study);
}
END_TEST

START_TEST(test_zip_and_range)
{
    json_t *study = load("{\"base\": " BASE ", \"sweep\": {\"mode\": \"zip\", \"parameters\": ["
                         "{\"pointer\": \"/bodies/0/spacing\", \"range\": {\"start\": 1, \"stop\": 2, \"num\": 3}},"
                         "{\"pointer\": \"/bodies/1/geometry\", \"values\": [{\"box\": 1}, [1, 2], \"x\"]}]}}");
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tstudy_child *c;
    size_t n;
    int rc = tstudy_expand(study, 100, &c, &n, &err);
    if (rc)
        dump_errors(&err);
    ck_assert_int_eq(rc, 0);
    ck_assert_int_eq(n, 3);
    ck_assert(num_at(c[0].scene, "/bodies/0/spacing") == 1.0);
    ck_assert(num_at(c[1].scene, "/bodies/0/spacing") == 1.5);
    ck_assert(num_at(c[2].scene, "/bodies/0/spacing") == 2.0);
    /* 1, 1.5, 2 are not all integral: all reals */
    ck_assert(json_is_real(tstudy_pointer_get(c[0].scene, "/bodies/0/spacing")));
    ck_assert(json_is_real(tstudy_pointer_get(c[1].scene, "/bodies/0/spacing")));
    /* a new key of an existing object, with object / array / string values */
    ck_assert(json_is_object(tstudy_pointer_get(c[0].scene, "/bodies/1/geometry")));
    ck_assert(num_at(c[0].scene, "/bodies/1/geometry/box") == 1);
    ck_assert(num_at(c[1].scene, "/bodies/1/geometry/1") == 2);
    ck_assert_str_eq(json_string_value(tstudy_pointer_get(c[2].scene, "/bodies/1/geometry")), "x");
    json_t *expect = json_pack("[i,i]", 1, 2);
    ck_assert(json_equal(json_object_get(c[1].params, "/bodies/1/geometry"), expect));
    json_decref(expect);
    tstudy_children_free(c, n);
    json_decref(study);

    /* exact linspace values, real ends */
    study = load("{\"base\": " BASE ", \"sweep\": {\"parameters\": ["
                 "{\"pointer\": \"/time/end\", \"range\": {\"start\": 1e-4, \"stop\": 3e-4, \"num\": 3}},"
                 "{\"pointer\": \"/time/cfl\", \"range\": {\"start\": 0.5, \"stop\": 0.5, \"num\": 1}},"
                 "{\"pointer\": \"/output\", \"values\": [{\"frames\": 4}]}]}}");
    rc = tstudy_expand(study, 100, &c, &n, &err);
    ck_assert_int_eq(rc, 0);
    ck_assert_int_eq(n, 3);
    ck_assert_int_eq(json_integer_value(tstudy_pointer_get(c[1].scene, "/output/frames")), 4);
    ck_assert(num_at(c[0].scene, "/time/end") == 1e-4);
    ck_assert(num_at(c[1].scene, "/time/end") == 1e-4 + (3e-4 - 1e-4) / 2.0);
    ck_assert(num_at(c[2].scene, "/time/end") == 3e-4);
    ck_assert(num_at(c[2].scene, "/time/cfl") == 0.5);
    tstudy_children_free(c, n);
    json_decref(study);
    /* integer ends with integral values stay integers (e.g. output.frames) */
    study = load("{\"base\": " BASE ", \"sweep\": {\"parameters\": ["
                 "{\"pointer\": \"/output\", \"values\": [{}]},"
                 "{\"pointer\": \"/time/frames\", \"range\": {\"start\": 10, \"stop\": 30, \"num\": 3}}]}}");
    rc = tstudy_expand(study, 100, &c, &n, &err);
    ck_assert_int_eq(rc, 0);
    ck_assert_int_eq(n, 3);
    ck_assert(json_is_integer(tstudy_pointer_get(c[1].scene, "/time/frames")));
    ck_assert_int_eq(json_integer_value(tstudy_pointer_get(c[1].scene, "/time/frames")), 20);
    ck_assert_int_eq(json_integer_value(tstudy_pointer_get(c[2].scene, "/time/frames")), 30);
    tstudy_children_free(c, n);
    json_decref(study);
    ck_assert_int_eq(err.count, 0);
    tlsph_errors_free(&err);
}
END_TEST

START_TEST(test_pointers)
{
    json_t *base = load(BASE);
    ck_assert(num_at(base, "/parameters/a~1b") == 1);
    ck_assert(num_at(base, "/parameters/t~0x") == 2);
    ck_assert(num_at(base, "/bodies/0/spacing") == 0.001);
    ck_assert(num_at(base, "/bodies/1/spacing") == 0.002);
    ck_assert_ptr_eq(tstudy_pointer_get(base, ""), base);
    ck_assert_ptr_null(tstudy_pointer_get(base, "/bodies/2/spacing"));   /* out of range */
    ck_assert_ptr_null(tstudy_pointer_get(base, "/bodies/01/spacing"));  /* leading zero */
    ck_assert_ptr_null(tstudy_pointer_get(base, "/bodies/-"));
    ck_assert_ptr_null(tstudy_pointer_get(base, "/bodies/-1"));
    ck_assert_ptr_null(tstudy_pointer_get(base, "/bodies/+0"));
    ck_assert_ptr_null(tstudy_pointer_get(base, "/parameters/a~2b")); /* bad escape */
    ck_assert_ptr_null(tstudy_pointer_get(base, "/parameters/a~"));
    ck_assert_ptr_null(tstudy_pointer_get(base, "parameters"));       /* no leading / */
    ck_assert_ptr_null(tstudy_pointer_get(base, "/name/x"));          /* through a string */
    ck_assert_ptr_null(tstudy_pointer_get(base, "/parameters/a/b"));  /* unescaped / */

    ck_assert_int_eq(tstudy_pointer_set(base, "/parameters/a~1b", json_integer(7)), 0);
    ck_assert(num_at(base, "/parameters/a~1b") == 7);
    ck_assert_int_eq(tstudy_pointer_set(base, "/parameters/new~0key", json_integer(8)), 0);
    ck_assert(num_at(base, "/parameters/new~0key") == 8);
    ck_assert(json_object_get(json_object_get(base, "parameters"), "new~key") != NULL);
    ck_assert_int_eq(tstudy_pointer_set(base, "/bodies/1", json_string("y")), 0);
    ck_assert_str_eq(json_string_value(tstudy_pointer_get(base, "/bodies/1")), "y");
    ck_assert_int_eq(json_array_size(json_object_get(base, "bodies")), 2);
    /* failures steal the value too (valgrind checks) */
    ck_assert_int_eq(tstudy_pointer_set(base, "/bodies/2", json_integer(1)), -1);
    ck_assert_int_eq(tstudy_pointer_set(base, "/bodies/-", json_integer(1)), -1);
    ck_assert_int_eq(tstudy_pointer_set(base, "/no/such", json_integer(1)), -1);
    ck_assert_int_eq(tstudy_pointer_set(base, "", json_integer(1)), -1);
    ck_assert_int_eq(tstudy_pointer_set(base, "/name/x", json_integer(1)), -1);
    ck_assert_int_eq(tstudy_pointer_set(base, "/x", NULL), -1);
    json_decref(base);

    /* a study with escaped pointers */
    json_t *study = load("{\"base\": " BASE ", \"sweep\": {\"parameters\": ["
                         "{\"pointer\": \"/parameters/a~1b\", \"values\": [10, 20]},"
                         "{\"pointer\": \"/parameters/t~0x\", \"values\": [30]}]}}");
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tstudy_child *c;
    size_t n;
    ck_assert_int_eq(tstudy_expand(study, 10, &c, &n, &err), 0);
    ck_assert_int_eq(n, 2);
    ck_assert_int_eq(json_integer_value(json_object_get(json_object_get(c[1].scene, "parameters"), "a/b")), 20);
    ck_assert_int_eq(json_integer_value(json_object_get(json_object_get(c[1].scene, "parameters"), "t~x")), 30);
    ck_assert_int_eq(json_integer_value(json_object_get(c[1].params, "/parameters/a~1b")), 20);
    tstudy_children_free(c, n);
    tlsph_errors_free(&err);
    json_decref(study);
}
END_TEST

/* ------------------------------------------------------------ errors */

static void expect_fail(const char *text, size_t max_children, struct tlsph_errors *err)
{
    json_t *study = load(text);
    ck_assert_ptr_nonnull(study);
    tlsph_errors_init(err);
    struct tstudy_child *c = (void *)1;
    size_t n = 99;
    ck_assert_int_eq(tstudy_expand(study, max_children, &c, &n, err), -1);
    ck_assert_ptr_null(c);
    ck_assert_int_eq(n, 0);
    ck_assert_int_gt(err->count, 0);
    json_decref(study);
}

START_TEST(test_errors_each)
{
    struct tlsph_errors e;
    expect_fail("[1]", 10, &e);
    ck_assert(has_error(&e, "", "object"));
    tlsph_errors_free(&e);

    expect_fail("{\"base\": 3, \"sweep\": {\"parameters\": [{\"pointer\": \"/a\", \"values\": [1]}]}}",
                10, &e);
    ck_assert(has_error(&e, "/base", NULL));
    ck_assert_int_eq(e.count, 1);
    tlsph_errors_free(&e);

    expect_fail("{\"base\": " BASE ", \"sweep\": {\"mode\": \"cartesian\", \"parameters\": "
                "[{\"pointer\": \"/time/end\", \"values\": [1]}]}}", 10, &e);
    ck_assert(has_error(&e, "/sweep/mode", NULL));
    ck_assert_int_eq(e.count, 1);
    tlsph_errors_free(&e);

    expect_fail("{\"base\": " BASE ", \"sweep\": {\"parameters\": []}}", 10, &e);
    ck_assert(has_error(&e, "/sweep/parameters", "non-empty"));
    tlsph_errors_free(&e);

    expect_fail("{\"base\": " BASE ", \"sweep\": {\"parameters\": "
                "[{\"pointer\": \"/time/end\", \"values\": [1]},"
                " {\"pointer\": \"/nothing/here\", \"values\": [1]}]}}", 10, &e);
    ck_assert(has_error(&e, "/sweep/parameters/1/pointer", "does not resolve"));
    ck_assert_int_eq(e.count, 1);
    tlsph_errors_free(&e);

    expect_fail("{\"base\": " BASE ", \"sweep\": {\"parameters\": "
                "[{\"pointer\": \"/time/end\", \"values\": [1], \"range\": {\"start\": 1, \"stop\": 2, \"num\": 2}}]}}",
                10, &e);
    ck_assert(has_error(&e, "/sweep/parameters/0", "not both"));
    tlsph_errors_free(&e);

    expect_fail("{\"base\": " BASE ", \"sweep\": {\"mode\": \"zip\", \"parameters\": "
                "[{\"pointer\": \"/time/end\", \"values\": [1, 2]},"
                " {\"pointer\": \"/time/cfl\", \"values\": [1, 2, 3]}]}}", 10, &e);
    ck_assert(has_error(&e, "/sweep/parameters/1", "equal lengths"));
    ck_assert_int_eq(e.count, 1);
    tlsph_errors_free(&e);

    expect_fail("{\"base\": " BASE ", \"sweep\": {\"parameters\": "
                "[{\"pointer\": \"/time/end\", \"range\": {\"start\": 1, \"stop\": 2, \"num\": 10}},"
                " {\"pointer\": \"/time/cfl\", \"range\": {\"start\": 1, \"stop\": 2, \"num\": 11}}]}}",
                100, &e);
    ck_assert(has_error(&e, "/sweep/parameters", "110 children"));
    ck_assert_int_eq(e.count, 1);
    tlsph_errors_free(&e);

    expect_fail("{\"base\": " BASE ", \"sweep\": {\"parameters\": [{\"pointer\": \"/time/end\", \"values\": [1]}]},"
                " \"outputs\": [{\"name\": \"peak\", \"series\": \"kinetic_energy\", \"reduce\": \"mean\"}]}",
                10, &e);
    ck_assert(has_error(&e, "/outputs/0/reduce", NULL));
    ck_assert_int_eq(e.count, 1);
    tlsph_errors_free(&e);
}
END_TEST

START_TEST(test_errors_all_at_once)
{
    struct tlsph_errors e;
    expect_fail("{\"base\": " BASE ", \"extra\": 1,"
                " \"sweep\": {\"mode\": \"diagonal\", \"parameters\": ["
                "  {\"pointer\": \"/time/end\", \"values\": []},"                              /* 0 */
                "  {\"pointer\": \"time/end\", \"values\": [1]},"                              /* 1 */
                "  {\"pointer\": \"/bodies/5/spacing\", \"values\": [1]},"                     /* 2 */
                "  {\"pointer\": \"/time/cfl\", \"values\": [1], \"range\": {\"start\": 0, \"stop\": 1, \"num\": 2}}," /* 3 */
                "  {\"pointer\": \"/time/x\", \"range\": {\"start\": \"a\", \"stop\": 1, \"num\": 0, \"step\": 1}}," /* 4 */
                "  {\"pointer\": \"/time\", \"values\": [1]},"                                 /* 5 overlaps 3/4? */
                "  {\"pointer\": \"/bodies/0/spacing\", \"values\": [1], \"unit\": \"m\"},"    /* 6 */
                "  {\"pointer\": \"/a~2\", \"values\": [1]},"                                  /* 7 */
                "  {\"values\": [1]},"                                                          /* 8 */
                "  7]},"                                                                        /* 9 */
                " \"outputs\": [{\"name\": \"bad name\", \"series\": \"../x\", \"component\": 3, \"reduce\": \"avg\"},"
                "               {\"name\": \"ok\", \"series\": \"kinetic_energy\"},"
                "               {\"name\": \"ok\", \"series\": \"kinetic_energy\", \"color\": 1},"
                "               {\"name\": \"steps\", \"series\": \"kinetic_energy\"}, 5]}",
                10, &e);
    if (getenv("VERBOSE"))
        dump_errors(&e);
    ck_assert(has_error(&e, "/extra", "unknown key"));
    ck_assert(has_error(&e, "/sweep/mode", NULL));
    ck_assert(has_error(&e, "/sweep/parameters/0/values", "non-empty"));
    ck_assert(has_error(&e, "/sweep/parameters/1/pointer", "RFC 6901"));
    ck_assert(has_error(&e, "/sweep/parameters/2/pointer", "does not resolve"));
    ck_assert(has_error(&e, "/sweep/parameters/3", "not both"));
    ck_assert(has_error(&e, "/sweep/parameters/4/range/start", NULL));
    ck_assert(has_error(&e, "/sweep/parameters/4/range/num", "1..1000"));
    ck_assert(has_error(&e, "/sweep/parameters/4/range/step", "unknown key"));
    ck_assert(has_error(&e, "/sweep/parameters/5/pointer", "overlaps"));
    ck_assert(has_error(&e, "/sweep/parameters/6/unit", "unknown key"));
    ck_assert(has_error(&e, "/sweep/parameters/7/pointer", NULL));
    ck_assert(has_error(&e, "/sweep/parameters/8", "missing \"pointer\""));
    ck_assert(has_error(&e, "/sweep/parameters/9", "object"));
    ck_assert(has_error(&e, "/outputs/0/name", NULL));
    ck_assert(has_error(&e, "/outputs/0/series", NULL));
    ck_assert(has_error(&e, "/outputs/0/component", NULL));
    ck_assert(has_error(&e, "/outputs/0/reduce", NULL));
    ck_assert(has_error(&e, "/outputs/2/name", "duplicate"));
    ck_assert(has_error(&e, "/outputs/2/color", "unknown key"));
    ck_assert(has_error(&e, "/outputs/3/name", "reserved"));
    ck_assert(has_error(&e, "/outputs/4", "object"));
    tlsph_errors_free(&e);

    /* missing members */
    expect_fail("{}", 10, &e);
    ck_assert(has_error(&e, "", "\"base\""));
    ck_assert(has_error(&e, "", "\"sweep\""));
    tlsph_errors_free(&e);
    expect_fail("{\"base\": {}, \"sweep\": {\"parameters\": [{\"pointer\": \"/x\", \"range\": {}}]}}", 10, &e);
    ck_assert(has_error(&e, "/sweep/parameters/0/range", "\"start\""));
    ck_assert(has_error(&e, "/sweep/parameters/0/range", "\"stop\""));
    ck_assert(has_error(&e, "/sweep/parameters/0/range", "\"num\""));
    tlsph_errors_free(&e);
    /* product overflow is caught, not wrapped */
    char text[8192];
    size_t len = (size_t)snprintf(text, sizeof text, "{\"base\": {\"a\": {}}, \"sweep\": {\"parameters\": [");
    for (int i = 0; i < 16; i++)
        len += (size_t)snprintf(text + len, sizeof text - len,
                                "%s{\"pointer\": \"/a/k%d\", \"range\": {\"start\": 0, \"stop\": 1, \"num\": 1000}}",
                                i ? "," : "", i);
    snprintf(text + len, sizeof text - len, "]}}");
    expect_fail(text, 100000, &e);
    ck_assert(has_error(&e, "/sweep/parameters", "too many"));
    tlsph_errors_free(&e);
    /* 17 parameters */
    len = (size_t)snprintf(text, sizeof text, "{\"base\": {\"a\": {}}, \"sweep\": {\"parameters\": [");
    for (int i = 0; i < 17; i++)
        len += (size_t)snprintf(text + len, sizeof text - len, "%s{\"pointer\": \"/a/k%d\", \"values\": [1]}",
                                i ? "," : "", i);
    snprintf(text + len, sizeof text - len, "]}}");
    expect_fail(text, 100000, &e);
    ck_assert(has_error(&e, "/sweep/parameters", "at most 16"));
    tlsph_errors_free(&e);
}
END_TEST

/* ------------------------------------------------------------ summary */

START_TEST(test_summary)
{
    char dir[] = "/tmp/test_study.XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    char cmd[2048], h5[600];
    snprintf(cmd, sizeof cmd, "'%s/tlsph-run' '%s/examples/elastic-strip.json' -o '%s/r' --quiet",
             env_or("top_builddir", "."), env_or("top_srcdir", "."), dir);
    ck_assert_int_eq(system(cmd), 0);
    snprintf(h5, sizeof h5, "%s/r/result.h5", dir);

    json_t *study = load("{\"base\": " BASE ", \"sweep\": {\"parameters\": ["
                         "{\"pointer\": \"/time/end\", \"values\": [4e-4, 8e-4]},"
                         "{\"pointer\": \"/bodies/0/name\", \"values\": [\"a,b\", \"say \\\"hi\\\"\\nthere\"]}]},"
                         " \"outputs\": [{\"name\": \"peak_rf\", \"series\": \"groups/right/reaction_force\", \"reduce\": \"max\"},"
                         "  {\"name\": \"final_ke\", \"series\": \"kinetic_energy\"},"
                         "  {\"name\": \"min_rf_mag\", \"series\": \"groups/right/reaction_force\", \"component\": -1, \"reduce\": \"min\"},"
                         "  {\"name\": \"missing\", \"series\": \"groups/nobody/reaction_force\"}]}");
    json_t *p0 = load("{\"/time/end\": 4e-4, \"/bodies/0/name\": \"a,b\"}");
    json_t *p1 = load("{\"/time/end\": 8e-4, \"/bodies/0/name\": \"say \\\"hi\\\"\\nthere\"}");
    json_t *cost = load("{\"particles\": 400, \"pairs\": 5000, \"steps\": 8004, \"wall_seconds\": 0.5,"
                        " \"particle_steps_per_second\": 6.4e6}");
    struct tstudy_row rows[2] = {
        {0, "aaaa", "successful", p0, h5, cost},
        {1, "bbbb", "failed", p1, "/nonexistent/result.h5", NULL},
    };
    json_t *s = tstudy_summary(study, rows, 2);
    ck_assert_ptr_nonnull(s);
    json_t *cols = load("[\"seq\",\"job_id\",\"status\",\"/time/end\",\"/bodies/0/name\",\"peak_rf\","
                        "\"final_ke\",\"min_rf_mag\",\"missing\",\"particles\",\"steps\",\"wall_seconds\","
                        "\"particle_steps_per_second\"]");
    ck_assert(json_equal(json_object_get(s, "columns"), cols));
    json_t *r0 = json_array_get(json_object_get(s, "rows"), 0),
           *r1 = json_array_get(json_object_get(s, "rows"), 1);
    ck_assert_int_eq(json_array_size(r0), 13);
    ck_assert_int_eq(json_array_size(r1), 13);
    ck_assert_int_eq(json_integer_value(json_array_get(r0, 0)), 0);
    ck_assert_str_eq(json_string_value(json_array_get(r0, 1)), "aaaa");
    ck_assert_str_eq(json_string_value(json_array_get(r0, 2)), "successful");
    ck_assert(json_real_value(json_array_get(r0, 3)) == 4e-4);
    ck_assert_str_eq(json_string_value(json_array_get(r0, 4)), "a,b");
    double fin, mx, mn;
    char err[256];
    ck_assert_int_eq(tres_series_reduce(h5, "groups/right/reaction_force", 0, &fin, &mx, &mn, err, sizeof err), 0);
    ck_assert(json_real_value(json_array_get(r0, 5)) == mx);
    ck_assert(mx > 0);
    ck_assert_int_eq(tres_series_reduce(h5, "kinetic_energy", 0, &fin, &mx, &mn, err, sizeof err), 0);
    ck_assert(json_real_value(json_array_get(r0, 6)) == fin);
    ck_assert_int_eq(tres_series_reduce(h5, "groups/right/reaction_force", -1, &fin, &mx, &mn, err, sizeof err), 0);
    ck_assert(json_real_value(json_array_get(r0, 7)) == mn);
    ck_assert(json_is_null(json_array_get(r0, 8))); /* no such series */
    ck_assert_int_eq(json_integer_value(json_array_get(r0, 9)), 400);
    ck_assert_int_eq(json_integer_value(json_array_get(r0, 10)), 8004);
    ck_assert(json_real_value(json_array_get(r0, 11)) == 0.5);
    ck_assert(json_real_value(json_array_get(r0, 12)) == 6.4e6);
    /* the missing result: every output and cost is null */
    for (size_t i = 5; i < 13; i++)
        ck_assert_msg(json_is_null(json_array_get(r1, i)), "column %zu", i);
    ck_assert_str_eq(json_string_value(json_array_get(r1, 2)), "failed");

    char *csv = tstudy_summary_csv(s);
    ck_assert_ptr_nonnull(csv);
    ck_assert(strncmp(csv, "seq,job_id,status,/time/end,/bodies/0/name,peak_rf,final_ke,min_rf_mag,"
                           "missing,particles,steps,wall_seconds,particle_steps_per_second\r\n", 128) == 0);
    char *line1 = strstr(csv, "\r\n") + 2;
    ck_assert(strncmp(line1, "0,aaaa,successful,0.0004,\"a,b\",", 31) == 0);
    ck_assert(strstr(line1, ",400,8004,0.5,6400000\r\n") != NULL);
    ck_assert(strstr(csv, "\r\n1,bbbb,failed,0.0008,\"say \"\"hi\"\"\nthere\",,,,,,,,\r\n") != NULL);
    free(csv);

    /* no outputs, no rows */
    json_t *plain = load("{\"base\": {}, \"sweep\": {\"parameters\": [{\"pointer\": \"/x\", \"values\": [1]}]}}");
    json_t *s2 = tstudy_summary(plain, NULL, 0);
    ck_assert_int_eq(json_array_size(json_object_get(s2, "columns")), 8);
    ck_assert_int_eq(json_array_size(json_object_get(s2, "rows")), 0);
    csv = tstudy_summary_csv(s2);
    ck_assert_str_eq(csv, "seq,job_id,status,/x,particles,steps,wall_seconds,particle_steps_per_second\r\n");
    free(csv);
    ck_assert_ptr_null(tstudy_summary_csv(p0)); /* not a summary */
    json_decref(s2);
    json_decref(plain);

    json_decref(cols);
    json_decref(s);
    json_decref(study);
    json_decref(p0);
    json_decref(p1);
    json_decref(cost);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(cmd), 0);
}
END_TEST

/* The example body of the schema tests (tests/daemon/examples/study.json) expands. */
START_TEST(test_example_study)
{
    char path[600];
    snprintf(path, sizeof path, "%s/tests/daemon/examples/study.json", env_or("top_srcdir", "."));
    json_error_t je;
    json_t *study = json_load_file(path, JSON_REJECT_DUPLICATES, &je);
    ck_assert_msg(study != NULL, "%s: %s", path, je.text);
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tstudy_child *c;
    size_t n;
    int rc = tstudy_expand(study, 64, &c, &n, &err);
    if (rc)
        dump_errors(&err);
    ck_assert_int_eq(rc, 0);
    ck_assert_int_eq(n, 6);
    ck_assert(num_at(c[0].scene, "/bodies/0/spacing") == 0.002);
    ck_assert(num_at(c[0].scene, "/parameters/vmax") == 0.05);
    ck_assert(num_at(c[5].scene, "/bodies/0/spacing") == 0.001);
    ck_assert(num_at(c[5].scene, "/parameters/vmax") == 0.15);
    ck_assert(fabs(num_at(c[4].scene, "/parameters/vmax") - 0.1) < 1e-15);
    tstudy_children_free(c, n);
    /* the same study with max_children 5 is refused with the count */
    ck_assert_int_eq(tstudy_expand(study, 5, &c, &n, &err), -1);
    ck_assert(has_error(&err, "/sweep/parameters", "6 children, at most 5"));
    tlsph_errors_free(&err);
    json_decref(study);
}
END_TEST

/* A range whose step (stop - start) / (num - 1) is not a finite double is
 * refused: -1e308..1e308 in 2 values used to yield one value (0 * inf is
 * NaN, which JSON cannot hold, and the append failed silently), and with a
 * second parameter of 1000 values a study of 1000 children instead of 2000.
 * Values that round to the same double are refused too. */
START_TEST(test_range_refused)
{
    static const struct {
        const char *parameters, *needle;
    } refused[] = {
        {"{\"pointer\": \"/time/end\", \"range\": {\"start\": -1e308, \"stop\": 1e308, \"num\": 2}},"
         "{\"pointer\": \"/time/cfl\", \"range\": {\"start\": 0.1, \"stop\": 0.9, \"num\": 1000}}",
         "not a finite number"},
        /* 1 + 2^-52 is the next double after 1: three values cannot be distinct */
        {"{\"pointer\": \"/time/end\", \"range\": {\"start\": 1, \"stop\": 1.0000000000000002, "
         "\"num\": 3}}",
         "below double precision"},
    };
    struct tlsph_errors e;
    for (size_t i = 0; i < sizeof refused / sizeof *refused; i++) {
        char text[1024];
        snprintf(text, sizeof text, "{\"base\": %s, \"sweep\": {\"parameters\": [%s]}}", BASE,
                 refused[i].parameters);
        expect_fail(text, 10000, &e);
        ck_assert(has_error(&e, "/sweep/parameters/0/range", refused[i].needle));
        ck_assert_int_eq(e.count, 1);
        tlsph_errors_free(&e);
    }
    /* the widest finite span that still has a finite step is accepted */
    json_t *study = load("{\"base\": " BASE ", \"sweep\": {\"parameters\": ["
                         "{\"pointer\": \"/time/end\", \"range\": {\"start\": -8e307, "
                         "\"stop\": 8e307, \"num\": 2}}]}}");
    struct tstudy_child *c;
    size_t n;
    tlsph_errors_init(&e);
    ck_assert_int_eq(tstudy_expand(study, 10, &c, &n, &e), 0);
    ck_assert_int_eq(n, 2);
    ck_assert(num_at(c[0].scene, "/time/end") == -8e307);
    ck_assert(num_at(c[1].scene, "/time/end") == 8e307);
    tstudy_children_free(c, n);
    json_decref(study);
    tlsph_errors_free(&e);
}
END_TEST

static Suite *study_suite(void)
{
    Suite *s = suite_create("study");
    TCase *tc = tcase_create("study");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_product_order);
    tcase_add_test(tc, test_zip_and_range);
    tcase_add_test(tc, test_pointers);
    tcase_add_test(tc, test_errors_each);
    tcase_add_test(tc, test_errors_all_at_once);
    tcase_add_test(tc, test_summary);
    tcase_add_test(tc, test_example_study);
    tcase_add_test(tc, test_range_refused);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return tlsph_check_run(study_suite());
}
