/* Unit tests of server/jobs.c, the jobs service without HTTP: validation with
 * pointers relative to the inputs, the particle limit, ids, directories
 * before rows, rollback when a directory cannot be made, cancel and remove,
 * the output quota, a study child removed only with its study, and the
 * intent files that make submissions and removals crash-safe (intent.c).
 * A scene from $top_srcdir/tests/scenes/good (default "."). */
#include <check.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "intent.h"
#include "jobdir.h"
#include "jobs.h"
#include "queue.h"
#include "support/check_main.h"

static char g_dir[] = "/tmp/test_jobs.XXXXXX";
static char g_jobs[256];
static struct tq *g_q;
static struct tcfg g_cfg;
static struct jobs_env g_env;

static void setup(void)
{
    ck_assert_ptr_nonnull(mkdtemp(g_dir));
    char db[PATH_MAX + 16], err[256];
    snprintf(db, sizeof db, "%s/q.sqlite", g_dir);
    snprintf(g_jobs, sizeof g_jobs, "%s/jobs", g_dir);
    ck_assert_msg(tq_open(db, &g_q, err, sizeof err) == 0, "tq_open: %s", err);
    memset(&g_cfg, 0, sizeof g_cfg);
    snprintf(g_cfg.jobs_dir, sizeof g_cfg.jobs_dir, "%s", g_jobs);
    g_cfg.max_particles = 100000;
    g_cfg.max_children = 4;
    g_cfg.threads_per_job = 2;
    g_cfg.wall_limit = 60;
    g_env = (struct jobs_env){.q = g_q, .cfg = &g_cfg, .sup = NULL};
}

static void teardown(void)
{
    tq_close(g_q);
    char cmd[PATH_MAX + 16];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_dir);
    ck_assert_int_eq(system(cmd), 0);
    strcpy(g_dir, "/tmp/test_jobs.XXXXXX");
}

static json_t *good_scene(void)
{
    const char *top = getenv("top_srcdir");
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/tests/scenes/good/strip_2d.json", top && *top ? top : ".");
    json_error_t e;
    json_t *scene = json_load_file(path, 0, &e);
    ck_assert_msg(scene != NULL, "%s: %s", path, e.text);
    return scene;
}

static bool has_error(const struct tlsph_errors *e, const char *pointer, const char *needle)
{
    for (size_t i = 0; i < e->count; i++)
        if (!strcmp(e->items[i].pointer, pointer) && strstr(e->items[i].message, needle))
            return true;
    return false;
}

/* Submits strip_2d as a run: JOBS_OK, with the id in sub->id. */
static void submit_good_run(struct jobs_submitted *sub)
{
    jobs_submitted_init(sub);
    json_t *inputs = json_pack("{s:o}", "scene", good_scene());
    ck_assert_int_eq(jobs_submit_run(&g_env, inputs, sub), JOBS_OK);
    json_decref(inputs);
    ck_assert(job_id_valid(sub->id));
}

static long count_jobs(void)
{
    long acc = -1;
    ck_assert_int_eq(tq_counts(g_q, &acc, NULL, NULL), TQ_OK);
    return acc;
}

START_TEST(test_run_refused_with_pointers)
{
    struct jobs_submitted sub;
    jobs_submitted_init(&sub);
    json_t *inputs = json_pack("{s:i}", "scene", 1);
    ck_assert_int_eq(jobs_submit_run(&g_env, inputs, &sub), JOBS_INVALID);
    ck_assert(has_error(&sub.errors, "/scene", "must be an object"));
    json_decref(inputs);
    jobs_submitted_free(&sub);

    /* the engine's validator, pointers under /scene */
    jobs_submitted_init(&sub);
    json_t *scene = good_scene();
    json_object_set_new(json_object_get(scene, "time"), "cfl", json_real(0));
    inputs = json_pack("{s:o}", "scene", scene);
    ck_assert_int_eq(jobs_submit_run(&g_env, inputs, &sub), JOBS_INVALID);
    ck_assert(has_error(&sub.errors, "/scene/time/cfl", "out of range"));
    json_decref(inputs);
    jobs_submitted_free(&sub);

    /* the daemon's particle limit */
    jobs_submitted_init(&sub);
    scene = good_scene();
    json_object_set_new(scene, "limits", json_pack("{s:i}", "max_particles", 200000));
    inputs = json_pack("{s:o}", "scene", scene);
    ck_assert_int_eq(jobs_submit_run(&g_env, inputs, &sub), JOBS_INVALID);
    ck_assert(has_error(&sub.errors, "/scene/limits/max_particles", "limit of 100000"));
    json_decref(inputs);
    jobs_submitted_free(&sub);
    ck_assert_int_eq(count_jobs(), 0);
}
END_TEST

