/* The Slurm executor's files in a job directory, see slurm_record.h. */
#include "slurm_record.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>

#include "durable.h"
#include "errmsg.h"
#include "jobdir.h"

int slurm_record_write(const char *jobs_dir, const char *id, const char *name, const char *task,
                       const char *slurm, char *err, size_t errsize)
{
    char dir[PATH_MAX], path[PATH_MAX], tmpl[PATH_MAX], text[SLURM_NAME_MAX + SLURM_TASK_MAX + SLURM_ID_MAX + 4];
    if (jobdir_path(dir, sizeof dir, jobs_dir, id, JOBDIR_FILES) < 0 ||
        jobdir_path(path, sizeof path, jobs_dir, id, JOBDIR_SLURM) < 0 ||
        snprintf(tmpl, sizeof tmpl, "%s.XXXXXX.tmp", path) >= (int)sizeof tmpl) {
        errmsg_set(err, errsize, "job directory path too long");
        return -1;
    }
    const int len = snprintf(text, sizeof text, "%s %s %s\n", name, task, slurm);
    if (len < 0 || (size_t)len >= sizeof text) {
        errmsg_set(err, errsize, "Slurm record too long");
        return -1;
    }
    return durable_write(dir, tmpl, path, text, (size_t)len, err, errsize);
}

int slurm_record_read(const char *jobs_dir, const char *id, char name[SLURM_NAME_MAX],
                      char task[SLURM_TASK_MAX], char slurm[SLURM_ID_MAX])
{
    char path[PATH_MAX];
    if (jobdir_path(path, sizeof path, jobs_dir, id, JOBDIR_SLURM) < 0)
        return -1;
    FILE *f = fopen(path, "r");
    if (!f)
        return errno == ENOENT ? 0 : -1;
    const int got = fscanf(f, "%95s %23s %63s", name, task, slurm);
    fclose(f);
    return got == 3 ? 1 : -1;
}

int slurm_exit_read(const char *jobs_dir, const char *id)
{
    char path[PATH_MAX];
    if (jobdir_path(path, sizeof path, jobs_dir, id, JOBDIR_EXIT) < 0)
        return -1;
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    int rc = -1;
    if (fscanf(f, "%d", &rc) != 1 || rc < 0 || rc > 255)
        rc = -1;
    fclose(f);
    return rc;
}
