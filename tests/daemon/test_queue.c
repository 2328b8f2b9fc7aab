/* The SQLite job queue (server/queue.c): schema setup and versioning, insert /
 * get / list, FIFO and concurrent claims, progress, finish, cancel, studies
 * (status and progress aggregation, also of a cancelled study), crash
 * recovery, delete rules, counts by process, the start-up integrity check,
 * rows rebuilt by --recover, and that user strings (quotes, unicode, SQL)
 * round-trip verbatim.
 * Each test gets a fresh database in its own mkdtemp directory under /tmp. */
#include <check.h>
#include <dirent.h>
#include <math.h>
#include <pthread.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "queue.h"
#include "support/check_main.h"

static char g_dir[64];
static char g_db[128];
static struct tq *g_q;

static void setup(void)
{
    snprintf(g_dir, sizeof g_dir, "/tmp/tq-test-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(g_dir));
    snprintf(g_db, sizeof g_db, "%s/jobs.db", g_dir);
    char err[512];
    ck_assert_msg(tq_open(g_db, &g_q, err, sizeof err) == 0, "tq_open: %s", err);
}

static void teardown(void)
{
    tq_close(g_q);
    g_q = NULL;
    DIR *d = opendir(g_dir);
    if (d) {
        struct dirent *e;
        while ((e = readdir(d))) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
                continue;
            char p[512];
            snprintf(p, sizeof p, "%s/%s", g_dir, e->d_name);
            unlink(p);
        }
        closedir(d);
    }
    rmdir(g_dir);
}

static char scene_json[] = "{\"time\":{\"end\":1e-4}}";

static struct tq_job mkjob(const char *id, const char *process)
{
    struct tq_job j;
    memset(&j, 0, sizeof j);
    snprintf(j.id, sizeof j.id, "%s", id);
    snprintf(j.process, sizeof j.process, "%s", process);
    j.seq = -1;
    j.input = scene_json;
    j.threads = 2;
    j.wall_limit = 3600;
    return j;
}

static void insert_run(const char *id)
{
    struct tq_job j = mkjob(id, "run");
    ck_assert_msg(tq_insert(g_q, &j) == 0, "insert %s: %s", id, tq_last_error(g_q));
}

/* A study "id" with n children "id-c<i>". */
static void insert_study(const char *id, size_t n)
{
    struct tq_job s = mkjob(id, "study");
    struct tq_job c[16];
    ck_assert(n <= 16);
    static char params[] = "{\"/bodies/0/spacing\": 0.001}";
    for (size_t i = 0; i < n; i++) {
        char cid[TQ_ID_LEN + 1];
        snprintf(cid, sizeof cid, "%s-c%zu", id, i);
        c[i] = mkjob(cid, "run");
        c[i].seq = (long)i;
        c[i].params = params;
    }
    ck_assert_msg(tq_insert_study(g_q, &s, c, n) == 0, "insert study: %s", tq_last_error(g_q));
}

static struct tq_job get(const char *id)
{
    struct tq_job j;
    int rc = tq_get(g_q, id, &j);
    ck_assert_msg(rc == 0, "get %s -> %d (%s)", id, rc, tq_last_error(g_q));
    return j;
}

static void assert_status(const char *id, const char *status)
{
    struct tq_job j = get(id);
    ck_assert_msg(!strcmp(j.status, status), "%s: status %s, want %s", id, j.status, status);
    tq_job_free(&j);
}

static void claim_expect(const char *id)
{
    struct tq_job j;
    int rc = tq_claim_next(g_q, &j);
    ck_assert_msg(rc == 0, "claim -> %d (%s)", rc, tq_last_error(g_q));
    ck_assert_str_eq(j.id, id);
    ck_assert_str_eq(j.status, TQ_RUNNING);
    tq_job_free(&j);
}

/* Raw single-value query on a separate plain connection. */
static void raw_query(const char *path, const char *sql, char *buf, size_t size)
{
    sqlite3 *db = NULL;
    ck_assert_int_eq(sqlite3_open_v2(path, &db, SQLITE_OPEN_READWRITE, NULL), SQLITE_OK);
    sqlite3_stmt *st = NULL;
    ck_assert_msg(sqlite3_prepare_v2(db, sql, -1, &st, NULL) == SQLITE_OK, "%s",
                  sqlite3_errmsg(db));
    buf[0] = '\0';
    if (sqlite3_step(st) == SQLITE_ROW && sqlite3_column_text(st, 0))
        snprintf(buf, size, "%s", (const char *)sqlite3_column_text(st, 0));
    sqlite3_finalize(st);
    sqlite3_close(db);
}

/* ------------------------------------------------------------------ open */

START_TEST(open_creates_wal_v1)
{
    char buf[64];
    ck_assert_str_eq(tq_last_error(g_q), "");
    raw_query(g_db, "PRAGMA journal_mode", buf, sizeof buf);
    ck_assert_str_eq(buf, "wal");
    raw_query(g_db, "PRAGMA user_version", buf, sizeof buf);
    ck_assert_str_eq(buf, "1");
    raw_query(g_db, "SELECT count(*) FROM sqlite_master WHERE type='index' AND tbl_name='jobs'"
                    " AND name IN ('jobs_status','jobs_study','jobs_created')",
              buf, sizeof buf);
    ck_assert_str_eq(buf, "3");
    /* A second handle on the same file opens without re-migrating. */
    struct tq *q2 = NULL;
    char err[512];
    ck_assert_msg(tq_open(g_db, &q2, err, sizeof err) == 0, "%s", err);
    tq_close(q2);
    raw_query(g_db, "PRAGMA user_version", buf, sizeof buf);
    ck_assert_str_eq(buf, "1");
}
END_TEST

START_TEST(reopen_keeps_data)
{
    insert_run("keepme");
    tq_close(g_q);
    g_q = NULL;
    char err[512];
    ck_assert_msg(tq_open(g_db, &g_q, err, sizeof err) == 0, "%s", err);
    struct tq_job j = get("keepme");
    ck_assert_str_eq(j.input, scene_json);
    ck_assert_str_eq(j.status, TQ_ACCEPTED);
    tq_job_free(&j);
}
END_TEST

