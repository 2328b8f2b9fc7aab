/* Unit tests of server/numtext.c: the shortest decimal that reads back as
 * the same double (references: strtod, and the digits Python's repr() prints
 * for these doubles), exponents written like jansson writes them; and
 * json_dumps with every real so rewritten (integral ones keep ".0"), strings
 * and integers untouched. */
#include <check.h>
#include <stdlib.h>
#include <string.h>

#include "numtext.h"
#include "support/check_main.h"

static void expect_real(double v, const char *text)
{
    char buf[NUMTEXT_REAL_MAX];
    numtext_real(buf, sizeof buf, v);
    ck_assert_str_eq(buf, text);
    ck_assert(strtod(buf, NULL) == v);
}

START_TEST(shortest_reals)
{
    expect_real(0.05, "0.05");           /* %.17g: 0.050000000000000003 */
    expect_real(0.1 + 0.2, "0.30000000000000004");
    expect_real(1.0, "1");
    expect_real(-0.0, "-0");
    expect_real(100000.0, "100000");
    expect_real(1e20, "1e20");
    expect_real(1e-7, "1e-7");
    expect_real(2.5e-5, "2.5e-5");
    expect_real(1.2345678901234568e20, "1.2345678901234568e20");
    expect_real(5e-324, "5e-324");
    expect_real(1.7976931348623157e308, "1.7976931348623157e308");
    expect_real(4.999183422063635e-07, "4.999183422063635e-7");
}
END_TEST

START_TEST(json_reals_only)
{
    json_t *v = json_pack("{s:f,s:s,s:[i,f,f,f],s:f}", "a", 0.05, "s", "0.050000000000000003 \" 1.5",
                          "b", (json_int_t)1, 2.5, -3e-5, 1e20, "c", 0.0);
    char *text = numtext_json_dumps(v, JSON_COMPACT | JSON_SORT_KEYS);
    ck_assert_ptr_nonnull(text);
    ck_assert_str_eq(text, "{\"a\":0.05,\"b\":[1,2.5,-3e-5,1e20],\"c\":0.0,"
                           "\"s\":\"0.050000000000000003 \\\" 1.5\"}");
    json_t *back = json_loads(text, 0, NULL);
    ck_assert(json_equal(back, v)); /* the same doubles, reals still reals */
    json_decref(back);
    free(text);
    json_decref(v);
}
END_TEST

TLSPH_CHECK_MAIN("numtext", 0, shortest_reals, json_reals_only)
