/* What the daemon checks before it serves, see startup.h. */
#include "startup.h"

#include <errno.h>
#include <limits.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "config.h"
#include "errmsg.h"
#include "intent.h"
#include "jobdir.h"
#include "queue.h"
#include "results.h"
#include "strbuf.h"

#define RECOVERED "recovered by tlsphd --recover (its row was lost)"

/* Renames db_path and its -wal and -shm to <db_path>.corrupt-<UTC time>. */
static int move_aside(const char *db_path, char *moved, size_t size, char *err, size_t errsize)
{
    char stamp[32], from[PATH_MAX], to[PATH_MAX];
    const time_t now = time(NULL);
    struct tm tm;
    gmtime_r(&now, &tm);
    strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", &tm);
    if (snprintf(moved, size, "%s.corrupt-%s", db_path, stamp) >= (int)size) {
        errmsg_set(err, errsize, "database path too long");
        return -1;
    }
    static const char *const parts[] = {"", "-wal", "-shm"};
    for (size_t i = 0; i < 3; i++) {
        snprintf(from, sizeof from, "%s%s", db_path, parts[i]);
        snprintf(to, sizeof to, "%s%s", moved, parts[i]);
        if (rename(from, to) != 0 && (i == 0 || errno != ENOENT)) {
            errmsg_set(err, errsize, "cannot move %s aside to %s: %s", from, to, strerror(errno));
            return -1;
        }
    }
    return 0;
}

static double mtime_of(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return 0;
    return (double)st.st_mtim.tv_sec + 1e-9 * (double)st.st_mtim.tv_nsec;
}

/* The row of a job directory that has none, as startup.h describes. */
static int rebuild_row(const struct tcfg *cfg, struct tq *q, const char *id, char *err,
                       size_t errsize)
{
    char dir[PATH_MAX], scene[PATH_MAX], result[PATH_MAX], log[PATH_MAX];
    if (jobdir_path(dir, sizeof dir, cfg->jobs_dir, id, JOBDIR_FILES) < 0 ||
        jobdir_path(scene, sizeof scene, cfg->jobs_dir, id, JOBDIR_SCENE) < 0 ||
        jobdir_path(result, sizeof result, cfg->jobs_dir, id, JOBDIR_RESULT) < 0 ||
        jobdir_path(log, sizeof log, cfg->jobs_dir, id, JOBDIR_LOG) < 0) {
        errmsg_set(err, errsize, "job directory path too long");
        return -1;
    }
    struct tq_job j;
    memset(&j, 0, sizeof j);
    snprintf(j.id, sizeof j.id, "%s", id);
    strcpy(j.process, "run");
    j.seq = -1;
    j.threads = cfg->threads_per_job;
    j.wall_limit = cfg->wall_limit;
    j.created = mtime_of(scene) > 0 ? mtime_of(scene) : mtime_of(dir);
    j.input = strbuf_read_file(scene, NULL);
    const bool has_scene = j.input != NULL;
    char status[64] = "", why[256] = "";
    const bool has_result = access(result, F_OK) == 0;
    if (has_result && tres_run_status(result, status, sizeof status, why, sizeof why) != TRES_OK)
        snprintf(status, sizeof status, "unreadable");
    const char *st = TQ_FAILED, *outcome = "interrupted";
    char *message = NULL;
    if (!has_scene) {
        message = errmsg_format("%s without its scene.json: it cannot run again", RECOVERED);
    } else if (!has_result && access(log, F_OK) != 0) {
        message = errmsg_format("%s before it ran (or it was cancelled first); submit it "
                                "again to run it",
                                RECOVERED);
    } else if (!has_result) {
        message = errmsg_format("%s; the engine left no result (see the log)", RECOVERED);
    } else if (!strcmp(status, "successful")) {
        st = TQ_SUCCESSFUL;
        outcome = "successful";
        j.progress = 100;
    } else if (!strcmp(status, "cancelled")) {
        st = TQ_DISMISSED;
        outcome = "cancelled";
    } else if (!strcmp(status, "unstable") || !strcmp(status, "io_error")) {
        outcome = !strcmp(status, "unstable") ? "unstable" : "io_error";
    } else {
        message = errmsg_format("%s; the run did not finish (its result file says \"%s\")",
                                RECOVERED, status);
    }
    snprintf(j.status, sizeof j.status, "%s", st);
    snprintf(j.outcome, sizeof j.outcome, "%s", outcome);
    j.message = message ? message : strdup(RECOVERED);
    j.attempts = has_result ? 1 : 0;
    j.started = has_result ? j.created : 0;
    j.finished = has_result ? mtime_of(result) : mtime_of(dir);
    if (!j.input)
        j.input = strdup("{}");
    int rc = 0;
    if (!j.input || !j.message) {
        errmsg_set(err, errsize, "out of memory");
        rc = -1;
    } else if (tq_insert_recovered(q, &j) != TQ_OK) {
        errmsg_set(err, errsize, "job %s: %s", id, tq_last_error(q));
        rc = -1;
    }
    free(j.input);
    free(j.message);
    return rc;
}

