/* The supervisor: the only file that forks, signals and reaps.  See supervisor.h.
 *
 * Threading: everything in struct tsup except the wake pipe and the stop flag
 * is private to the supervisor thread.  The thread forks the engines itself (the
 * "parent" for PR_SET_PDEATHSIG is the forking *thread*), so it lives as long as
 * any engine does.
 *
 * Process groups: each engine is the leader of its own group (pgid = pid).  The
 * leader is never reaped before the group has been SIGKILLed: waitid(WNOWAIT)
 * detects the exit while the zombie still pins the pid/pgid, so kill(-pgid)
 * can never hit a recycled group.
 *
 * Post-mortem: a result.h5 left open by a dead engine is repaired before the
 * job's final state is recorded, or at start-up after a daemon crash
 * (result_repair.h). */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include "supervisor.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "engine_report.h"
#include "errmsg.h"
#include "executor.h"
#include "executor_slurm.h"
#include "finals.h"
#include "jobdir.h"
#include "queue.h"
#include "result_repair.h"
#include "storage.h"
#include "thread_budget.h"
#include "util/clock.h"

#define TSUP_TICK_MS 200             /* poll timeout: reaping, limits, cancels */
#define TSUP_CLAIM_INTERVAL 1.0      /* s between claim attempts when not woken */
#define TSUP_PROGRESS_INTERVAL 0.25  /* s between queue progress writes per job */
#define TSUP_NOFILE 256              /* RLIMIT_NOFILE of an engine */
#define TSUP_RETRY_INTERVAL 1.0      /* s between writes of final states still waiting */
#define TSUP_STORAGE_INTERVAL 2.0    /* s between looks at the disk (floor, reserve) */

struct child {
    bool used;
    char id[JOB_ID_LEN + 1];
    pid_t pid;
    int threads;             /* the engine's OpenMP threads (booked in the budget) */
    int fd;                  /* progress pipe read end, -1 once closed */
    double t_start;          /* monotonic */
    double wall_limit;       /* s, <= 0 none */
    enum engine_stop reason;
    double t_term;           /* monotonic time SIGTERM was sent, 0 none */
    bool killed;             /* SIGKILL sent */
    struct engine_report report;
    bool pending;            /* progress not yet written to the queue */
    bool progress_failing;   /* the last progress write failed (logged once) */
    double t_update;         /* monotonic time of the last queue write */
};

struct tsup {
    /* configuration (owned copies) */
    char *db_path, *engine_path, *jobs_dir;
    char **engine_env; /* the engine's environment (engine_environment) */
    int max_jobs, threads_per_job, max_attempts;
    double wall_limit, kill_grace;
    long memory_limit_mb;
    long open_max;
    char h5clear[PATH_MAX]; /* result_repair_find_tool's answer, "" none */

    int wake_rd, wake_wr;
    atomic_int stop;
    pthread_t thread;

    /* start-up handshake */
    pthread_mutex_t mu;
    pthread_cond_t cv;
    int init_done, init_rc;
    char init_err[320];

    const struct tcfg *storage; /* NULL: the disk is not watched */
    const struct tcfg *slurm;   /* NULL: the local executor */
    struct finals *finals;      /* final states still to be written */

    /* thread-private */
    struct tq *q;
    double t_retry, t_storage;  /* monotonic times of the last retry and disk look */
    bool below_floor;           /* claims stopped for the free-space floor (logged once) */
    struct child *kids;      /* max_jobs slots */
    int nrunning;
    struct tbudget budget;   /* threads of the running engines against the cores */
    pid_t self;
};

/* ------------------------------------------------------------------ children */

static void child_clear(struct child *c)
{
    engine_report_free(&c->report);
    memset(c, 0, sizeof *c);
    c->fd = -1;
}

static void flush_progress(struct tsup *s, struct child *c, double now)
{
    if (!c->pending)
        return;
    const struct engine_report *r = &c->report;
    double p = r->end_time > 0 ? 100.0 * r->sim_time / r->end_time : 0.0;
    if (p < 0)
        p = 0;
    if (p > 100)
        p = 100;
    const bool failed =
        tq_update_progress(s->q, c->id, p, r->sim_time, r->end_time, r->step, r->eta) == TQ_ERROR;
    if (failed && !c->progress_failing)
        tlog("supervisor: job %s: cannot update progress: %s", c->id, tq_last_error(s->q));
    c->progress_failing = failed;
    c->pending = false;
    c->t_update = now;
}

