/* tlsphd: the TLSPH job daemon.
 *
 * Start-up: configuration (config.h), data directory (tlsphd.sqlite, jobs/),
 * the checks of startup.h (the database's integrity, interrupted submissions,
 * job directories without rows; --recover), the queue (tq_recover), the
 * reserve file (storage.h), the listening socket, supervisor (tsup_start),
 * HTTP (http_start).
 * Exit status: 0 after a stop by signal, 1 when something needed could not be
 * set up, 2 for a usage error, 3 (TLSPH_EXIT_UNTRUSTED) when the data
 * directory failed the start-up checks.
 * SIGTERM/SIGINT: stop accepting (MHD_quiesce_daemon), answer parked
 * long-polls and finish deferred tasks, stop MHD, stop the supervisor (it
 * requeues running jobs), close the queue, exit 0. */
#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include "config.h"
#include "errmsg.h"
#include "executor.h"
#include "http.h"
#include "queue.h"
#include "routes.h"
#include "startup.h"
#include "storage.h"
#include "strbuf.h"
#include "supervisor.h"

static int mkdir_p(const char *path)
{
    char buf[1200];
    snprintf(buf, sizeof buf, "%s", path);
    for (char *p = buf + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0755) != 0 && errno != EEXIST)
                return -1;
            *p = '/';
        }
    if (mkdir(buf, 0700) != 0 && errno != EEXIST)
        return -1;
    return 0;
}

/* The listening socket, bound here so that a failure names the address and
 * the reason (libmicrohttpd, handed only an address, would report "Failed to
 * bind to port 0").  -1 when it cannot be had (logged). */
static int open_listener(const struct tcfg *cfg)
{
    const struct sockaddr *addr = (const struct sockaddr *)&cfg->addr;
    int fd = socket(addr->sa_family, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    const int on = 1;
    if (fd >= 0 && (setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on) != 0 ||
                    (addr->sa_family == AF_INET6 &&
                     setsockopt(fd, IPPROTO_IPV6, IPV6_V6ONLY, &on, sizeof on) != 0) ||
                    bind(fd, addr, cfg->addrlen) != 0 || listen(fd, SOMAXCONN) != 0)) {
        const int e = errno;
        close(fd);
        fd = -1;
        errno = e;
    }
    if (fd < 0) {
        const int e = errno;
        const char *hint = e == EADDRINUSE ? ": another process listens on it (another tlsphd?); "
                                             "stop it or choose another --listen"
                           : e == EACCES ? ": ports below 1024 need privileges; choose a higher "
                                           "port or run behind a proxy"
                           : e == EADDRNOTAVAIL ? ": that address is not one of this machine's"
                                                : "";
        tlog("cannot listen on %s: %s%s", cfg->listen, strerror(e), hint);
    }
    return fd;
}

