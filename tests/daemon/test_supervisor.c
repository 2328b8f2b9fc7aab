/* Supervisor tests with real engine processes (tlsph-run from $top_builddir).
 * Each test gets a fresh temp dir with its own SQLite queue and jobs dir. */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include <stddef.h>

#include "jobdir.h"
#include "queue.h"
#include "supervisor.h"

#include <check.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <jansson.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include "support/check_main.h"

/* Every wait below ends on the event it waits for (a state in the queue, a
 * process gone, a file written); HANG_S only detects a hang, so that a
 * supervisor that never acts fails the test instead of hanging it.  No
 * assertion bounds how fast anything happens: on a loaded machine (load 5-10
 * on 2 cores) each step can take many times its idle duration. */
#define HANG_S 300.0

static char tmpdir[128];
static char db_path[256];
static char jobs_dir[256];
static char engine[2048];
static char srcdir[2048];
static struct tq *q;

/* The 2-D strip of examples/elastic-strip.json with a variable end time:
 * 4e-4 runs ~1 s, 1e-2 runs ~40 s (a frame every ~2 s). */
static const char *strip_fmt =
    "{\"name\":\"strip\",\"dimension\":2,\"parameters\":{\"vmax\":0.1,\"tau\":1e-4},"
    "\"time\":{\"end\":%g,\"cfl\":0.3},"
    "\"discretization\":{\"kernel\":\"wendland_c2\",\"support_factor\":2.01,"
    "\"hourglass\":{\"enabled\":true,\"coefficient\":1.0},"
    "\"viscosity\":{\"enabled\":true,\"linear\":1.0,\"quadratic\":0.0}},"
    "\"output\":{\"frames\":20,\"series_every\":10},"
    "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2.1e11,\"poisson_ratio\":0.3,"
    "\"eos\":{\"type\":\"linear\"},\"strength\":{\"type\":\"elastic\"}}},"
    "\"bodies\":[{\"name\":\"strip\",\"material\":\"steel\",\"spacing\":0.001,"
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.04,0.01,0]}}}],"
    "\"boundary_conditions\":["
    "{\"type\":\"velocity\",\"name\":\"left\",\"select\":{\"box\":{\"min\":[-1,-1,-1],"
    "\"max\":[0.001,1,1]}},\"velocity\":[\"-vmax*(1-exp(-t/tau))\",null,null]},"
    "{\"type\":\"velocity\",\"name\":\"right\",\"select\":{\"box\":{\"min\":[0.039,-1,-1],"
    "\"max\":[1,1,1]}},\"velocity\":[\"vmax*(1-exp(-t/tau))\",null,null]}]}";

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void sleep_ms(long ms)
{
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    while (nanosleep(&ts, &ts) < 0 && errno == EINTR)
        ;
}

static char *strip_scene(double end)
{
    char *s = NULL;
    ck_assert_int_ge(asprintf(&s, strip_fmt, end), 0);
    return s;
}

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = NULL;
    size_t len = 0, cap = 0;
    char tmp[4096];
    size_t n;
    while ((n = fread(tmp, 1, sizeof tmp, f)) > 0) {
        if (len + n + 1 > cap) {
            cap = (len + n + 1) * 2;
            char *p = realloc(buf, cap);
            ck_assert_ptr_nonnull(p);
            buf = p;
        }
        memcpy(buf + len, tmp, n);
        len += n;
    }
    fclose(f);
    if (!buf)
        buf = calloc(1, 1);
    else
        buf[len] = 0;
    return buf;
}

static void make_id(char id[TQ_ID_LEN + 1])
{
    static unsigned counter;
    unsigned char rnd[16];
    int fd = open("/dev/urandom", O_RDONLY | O_CLOEXEC);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(read(fd, rnd, sizeof rnd), (ssize_t)sizeof rnd);
    close(fd);
    rnd[0] = (unsigned char)counter++;
    for (int i = 0; i < 16; i++)
        snprintf(id + 2 * i, 3, "%02x", rnd[i]);
}

static void rm_tree(const char *path)
{
    DIR *d = opendir(path);
    if (!d) {
        unlink(path);
        return;
    }
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        char p[PATH_MAX];
        snprintf(p, sizeof p, "%s/%s", path, e->d_name);
        struct stat st;
        if (lstat(p, &st) == 0 && S_ISDIR(st.st_mode))
            rm_tree(p);
        else
            unlink(p);
    }
    closedir(d);
    rmdir(path);
}