/* Reads what is available. Closes the fd on EOF/error. */
static void read_progress(struct tsup *s, struct child *c)
{
    char buf[8192];
    while (c->fd >= 0) {
        ssize_t n = read(c->fd, buf, sizeof buf);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            if (errno == EAGAIN || errno == EWOULDBLOCK)
                return;
            tlog("supervisor: job %s: progress pipe: %s", c->id, strerror(errno));
            n = 0;
        }
        if (n == 0) {
            close(c->fd);
            c->fd = -1;
            c->pending |= engine_report_eof(&c->report);
            return;
        }
        if (engine_report_feed(&c->report, buf, (size_t)n)) {
            c->pending = true;
            const double now = tlsph_monotonic_seconds();
            if (now - c->t_update >= TSUP_PROGRESS_INTERVAL)
                flush_progress(s, c, now);
        }
    }
}

/* Repairs job id's result.h5 if its engine left it marked open; when it stays
 * so, says why after *message (malloc'ed or NULL; NULL: no message wanted). */
static void repair_result(struct tsup *s, const char *id, char **message)
{
    char msg[512];
    const enum result_repair_rc rc =
        result_repair_job(s->h5clear, s->jobs_dir, id, msg, sizeof msg);
    if (rc == RESULT_NOTHING_TO_DO)
        return;
    tlog("supervisor: job %s: result.h5 left open by the engine%s: %s", id,
         rc == RESULT_REPAIRED ? "" : ", not repaired", msg);
    if (rc == RESULT_REPAIRED || !message)
        return;
    char *m = errmsg_format("%s%sresult.h5 was left open by the engine and could not be repaired "
                            "(%s): read it with h5py's swmr=True, or run "
                            "'h5clear -s --increment=0' on it",
                            *message ? *message : "", *message ? "; " : "", msg);
    if (m) { /* else out of memory: the engine's message stays */
        free(*message);
        *message = m;
    }
}

/* At start-up, for the results that the engines of an earlier daemon left
 * open: repairs those of final jobs (unfinished ones are cleared when they
 * run again; no engine runs yet). */
static void repair_if_final(const char *id, void *ctx)
{
    struct tsup *s = ctx;
    struct tq_job j;
    memset(&j, 0, sizeof j);
    if (tq_get(s->q, id, &j) == TQ_OK && tq_status_final(j.status))
        repair_result(s, id, NULL); /* logged; the job's message was recorded before */
    tq_job_free(&j);
}

/* The leader has exited (zombie, not yet reaped): finish the job. */
static void finish_child(struct tsup *s, struct child *c, int wstatus)
{
    /* Drain the pipe.  The group has just been SIGKILLed, so any member still
     * holding the write end goes away within moments: wait briefly for EOF. */
    double t_end = tlsph_monotonic_seconds() + 0.2;
    read_progress(s, c);
    while (c->fd >= 0) {
        double left = t_end - tlsph_monotonic_seconds();
        if (left <= 0)
            break;
        struct pollfd pfd = {.fd = c->fd, .events = POLLIN};
        int pr = poll(&pfd, 1, (int)(left * 1000) + 1);
        if (pr < 0 && errno != EINTR)
            break;
        if (pr > 0)
            read_progress(s, c);
    }
    if (c->fd >= 0) {
        close(c->fd);
        c->fd = -1;
        c->pending |= engine_report_eof(&c->report); /* the leader is dead: its last words count */
    }

    struct engine_outcome out;
    engine_outcome(&c->report, wstatus, c->reason, c->wall_limit, &out);
    if (out.requeue) {
        if (tq_requeue(s->q, c->id, "interrupted by daemon shutdown") == TQ_ERROR)
            tlog("supervisor: job %s: cannot requeue", c->id);
    } else {
        struct engine_report *r = &c->report;
        if (!strcmp(out.status, TQ_SUCCESSFUL)) {
            r->sim_time = r->end_time > 0 ? r->end_time : r->sim_time;
            r->eta = 0;
            c->pending = true;
            if (r->end_time > 0) {
                flush_progress(s, c, tlsph_monotonic_seconds());
            } else if (tq_update_progress(s->q, c->id, 100.0, r->sim_time, r->end_time, r->step,
                                          0.0) == TQ_ERROR) {
                tlog("supervisor: job %s: cannot update progress", c->id);
            }
        } else {
            flush_progress(s, c, tlsph_monotonic_seconds());
        }
        repair_result(s, c->id, &out.message); /* before the job is seen final */
        finals_record(s->finals, s->q, c->id, out.status, out.outcome, out.message, r->cost);
    }
    free(out.message);
    tbudget_give(&s->budget, c->threads);
    child_clear(c);
    s->nrunning--;
}

