/* A job's directory, see jobdir.h. */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE /* dirfd, fstatat */
#endif
#include "jobdir.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "durable.h"
#include "errmsg.h"
#include "jobid.h"

static const struct {
    const char *name;
    bool output; /* written by the engine: cleared before a (re)run */
} files[JOBDIR_FILES] = {
    [JOBDIR_SCENE] = {"scene.json", false},
    [JOBDIR_RESULT] = {"result.h5", true},
    [JOBDIR_SIDECAR] = {"result.xmf", true},
    [JOBDIR_LOG] = {"log.txt", true},
    [JOBDIR_PROGRESS] = {"progress.jsonl", true},
    [JOBDIR_EXIT] = {"exit_status", true},
    [JOBDIR_SLURM] = {"slurm_job", false},
};

/* The engine writes the sidecar here and renames it (core/io/output/xdmf.c). */
#define SIDECAR_TMP "result.xmf.tmp"
/* scene.json is written here first (mkostemps fills in the X). */
#define SCENE_TMP "scene.json.XXXXXX.tmp"

static int path_of(char *buf, size_t size, const char *jobs_dir, const char *id, const char *name)
{
    if (!jobs_dir || !*jobs_dir || !job_id_valid(id))
        return -1;
    int n = name ? snprintf(buf, size, "%s/%s/%s", jobs_dir, id, name)
                 : snprintf(buf, size, "%s/%s", jobs_dir, id);
    return (n < 0 || (size_t)n >= size) ? -1 : 0;
}

int jobdir_path(char *buf, size_t size, const char *jobs_dir, const char *id,
                enum jobdir_file file)
{
    return path_of(buf, size, jobs_dir, id, file < JOBDIR_FILES ? files[file].name : NULL);
}

int jobdir_create(const char *jobs_dir, const char *id, const char *scene_json, char *err,
                  size_t errsize)
{
    char dir[PATH_MAX], tmp[PATH_MAX], dst[PATH_MAX];
    if (!jobs_dir || !*jobs_dir || !scene_json) {
        errmsg_set(err, errsize, "missing jobs directory or scene");
        return -1;
    }
    if (!job_id_valid(id)) {
        errmsg_set(err, errsize, "invalid job id");
        return -1;
    }
    if (jobdir_path(dir, sizeof dir, jobs_dir, id, JOBDIR_FILES) < 0 ||
        path_of(tmp, sizeof tmp, jobs_dir, id, SCENE_TMP) < 0 ||
        jobdir_path(dst, sizeof dst, jobs_dir, id, JOBDIR_SCENE) < 0) {
        errmsg_set(err, errsize, "job directory path too long");
        return -1;
    }
    if (mkdir(jobs_dir, 0750) < 0 && errno != EEXIST) {
        errmsg_set(err, errsize, "cannot create %s: %s", jobs_dir, strerror(errno));
        return -1;
    }
    if (mkdir(dir, 0750) < 0 && errno != EEXIST) {
        errmsg_set(err, errsize, "cannot create %s: %s", dir, strerror(errno));
        return -1;
    }
    struct stat st;
    if (lstat(dir, &st) < 0 || !S_ISDIR(st.st_mode)) {
        errmsg_set(err, errsize, "%s is not a directory", dir);
        return -1;
    }
    return durable_write(dir, tmp, dst, scene_json, strlen(scene_json), err, errsize);
}

static int unlink_quietly(int dfd, const char *name)
{
    return unlinkat(dfd, name, 0) < 0 && errno != ENOENT ? -1 : 0;
}

static bool is_tmp(const char *name)
{
    size_t n = strlen(name);
    return n >= 4 && strcmp(name + n - 4, ".tmp") == 0;
}

/* Opens the job's directory without following a symlink; -1 with errno. */
static int open_dir(const char *jobs_dir, const char *id, char *dir, size_t size)
{
    if (jobdir_path(dir, size, jobs_dir, id, JOBDIR_FILES) < 0) {
        errno = EINVAL;
        return -1;
    }
    return open(dir, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
}

int jobdir_clear_outputs(const char *jobs_dir, const char *id)
{
    char dir[PATH_MAX];
    int dfd = open_dir(jobs_dir, id, dir, sizeof dir);
    if (dfd < 0)
        return -1;
    int rc = 0;
    for (int f = 0; f < JOBDIR_FILES; f++)
        if (files[f].output && unlink_quietly(dfd, files[f].name) < 0)
            rc = -1;
    if (unlink_quietly(dfd, SIDECAR_TMP) < 0)
        rc = -1;
    close(dfd);
    return rc;
}

/* Every known file and every *.tmp in an open job directory. */
static int remove_files(int dfd)
{
    int rc = 0;
    for (int f = 0; f < JOBDIR_FILES; f++)
        if (unlink_quietly(dfd, files[f].name) < 0)
            rc = -1;
    int d2 = dup(dfd);
    if (d2 < 0)
        return -1;
    DIR *d = fdopendir(d2);
    if (!d) {
        close(d2);
        return -1;
    }
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (is_tmp(e->d_name) && unlink_quietly(dfd, e->d_name) < 0)
            rc = -1;
    closedir(d);
    return rc;
}

int jobdir_remove(const char *jobs_dir, const char *id)
{
    char dir[PATH_MAX];
    int dfd = open_dir(jobs_dir, id, dir, sizeof dir);
    if (dfd < 0)
        return errno == ENOENT ? 0 : -1;
    int rc = remove_files(dfd);
    close(dfd);
    if (rmdir(dir) < 0 && errno != ENOENT)
        rc = -1;
    return rc;
}

int jobdir_each(const char *jobs_dir, int (*fn)(void *ctx, const char *id), void *ctx)
{
    DIR *d = opendir(jobs_dir);
    if (!d)
        return errno == ENOENT ? 0 : -1;
    int rc = 0;
    struct dirent *e;
    while (rc == 0 && (e = readdir(d)) != NULL) {
        struct stat st;
        if (job_id_valid(e->d_name) && fstatat(dirfd(d), e->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0 &&
            S_ISDIR(st.st_mode))
            rc = fn(ctx, e->d_name);
    }
    closedir(d);
    return rc;
}