static void setup(void)
{
    const char *b = getenv("top_builddir");
    const char *sd = getenv("top_srcdir");
    snprintf(engine, sizeof engine, "%s/tlsph-run", b && *b ? b : ".");
    snprintf(srcdir, sizeof srcdir, "%s", sd && *sd ? sd : ".");
    snprintf(tmpdir, sizeof tmpdir, "/tmp/test_supervisor-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(tmpdir));
    snprintf(db_path, sizeof db_path, "%s/queue.db", tmpdir);
    snprintf(jobs_dir, sizeof jobs_dir, "%s/jobs", tmpdir);
    char err[256] = "";
    int rc = tq_open(db_path, &q, err, sizeof err);
    ck_assert_msg(rc == 0, "tq_open: %s", err);
}

static void teardown(void)
{
    if (q)
        tq_close(q);
    q = NULL;
    rm_tree(tmpdir);
}

static struct tsup *start_sup_ex(const char *engine_path, int max_jobs, double wall_limit,
                                 double kill_grace)
{
    struct tsup_config cfg = {.db_path = db_path,
                              .engine_path = engine_path,
                              .jobs_dir = jobs_dir,
                              .max_jobs = max_jobs,
                              .threads_per_job = 1,
                              .wall_limit = wall_limit,
                              .kill_grace = kill_grace,
                              .memory_limit_mb = 0,
                              .max_attempts = 3};
    struct tsup *s = NULL;
    char err[256] = "";
    int rc = tsup_start(&cfg, &s, err, sizeof err);
    ck_assert_msg(rc == 0, "tsup_start: %s", err);
    ck_assert_ptr_nonnull(s);
    return s;
}

static struct tsup *start_sup(int max_jobs, double wall_limit)
{
    return start_sup_ex(engine, max_jobs, wall_limit, 5.0);
}

/* Writes an executable shell script (a fake engine) into tmpdir. */
static void write_script(char *path, size_t size, const char *name, const char *body)
{
    snprintf(path, size, "%s/%s", tmpdir, name);
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fputs(body, f);
    ck_assert_int_eq(fclose(f), 0);
    ck_assert_int_eq(chmod(path, 0755), 0);
}

/* 1 if pid no longer exists (or is a zombie of someone else's). */
static int proc_gone(long pid)
{
    if (kill((pid_t)pid, 0) < 0 && errno == ESRCH)
        return 1;
    char p[64];
    snprintf(p, sizeof p, "/proc/%ld/stat", pid);
    char *st = read_text(p);
    if (!st)
        return 1;
    char *rp = strrchr(st, ')');
    int zombie = rp && rp[1] == ' ' && rp[2] == 'Z';
    free(st);
    return zombie;
}

static int wait_gone(long pid, double limit)
{
    double t0 = now_s();
    while (!proc_gone(pid)) {
        if (now_s() - t0 > limit)
            return 0;
        sleep_ms(50);
    }
    return 1;
}

/* Queues a run job; writes its scene.json unless scene_file is NULL-able raw
 * text to put there instead (write_dir = 0: the caller writes the dir). */
static void add_job(char id[TQ_ID_LEN + 1], const char *scene, double wall_limit, int write_dir)
{
    make_id(id);
    if (write_dir) {
        char err[256] = "";
        int rc = jobdir_create(jobs_dir, id, scene, err, sizeof err);
        ck_assert_msg(rc == 0, "jobdir_create: %s", err);
    }
    struct tq_job j;
    memset(&j, 0, sizeof j);
    memcpy(j.id, id, TQ_ID_LEN + 1);
    snprintf(j.process, sizeof j.process, "run");
    j.seq = -1;
    snprintf(j.status, sizeof j.status, TQ_ACCEPTED);
    j.input = (char *)scene;
    j.eta = -1;
    j.threads = 1;
    j.wall_limit = wall_limit;
    ck_assert_int_eq(tq_insert(q, &j), 0);
}

static int is_final(const char *st)
{
    return !strcmp(st, TQ_SUCCESSFUL) || !strcmp(st, TQ_FAILED) || !strcmp(st, TQ_DISMISSED);
}

/* Polls until the job is final; fills out (caller frees). */
static void wait_final(const char *id, struct tq_job *out, double limit)
{
    double t0 = now_s();
    for (;;) {
        memset(out, 0, sizeof *out);
        ck_assert_int_eq(tq_get(q, id, out), 0);
        if (is_final(out->status)) {
            if (getenv("TSUP_TEST_VERBOSE"))
                fprintf(stderr, "job %s: %s/%s: %s\n", id, out->status, out->outcome,
                        out->message ? out->message : "(no message)");
            return;
        }
        tq_job_free(out);
        ck_assert_msg(now_s() - t0 < limit, "job %s not final after %g s", id, limit);
        sleep_ms(100);
    }
}

/* Polls until the job runs with a pid (and progress > min_progress). Returns the pid. */
static long wait_running(const char *id, double min_progress)
{
    double t0 = now_s();
    for (;;) {
        struct tq_job j;
        memset(&j, 0, sizeof j);
        ck_assert_int_eq(tq_get(q, id, &j), 0);
        long pid = j.pid;
        int ok = !strcmp(j.status, TQ_RUNNING) && pid > 0 && j.progress > min_progress;
        ck_assert_msg(!is_final(j.status), "job %s ended early: %s/%s %s", id, j.status,
                      j.outcome, j.message ? j.message : "");
        tq_job_free(&j);
        if (ok)
            return pid;
        ck_assert_msg(now_s() - t0 < HANG_S, "job %s not running", id);
        sleep_ms(100);
    }
}

/* Number of live (non-zombie) processes in group pgid, from /proc. */
static int group_members(long pgid)
{
    DIR *d = opendir("/proc");
    ck_assert_ptr_nonnull(d);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] < '0' || e->d_name[0] > '9')
            continue;
        char p[300];
        snprintf(p, sizeof p, "/proc/%s/stat", e->d_name);
        char *st = read_text(p);
        if (!st)
            continue;
        char *rp = strrchr(st, ')');
        char state = 0;
        long ppid = 0, pgrp = 0;
        if (rp && sscanf(rp + 1, " %c %ld %ld", &state, &ppid, &pgrp) == 3 && pgrp == pgid &&
            state != 'Z')
            n++;
        free(st);
    }
    closedir(d);
    return n;
}