START_TEST(newer_schema_refused)
{
    char path[192];
    snprintf(path, sizeof path, "%s/future.db", g_dir);
    sqlite3 *db = NULL;
    ck_assert_int_eq(sqlite3_open(path, &db), SQLITE_OK);
    ck_assert_int_eq(sqlite3_exec(db, "CREATE TABLE x(a); PRAGMA user_version=999", NULL, NULL,
                                  NULL),
                     SQLITE_OK);
    sqlite3_close(db);
    struct tq *q = (struct tq *)1;
    char err[512] = "";
    ck_assert_int_eq(tq_open(path, &q, err, sizeof err), -1);
    ck_assert_ptr_null(q);
    ck_assert_msg(strstr(err, "999") && strstr(err, "newer"), "error: %s", err);
    char buf[64];
    raw_query(path, "PRAGMA user_version", buf, sizeof buf);
    ck_assert_str_eq(buf, "999"); /* untouched */

    /* Not a database at all. */
    snprintf(path, sizeof path, "%s/garbage.db", g_dir);
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    for (int i = 0; i < 100; i++)
        fputs("this is not an sqlite database\n", f);
    fclose(f);
    err[0] = '\0';
    ck_assert_int_eq(tq_open(path, &q, err, sizeof err), -1);
    ck_assert_msg(err[0] != '\0', "no error message");
}
END_TEST

/* ------------------------------------------------------------------ insert/get/list */

START_TEST(insert_get_list)
{
    char id[16];
    for (int i = 0; i < 5; i++) {
        snprintf(id, sizeof id, "run%d", i);
        insert_run(id);
    }
    insert_study("st", 2);

    struct tq_job j = get("run3");
    ck_assert_str_eq(j.process, "run");
    ck_assert_str_eq(j.study_id, "");
    ck_assert_int_eq(j.seq, -1);
    ck_assert_str_eq(j.status, TQ_ACCEPTED);
    ck_assert_str_eq(j.outcome, "");
    ck_assert_ptr_null(j.message);
    ck_assert_ptr_null(j.params);
    ck_assert_ptr_null(j.cost);
    ck_assert_int_eq(j.threads, 2);
    ck_assert(j.wall_limit == 3600);
    ck_assert(j.eta == -1);
    ck_assert(j.created > 1.6e9);
    ck_assert(j.started == 0 && j.finished == 0 && j.attempts == 0 && j.pid == 0);
    tq_job_free(&j);
    ck_assert_ptr_null(j.input); /* tq_job_free zeroes */

    j = get("st-c1");
    ck_assert_str_eq(j.study_id, "st");
    ck_assert_int_eq(j.seq, 1);
    ck_assert_str_eq(j.params, "{\"/bodies/0/spacing\": 0.001}");
    tq_job_free(&j);

    ck_assert_int_eq(tq_get(g_q, "nosuchjob", &j), 1);
    ck_assert_int_eq(tq_get(g_q, "../etc/passwd", &j), -1);
    ck_assert(strstr(tq_last_error(g_q), "invalid job id"));

    /* Duplicate id and bad process are errors. */
    struct tq_job dup = mkjob("run0", "run");
    ck_assert_int_eq(tq_insert(g_q, &dup), -1);
    ck_assert_msg(strstr(tq_last_error(g_q), "UNIQUE"), "%s", tq_last_error(g_q));
    struct tq_job bad = mkjob("x1", "walk");
    ck_assert_int_eq(tq_insert(g_q, &bad), -1);
    /* A child referencing a missing study violates the foreign key. */
    struct tq_job orphan = mkjob("orphan", "run");
    snprintf(orphan.study_id, sizeof orphan.study_id, "nostudy");
    ck_assert_int_eq(tq_insert(g_q, &orphan), -1);
    ck_assert_msg(strstr(tq_last_error(g_q), "FOREIGN KEY"), "%s", tq_last_error(g_q));
    /* ... and one naming a run job as its study is refused and rolled back. */
    snprintf(orphan.study_id, sizeof orphan.study_id, "run1");
    ck_assert_int_eq(tq_insert(g_q, &orphan), -1);
    ck_assert_msg(strstr(tq_last_error(g_q), "not a study"), "%s", tq_last_error(g_q));
    ck_assert_int_eq(tq_get(g_q, "orphan", &j), 1);
    /* A NULL handle is an error, not a crash. */
    ck_assert_int_eq(tq_insert(NULL, &dup), -1);
    ck_assert_int_eq(tq_counts(NULL, NULL, NULL, NULL), -1);
    ck_assert_str_eq(tq_last_error(NULL), "no queue handle");

    struct tq_job *a;
    size_t n;
    ck_assert_int_eq(tq_list(g_q, NULL, NULL, NULL, 100, 0, &a, &n), 0);
    ck_assert_uint_eq(n, 8);
    /* newest first: the study rows were inserted last, children after parent */
    ck_assert_str_eq(a[0].id, "st-c1");
    ck_assert_str_eq(a[1].id, "st-c0");
    ck_assert_str_eq(a[2].id, "st");
    ck_assert_str_eq(a[3].id, "run4");
    ck_assert_str_eq(a[7].id, "run0");
    for (size_t i = 0; i < n; i++)
        tq_job_free(&a[i]);
    free(a);

    ck_assert_int_eq(tq_list(g_q, "", "", "run", 100, 0, &a, &n), 0);
    ck_assert_uint_eq(n, 7);
    for (size_t i = 0; i < n; i++)
        tq_job_free(&a[i]);
    free(a);

    ck_assert_int_eq(tq_list(g_q, NULL, "st", NULL, 100, 0, &a, &n), 0);
    ck_assert_uint_eq(n, 2);
    for (size_t i = 0; i < n; i++) {
        ck_assert_str_eq(a[i].study_id, "st");
        tq_job_free(&a[i]);
    }
    free(a);

    ck_assert_int_eq(tq_list(g_q, NULL, NULL, "study", 100, 0, &a, &n), 0);
    ck_assert_uint_eq(n, 1);
    ck_assert_str_eq(a[0].id, "st");
    tq_job_free(&a[0]);
    free(a);

    /* limit / offset pages through run jobs without a study */
    ck_assert_int_eq(tq_list(g_q, TQ_ACCEPTED, NULL, "run", 2, 3, &a, &n), 0);
    ck_assert_uint_eq(n, 2);
    ck_assert_str_eq(a[0].id, "run3"); /* st-c1 st-c0 run4 | run3 run2 | run1 run0 */
    ck_assert_str_eq(a[1].id, "run2");
    for (size_t i = 0; i < n; i++)
        tq_job_free(&a[i]);
    free(a);
    ck_assert_int_eq(tq_list(g_q, TQ_ACCEPTED, NULL, "run", 2, 5, &a, &n), 0);
    ck_assert_uint_eq(n, 2);
    ck_assert_str_eq(a[0].id, "run1");
    ck_assert_str_eq(a[1].id, "run0");
    for (size_t i = 0; i < n; i++)
        tq_job_free(&a[i]);
    free(a);
    ck_assert_int_eq(tq_list(g_q, NULL, NULL, NULL, 10, 100, &a, &n), 0);
    ck_assert_uint_eq(n, 0);
    free(a);

    ck_assert_int_eq(tq_list(g_q, TQ_RUNNING, NULL, NULL, 10, 0, &a, &n), 0);
    ck_assert_uint_eq(n, 0);
    free(a);

    ck_assert_int_eq(tq_list(g_q, NULL, NULL, NULL, 0, 0, &a, &n), -1);
    ck_assert(strstr(tq_last_error(g_q), "limit"));
    ck_assert_int_eq(tq_list(g_q, NULL, NULL, NULL, 10001, 0, &a, &n), -1);
    ck_assert_int_eq(tq_list(g_q, NULL, NULL, NULL, 10000, -1, &a, &n), -1);
    ck_assert(strstr(tq_last_error(g_q), "offset"));

    long acc = -1, run = -1, fin = -1;
    ck_assert_int_eq(tq_counts(g_q, &acc, &run, &fin), 0);
    ck_assert_int_eq(acc, 7); /* run jobs only: 5 + 2 children */
    ck_assert_int_eq(run, 0);
    ck_assert_int_eq(fin, 0);
}
END_TEST

