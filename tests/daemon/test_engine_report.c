/* Unit tests of server/engine_report.c: the daemon's reader of the engine
 * protocol (core/run/protocol.h, docs/protocol.md).  Lines arrive in any
 * chunking; junk and over-long lines are skipped; the job's final state comes
 * from the exit status and its message from the final event alone. */
#include <check.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>

#include "engine_report.h"
#include "queue.h"
#include "run/protocol.h"
#include "strbuf.h"
#include "support/check_main.h"

#define EXITED(code) ((code) << 8) /* a wait status as waitpid reports it (Linux) */

static bool feed(struct engine_report *r, const char *text)
{
    return engine_report_feed(r, text, strlen(text));
}

START_TEST(test_chunked_progress)
{
    struct engine_report r;
    engine_report_init(&r, 5.0);
    ck_assert_double_eq(r.end_time, 5.0);
    ck_assert_double_eq(r.eta, -1.0);
    /* a started event split over three reads */
    ck_assert(!feed(&r, "{\"event\":\"sta"));
    ck_assert(!feed(&r, "rted\",\"end_time\":"));
    ck_assert(feed(&r, "2.5,\"particles\":10}\n"));
    ck_assert_double_eq(r.end_time, 2.5);
    /* two progress events in one read: the later wins */
    ck_assert(feed(&r, "{\"event\":\"progress\",\"step\":3,\"time\":0.5,\"end_time\":2.5,\"eta_seconds\":9}\n"
                       "{\"event\":\"progress\",\"step\":7,\"time\":1.25,\"end_time\":2.5,\"eta_seconds\":4}\n"));
    ck_assert_int_eq(r.step, 7);
    ck_assert_double_eq(r.sim_time, 1.25);
    ck_assert_double_eq(r.eta, 4.0);
    ck_assert(!r.finished);
    engine_report_free(&r);
}
END_TEST

START_TEST(test_junk_and_long_lines)
{
    struct engine_report r;
    engine_report_init(&r, 1.0);
    ck_assert(!feed(&r, "not json\n[1,2]\n{\"no\":\"event\"}\n\n"));
    /* a line one byte over the limit (newline not counted) is dropped whole,
     * the next one counts */
    struct strbuf big = {0};
    strbuf_adds(&big, "{\"event\":\"progress\",\"step\":99,\"pad\":\"");
    while (big.len < ENGINE_LINE_MAX - 1)
        strbuf_adds(&big, "x");
    strbuf_adds(&big, "\"}\n");
    ck_assert_uint_eq(big.len, ENGINE_LINE_MAX + 2);
    for (size_t off = 0; off < big.len; off += 4096) /* in pipe-sized reads */
        ck_assert(!engine_report_feed(&r, big.p + off, big.len - off < 4096 ? big.len - off : 4096));
    strbuf_free(&big);
    ck_assert_int_eq(r.step, 0);
    ck_assert(feed(&r, "{\"event\":\"progress\",\"step\":5,\"time\":0.1}\n"));
    ck_assert_int_eq(r.step, 5);
    engine_report_free(&r);
}
END_TEST

START_TEST(test_last_words_without_newline)
{
    struct engine_report r;
    engine_report_init(&r, 1.0);
    feed(&r, "{\"event\":\"finished\",\"status\":\"successful\",\"step\":4,\"time\":1.0,"
             "\"cost\":{\"steps\":4}}");
    ck_assert(!r.finished);
    ck_assert(engine_report_eof(&r)); /* its step and time are the job's last */
    ck_assert(r.finished);
    ck_assert_int_eq(r.step, 4);
    ck_assert_str_eq(r.cost, "{\"steps\":4}");
    struct engine_outcome o;
    engine_outcome(&r, EXITED(TLSPH_EXIT_SUCCESS), ENGINE_NOT_STOPPED, 60, &o);
    ck_assert(!o.requeue);
    ck_assert_str_eq(o.status, TQ_SUCCESSFUL);
    ck_assert_str_eq(o.outcome, "successful");
    ck_assert_ptr_null(o.message);
    engine_report_free(&r);
}
END_TEST

/* The invalid-scene message is the errors of the final event, formatted as
 * the engine prints them, at most five; the log is never read. */
START_TEST(test_invalid_from_event)
{
    struct engine_report r;
    engine_report_init(&r, 1.0);
    feed(&r, "{\"event\":\"finished\",\"status\":\"invalid\",\"errors\":["
             "{\"pointer\":\"\",\"detail\":\"invalid JSON at line 1\"},"
             "{\"pointer\":\"/time/cfl\",\"detail\":\"'cfl' = 0 is out of range\"},"
             "{\"pointer\":\"/a\",\"detail\":\"3\"},{\"pointer\":\"/b\",\"detail\":\"4\"},"
             "{\"pointer\":\"/c\",\"detail\":\"5\"},{\"pointer\":\"/d\",\"detail\":\"6\"}]}\n");
    struct engine_outcome o;
    engine_outcome(&r, EXITED(TLSPH_EXIT_INVALID), ENGINE_NOT_STOPPED, 60, &o);
    ck_assert_str_eq(o.status, TQ_FAILED);
    ck_assert_str_eq(o.outcome, "invalid");
    ck_assert_str_eq(o.message, "(scene): invalid JSON at line 1\n/time/cfl: 'cfl' = 0 is out of "
                                "range\n/a: 3\n/b: 4\n/c: 5");
    free(o.message);
    engine_report_free(&r);

    engine_report_init(&r, 1.0); /* no final event at all */
    engine_outcome(&r, EXITED(TLSPH_EXIT_INVALID), ENGINE_NOT_STOPPED, 60, &o);
    ck_assert_str_eq(o.message, "invalid scene");
    free(o.message);
    engine_report_free(&r);
}
END_TEST