struct scan {
    const struct tcfg *cfg;
    struct tq *q;
    long orphans;
    char first[JOB_ID_LEN + 1];
    char err[400];
};

static int has_row(void *ctx, const char *id)
{
    const enum tq_rc rc = tq_has_row(ctx, id);
    return rc == TQ_OK ? 1 : rc == TQ_NOT_FOUND ? 0 : -1;
}

static int scan_one(void *ctx, const char *id)
{
    struct scan *s = ctx;
    const int known = has_row(s->q, id);
    if (known < 0) {
        errmsg_set(s->err, sizeof s->err, "job %s: %s", id, tq_last_error(s->q));
        return -1;
    }
    if (known)
        return 0;
    if (!s->orphans++)
        snprintf(s->first, sizeof s->first, "%s", id);
    return s->cfg->recover ? rebuild_row(s->cfg, s->q, id, s->err, sizeof s->err) : 0;
}

enum startup_rc startup_check(const struct tcfg *cfg, struct tq **out, struct startup_report *rep,
                              char *err, size_t errsize)
{
    *out = NULL;
    memset(rep, 0, sizeof *rep);
    switch (tq_check_file(cfg->db_path, rep->damage, sizeof rep->damage)) {
    case TQ_TRUSTED:
        break;
    case TQ_UNREADABLE:
        errmsg_set(err, errsize, "cannot check the database %s: %s", cfg->db_path, rep->damage);
        return STARTUP_FAILED;
    case TQ_CORRUPT:
        if (!cfg->recover) {
            errmsg_set(err, errsize,
                       "the database %s failed PRAGMA integrity_check (%s); refusing to start "
                       "on it.  Restore it from a backup (docs/deployment.md), or start once "
                       "with --recover: the damaged file is kept as %s.corrupt-<time> and the "
                       "jobs get rows again from their directories",
                       cfg->db_path, rep->damage, cfg->db_path);
            return STARTUP_REFUSED;
        }
        if (move_aside(cfg->db_path, rep->moved_to, sizeof rep->moved_to, err, errsize) != 0)
            return STARTUP_FAILED;
        break;
    }
    struct tq *q = NULL;
    char why[512];
    if (tq_open(cfg->db_path, &q, why, sizeof why) != 0) {
        errmsg_set(err, errsize, "cannot open %s: %s", cfg->db_path, why);
        return STARTUP_FAILED;
    }
    if (intent_replay(cfg->jobs_dir, has_row, q, &rep->interrupted, why, sizeof why) != 0) {
        errmsg_set(err, errsize, "cannot finish an interrupted submission or removal: %s", why);
        tq_close(q);
        return STARTUP_FAILED;
    }
    struct scan s = {.cfg = cfg, .q = q};
    if (jobdir_each(cfg->jobs_dir, scan_one, &s) != 0) {
        errmsg_set(err, errsize, "checking the job directories under %s: %s", cfg->jobs_dir,
                   s.err[0] ? s.err : strerror(errno));
        tq_close(q);
        return STARTUP_FAILED;
    }
    if (s.orphans > 0 && !cfg->recover) {
        errmsg_set(err, errsize,
                   "%ld job director%s under %s ha%s no row in the database %s (e.g. %s): the "
                   "database was lost, emptied or replaced by an older copy.  Refusing to "
                   "start, which would orphan %s.  Restore the database from a backup, move "
                   "the directories aside, or start once with --recover to rebuild their rows "
                   "from the directories",
                   s.orphans, s.orphans == 1 ? "y" : "ies", cfg->jobs_dir,
                   s.orphans == 1 ? "s" : "ve", cfg->db_path, s.first,
                   s.orphans == 1 ? "it" : "them");
        tq_close(q);
        return STARTUP_REFUSED;
    }
    rep->recovered = cfg->recover ? s.orphans : 0;
    *out = q;
    return STARTUP_OK;
}