START_TEST(new_ids)
{
    char a[TQ_ID_LEN + 1], b[TQ_ID_LEN + 1];
    ck_assert_int_eq(job_id_new(a), 0);
    ck_assert_int_eq(job_id_new(b), 0);
    ck_assert_uint_eq(strlen(a), TQ_ID_LEN);
    ck_assert_uint_eq(strspn(a, "0123456789abcdef"), TQ_ID_LEN);
    ck_assert_str_ne(a, b);
    struct tq_job j = mkjob(a, "run");
    ck_assert_int_eq(tq_insert(g_q, &j), 0);
    assert_status(a, TQ_ACCEPTED);
}
END_TEST

/* ------------------------------------------------------------------ claim */

START_TEST(claim_fifo)
{
    insert_run("first");
    insert_run("second");
    insert_study("st", 2);
    insert_run("third");
    struct tq_job j;
    ck_assert_int_eq(tq_claim_next(g_q, &j), 0);
    ck_assert_str_eq(j.id, "first");
    ck_assert_str_eq(j.status, TQ_RUNNING);
    ck_assert_int_eq(j.attempts, 1);
    ck_assert(j.started >= j.created && j.started > 0);
    ck_assert_str_eq(j.input, scene_json);
    tq_job_free(&j);
    claim_expect("second");
    claim_expect("st-c0"); /* the study parent itself is never claimed */
    assert_status("st", TQ_RUNNING);
    claim_expect("st-c1");
    claim_expect("third");
    ck_assert_int_eq(tq_claim_next(g_q, &j), 1);
    ck_assert_ptr_null(j.input);
    assert_status("st", TQ_RUNNING);
    long acc, run, fin;
    ck_assert_int_eq(tq_counts(g_q, &acc, &run, &fin), 0);
    ck_assert_int_eq(acc, 0);
    ck_assert_int_eq(run, 5);
}
END_TEST

#define NCONC 300

struct claimer {
    pthread_barrier_t *barrier;
    char ids[NCONC][TQ_ID_LEN + 1];
    int n;
    int errors;
    char err[512];
};

static void *claim_thread(void *arg)
{
    struct claimer *c = arg;
    struct tq *q = NULL;
    int ok = tq_open(g_db, &q, c->err, sizeof c->err) == 0;
    pthread_barrier_wait(c->barrier);
    if (!ok) {
        c->errors++;
        return NULL;
    }
    for (;;) {
        struct tq_job j;
        int rc = tq_claim_next(q, &j);
        if (rc == 1)
            break;
        if (rc < 0) {
            snprintf(c->err, sizeof c->err, "%s", tq_last_error(q));
            c->errors++;
            break;
        }
        if (c->n < NCONC)
            snprintf(c->ids[c->n], sizeof c->ids[0], "%s", j.id);
        c->n++;
        tq_job_free(&j);
        usleep(300); /* "spawn the engine": lets the other thread's claim in */
    }
    tq_close(q);
    return NULL;
}

START_TEST(concurrent_claim)
{
    char id[16];
    for (int i = 0; i < NCONC; i++) {
        snprintf(id, sizeof id, "job%03d", i);
        insert_run(id);
    }
    pthread_barrier_t barrier;
    pthread_barrier_init(&barrier, NULL, 2);
    struct claimer *c = calloc(2, sizeof *c);
    ck_assert_ptr_nonnull(c);
    pthread_t th[2];
    for (int t = 0; t < 2; t++) {
        c[t].barrier = &barrier;
        ck_assert_int_eq(pthread_create(&th[t], NULL, claim_thread, &c[t]), 0);
    }
    for (int t = 0; t < 2; t++)
        pthread_join(th[t], NULL);
    pthread_barrier_destroy(&barrier);
    for (int t = 0; t < 2; t++)
        ck_assert_msg(c[t].errors == 0, "thread %d: %s", t, c[t].err);
    ck_assert_int_eq(c[0].n + c[1].n, NCONC);
    int seen[NCONC] = {0};
    for (int t = 0; t < 2; t++)
        for (int k = 0; k < c[t].n; k++) {
            int i = atoi(c[t].ids[k] + 3);
            ck_assert(i >= 0 && i < NCONC);
            seen[i]++;
        }
    for (int i = 0; i < NCONC; i++)
        ck_assert_msg(seen[i] == 1, "job%03d claimed %d times", i, seen[i]);
    /* Both really competed (otherwise the test proves nothing). */
    ck_assert_msg(c[0].n > 0 && c[1].n > 0, "claims %d / %d", c[0].n, c[1].n);
    free(c);
    long acc, run, fin;
    ck_assert_int_eq(tq_counts(g_q, &acc, &run, &fin), 0);
    ck_assert_int_eq(run, NCONC);
    ck_assert_int_eq(acc, 0);
    struct tq_job j = get("job123");
    ck_assert_int_eq(j.attempts, 1);
    tq_job_free(&j);
}
END_TEST