/* Waits until the process group is gone (kill(-pgid, 0) fails with ESRCH) or
 * only zombies are left in it (reaping them is init's business); 0 only when
 * live members remain after HANG_S. */
static int group_gone(long pgid)
{
    double t0 = now_s();
    for (;;) {
        if (kill(-(pid_t)pgid, 0) < 0 && errno == ESRCH)
            return 1;
        if (group_members(pgid) == 0)
            return 1;
        if (now_s() - t0 > HANG_S)
            return 0;
        sleep_ms(20);
    }
}

/* Open descriptors of this process, not counting the SQLite database files:
 * SQLite keeps a closed connection's descriptor open while another connection
 * of the process (the test's own) holds POSIX locks on the same file. */
static int count_fds(void)
{
    DIR *d = opendir("/proc/self/fd");
    ck_assert_ptr_nonnull(d);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        char l[PATH_MAX], t[PATH_MAX] = "";
        snprintf(l, sizeof l, "/proc/self/fd/%s", e->d_name);
        ssize_t k = readlink(l, t, sizeof t - 1);
        if (k > 0)
            t[k] = 0;
        if (strncmp(t, db_path, strlen(db_path)) == 0)
            continue;
        n++;
    }
    closedir(d);
    return n;
}

static void job_file(char *buf, size_t size, const char *id, const char *name)
{
    snprintf(buf, size, "%s/%s/%s", jobs_dir, id, name);
}

/* ------------------------------------------------------------------ tests */

START_TEST(test_successful)
{
    int fds0 = count_fds();
    struct tsup *s = start_sup(1, 600);
    char id[TQ_ID_LEN + 1];
    char *scene = strip_scene(4e-4);
    add_job(id, scene, 0, 1);
    tsup_wake(s);
    struct tq_job j;
    wait_final(id, &j, HANG_S);
    ck_assert_msg(!strcmp(j.status, TQ_SUCCESSFUL), "status %s/%s: %s", j.status, j.outcome,
                  j.message ? j.message : "");
    ck_assert_str_eq(j.outcome, "successful");
    ck_assert_double_eq_tol(j.progress, 100.0, 1e-9);
    ck_assert_int_ge(j.step, 1);
    ck_assert_ptr_nonnull(j.cost);
    json_error_t jerr;
    json_t *cost = json_loads(j.cost, 0, &jerr);
    ck_assert_ptr_nonnull(cost);
    ck_assert_int_gt(json_integer_value(json_object_get(cost, "particles")), 0);
    ck_assert_int_gt(json_integer_value(json_object_get(cost, "steps")), 0);
    json_decref(cost);
    tq_job_free(&j);

    char p[PATH_MAX];
    struct stat st;
    job_file(p, sizeof p, id, "result.h5");
    ck_assert_int_eq(stat(p, &st), 0);
    ck_assert_int_gt(st.st_size, 0);
    job_file(p, sizeof p, id, "log.txt");
    char *log = read_text(p);
    ck_assert_ptr_nonnull(log);
    ck_assert_msg(strstr(log, "particles") && strstr(log, "tlsph: successful"), "log: %s", log);
    free(log);

    tsup_stop(s);
    ck_assert_int_eq(count_fds(), fds0 + 0);
    ck_assert_int_eq(waitpid(-1, NULL, WNOHANG), -1); /* no children, no zombies */
    ck_assert_int_eq(errno, ECHILD);

    /* the job dir can be removed afterwards */
    ck_assert_int_eq(jobdir_remove(jobs_dir, id), 0);
    job_file(p, sizeof p, id, "");
    ck_assert_int_lt(stat(p, &st), 0);
    free(scene);
}
END_TEST

