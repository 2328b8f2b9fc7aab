/* tlsphd: the TLSPH job daemon.
 *
 * Start-up: configuration (config.h), data directory (tlsphd.sqlite, jobs/),
 * queue (tq_open + tq_recover), supervisor (tsup_start), HTTP (http_start).
 * SIGTERM/SIGINT: stop accepting (MHD_quiesce_daemon), answer parked
 * long-polls and finish deferred tasks, stop MHD, stop the supervisor (it
 * requeues running jobs), close the queue, exit 0. */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "config.h"
#include "errmsg.h"
#include "http.h"
#include "queue.h"
#include "routes.h"
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

/* The whole file (malloc'ed, *len bytes), or NULL. */
static char *read_file(const char *path, size_t *len)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return NULL;
    struct strbuf b = {0};
    int rc = strbuf_read_fd(&b, fd);
    close(fd);
    *len = b.len;
    if (rc != 0) {
        strbuf_free(&b);
        return NULL;
    }
    return strbuf_take(&b);
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
    if (tq_open(cfg.db_path, &q, err, sizeof err) != 0) {
        tlog("cannot open %s: %s", cfg.db_path, err);
        tcfg_free(&cfg);
        return 1;
    }
    int recovered = tq_recover(q, cfg.max_attempts);
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
        .wall_limit = cfg.wall_limit,
        .kill_grace = cfg.kill_grace,
        .memory_limit_mb = cfg.memory_limit_mb,
        .max_attempts = cfg.max_attempts,
    };
    struct tsup *sup = NULL;
    if (tsup_start(&sc, &sup, err, sizeof err) != 0) {
        tlog("cannot start the supervisor: %s", err);
        tq_close(q);
        tcfg_free(&cfg);
        return 1;
    }

    struct tapp app = {.cfg = &cfg, .q = q, .sup = sup};
    char oapath[1200];
    snprintf(oapath, sizeof oapath, "%s/openapi.json", cfg.schemas_dir);
    app.openapi = read_file(oapath, &app.openapi_len);
    if (!app.openapi)
        tlog("warning: %s not found; /openapi.json will answer 404", oapath);

    struct http_config hc = {
        .addr = (const struct sockaddr *)&cfg.addr,
        .addrlen = cfg.addrlen,
        .connection_limit = cfg.connection_limit,
        .per_ip_limit = cfg.per_ip_limit,
        .connection_timeout = cfg.connection_timeout,
        .body_limit = cfg.body_limit,
        .max_waiters = (size_t)(cfg.connection_limit / 2),
        .route = troutes_route,
        .thread_init = troutes_thread_init,
        .thread_fini = troutes_thread_fini,
        .wait_ready = troutes_wait_ready,
        .app = &app,
    };
    struct http *h = http_start(&hc);
    if (!h) {
        tsup_stop(sup);
        tq_close(q);
        free(app.openapi);
        tcfg_free(&cfg);
        return 1;
    }
    tlog("listening on %s (data %s, engine %s, max-jobs %d, threads-per-job %d, auth %s)",
         cfg.listen, cfg.data_dir, cfg.engine, cfg.max_jobs, cfg.threads_per_job,
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
