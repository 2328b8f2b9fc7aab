/* Unit tests of server/thread_budget.c and of how tcfg_load settles the
 * threads: the rules of thread_budget.h.  Reference: the invariant itself,
 * sum of the running engines' threads <= cores, checked after every start
 * and end of a scripted day of jobs and studies; and the shares by hand
 * (2 cores, 2 jobs: 1 thread each). */
#include <check.h>
#include <stdlib.h>
#include <string.h>

#include "../../server/config.h" /* not the build's config.h */
#include "support/check_main.h"
#include "thread_budget.h"

START_TEST(configure_shares_the_cores)
{
    char w[256];
    int t = 0; /* unset: cores / max_jobs */
    ck_assert_int_eq(tbudget_configure(2, 2, &t, w, sizeof w), 0);
    ck_assert_int_eq(t, 1);
    t = 0;
    ck_assert_int_eq(tbudget_configure(8, 1, &t, w, sizeof w), 0);
    ck_assert_int_eq(t, 8);
    t = 0;
    ck_assert_int_eq(tbudget_configure(8, 3, &t, w, sizeof w), 0);
    ck_assert_int_eq(t, 2); /* 3 x 2 <= 8; the spare core is granted to none */
    t = 1;                  /* a fit asked for stays */
    ck_assert_int_eq(tbudget_configure(8, 3, &t, w, sizeof w), 0);
    ck_assert_int_eq(t, 1);
    ck_assert_str_eq(w, "");
}
END_TEST

START_TEST(configure_clamps_oversubscription)
{
    char w[256];
    int t = 2; /* 2 x 2 > 2 cores: lowered, with a warning naming the keys */
    ck_assert_int_eq(tbudget_configure(2, 2, &t, w, sizeof w), 1);
    ck_assert_int_eq(t, 1);
    ck_assert_ptr_nonnull(strstr(w, "threads_per_job 2 x max_jobs 2 > cores 2"));
    t = 0; /* more jobs than cores: one thread each, and a warning that jobs wait */
    ck_assert_int_eq(tbudget_configure(2, 4, &t, w, sizeof w), 1);
    ck_assert_int_eq(t, 1);
    ck_assert_ptr_nonnull(strstr(w, "max_jobs 4 > cores 2"));
}
END_TEST

START_TEST(grant_never_exceeds_the_cores)
{
    struct tbudget b = {.cores = 2, .used = 0};
    /* two 1-thread jobs of a study run side by side; a third waits */
    int a = tbudget_grant(&b, 1);
    tbudget_take(&b, a);
    int c = tbudget_grant(&b, 1);
    tbudget_take(&b, c);
    ck_assert_int_eq(a, 1);
    ck_assert_int_eq(c, 1);
    ck_assert_int_eq(tbudget_grant(&b, 1), 0);
    tbudget_give(&b, a); /* one ends: the next starts */
    ck_assert_int_eq(tbudget_grant(&b, 1), 1);
    /* a job that asks for more than is free gets what is free */
    ck_assert_int_eq(tbudget_grant(&b, 4), 1);
    tbudget_give(&b, c);
    ck_assert_int_eq(tbudget_grant(&b, 4), 2);
    ck_assert_int_eq(tbudget_grant(&b, 0), 1); /* < 1 counts as 1 */

    /* a scripted mix on 3 cores: starts of 1..4 threads and ends, the sum
     * checked after each; a fixed sequence, no clock and no random seed */
    struct tbudget m = {.cores = 3, .used = 0};
    int running[16], n = 0;
    const int script[] = {2, 1, 4, -1, 3, 1, -1, -1, 2, 2, -1, 1, -1, -1, 4, -1};
    for (size_t k = 0; k < sizeof script / sizeof *script; k++) {
        if (script[k] > 0) {
            const int g = tbudget_grant(&m, script[k]);
            ck_assert_int_le(g, script[k]);
            if (g > 0) {
                tbudget_take(&m, g);
                running[n++] = g;
            } else {
                ck_assert_int_eq(m.used, m.cores); /* waits only when none is free */
            }
        } else if (n > 0) {
            tbudget_give(&m, running[--n]);
        }
        ck_assert_int_le(m.used, m.cores);
        ck_assert_int_ge(m.used, 0);
    }
}
END_TEST

START_TEST(config_settles_threads_per_job)
{
    struct tcfg c;
    char err[300] = "";
    char *a1[] = {"tlsphd", "--cores", "2", "--max-jobs", "2", NULL};
    ck_assert_int_eq(tcfg_load(&c, 5, a1, err, sizeof err), TCFG_OK);
    ck_assert_int_eq(c.cores, 2);
    ck_assert_int_eq(c.threads_per_job, 1);
    ck_assert_str_eq(c.budget_warning, "");
    tcfg_free(&c);
    char *a2[] = {"tlsphd", "--cores", "2", "--max-jobs", "2", "--threads-per-job", "2", NULL};
    ck_assert_int_eq(tcfg_load(&c, 7, a2, err, sizeof err), TCFG_OK);
    ck_assert_int_eq(c.threads_per_job, 1);
    ck_assert_ptr_nonnull(strstr(c.budget_warning, "lowered threads_per_job to 1"));
    tcfg_free(&c);
    char *a3[] = {"tlsphd", "--cores", "0", NULL}; /* the range is 1..4096 */
    ck_assert_int_eq(tcfg_load(&c, 3, a3, err, sizeof err), TCFG_ERROR);
    ck_assert_ptr_nonnull(strstr(err, "--cores"));
    tcfg_free(&c);
    char *a4[] = {"tlsphd", NULL}; /* detected: at least one core, all of them for one job */
    ck_assert_int_eq(tcfg_load(&c, 1, a4, err, sizeof err), TCFG_OK);
    ck_assert_int_ge(c.cores, 1);
    ck_assert_int_eq(c.threads_per_job, c.cores < 1024 ? c.cores : 1024);
    tcfg_free(&c);
}
END_TEST

TLSPH_CHECK_MAIN("thread_budget", 0, configure_shares_the_cores, configure_clamps_oversubscription,
                 grant_never_exceeds_the_cores, config_settles_threads_per_job)