/* ------------------------------------------------------------------ progress/finish */

START_TEST(progress_and_finish)
{
    insert_run("a");
    insert_run("b");
    ck_assert_int_eq(tq_update_progress(g_q, "a", 10, 1e-5, 1e-4, 100, 20), 1); /* not running */
    claim_expect("a");
    ck_assert_int_eq(tq_set_pid(g_q, "a", 4242), 0);
    ck_assert_int_eq(tq_set_pid(g_q, "b", 4243), 1);
    ck_assert_int_eq(tq_update_progress(g_q, "a", 42.5, 4.25e-5, 1e-4, 1234, 17.5), 0);
    struct tq_job j = get("a");
    ck_assert(fabs(j.progress - 42.5) < 1e-12);
    ck_assert(j.sim_time == 4.25e-5 && j.end_time == 1e-4);
    ck_assert_int_eq(j.step, 1234);
    ck_assert(j.eta == 17.5);
    ck_assert_int_eq(j.pid, 4242);
    tq_job_free(&j);
    ck_assert_int_eq(tq_update_progress(g_q, "a", 250, 1e-4, 1e-4, 2000, 0), 0);
    j = get("a");
    ck_assert(j.progress == 100); /* clamped */
    tq_job_free(&j);
    ck_assert_int_eq(tq_update_progress(g_q, "a", 60, 6e-5, 1e-4, 1500, 5), 0);

    ck_assert_int_eq(tq_finish(g_q, "a", "running", "", NULL, NULL), -1);
    ck_assert_int_eq(tq_finish(g_q, "a", TQ_SUCCESSFUL, "much_too_long_outcome", NULL, NULL), -1);
    ck_assert_int_eq(tq_finish(g_q, "a", TQ_SUCCESSFUL, "successful", "done",
                               "{\"steps\":2000,\"wall_seconds\":1.5}"),
                     0);
    j = get("a");
    ck_assert_str_eq(j.status, TQ_SUCCESSFUL);
    ck_assert_str_eq(j.outcome, "successful");
    ck_assert_str_eq(j.message, "done");
    ck_assert_str_eq(j.cost, "{\"steps\":2000,\"wall_seconds\":1.5}");
    ck_assert(j.progress == 100);
    ck_assert(j.finished >= j.started && j.finished > 0);
    ck_assert_int_eq(j.pid, 0);
    tq_job_free(&j);
    /* A final job does not change again. */
    ck_assert_int_eq(tq_finish(g_q, "a", TQ_FAILED, "crashed", "late", NULL), 1);
    assert_status("a", TQ_SUCCESSFUL);
    ck_assert_int_eq(tq_update_progress(g_q, "a", 5, 0, 1, 1, 1), 1);
    ck_assert_int_eq(tq_finish(g_q, "nosuch", TQ_FAILED, "crashed", NULL, NULL), 1);

    claim_expect("b");
    ck_assert_int_eq(tq_update_progress(g_q, "b", 30, 3e-5, 1e-4, 300, 7), 0);
    ck_assert_int_eq(tq_finish(g_q, "b", TQ_FAILED, "unstable", "particle 12: J < 0", NULL), 0);
    j = get("b");
    ck_assert_str_eq(j.status, TQ_FAILED);
    ck_assert_str_eq(j.outcome, "unstable");
    ck_assert(fabs(j.progress - 30) < 1e-12); /* failed keeps its progress */
    ck_assert_ptr_null(j.cost);
    tq_job_free(&j);
    long acc, run, fin;
    ck_assert_int_eq(tq_counts(g_q, &acc, &run, &fin), 0);
    ck_assert(acc == 0 && run == 0 && fin == 2);
}
END_TEST

START_TEST(requeue)
{
    insert_run("a");
    insert_run("b");
    claim_expect("a");
    claim_expect("b");
    ck_assert_int_eq(tq_update_progress(g_q, "a", 50, 5e-5, 1e-4, 500, 3), 0);
    ck_assert_int_eq(tq_requeue(g_q, "a", "daemon shutting down"), 0);
    struct tq_job j = get("a");
    ck_assert_str_eq(j.status, TQ_ACCEPTED);
    ck_assert_str_eq(j.message, "daemon shutting down");
    ck_assert(j.progress == 0 && j.started == 0 && j.pid == 0);
    ck_assert_int_eq(j.attempts, 1);
    tq_job_free(&j);
    ck_assert_int_eq(tq_requeue(g_q, "a", "again"), 1); /* not running */
    /* a pending cancel wins over requeue */
    ck_assert_int_eq(tq_request_cancel(g_q, "b"), 0);
    ck_assert_int_eq(tq_requeue(g_q, "b", "shutdown"), 0);
    j = get("b");
    ck_assert_str_eq(j.status, TQ_DISMISSED);
    ck_assert_str_eq(j.outcome, "cancelled");
    tq_job_free(&j);
    ck_assert_int_eq(tq_claim_next(g_q, &j), 0);
    ck_assert_str_eq(j.id, "a");
    ck_assert_int_eq(j.attempts, 2);
    tq_job_free(&j);
}
END_TEST

/* ------------------------------------------------------------------ cancel */