START_TEST(test_invalid_scene)
{
    struct tsup *s = start_sup(1, 600);
    char id[TQ_ID_LEN + 1];
    char *scene = strip_scene(4e-4);
    add_job(id, scene, 0, 1);
    /* replace the scene file behind the daemon's back: invalid JSON */
    char p[PATH_MAX];
    job_file(p, sizeof p, id, "scene.json");
    FILE *f = fopen(p, "w");
    ck_assert_ptr_nonnull(f);
    fputs("{\"name\": \"broken\n", f);
    ck_assert_int_eq(fclose(f), 0);
    tsup_wake(s);
    struct tq_job j;
    wait_final(id, &j, HANG_S);
    ck_assert_str_eq(j.status, TQ_FAILED);
    ck_assert_str_eq(j.outcome, "invalid");
    ck_assert_ptr_nonnull(j.message);
    ck_assert_msg(strstr(j.message, "invalid JSON"), "message: %s", j.message);
    tq_job_free(&j);
    tsup_stop(s);
    free(scene);
}
END_TEST

START_TEST(test_unstable)
{
    char p[PATH_MAX];
    snprintf(p, sizeof p, "%s/tests/scenes/good/unstable.json", srcdir);
    char *scene = read_text(p);
    ck_assert_msg(scene != NULL, "cannot read %s", p);
    struct tsup *s = start_sup(1, 600);
    char id[TQ_ID_LEN + 1];
    add_job(id, scene, 0, 1);
    tsup_wake(s);
    struct tq_job j;
    wait_final(id, &j, HANG_S);
    ck_assert_str_eq(j.status, TQ_FAILED);
    ck_assert_str_eq(j.outcome, "unstable");
    ck_assert_ptr_nonnull(j.message);
    ck_assert_msg(strstr(j.message, "numerically unstable at step"), "message: %s", j.message);
    ck_assert_ptr_nonnull(j.cost);
    tq_job_free(&j);
    tsup_stop(s);
    free(scene);
}
END_TEST

START_TEST(test_missing_scene)
{
    struct tsup *s = start_sup(1, 600);
    char id[TQ_ID_LEN + 1];
    add_job(id, "{}", 0, 0); /* no job directory */
    tsup_wake(s);
    struct tq_job j;
    wait_final(id, &j, HANG_S);
    ck_assert_str_eq(j.status, TQ_FAILED);
    ck_assert_str_eq(j.outcome, "crashed");
    ck_assert_ptr_nonnull(j.message);
    ck_assert_msg(strstr(j.message, "scene.json"), "message: %s", j.message);
    tq_job_free(&j);
    tsup_stop(s);
}
END_TEST

START_TEST(test_cancel)
{
    int fds0 = count_fds();
    struct tsup *s = start_sup(1, 600);
    char id[TQ_ID_LEN + 1];
    char *scene = strip_scene(1e-2);
    add_job(id, scene, 0, 1);
    tsup_wake(s);
    long pid = wait_running(id, 0.0); /* progress reached the queue */
    ck_assert_int_eq(kill((pid_t)pid, 0), 0);
    ck_assert_int_eq(getpgid((pid_t)pid), (pid_t)pid); /* own process group */
    ck_assert_int_eq(tq_request_cancel(q, id), 0);
    tsup_wake(s);
    struct tq_job j;
    wait_final(id, &j, HANG_S);
    /* dismissed, not successful: the cancel ended the run before its end */
    ck_assert_str_eq(j.status, TQ_DISMISSED);
    ck_assert_str_eq(j.outcome, "cancelled");
    tq_job_free(&j);
    ck_assert_msg(group_gone(pid), "process group %ld still exists", pid);
    tsup_stop(s);
    ck_assert_int_eq(count_fds(), fds0);
    free(scene);
}
END_TEST

START_TEST(test_kill9_then_next)
{
    struct tsup *s = start_sup(1, 600);
    char id[TQ_ID_LEN + 1], id2[TQ_ID_LEN + 1];
    char *scene = strip_scene(1e-2);
    char *quick = strip_scene(4e-4);
    add_job(id, scene, 0, 1);
    tsup_wake(s);
    long pid = wait_running(id, -1.0);
    ck_assert_int_eq(kill((pid_t)pid, SIGKILL), 0);
    struct tq_job j;
    wait_final(id, &j, HANG_S);
    ck_assert_str_eq(j.status, TQ_FAILED);
    ck_assert_str_eq(j.outcome, "crashed");
    ck_assert_ptr_nonnull(j.message);
    ck_assert_msg(strstr(j.message, "signal 9"), "message: %s", j.message);
    tq_job_free(&j);
    ck_assert(group_gone(pid));

    add_job(id2, quick, 0, 1);
    tsup_wake(s);
    wait_final(id2, &j, HANG_S);
    ck_assert_msg(!strcmp(j.status, TQ_SUCCESSFUL), "second job: %s/%s %s", j.status, j.outcome,
                  j.message ? j.message : "");
    tq_job_free(&j);
    tsup_stop(s);
    free(scene);
    free(quick);
}
END_TEST