START_TEST(test_run_queued_then_removed)
{
    struct jobs_submitted sub;
    submit_good_run(&sub);

    struct tq_job j;
    ck_assert_int_eq(tq_get(g_q, sub.id, &j), TQ_OK);
    ck_assert_str_eq(j.status, TQ_ACCEPTED);
    ck_assert_int_eq(j.threads, 2);
    /* the stored scene carries the daemon's limit */
    json_t *stored = json_loads(j.input, 0, NULL);
    ck_assert_int_eq(json_integer_value(json_object_get(json_object_get(stored, "limits"),
                                                        "max_particles")), 100000);
    json_decref(stored);
    char path[PATH_MAX];
    ck_assert_int_eq(jobdir_path(path, sizeof path, g_jobs, sub.id, JOBDIR_SCENE), 0);
    ck_assert_int_eq(access(path, R_OK), 0);

    /* not final: cannot be removed; cancel dismisses it, then it can */
    ck_assert_int_eq(jobs_remove(&g_env, &j), JOBS_NOT_FINAL);
    ck_assert_int_eq(jobs_cancel(&g_env, sub.id), JOBS_OK);
    tq_job_free(&j);
    ck_assert_int_eq(tq_get(g_q, sub.id, &j), TQ_OK);
    ck_assert_str_eq(j.status, TQ_DISMISSED);
    ck_assert_int_eq(jobs_remove(&g_env, &j), JOBS_OK);
    ck_assert_int_eq(access(path, F_OK), -1);
    ck_assert_int_eq(jobs_remove(&g_env, &j), JOBS_NO_SUCH_JOB);
    tq_job_free(&j);
    jobs_submitted_free(&sub);
}
END_TEST

START_TEST(test_study_children_and_errors)
{
    struct jobs_submitted sub;
    jobs_submitted_init(&sub);
    /* a swept value that breaks a child points at the sweep parameter */
    json_t *inputs = json_pack(
        "{s:o, s:{s:s, s:[{s:s, s:[f, f]}]}}", "base", good_scene(), "sweep", "mode", "product",
        "parameters", "pointer", "/time/cfl", "values", 0.5, 0.0);
    ck_assert_int_eq(jobs_submit_study(&g_env, inputs, &sub), JOBS_INVALID);
    ck_assert(has_error(&sub.errors, "/sweep/parameters/0", "child 1"));
    json_decref(inputs);
    jobs_submitted_free(&sub);

    jobs_submitted_init(&sub);
    inputs = json_pack("{s:o, s:{s:s, s:[{s:s, s:[f, f, f]}]}}", "base", good_scene(), "sweep",
                       "mode", "product", "parameters", "pointer", "/time/cfl", "values", 0.3,
                       0.4, 0.5);
    ck_assert_int_eq(jobs_submit_study(&g_env, inputs, &sub), JOBS_OK);
    json_decref(inputs);
    struct tq_job *kids = NULL;
    size_t nk = 0;
    ck_assert_int_eq(jobs_study_children(&g_env, sub.id, &kids, &nk), 0);
    ck_assert_uint_eq(nk, 3);
    for (size_t i = 0; i < nk; i++) {
        ck_assert_int_eq(kids[i].seq, (long)i);
        ck_assert_str_eq(kids[i].study_id, sub.id);
        char path[PATH_MAX];
        ck_assert_int_eq(jobdir_path(path, sizeof path, g_jobs, kids[i].id, JOBDIR_SCENE), 0);
        ck_assert_int_eq(access(path, R_OK), 0);
    }
    tq_jobs_free(kids, nk);
    ck_assert_int_eq(count_jobs(), 3);
    jobs_submitted_free(&sub);
}
END_TEST