START_TEST(cancel_semantics)
{
    insert_run("run");
    insert_run("fin");
    insert_run("acc");
    claim_expect("run");
    claim_expect("fin");
    ck_assert_int_eq(tq_finish(g_q, "fin", TQ_SUCCESSFUL, "successful", NULL, NULL), 0);

    ck_assert_int_eq(tq_request_cancel(g_q, "acc"), 0);
    struct tq_job j = get("acc");
    ck_assert_str_eq(j.status, TQ_DISMISSED);
    ck_assert_str_eq(j.outcome, "cancelled");
    ck_assert(j.finished > 0);
    ck_assert_int_eq(j.cancel_requested, 0);
    tq_job_free(&j);
    ck_assert_int_eq(tq_claim_next(g_q, &j), 1); /* nothing left to run */

    char (*ids)[TQ_ID_LEN + 1];
    size_t n;
    ck_assert_int_eq(tq_cancel_requests(g_q, &ids, &n), 0);
    ck_assert_uint_eq(n, 0);
    free(ids);

    ck_assert_int_eq(tq_request_cancel(g_q, "run"), 0);
    j = get("run");
    ck_assert_str_eq(j.status, TQ_RUNNING); /* the supervisor stops it */
    ck_assert_int_eq(j.cancel_requested, 1);
    tq_job_free(&j);
    ck_assert_int_eq(tq_cancel_requests(g_q, &ids, &n), 0);
    ck_assert_uint_eq(n, 1);
    ck_assert_str_eq(ids[0], "run");
    free(ids);

    ck_assert_int_eq(tq_request_cancel(g_q, "fin"), 0); /* final: no change */
    j = get("fin");
    ck_assert_str_eq(j.status, TQ_SUCCESSFUL);
    ck_assert_int_eq(j.cancel_requested, 0);
    ck_assert_str_eq(j.outcome, "successful");
    tq_job_free(&j);
    ck_assert_int_eq(tq_request_cancel(g_q, "nosuch"), 1);

    ck_assert_int_eq(tq_finish(g_q, "run", TQ_DISMISSED, "cancelled", "stopped", NULL), 0);
    assert_status("run", TQ_DISMISSED);
    ck_assert_int_eq(tq_cancel_requests(g_q, &ids, &n), 0);
    ck_assert_uint_eq(n, 0);
    free(ids);
}
END_TEST

/* ------------------------------------------------------------------ studies */

static double study_progress(void)
{
    struct tq_job s = get("st");
    double p = s.progress;
    tq_job_free(&s);
    return p;
}

START_TEST(study_all_successful)
{
    insert_study("st", 6);
    struct tq_job s = get("st");
    ck_assert_str_eq(s.process, "study");
    ck_assert_str_eq(s.status, TQ_ACCEPTED);
    ck_assert(s.progress == 0);
    tq_job_free(&s);

    struct tq_job *a;
    size_t n;
    ck_assert_int_eq(tq_list(g_q, NULL, "st", NULL, 100, 0, &a, &n), 0);
    ck_assert_uint_eq(n, 6);
    for (size_t i = 0; i < n; i++) {
        ck_assert_int_eq(a[i].seq, (long)(5 - i)); /* newest first */
        tq_job_free(&a[i]);
    }
    free(a);

    claim_expect("st-c0");
    assert_status("st", TQ_RUNNING);
    ck_assert_int_eq(tq_update_progress(g_q, "st-c0", 50, 0, 1, 1, 1), 0);
    ck_assert_msg(fabs(study_progress() - 50.0 / 6) < 1e-9, "progress %g", study_progress());
    ck_assert_int_eq(tq_finish(g_q, "st-c0", TQ_SUCCESSFUL, "successful", NULL, NULL), 0);
    ck_assert(fabs(study_progress() - 100.0 / 6) < 1e-9);
    assert_status("st", TQ_RUNNING);
    claim_expect("st-c1");
    ck_assert_int_eq(tq_update_progress(g_q, "st-c1", 30, 0, 1, 1, 1), 0);
    ck_assert(fabs(study_progress() - 130.0 / 6) < 1e-9);

    double first_started = 0;
    s = get("st-c0");
    first_started = s.started;
    tq_job_free(&s);
    double last_finished = 0;
    ck_assert_int_eq(tq_finish(g_q, "st-c1", TQ_SUCCESSFUL, "successful", NULL, NULL), 0);
    for (int i = 2; i < 6; i++) {
        char id[16];
        snprintf(id, sizeof id, "st-c%d", i);
        claim_expect(id);
        ck_assert_int_eq(tq_finish(g_q, id, TQ_SUCCESSFUL, "successful", NULL, NULL), 0);
        if (i < 5)
            assert_status("st", TQ_RUNNING);
        s = get(id);
        last_finished = s.finished;
        tq_job_free(&s);
    }
    s = get("st");
    ck_assert_str_eq(s.status, TQ_SUCCESSFUL);
    ck_assert_str_eq(s.outcome, "successful");
    ck_assert(s.progress == 100);
    ck_assert(s.started == first_started);
    ck_assert(s.finished == last_finished);
    tq_job_free(&s);
    ck_assert_int_eq(tq_study_refresh(g_q, "st"), 0); /* idempotent */
    assert_status("st", TQ_SUCCESSFUL);
    ck_assert_int_eq(tq_study_refresh(g_q, "nosuch"), 1);
    ck_assert_int_eq(tq_study_refresh(g_q, "st-c0"), -1); /* not a study */
}
END_TEST

START_TEST(study_one_failed)
{
    insert_study("st", 6);
    for (int i = 0; i < 6; i++) {
        char id[16];
        snprintf(id, sizeof id, "st-c%d", i);
        claim_expect(id);
    }
    ck_assert(study_progress() == 0);
    for (int i = 0; i < 6; i++) {
        char id[16];
        snprintf(id, sizeof id, "st-c%d", i);
        ck_assert_int_eq(tq_finish(g_q, id, i == 3 ? TQ_FAILED : TQ_SUCCESSFUL,
                                   i == 3 ? "unstable" : "successful", NULL, NULL),
                         0);
        if (i < 5) {
            assert_status("st", TQ_RUNNING);
            ck_assert(fabs(study_progress() - 100.0 * (i + 1) / 6) < 1e-9);
        }
    }
    struct tq_job s = get("st");
    ck_assert_str_eq(s.status, TQ_FAILED);
    ck_assert_ptr_nonnull(s.message);
    ck_assert_str_eq(s.message, "1 of 6 children failed/dismissed");
    ck_assert(s.progress == 100);
    ck_assert(s.finished > 0);
    tq_job_free(&s);
}
END_TEST