int main(int argc, char **argv)
{
    struct tcfg cfg;
    char err[512] = "";
    enum tcfg_rc rc = tcfg_load(&cfg, argc, argv, err, sizeof err);
    if (rc == TCFG_HELP) {
        tcfg_usage(stdout);
        tcfg_free(&cfg);
        return 0;
    }
    if (rc != TCFG_OK) {
        tlog("%s", err);
        tcfg_usage(stderr);
        tcfg_free(&cfg);
        return 2;
    }
    signal(SIGPIPE, SIG_IGN);
    /* block the stop signals in every thread; main waits for them with sigwait */
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGTERM);
    sigaddset(&stop, SIGINT);
    pthread_sigmask(SIG_BLOCK, &stop, NULL);

    umask(077);
    if (mkdir_p(cfg.data_dir) != 0 || mkdir_p(cfg.jobs_dir) != 0) {
        tlog("cannot create data directory %s: %s", cfg.data_dir, strerror(errno));
        tcfg_free(&cfg);
        return 1;
    }
    struct tq *q = NULL;
    struct startup_report rep;
    switch (startup_check(&cfg, &q, &rep, err, sizeof err)) {
    case STARTUP_OK:
        break;
    case STARTUP_FAILED:
        tlog("%s", err);
        tcfg_free(&cfg);
        return 1;
    case STARTUP_REFUSED:
        tlog("%s", err);
        tcfg_free(&cfg);
        return TLSPHD_EXIT_UNTRUSTED;
    }
    if (rep.moved_to[0])
        tlog("--recover: %s failed PRAGMA integrity_check (%s); moved it aside as %s and started "
             "a fresh database",
             cfg.db_path, rep.damage, rep.moved_to);
    if (rep.interrupted > 0)
        tlog("removed %ld job director%s of a submission or removal that a crash interrupted",
             rep.interrupted, rep.interrupted == 1 ? "y" : "ies");
    if (cfg.recover)
        tlog("--recover: rebuilt %ld job row(s) from their directories", rep.recovered);
    if (storage_keep_reserve(&cfg, err, sizeof err) != 0)
        tlog("warning: %s", err);
    const bool slurm = texec_kind_of(cfg.executor) == TEXEC_SLURM;
    /* Slurm jobs outlive the daemon: the Slurm executor adopts them (executor_slurm.h) */
    int recovered = slurm ? 0 : tq_recover(q, cfg.max_attempts);
    if (recovered < 0)
        tlog("recovery failed: %s", tq_last_error(q));
    else if (recovered > 0)
        tlog("recovered %d job(s) left running by a previous daemon", recovered);
    if (access(cfg.engine, X_OK) != 0)
        tlog("warning: engine %s is not executable (%s)", cfg.engine, strerror(errno));

    struct tsup_config sc = {
        .db_path = cfg.db_path,
        .engine_path = cfg.engine,
        .jobs_dir = cfg.jobs_dir,
        .max_jobs = cfg.max_jobs,
        .threads_per_job = cfg.threads_per_job,
        .cores = cfg.cores,
        .wall_limit = cfg.wall_limit,
        .kill_grace = cfg.kill_grace,
        .memory_limit_mb = cfg.memory_limit_mb,
        .max_attempts = cfg.max_attempts,
        .storage = &cfg,
        .slurm = slurm ? &cfg : NULL,
    };
    const int listen_fd = open_listener(&cfg);
    if (listen_fd < 0) {
        tq_close(q);
        tcfg_free(&cfg);
        return 1;
    }
    struct tsup *sup = NULL;
    if (tsup_start(&sc, &sup, err, sizeof err) != 0) {
        tlog("cannot start the supervisor: %s", err);
        close(listen_fd);
        tq_close(q);
        tcfg_free(&cfg);
        return 1;
    }

    struct tapp app = {.cfg = &cfg, .q = q, .sup = sup};
    char oapath[1200];
    snprintf(oapath, sizeof oapath, "%s/openapi.json", cfg.schemas_dir);
    app.openapi = strbuf_read_file(oapath, &app.openapi_len);
    if (!app.openapi)
        tlog("warning: %s not found; /openapi.json will answer 404", oapath);

    struct http_config hc = {
        .addr = (const struct sockaddr *)&cfg.addr,
        .addrlen = cfg.addrlen,
        .listen_fd = listen_fd,
        .connection_limit = cfg.connection_limit,
        .per_ip_limit = cfg.per_ip_limit,
        .connection_timeout = cfg.connection_timeout,
        .header_timeout = cfg.header_timeout,
        .body_timeout = cfg.body_timeout,
        .body_limit = cfg.body_limit,
        .max_waiters = (size_t)(cfg.connection_limit / 2),
        .hold_path = cfg.test_hold_heavy[0] ? cfg.test_hold_heavy : NULL,
        .hold_lane = LANE_HEAVY,
        .admit = troutes_admit,
        .route = troutes_route,
        .nlanes = LANE_COUNT,
        .lane_threads = {[LANE_LIGHT] = 1, [LANE_WRITE] = 1, [LANE_HEAVY] = cfg.heavy_threads},
        .thread_init = troutes_thread_init,
        .thread_fini = troutes_thread_fini,
        .wait_ready = troutes_wait_ready,
        .app = &app,
    };
    struct http *h = http_start(&hc);
    if (!h) {
        close(listen_fd);
        tsup_stop(sup);
        tq_close(q);
        free(app.openapi);
        tcfg_free(&cfg);
        return 1;
    }
    if (cfg.per_ip_limit > 0 && cfg.per_ip_limit * 4 > cfg.connection_limit)
        tlog("warning: per_ip_limit %d x 4 addresses > connection_limit %d: a few clients can "
             "take every connection (docs/deployment.md, \"Hostile clients\")",
             cfg.per_ip_limit, cfg.connection_limit);
    else if (cfg.per_ip_limit == 0 && !cfg.loopback)
        tlog("warning: per_ip_limit 0 (no limit per address) on %s: one client can take every "
             "connection",
             cfg.listen);
    if (cfg.budget_warning[0])
        tlog("warning: %s (docs/deployment.md, \"Threads and cores\")", cfg.budget_warning);
    tlog("listening on %s (data %s, engine %s, executor %s, max-jobs %d, cores %d, "
         "threads-per-job %d, auth %s)",
         cfg.listen, cfg.data_dir, cfg.engine, cfg.executor, cfg.max_jobs, cfg.cores,
         cfg.threads_per_job,
         tauth_enabled(&cfg.auth) ? "bearer" : "off");

    int sig = 0;
    while (sigwait(&stop, &sig) != 0)
        ;
    tlog("signal %d, shutting down", sig);
    http_quiesce(h);
    http_stop(h);
    tsup_stop(sup);
    tq_close(q);
    free(app.openapi);
    tcfg_free(&cfg);
    tlog("stopped");
    return 0;
}