/* Checks one child for exit; kills the rest of its group and reaps it.
 * True when the slot became free. */
static bool check_child(struct tsup *s, struct child *c)
{
    siginfo_t si;
    memset(&si, 0, sizeof si);
    if (waitid(P_PID, (id_t)c->pid, &si, WEXITED | WNOHANG | WNOWAIT) < 0) {
        if (errno == EINTR)
            return false;
        tlog("supervisor: job %s: waitid(%ld): %s", c->id, (long)c->pid, strerror(errno));
        /* ECHILD: reaped elsewhere (waitpid(-1) or SIGCHLD ignored) */
        if (errno == ECHILD) {
            finish_child(s, c, -1);
            return true;
        }
        return false;
    }
    if (si.si_pid == 0)
        return false; /* still running */
    /* the leader is a zombie: the pgid cannot be reused yet, so take the group down */
    if (kill(-c->pid, SIGKILL) < 0 && errno != ESRCH)
        tlog("supervisor: job %s: kill(-%ld): %s", c->id, (long)c->pid, strerror(errno));
    int st = 0;
    pid_t r;
    do {
        r = waitpid(c->pid, &st, 0);
    } while (r < 0 && errno == EINTR);
    if (r < 0) {
        tlog("supervisor: job %s: waitpid: %s", c->id, strerror(errno));
        st = -1; /* status unknown */
    }
    finish_child(s, c, st);
    return true;
}

static void signal_group(struct child *c, int sig)
{
    if (kill(-c->pid, sig) < 0 && errno != ESRCH)
        tlog("supervisor: job %s: kill(-%ld, %d): %s", c->id, (long)c->pid, sig, strerror(errno));
}

static void request_stop(struct child *c, enum engine_stop why, double now)
{
    if (c->reason == ENGINE_NOT_STOPPED || (why == ENGINE_STOP_CANCEL && c->reason != ENGINE_STOP_CANCEL))
        c->reason = why;
    if (c->t_term == 0) {
        c->t_term = now;
        signal_group(c, SIGTERM);
    }
}

/* The daemon's environment for its engines, built before any fork (the child
 * may not allocate), with OMP_WAIT_POLICY=passive unless the daemon's own
 * environment chooses.  Engines share the cores with each other and with other
 * work; a waiting OpenMP thread that spins takes the core its partner needs:
 * measured on 2 cores with one competing CPU-bound process, 2 threads took
 * 30.9-32.5 s by default and 14.8-15.0 s passive, against 14.7 s for 1 thread;
 * idle, passive costs 2-3 % (7.9 vs 7.7 s).  A NULL-terminated array of owned
 * strings, or NULL when out of memory. */
static char **engine_environment(void)
{
    size_t n = 0;
    int has_policy = 0;
    for (char **e = environ; *e; e++, n++)
        has_policy |= !strncmp(*e, "OMP_WAIT_POLICY=", 16);
    char **env = calloc(n + 2, sizeof *env);
    if (!env)
        return NULL;
    size_t k = 0;
    for (char **e = environ; *e; e++)
        if (!(env[k++] = strdup(*e)))
            goto oom;
    if (!has_policy && !(env[k++] = strdup("OMP_WAIT_POLICY=passive")))
        goto oom;
    return env;
oom:
    for (size_t i = 0; i < k; i++)
        free(env[i]);
    free(env);
    return NULL;
}

/* In the child after fork: only async-signal-safe calls. */
struct spawn_args {
    pid_t parent;
    int pipe_wr;
    const char *dir, *log_path;
    char *const *argv;
    char *const *envp;
    const char *engine;
    long memory_limit_mb;
    long open_max;
};

static void child_warn(int fd, const char *what)
{
    static const char pre[] = "tlsphd: warning: ";
    ssize_t r = write(fd, pre, sizeof pre - 1);
    r = write(fd, what, strlen(what));
    r = write(fd, "\n", 1);
    (void)r;
}

static void child_fail(int fd, const char *what) __attribute__((noreturn));
static void child_fail(int fd, const char *what)
{
    if (fd >= 0) {
        static const char pre[] = "tlsphd: cannot start the engine: ";
        ssize_t r = write(fd, pre, sizeof pre - 1);
        r = write(fd, what, strlen(what));
        r = write(fd, "\n", 1);
        (void)r;
    }
    _exit(127);
}