START_TEST(study_cancel)
{
    insert_study("st", 6);
    claim_expect("st-c0");
    claim_expect("st-c1");
    ck_assert_int_eq(tq_finish(g_q, "st-c0", TQ_SUCCESSFUL, "successful", NULL, NULL), 0);
    claim_expect("st-c2");
    ck_assert_int_eq(tq_request_cancel(g_q, "st"), 0);
    for (int i = 3; i < 6; i++) {
        char id[16];
        snprintf(id, sizeof id, "st-c%d", i);
        struct tq_job c = get(id);
        ck_assert_str_eq(c.status, TQ_DISMISSED);
        ck_assert_str_eq(c.outcome, "cancelled");
        tq_job_free(&c);
    }
    assert_status("st-c0", TQ_SUCCESSFUL);
    assert_status("st", TQ_RUNNING); /* two children still stopping */
    char (*ids)[TQ_ID_LEN + 1];
    size_t n;
    ck_assert_int_eq(tq_cancel_requests(g_q, &ids, &n), 0);
    ck_assert_uint_eq(n, 2); /* the study row itself is not listed */
    ck_assert_str_eq(ids[0], "st-c1");
    ck_assert_str_eq(ids[1], "st-c2");
    free(ids);
    struct tq_job j;
    ck_assert_int_eq(tq_claim_next(g_q, &j), 1);

    ck_assert_int_eq(tq_finish(g_q, "st-c1", TQ_DISMISSED, "cancelled", NULL, NULL), 0);
    assert_status("st", TQ_RUNNING);
    ck_assert_int_eq(tq_finish(g_q, "st-c2", TQ_DISMISSED, "cancelled", NULL, NULL), 0);
    struct tq_job s = get("st");
    ck_assert_str_eq(s.status, TQ_DISMISSED);
    ck_assert_str_eq(s.outcome, "cancelled");
    ck_assert(s.finished > 0);
    tq_job_free(&s);

    /* cancelling a study that has not started dismisses it at once */
    struct tq_job s2 = mkjob("s2", "study");
    struct tq_job c2[2] = {mkjob("s2-a", "run"), mkjob("s2-b", "run")};
    ck_assert_int_eq(tq_insert_study(g_q, &s2, c2, 2), 0);
    ck_assert_int_eq(tq_request_cancel(g_q, "s2"), 0);
    assert_status("s2", TQ_DISMISSED);
    assert_status("s2-a", TQ_DISMISSED);
    j = get("s2-b");
    ck_assert_int_eq(j.seq, 1); /* seq defaults to the index */
    tq_job_free(&j);

    /* cancelling one child only affects that child */
    insert_study("s3", 3);
    ck_assert_int_eq(tq_request_cancel(g_q, "s3-c1"), 0);
    assert_status("s3-c1", TQ_DISMISSED);
    assert_status("s3-c0", TQ_ACCEPTED);
    assert_status("s3", TQ_RUNNING); /* some final, some accepted */
}
END_TEST

START_TEST(study_insert_errors)
{
    struct tq_job s = mkjob("st", "study");
    struct tq_job c[2] = {mkjob("st-a", "run"), mkjob("st-a", "run")}; /* duplicate */
    ck_assert_int_eq(tq_insert_study(g_q, &s, c, 2), -1);
    struct tq_job j;
    ck_assert_int_eq(tq_get(g_q, "st", &j), 1); /* whole transaction rolled back */
    ck_assert_int_eq(tq_get(g_q, "st-a", &j), 1);
    ck_assert_int_eq(tq_insert_study(g_q, &s, c, 0), -1);
    struct tq_job notstudy = mkjob("st", "run");
    ck_assert_int_eq(tq_insert_study(g_q, &notstudy, c, 1), -1);
}
END_TEST

/* ------------------------------------------------------------------ recover */

START_TEST(recover)
{
    insert_run("a");
    insert_run("b");
    insert_run("c");
    insert_study("st", 2);
    claim_expect("a");
    claim_expect("b");
    claim_expect("c");
    claim_expect("st-c0");
    ck_assert_int_eq(tq_set_pid(g_q, "a", 999), 0);
    ck_assert_int_eq(tq_request_cancel(g_q, "c"), 0);
    assert_status("st", TQ_RUNNING);

    /* a: attempts 1 < 2 -> requeued; b likewise; c cancel pending -> dismissed */
    ck_assert_int_eq(tq_recover(g_q, 2), 4);
    struct tq_job j = get("a");
    ck_assert_str_eq(j.status, TQ_ACCEPTED);
    ck_assert_int_eq(j.pid, 0);
    ck_assert_str_eq(j.message, "requeued after daemon restart");
    ck_assert_int_eq(j.attempts, 1);
    tq_job_free(&j);
    j = get("c");
    ck_assert_str_eq(j.status, TQ_DISMISSED);
    ck_assert_str_eq(j.outcome, "cancelled");
    tq_job_free(&j);
    assert_status("st-c0", TQ_ACCEPTED);
    assert_status("st", TQ_ACCEPTED); /* refreshed: no child running any more */
    ck_assert_int_eq(tq_recover(g_q, 2), 0);

    claim_expect("a"); /* attempts 2 */
    claim_expect("b");
    ck_assert_int_eq(tq_recover(g_q, 2), 2);
    j = get("a");
    ck_assert_str_eq(j.status, TQ_FAILED);
    ck_assert_str_eq(j.outcome, "interrupted");
    ck_assert_ptr_nonnull(j.message);
    ck_assert_msg(strstr(j.message, "interrupted") && strstr(j.message, "2"), "%s", j.message);
    ck_assert(j.finished > 0);
    tq_job_free(&j);
    assert_status("b", TQ_FAILED);

    /* a study child that runs out of attempts fails the study once all are final */
    claim_expect("st-c0"); /* attempts 2 */
    claim_expect("st-c1"); /* attempts 1 */
    ck_assert_int_eq(tq_finish(g_q, "st-c1", TQ_SUCCESSFUL, "successful", NULL, NULL), 0);
    ck_assert_int_eq(tq_recover(g_q, 2), 1);
    assert_status("st-c0", TQ_FAILED);
    assert_status("st", TQ_FAILED);
}
END_TEST