START_TEST(test_wall_limit)
{
    struct tsup *s = start_sup(1, 600);
    char id[TQ_ID_LEN + 1];
    char *scene = strip_scene(1e-2);
    add_job(id, scene, 1.0, 1); /* per-job limit 1 s */
    tsup_wake(s);
    long pid = wait_running(id, -1.0);
    struct tq_job j;
    wait_final(id, &j, HANG_S);
    ck_assert_str_eq(j.status, TQ_FAILED);
    ck_assert_str_eq(j.outcome, "timed_out");
    ck_assert_ptr_nonnull(j.message);
    ck_assert_msg(strstr(j.message, "wall-clock limit of 1 s exceeded"), "message: %s", j.message);
    tq_job_free(&j);
    ck_assert(group_gone(pid));
    tsup_stop(s);
    free(scene);
}
END_TEST

START_TEST(test_default_wall_limit)
{
    struct tsup *s = start_sup(1, 1.0); /* the configured default applies */
    char id[TQ_ID_LEN + 1];
    char *scene = strip_scene(1e-2);
    add_job(id, scene, 0, 1);
    tsup_wake(s);
    struct tq_job j;
    wait_final(id, &j, HANG_S);
    ck_assert_str_eq(j.status, TQ_FAILED);
    ck_assert_str_eq(j.outcome, "timed_out");
    tq_job_free(&j);
    tsup_stop(s);
    free(scene);
}
END_TEST

START_TEST(test_stop_requeues)
{
    int fds0 = count_fds();
    struct tsup *s = start_sup(1, 600);
    char id[TQ_ID_LEN + 1];
    char *scene = strip_scene(1e-2);
    add_job(id, scene, 0, 1);
    tsup_wake(s);
    long pid = wait_running(id, -1.0);
    tsup_stop(s); /* returns once its engines are stopped and reaped */
    ck_assert(group_gone(pid));
    ck_assert_int_eq(waitpid(-1, NULL, WNOHANG), -1);
    ck_assert_int_eq(errno, ECHILD);
    ck_assert_int_eq(count_fds(), fds0);
    struct tq_job j;
    memset(&j, 0, sizeof j);
    ck_assert_int_eq(tq_get(q, id, &j), 0);
    ck_assert_str_eq(j.status, TQ_ACCEPTED);
    ck_assert_ptr_nonnull(j.message);
    ck_assert_msg(strstr(j.message, "shutdown"), "message: %s", j.message);
    tq_job_free(&j);

    /* a new supervisor picks it up again (and we cancel it) */
    s = start_sup(1, 600);
    pid = wait_running(id, -1.0);
    ck_assert_int_eq(tq_request_cancel(q, id), 0);
    tsup_wake(s);
    wait_final(id, &j, HANG_S);
    ck_assert_str_eq(j.status, TQ_DISMISSED);
    ck_assert_int_ge(j.attempts, 2);
    tq_job_free(&j);
    tsup_stop(s);
    free(scene);
}
END_TEST

START_TEST(test_two_at_once)
{
    struct tsup *s = start_sup(2, 600);
    char a[TQ_ID_LEN + 1], b[TQ_ID_LEN + 1], c[TQ_ID_LEN + 1];
    char *scene = strip_scene(1e-2);
    add_job(a, scene, 0, 1);
    add_job(b, scene, 0, 1);
    add_job(c, scene, 0, 1);
    tsup_wake(s);
    long pa = wait_running(a, -1.0);
    long pb = wait_running(b, -1.0);
    /* both alive at the same time, the third waits */
    ck_assert_int_eq(kill((pid_t)pa, 0), 0);
    ck_assert_int_eq(kill((pid_t)pb, 0), 0);
    ck_assert_int_ne(pa, pb);
    struct tq_job j;
    memset(&j, 0, sizeof j);
    ck_assert_int_eq(tq_get(q, c, &j), 0);
    ck_assert_str_eq(j.status, TQ_ACCEPTED);
    tq_job_free(&j);
    long running = -1, accepted = -1, final = -1;
    ck_assert_int_eq(tq_counts(q, &accepted, &running, &final), 0);
    ck_assert_int_eq(running, 2);
    ck_assert_int_eq(accepted, 1);

    /* cancel a: c takes its place */
    ck_assert_int_eq(tq_request_cancel(q, a), 0);
    tsup_wake(s);
    wait_final(a, &j, HANG_S);
    ck_assert_str_eq(j.status, TQ_DISMISSED);
    tq_job_free(&j);
    long pc = wait_running(c, -1.0);
    ck_assert_int_gt(pc, 0);
    ck_assert_int_eq(kill((pid_t)pb, 0), 0);
    tsup_stop(s);
    ck_assert(group_gone(pb));
    ck_assert(group_gone(pc));
    free(scene);
}
END_TEST