START_TEST(test_unstable_and_io)
{
    struct engine_report r;
    engine_report_init(&r, 1.0);
    feed(&r, "{\"event\":\"finished\",\"status\":\"unstable\",\"step\":5,\"time\":2e-5,"
             "\"cost\":{\"steps\":5},\"diagnostic\":{\"quantity\":\"det_F\","
             "\"message\":\"numerically unstable at step 5\"}}\n");
    struct engine_outcome o;
    engine_outcome(&r, EXITED(TLSPH_EXIT_UNSTABLE), ENGINE_NOT_STOPPED, 60, &o);
    ck_assert_str_eq(o.outcome, "unstable");
    ck_assert_str_eq(o.message, "numerically unstable at step 5");
    ck_assert_int_eq(r.step, 5);
    free(o.message);
    engine_report_free(&r);

    engine_report_init(&r, 1.0);
    feed(&r, "{\"event\":\"finished\",\"status\":\"io_error\",\"errors\":[{\"pointer\":\"\","
             "\"detail\":\"cannot create result.h5\"}]}\n");
    engine_outcome(&r, EXITED(TLSPH_EXIT_IO), ENGINE_NOT_STOPPED, 60, &o);
    ck_assert_str_eq(o.outcome, "io_error");
    ck_assert_str_eq(o.message, "I/O failure: (scene): cannot create result.h5");
    free(o.message);
    engine_report_free(&r);
}
END_TEST

/* Why the daemon stopped the engine decides before the exit code, except that
 * a successful exit always counts.  message NULL: none expected; a leading
 * '~': the message contains the rest. */
static const struct {
    int wstatus;
    enum engine_stop why;
    const char *status, *outcome, *message;
} stops[] = {
    {EXITED(TLSPH_EXIT_CANCELLED), ENGINE_NOT_STOPPED, TQ_DISMISSED, "cancelled", "cancelled"},
    {SIGKILL, ENGINE_STOP_CANCEL, TQ_DISMISSED, "cancelled", "cancelled"},
    {SIGKILL, ENGINE_STOP_TIMEOUT, TQ_FAILED, "timed_out", "wall-clock limit of 2 s exceeded"},
    {EXITED(0), ENGINE_STOP_TIMEOUT, TQ_SUCCESSFUL, "successful", NULL},
    {SIGKILL, ENGINE_NOT_STOPPED, TQ_FAILED, "crashed",
     "killed by signal 9 (SIGKILL): killed externally or out of memory"},
    {EXITED(127), ENGINE_NOT_STOPPED, TQ_FAILED, "crashed", "~unexpected status 127"},
    {-1, ENGINE_NOT_STOPPED, TQ_FAILED, "crashed", "~exit status was lost"},
};

START_TEST(test_stops_and_deaths)
{
    struct engine_report r;
    engine_report_init(&r, 1.0);
    struct engine_outcome o;
    /* a shutdown requeues, whatever the engine said */
    engine_outcome(&r, EXITED(TLSPH_EXIT_CANCELLED), ENGINE_STOP_SHUTDOWN, 60, &o);
    ck_assert(o.requeue);
    for (size_t k = 0; k < sizeof stops / sizeof stops[0]; k++) {
        engine_outcome(&r, stops[k].wstatus, stops[k].why, 2, &o);
        ck_assert_msg(!o.requeue, "case %zu", k);
        ck_assert_str_eq(o.status, stops[k].status);
        ck_assert_str_eq(o.outcome, stops[k].outcome);
        const char *want = stops[k].message;
        if (!want)
            ck_assert_ptr_null(o.message);
        else if (want[0] == '~')
            ck_assert_msg(o.message && strstr(o.message, want + 1), "case %zu: %s", k, o.message);
        else
            ck_assert_str_eq(o.message, want);
        free(o.message);
    }
    engine_report_free(&r);
}
END_TEST

/* A cancelled run's final event carries its last step and time: they move the
 * job's progress, so that simulation.step agrees with cost.steps. */
START_TEST(test_final_event_moves_progress)
{
    struct engine_report r;
    engine_report_init(&r, 1.0);
    ck_assert(feed(&r, "{\"event\":\"progress\",\"step\":4002,\"time\":0.0002}\n"));
    ck_assert(feed(&r, "{\"event\":\"finished\",\"status\":\"cancelled\",\"step\":5072,"
                       "\"time\":0.00025,\"cost\":{\"steps\":5072}}\n"));
    ck_assert(r.finished);
    ck_assert_int_eq(r.step, 5072);
    ck_assert(r.sim_time == 0.00025);
    engine_report_free(&r);
}
END_TEST

static Suite *report_suite(void)
{
    Suite *s = suite_create("engine_report");
    TCase *tc = tcase_create("engine_report");
    tcase_add_test(tc, test_chunked_progress);
    tcase_add_test(tc, test_final_event_moves_progress);
    tcase_add_test(tc, test_junk_and_long_lines);
    tcase_add_test(tc, test_last_words_without_newline);
    tcase_add_test(tc, test_invalid_from_event);
    tcase_add_test(tc, test_unstable_and_io);
    tcase_add_test(tc, test_stops_and_deaths);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return tlsph_check_run(report_suite());
}