/* ------------------------------------------------------------------ delete */

START_TEST(delete_rules)
{
    insert_run("acc");
    insert_run("run");
    insert_study("st", 3);
    ck_assert_int_eq(tq_delete(g_q, "acc"), 2);
    claim_expect("acc");
    claim_expect("run");
    ck_assert_int_eq(tq_delete(g_q, "run"), 2);
    ck_assert_int_eq(tq_finish(g_q, "acc", TQ_FAILED, "crashed", NULL, NULL), 0);
    ck_assert_int_eq(tq_delete(g_q, "acc"), 0);
    struct tq_job j;
    ck_assert_int_eq(tq_get(g_q, "acc", &j), 1);
    ck_assert_int_eq(tq_delete(g_q, "acc"), 1);
    ck_assert_int_eq(tq_delete(g_q, "nosuch"), 1);

    claim_expect("st-c0");
    ck_assert_int_eq(tq_finish(g_q, "st-c0", TQ_SUCCESSFUL, "successful", NULL, NULL), 0);
    ck_assert_int_eq(tq_delete(g_q, "st-c0"), 2); /* its study is not final */
    ck_assert_int_eq(tq_delete(g_q, "st"), 2);
    ck_assert_int_eq(tq_request_cancel(g_q, "st"), 0);
    assert_status("st", TQ_DISMISSED);
    ck_assert_int_eq(tq_delete(g_q, "st"), 0);
    ck_assert_int_eq(tq_get(g_q, "st", &j), 1);
    for (int i = 0; i < 3; i++) {
        char id[16];
        snprintf(id, sizeof id, "st-c%d", i);
        ck_assert_msg(tq_get(g_q, id, &j) == 1, "%s survived its study", id);
    }
    struct tq_job *a;
    size_t n;
    ck_assert_int_eq(tq_list(g_q, NULL, NULL, NULL, 100, 0, &a, &n), 0);
    ck_assert_uint_eq(n, 1);
    ck_assert_str_eq(a[0].id, "run");
    tq_job_free(&a[0]);
    free(a);
}
END_TEST

/* ------------------------------------------------------------------ strings */

START_TEST(strings_round_trip)
{
    static const char evil[] = "Robert'); DROP TABLE jobs;-- \"quoted\" \\ back`tick` "
                               "h\xc3\xa9llo \xe2\x80\x94 \xe6\x97\xa5\xe6\x9c\xac \xe2\x9c\x93 "
                               "\xf0\x9f\x9a\x80 %s %n";
    char input[] = "{\"name\": \"O'Brien \\\"x\\\" \xc3\xa9\", \"sql\": \"'; DELETE FROM jobs; --\"}";
    struct tq_job j = mkjob("strs", "run");
    j.input = input;
    char msg[sizeof evil];
    memcpy(msg, evil, sizeof evil);
    j.message = msg;
    ck_assert_int_eq(tq_insert(g_q, &j), 0);
    struct tq_job g = get("strs");
    ck_assert_str_eq(g.input, input);
    ck_assert_str_eq(g.message, evil);
    tq_job_free(&g);
    claim_expect("strs");
    ck_assert_int_eq(tq_finish(g_q, "strs", TQ_FAILED, "crashed", evil, "{\"k\":\"v'\"}"), 0);
    g = get("strs");
    ck_assert_str_eq(g.message, evil);
    ck_assert_str_eq(g.cost, "{\"k\":\"v'\"}");
    tq_job_free(&g);

    /* Filters are bound values, not SQL. */
    struct tq_job *a;
    size_t n;
    ck_assert_int_eq(tq_list(g_q, "x' OR '1'='1", NULL, NULL, 10, 0, &a, &n), 0);
    ck_assert_uint_eq(n, 0);
    free(a);
    ck_assert_int_eq(tq_list(g_q, NULL, NULL, "run' OR 1=1 --", 10, 0, &a, &n), 0);
    ck_assert_uint_eq(n, 0);
    free(a);
    ck_assert_int_eq(tq_list(g_q, NULL, NULL, NULL, 10, 0, &a, &n), 0);
    ck_assert_uint_eq(n, 1);
    tq_job_free(&a[0]);
    free(a);
}
END_TEST

/* A cancelled study reports the work its children did: 100 for each that ran
 * to its end, the progress a cancelled one reached, 0 for those that never
 * started; (100 + 40 + 0 + 0) / 4 = 35 here, not 100. */
START_TEST(study_cancel_progress)
{
    insert_study("st", 4);
    claim_expect("st-c0");
    ck_assert_int_eq(tq_finish(g_q, "st-c0", TQ_SUCCESSFUL, "successful", NULL, NULL), 0);
    claim_expect("st-c1");
    ck_assert_int_eq(tq_update_progress(g_q, "st-c1", 40, 0, 1, 1, 1), 0);
    ck_assert_int_eq(tq_request_cancel(g_q, "st"), 0);
    ck_assert_int_eq(tq_finish(g_q, "st-c1", TQ_DISMISSED, "cancelled", NULL, NULL), 0);
    assert_status("st", TQ_DISMISSED);
    ck_assert_msg(fabs(study_progress() - 35.0) < 1e-9, "progress %g", study_progress());
}
END_TEST

/* /healthz's counts: run jobs (study children included) and studies apart. */
START_TEST(counts_by_process)
{
    insert_run("a");
    insert_study("st", 3);
    claim_expect("a");
    long acc = -1, run = -1, fin = -1;
    ck_assert_int_eq(tq_counts_of(g_q, "run", &acc, &run, &fin), 0);
    ck_assert(acc == 3 && run == 1 && fin == 0);
    ck_assert_int_eq(tq_counts_of(g_q, "study", &acc, &run, &fin), 0);
    ck_assert(acc == 1 && run == 0 && fin == 0);
    ck_assert_int_eq(tq_counts(g_q, &acc, &run, &fin), 0); /* runs, as before */
    ck_assert(acc == 3 && run == 1 && fin == 0);
}
END_TEST