START_TEST(test_job_dirs)
{
    char err[256];
    const char *scene = "{\"x\": 1}";
    ck_assert_int_eq(jobdir_create(jobs_dir, "../../etc", scene, err, sizeof err), -1);
    ck_assert_int_eq(
        jobdir_create(jobs_dir, "0123456789ABCDEF0123456789abcdef", scene, err, sizeof err),
        -1);
    ck_assert_int_eq(
        jobdir_create(jobs_dir, "0123456789abcdef0123456789abcde", scene, err, sizeof err),
        -1);
    ck_assert_int_eq(
        jobdir_create(jobs_dir, "0123456789abcdef0123456789abcdef0", scene, err, sizeof err),
        -1);
    ck_assert_int_eq(jobdir_create(jobs_dir, "", scene, err, sizeof err), -1);
    ck_assert_int_eq(jobdir_create(jobs_dir, NULL, scene, err, sizeof err), -1);
    ck_assert_int_eq(jobdir_remove(jobs_dir, ".."), -1);
    ck_assert_int_eq(jobdir_remove(jobs_dir, "a/b"), -1);

    const char *id = "0123456789abcdef0123456789abcdef";
    ck_assert_int_eq(jobdir_create(jobs_dir, id, scene, err, sizeof err), 0);
    ck_assert_int_eq(jobdir_create(jobs_dir, id, "{\"x\": 2}", err, sizeof err), 0);
    char p[PATH_MAX];
    job_file(p, sizeof p, id, "scene.json");
    char *text = read_text(p);
    ck_assert_ptr_nonnull(text);
    ck_assert_str_eq(text, "{\"x\": 2}");
    free(text);
    struct stat st;
    job_file(p, sizeof p, id, "");
    ck_assert_int_eq(stat(p, &st), 0);
    ck_assert_int_eq(st.st_mode & 0777, 0750);
    /* only scene.json is there: no temp files left */
    int n = 0;
    DIR *d = opendir(p);
    ck_assert_ptr_nonnull(d);
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (e->d_name[0] != '.')
            n++;
    closedir(d);
    ck_assert_int_eq(n, 1);

    /* daemon files and temp files are removed, then the dir */
    const char *files[] = {"log.txt", "result.h5", "result.xmf", "result.xmf.tmp"};
    for (size_t i = 0; i < 4; i++) {
        job_file(p, sizeof p, id, files[i]);
        FILE *f = fopen(p, "w");
        ck_assert_ptr_nonnull(f);
        fclose(f);
    }
    ck_assert_int_eq(jobdir_remove(jobs_dir, id), 0);
    job_file(p, sizeof p, id, "");
    ck_assert_int_lt(stat(p, &st), 0);
    ck_assert_int_eq(jobdir_remove(jobs_dir, id), 0); /* already gone */

    /* a foreign file is not deleted: the dir stays and the call fails */
    ck_assert_int_eq(jobdir_create(jobs_dir, id, scene, err, sizeof err), 0);
    job_file(p, sizeof p, id, "foreign.dat");
    FILE *f = fopen(p, "w");
    ck_assert_ptr_nonnull(f);
    fclose(f);
    ck_assert_int_eq(jobdir_remove(jobs_dir, id), -1);
    ck_assert_int_eq(stat(p, &st), 0);
}
END_TEST

START_TEST(test_start_errors)
{
    struct tsup_config cfg = {.db_path = db_path,
                              .engine_path = "/nonexistent/tlsph-run",
                              .jobs_dir = jobs_dir,
                              .max_jobs = 1,
                              .threads_per_job = 1,
                              .wall_limit = 10,
                              .kill_grace = 1,
                              .max_attempts = 3};
    struct tsup *s = NULL;
    char err[256] = "";
    ck_assert_int_eq(tsup_start(&cfg, &s, err, sizeof err), -1);
    ck_assert_ptr_null(s);
    ck_assert(strlen(err) > 0);
    cfg.engine_path = engine;
    cfg.max_jobs = 0;
    ck_assert_int_eq(tsup_start(&cfg, &s, err, sizeof err), -1);
    /* stop right after start, nothing running */
    s = start_sup(1, 10);
    tsup_wake(s);
    tsup_stop(s);
}
END_TEST

/* A fake engine shows what the child gets: argv, rlimits, cwd, descriptors;
 * its background grandchild must die with the group when the leader exits. */