static void run_child(const struct spawn_args *a) __attribute__((noreturn));
static void run_child(const struct spawn_args *a)
{
    if (setpgid(0, 0) < 0)
        _exit(127);
    if (prctl(PR_SET_PDEATHSIG, SIGKILL, 0, 0, 0) < 0)
        _exit(127);
    if (getppid() != a->parent)
        _exit(127); /* the daemon died before prctl */

    /* signals: default dispositions, empty mask */
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = SIG_DFL;
    sigemptyset(&sa.sa_mask);
    for (int sig = 1; sig < NSIG; sig++)
        if (sig != SIGKILL && sig != SIGSTOP)
            (void)sigaction(sig, &sa, NULL);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, NULL);

    int logfd = open(a->log_path, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW, 0640);
    if (logfd < 0)
        _exit(127);
    int nullfd = open("/dev/null", O_RDONLY | O_CLOEXEC);
    if (nullfd < 0)
        child_fail(logfd, "cannot open /dev/null");
    /* move everything above the standard fds first so the dup2s cannot clobber */
    int log_hi = fcntl(logfd, F_DUPFD_CLOEXEC, 10);
    int null_hi = fcntl(nullfd, F_DUPFD_CLOEXEC, 10);
    int pipe_hi = fcntl(a->pipe_wr, F_DUPFD_CLOEXEC, 10);
    if (log_hi < 0 || null_hi < 0 || pipe_hi < 0)
        child_fail(logfd, "fcntl failed");
    if (dup2(null_hi, 0) < 0 || dup2(log_hi, 1) < 0 || dup2(log_hi, 2) < 0 ||
        dup2(pipe_hi, 3) < 0)
        child_fail(log_hi, "dup2 failed");
    if (close_range(4, ~0U, 0) < 0) {
        for (long fd = 4; fd < a->open_max; fd++)
            close((int)fd);
    }

    struct rlimit rl;
    rl.rlim_cur = rl.rlim_max = 0;
    if (setrlimit(RLIMIT_CORE, &rl) < 0)
        child_fail(2, "setrlimit(RLIMIT_CORE) failed");
    if (a->memory_limit_mb > 0) {
        rlim_t want = (rlim_t)a->memory_limit_mb * 1024 * 1024;
        if (getrlimit(RLIMIT_AS, &rl) < 0)
            child_fail(2, "getrlimit(RLIMIT_AS) failed");
        if (rl.rlim_max == RLIM_INFINITY || rl.rlim_max > want)
            rl.rlim_max = want;
        rl.rlim_cur = rl.rlim_max;
        if (setrlimit(RLIMIT_AS, &rl) < 0)
            child_fail(2, "setrlimit(RLIMIT_AS) failed");
    }
    /* open files: defence in depth only, so a refusal (e.g. under valgrind,
     * which guards its own descriptors) is logged, not fatal */
    if (getrlimit(RLIMIT_NOFILE, &rl) == 0) {
        if (rl.rlim_max == RLIM_INFINITY || rl.rlim_max > TSUP_NOFILE)
            rl.rlim_max = TSUP_NOFILE;
        rl.rlim_cur = rl.rlim_max;
        if (setrlimit(RLIMIT_NOFILE, &rl) < 0)
            child_warn(2, "setrlimit(RLIMIT_NOFILE) refused, continuing");
    }
    umask(027);
    if (chdir(a->dir) < 0)
        child_fail(2, "cannot enter the job directory");
    execve(a->engine, a->argv, a->envp);
    child_fail(2, "execv failed");
}

/* A claimed job that could not be started ends as failed with outcome and a
 * message for its user. */