/* Start-up trust: PRAGMA integrity_check finds damage that opening does not;
 * a missing file is a fresh start; a 0-byte file is an empty database. */
START_TEST(check_file)
{
    char report[256], path[160];
    for (int i = 0; i < 60; i++) {
        char id[16];
        snprintf(id, sizeof id, "j%d", i);
        insert_run(id);
    }
    tq_close(g_q); /* checkpoints the WAL into the file */
    g_q = NULL;
    ck_assert_int_eq(tq_check_file(g_db, report, sizeof report), TQ_TRUSTED);
    ck_assert_str_eq(report, "ok");
    FILE *f = fopen(g_db, "r+b");
    ck_assert_ptr_nonnull(f);
    ck_assert_int_eq(fseek(f, 4096, SEEK_SET), 0);
    for (int i = 0; i < 4096; i++)
        fputc((i * 7919) & 0xff, f); /* page 2 overwritten */
    fclose(f);
    ck_assert_int_eq(tq_check_file(g_db, report, sizeof report), TQ_CORRUPT);
    ck_assert_msg(strlen(report) > 0 && strcmp(report, "ok"), "report: %s", report);
    snprintf(path, sizeof path, "%s/missing.db", g_dir);
    ck_assert_int_eq(tq_check_file(path, report, sizeof report), TQ_TRUSTED);
    ck_assert_int_ne(access(path, F_OK), 0); /* not created */
    snprintf(path, sizeof path, "%s/empty.db", g_dir);
    f = fopen(path, "w");
    fclose(f);
    ck_assert_int_eq(tq_check_file(path, report, sizeof report), TQ_TRUSTED);
}
END_TEST

/* Rows rebuilt from job directories (tlsphd --recover) keep what they are given. */
START_TEST(insert_recovered)
{
    struct tq_job j = mkjob("rec", "run");
    strcpy(j.status, TQ_SUCCESSFUL);
    strcpy(j.outcome, "successful");
    j.message = (char *)"recovered";
    j.progress = 100;
    j.created = 10;
    j.started = 11;
    j.finished = 12;
    j.attempts = 1;
    ck_assert_int_eq(tq_has_row(g_q, "rec"), TQ_NOT_FOUND);
    ck_assert_int_eq(tq_insert_recovered(g_q, &j), TQ_OK);
    ck_assert_int_eq(tq_has_row(g_q, "rec"), TQ_OK);
    struct tq_job got = get("rec");
    ck_assert_str_eq(got.status, TQ_SUCCESSFUL);
    ck_assert_str_eq(got.outcome, "successful");
    ck_assert_str_eq(got.message, "recovered");
    ck_assert(got.progress == 100 && got.created == 10 && got.finished == 12 && got.attempts == 1);
    tq_job_free(&got);
    ck_assert_int_eq(tq_insert_recovered(g_q, &j), TQ_ERROR); /* the id is taken */
}
END_TEST

/* The Slurm executor's claim of a study (all accepted children at once, one
 * job array) and its messages on running jobs. */
START_TEST(claim_siblings_and_message)
{
    insert_study("s", 4);
    claim_expect("s-c0");
    ck_assert_int_eq(tq_request_cancel(g_q, "s-c3"), 0); /* accepted: dismissed at once */
    struct tq_job *rest;
    size_t n;
    ck_assert_int_eq(tq_claim_siblings(g_q, "s", &rest, &n), 0);
    ck_assert_uint_eq(n, 2); /* c1, c2: c0 is running already, c3 dismissed */
    for (size_t i = 0; i < n; i++) {
        ck_assert_str_eq(rest[i].status, TQ_RUNNING);
        ck_assert_int_eq(rest[i].attempts, 1);
        ck_assert(rest[i].started > 0);
    }
    tq_jobs_free(rest, n);
    assert_status("s", TQ_RUNNING);
    ck_assert_int_eq(tq_claim_siblings(g_q, "s", &rest, &n), 0);
    ck_assert_uint_eq(n, 0);
    tq_jobs_free(rest, n);
    struct tq_job none;
    ck_assert_int_eq(tq_claim_next(g_q, &none), TQ_NOT_FOUND);

    ck_assert_int_eq(tq_set_message(g_q, "s-c1", "Slurm job 7_1: PENDING (Priority)"), 0);
    struct tq_job j = get("s-c1");
    ck_assert_str_eq(j.message, "Slurm job 7_1: PENDING (Priority)");
    tq_job_free(&j);
    ck_assert_int_eq(tq_set_message(g_q, "s-c3", "x"), TQ_NOT_FOUND); /* not running */
    ck_assert_int_eq(tq_set_message(g_q, "s", "x"), TQ_NOT_FOUND);    /* not a run */
}
END_TEST

static Suite *queue_suite(void)
{
    Suite *s = suite_create("queue");
    TCase *tc = tcase_create("queue");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, open_creates_wal_v1);
    tcase_add_test(tc, reopen_keeps_data);
    tcase_add_test(tc, newer_schema_refused);
    tcase_add_test(tc, insert_get_list);
    tcase_add_test(tc, new_ids);
    tcase_add_test(tc, claim_fifo);
    tcase_add_test(tc, concurrent_claim);
    tcase_add_test(tc, progress_and_finish);
    tcase_add_test(tc, requeue);
    tcase_add_test(tc, cancel_semantics);
    tcase_add_test(tc, study_all_successful);
    tcase_add_test(tc, study_one_failed);
    tcase_add_test(tc, study_cancel);
    tcase_add_test(tc, study_insert_errors);
    tcase_add_test(tc, recover);
    tcase_add_test(tc, delete_rules);
    tcase_add_test(tc, strings_round_trip);
    tcase_add_test(tc, study_cancel_progress);
    tcase_add_test(tc, counts_by_process);
    tcase_add_test(tc, check_file);
    tcase_add_test(tc, insert_recovered);
    tcase_add_test(tc, claim_siblings_and_message);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return tlsph_check_run(queue_suite());
}