START_TEST(test_child_setup)
{
    char script[PATH_MAX];
    write_script(script, sizeof script, "fake-engine.sh",
                 "#!/bin/sh\n"
                 "echo \"args: $*\"\n"
                 "echo \"nofile: $(ulimit -n)\"\n"
                 "echo \"core: $(ulimit -c)\"\n"
                 "echo \"cwd: $(pwd)\"\n"
                 "echo \"wait policy: $OMP_WAIT_POLICY\"\n"
                 "ls -l /proc/$$/fd\n"
                 "echo '{\"event\":\"started\",\"end_time\":1.0}' >&3\n"
                 "echo '{\"event\":\"progress\",\"step\":5,\"time\":0.5,\"end_time\":1.0,"
                 "\"eta_seconds\":1}' >&3\n"
                 "printf '{\"event\":\"finished\",\"status\":\"successful\",\"step\":9,"
                 "\"cost\":{\"particles\":7}}' >&3\n"
                 "sleep 100 </dev/null >/dev/null 2>&1 &\n"
                 "echo $! > grandchild.pid\n"
                 "exit 0\n");
    struct tsup *s = start_sup_ex(script, 1, 600, 5.0);
    char id[TQ_ID_LEN + 1];
    add_job(id, "{}", 0, 1);
    tsup_wake(s);
    struct tq_job j;
    wait_final(id, &j, HANG_S);
    ck_assert_msg(!strcmp(j.status, TQ_SUCCESSFUL), "status %s/%s: %s", j.status, j.outcome,
                  j.message ? j.message : "");
    ck_assert_ptr_nonnull(j.cost); /* unterminated last line still parsed */
    ck_assert_msg(strstr(j.cost, "\"particles\":7"), "cost %s", j.cost);
    ck_assert_double_eq_tol(j.progress, 100.0, 1e-9);
    tq_job_free(&j);

    char p[PATH_MAX];
    job_file(p, sizeof p, id, "log.txt");
    char *log = read_text(p);
    ck_assert_ptr_nonnull(log);
    char want[2 * PATH_MAX + 256];
    snprintf(want, sizeof want, "args: %s/%s/scene.json -o %s/%s --progress-fd 3 --threads 1\n",
             jobs_dir, id, jobs_dir, id);
    ck_assert_msg(strstr(log, want), "log: %s\nwanted: %s", log, want);
    ck_assert_msg(!strstr(log, "--quiet"), "log: %s", log);
    /* valgrind (LD_PRELOAD vgpreload) refuses RLIMIT_NOFILE changes; the
     * supervisor then logs a warning and goes on */
    const char *pre = getenv("LD_PRELOAD");
    int under_valgrind = pre && strstr(pre, "vgpreload");
    ck_assert_msg(strstr(log, "nofile: 256\n") ||
                      (under_valgrind && strstr(log, "setrlimit(RLIMIT_NOFILE) refused")),
                  "log: %s", log);
    ck_assert_msg(strstr(log, "core: 0\n"), "log: %s", log);
    /* engines wait passively (server/supervisor.c engine_environment) unless
     * the daemon's environment says otherwise */
    const char *policy = getenv("OMP_WAIT_POLICY");
    snprintf(want, sizeof want, "wait policy: %s\n", policy ? policy : "passive");
    ck_assert_msg(strstr(log, want), "log: %s\nwanted: %s", log, want);
    snprintf(want, sizeof want, "cwd: %s/%s\n", jobs_dir, id);
    ck_assert_msg(strstr(log, want), "log: %s", log);
    ck_assert_msg(!strstr(log, "queue.db"), "queue descriptor leaked into the engine: %s", log);
    free(log);

    job_file(p, sizeof p, id, "grandchild.pid");
    char *gp = read_text(p);
    ck_assert_ptr_nonnull(gp);
    long gpid = atol(gp);
    free(gp);
    ck_assert_int_gt(gpid, 0);
    ck_assert_msg(wait_gone(gpid, 5.0), "grandchild %ld survived its group", gpid);
    tsup_stop(s);
}
END_TEST

/* An engine that ignores SIGTERM gets SIGKILL after the grace period. */
START_TEST(test_term_ignored)
{
    char script[PATH_MAX];
    write_script(script, sizeof script, "stubborn.sh",
                 "#!/bin/sh\n"
                 "trap '' TERM\n"
                 "echo '{\"event\":\"started\",\"end_time\":1.0}' >&3\n"
                 "sleep 100000 &\n"
                 "echo $! > grandchild.pid\n"
                 "wait\n");
    struct tsup *s = start_sup_ex(script, 1, 600, 1.0);
    char id[TQ_ID_LEN + 1];
    add_job(id, "{}", 0, 1);
    tsup_wake(s);
    long pid = wait_running(id, -1.0);
    char p[PATH_MAX];
    job_file(p, sizeof p, id, "grandchild.pid");
    double t0 = now_s();
    struct stat st;
    while (stat(p, &st) < 0 || st.st_size == 0) {
        ck_assert_msg(now_s() - t0 < HANG_S, "no grandchild.pid");
        sleep_ms(50);
    }
    sleep_ms(100);
    char *gp = read_text(p);
    long gpid = atol(gp);
    free(gp);
    ck_assert_int_gt(gpid, 0);

    t0 = now_s();
    ck_assert_int_eq(tq_request_cancel(q, id), 0);
    tsup_wake(s);
    struct tq_job j;
    wait_final(id, &j, HANG_S);
    double dt = now_s() - t0;
    ck_assert_str_eq(j.status, TQ_DISMISSED);
    ck_assert_str_eq(j.outcome, "cancelled");
    tq_job_free(&j);
    /* The script ignores SIGTERM and its grandchild sleeps for a day: the run
     * ended only because SIGKILL came, and not before the 1 s grace (a lower
     * bound, which load can only lengthen). */
    ck_assert_msg(dt >= 0.9, "SIGKILL after %g s, before the grace of 1 s", dt);
    ck_assert(group_gone(pid));
    ck_assert_msg(wait_gone(gpid, HANG_S), "grandchild %ld survived", gpid);
    tsup_stop(s);
}
END_TEST