static void fail_start(struct tsup *s, const char *id, const char *outcome, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void fail_start(struct tsup *s, const char *id, const char *outcome, const char *fmt, ...)
{
    char message[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof message, fmt, ap);
    va_end(ap);
    finals_record(s->finals, s->q, id, TQ_FAILED, outcome, message, NULL);
}

/* Starts a claimed job in slot c with threads OpenMP threads (>= 1, booked
 * in the budget once it runs).  On failure the job is finished as failed. */
static void start_job(struct tsup *s, struct child *c, const struct tq_job *j, int threads)
{
    char dir[PATH_MAX], scene[PATH_MAX], logp[PATH_MAX];
    const char *id = j->id;
    if (!job_id_valid(id)) {
        tlog("supervisor: refusing job with invalid id");
        fail_start(s, id, "crashed", "invalid job id");
        return;
    }
    if (jobdir_path(dir, sizeof dir, s->jobs_dir, id, JOBDIR_FILES) < 0 ||
        jobdir_path(scene, sizeof scene, s->jobs_dir, id, JOBDIR_SCENE) < 0 ||
        jobdir_path(logp, sizeof logp, s->jobs_dir, id, JOBDIR_LOG) < 0) {
        fail_start(s, id, "crashed", "job directory path too long");
        return;
    }
    struct stat st;
    int serr = stat(scene, &st) < 0 ? errno : (!S_ISREG(st.st_mode) ? EINVAL : 0);
    if (serr) {
        fail_start(s, id, "crashed", "job directory or scene.json missing (%s)", strerror(serr));
        return;
    }
    if (jobdir_clear_outputs(s->jobs_dir, id) < 0) {
        fail_start(s, id, "io_error", "cannot remove stale results: %s", strerror(errno));
        return;
    }

    char tbuf[32];
    snprintf(tbuf, sizeof tbuf, "%d", threads);
    char *argv[] = {s->engine_path, scene, (char *)"-o", dir, (char *)"--progress-fd",
                    (char *)"3", (char *)"--threads", tbuf, NULL};

    int pfd[2];
    if (pipe2(pfd, O_CLOEXEC) < 0) {
        fail_start(s, id, "crashed", "cannot create the progress pipe: %s", strerror(errno));
        return;
    }
    struct spawn_args a = {.parent = s->self,
                           .pipe_wr = pfd[1],
                           .dir = dir,
                           .log_path = logp,
                           .argv = argv,
                           .envp = s->engine_env,
                           .engine = s->engine_path,
                           .memory_limit_mb = s->memory_limit_mb,
                           .open_max = s->open_max};
    pid_t pid = fork();
    if (pid < 0) {
        int e = errno;
        close(pfd[0]);
        close(pfd[1]);
        fail_start(s, id, "crashed", "cannot fork the engine: %s", strerror(e));
        return;
    }
    if (pid == 0)
        run_child(&a);

    /* parent */
    close(pfd[1]);
    if (setpgid(pid, pid) < 0 && errno != EACCES && errno != ESRCH)
        tlog("supervisor: job %s: setpgid: %s", id, strerror(errno));
    int fl = fcntl(pfd[0], F_GETFL);
    if (fl < 0 || fcntl(pfd[0], F_SETFL, fl | O_NONBLOCK) < 0)
        tlog("supervisor: job %s: cannot make the pipe non-blocking: %s", id, strerror(errno));

    child_clear(c);
    c->used = true;
    memcpy(c->id, id, JOB_ID_LEN + 1);
    c->pid = pid;
    c->threads = threads;
    tbudget_take(&s->budget, threads);
    c->fd = pfd[0];
    c->t_start = tlsph_monotonic_seconds();
    c->wall_limit = j->wall_limit > 0 ? j->wall_limit : s->wall_limit;
    engine_report_init(&c->report, j->end_time);
    s->nrunning++;
    if (tq_set_pid(s->q, id, (long)pid) == TQ_ERROR)
        tlog("supervisor: job %s: cannot record pid", id);
}

/* Below the free-space floor no engine starts: it would only fill the disk
 * further or fail at its first write.  Queued jobs wait for the space. */
static bool room_to_start(struct tsup *s)
{
    const bool below = s->storage && storage_below_floor(s->storage);
    if (below != s->below_floor)
        tlog(below ? "supervisor: free space below the floor (min_free_mb): no job starts until "
                     "space is freed"
                   : "supervisor: free space above the floor again: jobs start");
    s->below_floor = below;
    return !below;
}

/* Every TSUP_RETRY_INTERVAL: the final states still waiting; every
 * TSUP_STORAGE_INTERVAL: the reserve file. */
static void keep_records(struct tsup *s, double now)
{
    char err[300];
    if (now - s->t_retry >= TSUP_RETRY_INTERVAL) {
        s->t_retry = now;
        if (finals_pending(s->finals, NULL, 0) > 0)
            finals_retry(s->finals, s->q);
    }
    if (s->storage && now - s->t_storage >= TSUP_STORAGE_INTERVAL) {
        s->t_storage = now;
        if (storage_keep_reserve(s->storage, err, sizeof err) != 0)
            tlog("supervisor: %s", err);
    }
}

static void claim_jobs(struct tsup *s)
{
    if (s->nrunning < s->max_jobs && !room_to_start(s))
        return;
    while (s->nrunning < s->max_jobs && !atomic_load(&s->stop)) {
        struct child *slot = NULL;
        for (int i = 0; i < s->max_jobs; i++)
            if (!s->kids[i].used) {
                slot = &s->kids[i];
                break;
            }
        if (!slot || tbudget_grant(&s->budget, 1) == 0)
            return; /* no free slot, or no free core: claimed when an engine ends */
        struct tq_job j;
        memset(&j, 0, sizeof j);
        enum tq_rc rc = tq_claim_next(s->q, &j);
        if (rc != TQ_OK) {
            if (rc == TQ_ERROR)
                tlog("supervisor: cannot claim a job");
            return;
        }
        /* a job keeps the threads it was granted at start: OpenMP cannot
         * change a running engine's count, and a job granted fewer than it
         * asked for still beats one that waits for a core */
        const long want = j.threads > 0 ? j.threads : s->threads_per_job;
        start_job(s, slot, &j, tbudget_grant(&s->budget, want > INT_MAX ? INT_MAX : (int)want));
        tq_job_free(&j);
    }
}

static void check_cancels(struct tsup *s, double now)
{
    if (s->nrunning == 0)
        return;
    char (*ids)[TQ_ID_LEN + 1] = NULL;
    size_t n = 0;
    if (tq_cancel_requests(s->q, &ids, &n) == TQ_ERROR) {
        tlog("supervisor: cannot read cancel requests");
        return;
    }
    for (size_t k = 0; k < n; k++)
        for (int i = 0; i < s->max_jobs; i++) {
            struct child *c = &s->kids[i];
            if (c->used && strcmp(c->id, ids[k]) == 0 && c->reason != ENGINE_STOP_CANCEL) {
                c->reason = ENGINE_NOT_STOPPED;
                request_stop(c, ENGINE_STOP_CANCEL, now);
            }
        }
    free(ids);
}

static void drain_wake(struct tsup *s)
{
    char buf[64];
    while (read(s->wake_rd, buf, sizeof buf) > 0)
        ;
}

/* ------------------------------------------------------------------ thread */

static void host_keep_records(void *sup, double now)
{
    keep_records(sup, now);
}

static bool host_room(void *sup)
{
    return room_to_start(sup);
}

/* The Slurm executor's loop on this thread, then the same end as the local one. */
static void run_slurm(struct tsup *s)
{
    const struct texec_host h = {.q = s->q,
                                 .finals = s->finals,
                                 .jobs_dir = s->jobs_dir,
                                 .engine_path = s->engine_path,
                                 .threads_per_job = s->threads_per_job,
                                 .max_attempts = s->max_attempts,
                                 .wall_limit = s->wall_limit,
                                 .wake_rd = s->wake_rd,
                                 .stop = &s->stop,
                                 .keep_records = host_keep_records,
                                 .room = host_room,
                                 .sup = s};
    texec_slurm_run(&h, s->slurm);
    const size_t lost = finals_retry(s->finals, s->q);
    if (lost > 0)
        tlog("supervisor: %zu final state(s) could not be recorded before the stop", lost);
    tq_close(s->q);
    s->q = NULL;
}

static void *sup_main(void *arg)
{
    struct tsup *s = arg;
    char err[256] = "";
    sigset_t all;
    sigfillset(&all);
    pthread_sigmask(SIG_BLOCK, &all, NULL); /* signals belong to the main thread */

    int rc = tq_open(s->db_path, &s->q, err, sizeof err);
    /* Slurm jobs outlive the daemon: the Slurm executor adopts them instead */
    if (rc == 0 && !s->slurm && tq_recover(s->q, s->max_attempts) < 0)
        tlog("supervisor: start-up recovery failed");
    if (rc == 0)
        result_repair_each_left_open(s->jobs_dir, repair_if_final, s);
    pthread_mutex_lock(&s->mu);
    s->init_done = 1;
    s->init_rc = rc;
    if (rc < 0)
        snprintf(s->init_err, sizeof s->init_err, "cannot open the queue: %s", err);
    pthread_cond_signal(&s->cv);
    pthread_mutex_unlock(&s->mu);
    if (rc < 0)
        return NULL;
    if (s->slurm) {
        run_slurm(s);
        return NULL;
    }

    struct pollfd *pfds = calloc((size_t)s->max_jobs + 1, sizeof *pfds);
    int *idx = calloc((size_t)s->max_jobs + 1, sizeof *idx);
    if (!pfds || !idx) {
        tlog("supervisor: out of memory");
        free(pfds);
        free(idx);
        tq_close(s->q);
        s->q = NULL;
        return NULL;
    }

    int want_claim = 1, stopping = 0;
    double last_claim = 0;
    for (;;) {
        double now = tlsph_monotonic_seconds();
        if (!stopping && atomic_load(&s->stop)) {
            stopping = 1;
            for (int i = 0; i < s->max_jobs; i++)
                if (s->kids[i].used)
                    request_stop(&s->kids[i], ENGINE_STOP_SHUTDOWN, now);
        }
        if (stopping && s->nrunning == 0)
            break;
        if (!stopping && (want_claim || now - last_claim >= TSUP_CLAIM_INTERVAL)) {
            claim_jobs(s);
            want_claim = 0;
            last_claim = now;
        }

        nfds_t n = 0;
        pfds[n].fd = s->wake_rd;
        pfds[n].events = POLLIN;
        idx[n++] = -1;
        for (int i = 0; i < s->max_jobs; i++)
            if (s->kids[i].used && s->kids[i].fd >= 0) {
                pfds[n].fd = s->kids[i].fd;
                pfds[n].events = POLLIN;
                idx[n++] = i;
            }
        int pr = poll(pfds, n, TSUP_TICK_MS);
        if (pr < 0 && errno != EINTR)
            tlog("supervisor: poll: %s", strerror(errno));
        if (pr > 0) {
            for (nfds_t k = 0; k < n; k++) {
                if (!pfds[k].revents)
                    continue;
                if (idx[k] < 0) {
                    drain_wake(s);
                    want_claim = 1;
                } else {
                    struct child *c = &s->kids[idx[k]];
                    read_progress(s, c);
                }
            }
        }

        /* the tick: cancels, limits, escalation, progress, reaping */
        now = tlsph_monotonic_seconds();
        if (!stopping)
            check_cancels(s, now);
        keep_records(s, now);
        for (int i = 0; i < s->max_jobs; i++) {
            struct child *c = &s->kids[i];
            if (!c->used)
                continue;
            if (c->wall_limit > 0 && c->reason == ENGINE_NOT_STOPPED && now - c->t_start > c->wall_limit)
                request_stop(c, ENGINE_STOP_TIMEOUT, now);
            if (c->t_term > 0 && !c->killed && now - c->t_term >= s->kill_grace) {
                signal_group(c, SIGKILL);
                c->killed = true;
            }
            if (c->pending && now - c->t_update >= TSUP_PROGRESS_INTERVAL)
                flush_progress(s, c, now);
            if (check_child(s, c))
                want_claim = 1;
        }
    }

    const size_t lost = finals_retry(s->finals, s->q);
    if (lost > 0)
        tlog("supervisor: %zu final state(s) could not be recorded before the stop; the next "
             "start requeues those jobs",
             lost);
    free(pfds);
    free(idx);
    tq_close(s->q);
    s->q = NULL;
    return NULL;
}

/* ------------------------------------------------------------------ API */

static void tsup_free(struct tsup *s)
{
    if (!s)
        return;
    if (s->wake_rd >= 0)
        close(s->wake_rd);
    if (s->wake_wr >= 0)
        close(s->wake_wr);
    if (s->kids) {
        for (int i = 0; i < s->max_jobs; i++)
            child_clear(&s->kids[i]);
        free(s->kids);
    }
    finals_free(s->finals);
    free(s->db_path);
    free(s->engine_path);
    free(s->jobs_dir);
    if (s->engine_env) {
        for (char **e = s->engine_env; *e; e++)
            free(*e);
        free(s->engine_env);
    }
    pthread_mutex_destroy(&s->mu);
    pthread_cond_destroy(&s->cv);
    free(s);
}

static char *absolute_path(const char *p)
{
    if (p[0] == '/')
        return strdup(p);
    char *cwd = getcwd(NULL, 0);
    if (!cwd)
        return NULL;
    char *out = errmsg_format("%s/%s", cwd, p);
    free(cwd);
    return out;
}

int tsup_start(const struct tsup_config *cfg, struct tsup **out, char *err, size_t errsize)
{
    if (!cfg || !out || !cfg->db_path || !cfg->engine_path || !cfg->jobs_dir ||
        !*cfg->jobs_dir || !*cfg->engine_path) {
        errmsg_set(err, errsize, "incomplete supervisor configuration");
        return -1;
    }
    if (cfg->max_jobs < 1 || cfg->threads_per_job < 1) {
        errmsg_set(err, errsize, "max_jobs and threads_per_job must be >= 1");
        return -1;
    }
    *out = NULL;
    struct tsup *s = calloc(1, sizeof *s);
    if (!s) {
        errmsg_set(err, errsize, "out of memory");
        return -1;
    }
    s->wake_rd = s->wake_wr = -1;
    pthread_mutex_init(&s->mu, NULL);
    pthread_cond_init(&s->cv, NULL);
    s->max_jobs = cfg->max_jobs;
    s->threads_per_job = cfg->threads_per_job;
    s->budget.cores = cfg->cores > 0 ? cfg->cores : cfg->max_jobs * cfg->threads_per_job;
    s->max_attempts = cfg->max_attempts;
    s->wall_limit = cfg->wall_limit;
    s->kill_grace = cfg->kill_grace >= 0 ? cfg->kill_grace : 0;
    s->memory_limit_mb = cfg->memory_limit_mb;
    long om = sysconf(_SC_OPEN_MAX);
    s->open_max = om > 0 ? om : 1024;
    s->self = getpid();
    atomic_init(&s->stop, 0);
    s->db_path = strdup(cfg->db_path);
    s->engine_path = absolute_path(cfg->engine_path);
    s->jobs_dir = absolute_path(cfg->jobs_dir);
    s->engine_env = engine_environment();
    s->kids = calloc((size_t)cfg->max_jobs, sizeof *s->kids);
    s->storage = cfg->storage;
    s->slurm = cfg->slurm;
    s->finals = finals_new(cfg->storage);
    if (!s->db_path || !s->engine_path || !s->jobs_dir || !s->engine_env || !s->kids ||
        !s->finals) {
        errmsg_set(err, errsize, "out of memory");
        tsup_free(s);
        return -1;
    }
    for (int i = 0; i < s->max_jobs; i++)
        s->kids[i].fd = -1;
    if (result_repair_find_tool(s->h5clear, sizeof s->h5clear) < 0)
        tlog("supervisor: h5clear (Debian: hdf5-tools) not found: results left open by killed "
             "engines stay so (h5py opens them with swmr=True)");
    if (access(s->engine_path, X_OK) < 0) {
        errmsg_set(err, errsize, "engine %s is not executable: %s", s->engine_path, strerror(errno));
        tsup_free(s);
        return -1;
    }
    if (mkdir(s->jobs_dir, 0750) < 0 && errno != EEXIST) {
        errmsg_set(err, errsize, "cannot create %s: %s", s->jobs_dir, strerror(errno));
        tsup_free(s);
        return -1;
    }
    /* With SIGCHLD ignored the kernel reaps children itself and their exit
     * status is lost: the supervisor owns the children, so restore the default. */
    struct sigaction oldsa;
    if (sigaction(SIGCHLD, NULL, &oldsa) == 0 && !(oldsa.sa_flags & SA_SIGINFO) &&
        oldsa.sa_handler == SIG_IGN) {
        struct sigaction dfl;
        memset(&dfl, 0, sizeof dfl);
        dfl.sa_handler = SIG_DFL;
        sigemptyset(&dfl.sa_mask);
        if (sigaction(SIGCHLD, &dfl, NULL) == 0)
            tlog("supervisor: SIGCHLD was ignored; restored the default so engines can be reaped");
    }
    int wp[2];
    if (pipe2(wp, O_CLOEXEC | O_NONBLOCK) < 0) {
        errmsg_set(err, errsize, "pipe: %s", strerror(errno));
        tsup_free(s);
        return -1;
    }
    s->wake_rd = wp[0];
    s->wake_wr = wp[1];
    int e = pthread_create(&s->thread, NULL, sup_main, s);
    if (e != 0) {
        errmsg_set(err, errsize, "pthread_create: %s", strerror(e));
        tsup_free(s);
        return -1;
    }
    pthread_mutex_lock(&s->mu);
    while (!s->init_done)
        pthread_cond_wait(&s->cv, &s->mu);
    int rc = s->init_rc;
    pthread_mutex_unlock(&s->mu);
    if (rc < 0) {
        errmsg_set(err, errsize, "%s", s->init_err);
        pthread_join(s->thread, NULL);
        tsup_free(s);
        return -1;
    }
    *out = s;
    return 0;
}

void tsup_wake(struct tsup *s)
{
    if (!s)
        return;
    char b = 1;
    ssize_t r;
    do {
        r = write(s->wake_wr, &b, 1);
    } while (r < 0 && errno == EINTR);
    /* EAGAIN: the pipe is full, so the thread is going to wake anyway */
}

size_t tsup_unrecorded(struct tsup *s, char *why, size_t size)
{
    return s ? finals_pending(s->finals, why, size) : (errmsg_set(why, size, "%s", ""), 0);
}

void tsup_stop(struct tsup *s)
{
    if (!s)
        return;
    atomic_store(&s->stop, 1);
    tsup_wake(s);
    pthread_join(s->thread, NULL);
    tsup_free(s);
}