/* A job directory that cannot be made: nothing is queued, nothing is left. */
START_TEST(test_rollback_without_directory)
{
    FILE *f = fopen(g_jobs, "w"); /* jobs_dir is a file */
    ck_assert_ptr_nonnull(f);
    fclose(f);
    struct jobs_submitted sub;
    jobs_submitted_init(&sub);
    json_t *inputs = json_pack("{s:o}", "scene", good_scene());
    ck_assert_int_eq(jobs_submit_run(&g_env, inputs, &sub), JOBS_NO_DIRECTORY);
    ck_assert(sub.why[0] != '\0');
    json_decref(inputs);
    jobs_submitted_free(&sub);

    jobs_submitted_init(&sub);
    inputs = json_pack("{s:o, s:{s:s, s:[{s:s, s:[f, f]}]}}", "base", good_scene(), "sweep",
                       "mode", "product", "parameters", "pointer", "/time/cfl", "values", 0.3, 0.4);
    ck_assert_int_eq(jobs_submit_study(&g_env, inputs, &sub), JOBS_NOT_QUEUED);
    json_decref(inputs);
    jobs_submitted_free(&sub);
    ck_assert_int_eq(count_jobs(), 0);
    struct tq_job *all = NULL;
    size_t n = 0;
    ck_assert_int_eq(tq_list(g_q, NULL, NULL, NULL, 10, 0, &all, &n), TQ_OK);
    ck_assert_uint_eq(n, 0);
    tq_jobs_free(all, n);
}
END_TEST

/* The estimate of a result file against the per-job quota: strip_2d has 250
 * particles (50 x 5 at 2 mm); the engine's field table writes 52 B per
 * particle once and 136 B per particle and frame (docs/api.md); frames + 1
 * records.  101 records: 250 x (52 + 101 x 136) B = 3.3 MiB > 1 MiB. */
START_TEST(test_output_quota)
{
    g_cfg.max_output_mb = 1;
    struct jobs_submitted sub;
    jobs_submitted_init(&sub);
    json_t *scene = good_scene();
    json_object_set_new(json_object_get(scene, "output"), "frames", json_integer(100));
    json_t *inputs = json_pack("{s:o}", "scene", scene);
    ck_assert_int_eq(jobs_submit_run(&g_env, inputs, &sub), JOBS_OVER_QUOTA);
    ck_assert(has_error(&sub.errors, "/scene/output/frames",
                        "250 particles x (52 B + 101 frames x 136 B)"));
    ck_assert(sub.output_bytes == 250.0 * (52 + 101 * 136));
    ck_assert_msg(strstr(sub.detail, "3.3 MiB") && strstr(sub.detail, "1.0 MiB"), "%s", sub.detail);
    json_decref(inputs);
    jobs_submitted_free(&sub);
    ck_assert_int_eq(count_jobs(), 0);

    /* 11 records: 387 000 B fit */
    submit_good_run(&sub);
    ck_assert(sub.output_bytes == 250.0 * (52 + 11 * 136));
    jobs_submitted_free(&sub);

    /* a study: the child above the quota is named */
    jobs_submitted_init(&sub);
    inputs = json_pack("{s:o, s:{s:[{s:s, s:[i, i]}]}}", "base", good_scene(), "sweep",
                       "parameters", "pointer", "/output/frames", "values", 10, 100);
    ck_assert_int_eq(jobs_submit_study(&g_env, inputs, &sub), JOBS_OVER_QUOTA);
    ck_assert(has_error(&sub.errors, "/base/output/frames", "child 1 {\"/output/frames\":100}"));
    ck_assert_uint_eq(sub.errors.count, 1);
    json_decref(inputs);
    jobs_submitted_free(&sub);
    ck_assert_int_eq(count_jobs(), 1);
}
END_TEST

/* A child of a study goes only with its study: the study's summary has a row
 * and its message a count for every child. */