/* The daemon dies (SIGKILL): PR_SET_PDEATHSIG takes the engine along, and the
 * next supervisor recovers the job left "running". */
START_TEST(test_daemon_death)
{
    char id[TQ_ID_LEN + 1];
    /* a run far longer than HANG_S: only its daemon's death can end it in time */
    char *scene = strip_scene(1.0);
    add_job(id, scene, 0, 1);
    pid_t d = fork();
    ck_assert_int_ge(d, 0);
    if (d == 0) {
        struct tsup_config cfg = {.db_path = db_path,
                                  .engine_path = engine,
                                  .jobs_dir = jobs_dir,
                                  .max_jobs = 1,
                                  .threads_per_job = 1,
                                  .wall_limit = 600,
                                  .kill_grace = 5,
                                  .max_attempts = 3};
        struct tsup *s = NULL;
        char err[256];
        if (tsup_start(&cfg, &s, err, sizeof err) < 0)
            _exit(1);
        for (;;)
            pause();
    }
    long pid = wait_running(id, -1.0);
    ck_assert_int_eq(kill(d, SIGKILL), 0);
    ck_assert_int_eq(waitpid(d, NULL, 0), d);
    ck_assert_msg(wait_gone(pid, HANG_S), "engine %ld survived its daemon", pid);
    struct tq_job j;
    memset(&j, 0, sizeof j);
    ck_assert_int_eq(tq_get(q, id, &j), 0);
    ck_assert_str_eq(j.status, TQ_RUNNING); /* nobody finished it */
    tq_job_free(&j);

    struct tsup *s = start_sup(1, 600); /* recovery requeues, then it runs again */
    long pid2 = wait_running(id, -1.0);
    ck_assert_int_ne(pid2, pid);
    ck_assert_int_eq(tq_request_cancel(q, id), 0);
    tsup_wake(s);
    wait_final(id, &j, HANG_S);
    ck_assert_str_eq(j.status, TQ_DISMISSED);
    ck_assert_int_eq(j.attempts, 2);
    tq_job_free(&j);
    tsup_stop(s);
    free(scene);
}
END_TEST

/* RLIMIT_AS is applied: 8 MiB is too little even to load the engine. */
START_TEST(test_memory_limit)
{
    struct tsup_config cfg = {.db_path = db_path,
                              .engine_path = engine,
                              .jobs_dir = jobs_dir,
                              .max_jobs = 1,
                              .threads_per_job = 1,
                              .wall_limit = 60,
                              .kill_grace = 5,
                              .memory_limit_mb = 8,
                              .max_attempts = 3};
    struct tsup *s = NULL;
    char err[256] = "";
    ck_assert_msg(tsup_start(&cfg, &s, err, sizeof err) == 0, "tsup_start: %s", err);
    char id[TQ_ID_LEN + 1];
    char *scene = strip_scene(4e-4);
    add_job(id, scene, 0, 1);
    tsup_wake(s);
    struct tq_job j;
    wait_final(id, &j, HANG_S);
    ck_assert_str_eq(j.status, TQ_FAILED);
    ck_assert_ptr_nonnull(j.message);
    ck_assert_msg(strstr(j.message, "unexpected status") || strstr(j.message, "signal"),
                  "message: %s", j.message);
    tq_job_free(&j);
    tsup_stop(s);
    free(scene);
}
END_TEST

static Suite *supervisor_suite(void)
{
    Suite *s = suite_create("supervisor");
    TCase *tc = tcase_create("jobs");
    tcase_add_checked_fixture(tc, setup, teardown);
    /* Check's timeout is the hang detector of a whole test (several waits) */
    tcase_set_timeout(tc, 4 * HANG_S);
    tcase_add_test(tc, test_job_dirs);
    tcase_add_test(tc, test_start_errors);
    tcase_add_test(tc, test_successful);
    tcase_add_test(tc, test_invalid_scene);
    tcase_add_test(tc, test_unstable);
    tcase_add_test(tc, test_missing_scene);
    tcase_add_test(tc, test_cancel);
    tcase_add_test(tc, test_kill9_then_next);
    tcase_add_test(tc, test_wall_limit);
    tcase_add_test(tc, test_default_wall_limit);
    tcase_add_test(tc, test_stop_requeues);
    tcase_add_test(tc, test_two_at_once);
    tcase_add_test(tc, test_child_setup);
    tcase_add_test(tc, test_term_ignored);
    tcase_add_test(tc, test_daemon_death);
    tcase_add_test(tc, test_memory_limit);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    char engine_path[2048];
    const char *b = getenv("top_builddir");
    snprintf(engine_path, sizeof engine_path, "%s/tlsph-run", b && *b ? b : ".");
    if (access(engine_path, X_OK) < 0) {
        fprintf(stderr, "test_supervisor: %s not built, skipping\n", engine_path);
        return 77;
    }
    return tlsph_check_run(supervisor_suite());
}
