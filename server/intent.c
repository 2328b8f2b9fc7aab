/* Intent files, see intent.h. */
#include "intent.h"

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "durable.h"
#include "errmsg.h"
#include "jobdir.h"
#include "jobid.h"
#include "strbuf.h"

#define INTENT_PREFIX ".intent-"

int intent_begin(struct intent *in, const char *jobs_dir, const char *const *ids, size_t n,
                 char *err, size_t errsize)
{
    in->path[0] = '\0';
    char name[JOB_ID_LEN + 1], tmp[PATH_MAX];
    if (job_id_new(name) != 0) {
        errmsg_set(err, errsize, "intent file: no random name: %s", strerror(errno));
        return -1;
    }
    int len = snprintf(in->path, sizeof in->path, "%s/" INTENT_PREFIX "%s", jobs_dir, name);
    int tlen = snprintf(tmp, sizeof tmp, "%s/" INTENT_PREFIX "%s.XXXXXX.tmp", jobs_dir, name);
    if (len < 0 || (size_t)len >= sizeof in->path || tlen < 0 || (size_t)tlen >= sizeof tmp) {
        in->path[0] = '\0';
        errmsg_set(err, errsize, "intent file: path too long");
        return -1;
    }
    if (mkdir(jobs_dir, 0750) != 0 && errno != EEXIST) {
        errmsg_set(err, errsize, "cannot create %s: %s", jobs_dir, strerror(errno));
        in->path[0] = '\0';
        return -1;
    }
    struct strbuf b = {0};
    for (size_t i = 0; i < n; i++)
        strbuf_printf(&b, "%s\n", ids[i]);
    int rc = -1;
    if (b.oom)
        errmsg_set(err, errsize, "intent file: out of memory");
    else
        rc = durable_write(jobs_dir, tmp, in->path, b.p ? b.p : "", b.len, err, errsize);
    strbuf_free(&b);
    if (rc < 0)
        in->path[0] = '\0';
    return rc;
}

void intent_end(struct intent *in)
{
    if (in->path[0])
        unlink(in->path);
    in->path[0] = '\0';
}

/* Replays one intent file: 0 (and the file is gone) or -1. */
static int replay_one(const char *jobs_dir, const char *path, intent_has_row_fn *has_row,
                      void *ctx, long *removed, char *err, size_t errsize)
{
    FILE *f = fopen(path, "re");
    if (!f) {
        errmsg_set(err, errsize, "%s: %s", path, strerror(errno));
        return -1;
    }
    char line[128];
    int rc = 0;
    while (rc == 0 && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        if (!job_id_valid(line))
            continue; /* not one of ours: never made into a path */
        int known = has_row(ctx, line);
        if (known < 0) {
            errmsg_set(err, errsize, "%s: the queue did not answer for job %s", path, line);
            rc = -1;
        } else if (known == 0) {
            char dir[PATH_MAX];
            if (jobdir_path(dir, sizeof dir, jobs_dir, line, JOBDIR_FILES) == 0 &&
                access(dir, F_OK) == 0) {
                if (jobdir_remove(jobs_dir, line) != 0) {
                    errmsg_set(err, errsize, "cannot remove %s: %s", dir, strerror(errno));
                    rc = -1;
                } else {
                    (*removed)++;
                }
            }
        }
    }
    fclose(f);
    if (rc == 0 && unlink(path) < 0 && errno != ENOENT) {
        errmsg_set(err, errsize, "cannot remove %s: %s", path, strerror(errno));
        rc = -1;
    }
    return rc;
}

int intent_replay(const char *jobs_dir, intent_has_row_fn *has_row, void *ctx, long *removed,
                  char *err, size_t errsize)
{
    *removed = 0;
    DIR *d = opendir(jobs_dir);
    if (!d) {
        if (errno == ENOENT)
            return 0;
        errmsg_set(err, errsize, "cannot read %s: %s", jobs_dir, strerror(errno));
        return -1;
    }
    int rc = 0;
    const size_t plen = strlen(INTENT_PREFIX);
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strncmp(e->d_name, INTENT_PREFIX, plen) != 0)
            continue;
        char path[PATH_MAX];
        if (snprintf(path, sizeof path, "%s/%s", jobs_dir, e->d_name) >= (int)sizeof path)
            continue;
        const size_t n = strlen(e->d_name);
        if (n > 4 && !strcmp(e->d_name + n - 4, ".tmp")) {
            unlink(path); /* never renamed into place: no directory was made after it */
            continue;
        }
        if (replay_one(jobs_dir, path, has_row, ctx, removed, err, errsize) < 0)
            rc = -1;
    }
    closedir(d);
    return rc;
}