START_TEST(test_child_removed_with_its_study)
{
    struct jobs_submitted sub;
    jobs_submitted_init(&sub);
    json_t *inputs = json_pack("{s:o, s:{s:[{s:s, s:[f, f]}]}}", "base", good_scene(), "sweep",
                               "parameters", "pointer", "/time/cfl", "values", 0.3, 0.4);
    ck_assert_int_eq(jobs_submit_study(&g_env, inputs, &sub), JOBS_OK);
    json_decref(inputs);
    ck_assert_int_eq(jobs_cancel(&g_env, sub.id), JOBS_OK); /* all final */
    struct tq_job *kids = NULL;
    size_t nk = 0;
    ck_assert_int_eq(jobs_study_children(&g_env, sub.id, &kids, &nk), 0);
    ck_assert_uint_eq(nk, 2);
    ck_assert_str_eq(kids[0].status, TQ_DISMISSED);
    ck_assert_int_eq(jobs_remove(&g_env, &kids[0]), JOBS_STUDY_CHILD);
    ck_assert_int_eq(tq_has_row(g_q, kids[0].id), TQ_OK);
    struct tq_job study;
    ck_assert_int_eq(tq_get(g_q, sub.id, &study), TQ_OK);
    ck_assert_int_eq(jobs_remove(&g_env, &study), JOBS_OK); /* the study takes them along */
    ck_assert_int_eq(tq_has_row(g_q, kids[0].id), TQ_NOT_FOUND);
    char path[PATH_MAX];
    ck_assert_int_eq(jobdir_path(path, sizeof path, g_jobs, kids[1].id, JOBDIR_FILES), 0);
    ck_assert_int_eq(access(path, F_OK), -1);
    tq_job_free(&study);
    tq_jobs_free(kids, nk);
    jobs_submitted_free(&sub);
}
END_TEST

static int has_row_cb(void *ctx, const char *id)
{
    (void)ctx;
    const enum tq_rc rc = tq_has_row(g_q, id);
    return rc == TQ_OK ? 1 : rc == TQ_NOT_FOUND ? 0 : -1;
}

/* An intent file left by a crash: the listed directories without a row go
 * (a submission that never committed, a removal that did), those with a row
 * stay, directories it does not list are not its business. */
START_TEST(test_intent_replay)
{
    struct jobs_submitted sub;
    submit_good_run(&sub);
    char ids[3][JOB_ID_LEN + 1], path[PATH_MAX], err[256];
    snprintf(ids[0], sizeof ids[0], "%s", sub.id); /* has a row */
    for (int i = 1; i < 3; i++) {
        ck_assert_int_eq(job_id_new(ids[i]), 0);
        ck_assert_int_eq(jobdir_create(g_jobs, ids[i], "{}", err, sizeof err), 0);
    }
    const char *listed[] = {ids[0], ids[1]}; /* ids[2]: a directory it does not list */
    struct intent in;
    ck_assert_int_eq(intent_begin(&in, g_jobs, listed, 2, err, sizeof err), 0);
    ck_assert_int_eq(access(in.path, R_OK), 0);
    long removed = -1;
    ck_assert_int_eq(intent_replay(g_jobs, has_row_cb, NULL, &removed, err, sizeof err), 0);
    ck_assert_int_eq(removed, 1);
    ck_assert_int_eq(access(in.path, F_OK), -1);
    for (int i = 0; i < 3; i++) {
        ck_assert_int_eq(jobdir_path(path, sizeof path, g_jobs, ids[i], JOBDIR_FILES), 0);
        ck_assert_int_eq(access(path, F_OK), i == 1 ? -1 : 0);
    }
    ck_assert_int_eq(intent_replay(g_jobs, has_row_cb, NULL, &removed, err, sizeof err), 0);
    ck_assert_int_eq(removed, 0);
    jobs_submitted_free(&sub);
}
END_TEST

static Suite *jobs_suite(void)
{
    Suite *s = suite_create("jobs");
    TCase *tc = tcase_create("jobs");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_run_refused_with_pointers);
    tcase_add_test(tc, test_run_queued_then_removed);
    tcase_add_test(tc, test_study_children_and_errors);
    tcase_add_test(tc, test_rollback_without_directory);
    tcase_add_test(tc, test_output_quota);
    tcase_add_test(tc, test_child_removed_with_its_study);
    tcase_add_test(tc, test_intent_replay);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return tlsph_check_run(jobs_suite());
}
