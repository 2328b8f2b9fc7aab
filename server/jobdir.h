/* A job's directory (server/jobdir.c): the only code that knows which files a
 * job has and where they are.
 *
 *   <jobs_dir>/<id>/scene.json   the scene as submitted (written here, atomically)
 *   <jobs_dir>/<id>/result.h5    the engine's result (docs/output.md)
 *   <jobs_dir>/<id>/result.xmf   its XDMF sidecar (written as result.xmf.tmp, renamed)
 *   <jobs_dir>/<id>/log.txt      the engine's stdout and stderr, for people
 *   <jobs_dir>/<id>/progress.jsonl  Slurm executor: the engine's progress stream
 *                                (the lines of its --progress-fd), written on the node
 *   <jobs_dir>/<id>/exit_status  Slurm executor: the engine's exit status, one line
 *                                (written as exit_status.tmp and renamed)
 *   <jobs_dir>/<id>/slurm_job    Slurm executor: which Slurm job runs it (executor_slurm.c)
 *
 * Only ids that pass job_id_valid (jobid.h) become paths, and only these
 * files (plus leftover *.tmp) are ever removed.  Every function returns 0 or
 * -1 (errmsg.h); jobdir_create says why in err. */
#ifndef TLSPHD_JOBDIR_H
#define TLSPHD_JOBDIR_H

#include <stddef.h>

enum jobdir_file {
    JOBDIR_SCENE,   /* input: the engine reads it */
    JOBDIR_RESULT,  /* output: result.h5 */
    JOBDIR_SIDECAR, /* output: result.xmf */
    JOBDIR_LOG,     /* output: the engine's log */
    JOBDIR_PROGRESS, /* output (Slurm): the progress stream */
    JOBDIR_EXIT,    /* output (Slurm): the exit status */
    JOBDIR_SLURM,   /* the Slurm submission record: rewritten at each submission */
    JOBDIR_FILES
};

/* The directory (file = JOBDIR_FILES) or one file of job id into buf.
 * -1 when the id is not valid or the path does not fit. */
int jobdir_path(char *buf, size_t size, const char *jobs_dir, const char *id,
                enum jobdir_file file);
/* Creates the directory (and jobs_dir) and writes scene.json durably:
 * a temporary file, fsync, rename, fsync of the directory. */
int jobdir_create(const char *jobs_dir, const char *id, const char *scene_json, char *err,
                  size_t errsize);
/* Removes the outputs of an earlier attempt before the engine runs (again). */
int jobdir_clear_outputs(const char *jobs_dir, const char *id);
/* Removes the job's files and its directory; a missing directory is fine. */
int jobdir_remove(const char *jobs_dir, const char *id);
/* Calls fn(ctx, id) for every directory under jobs_dir named by a job id
 * (job_id_valid; other names are not job directories); stops at the first
 * non-zero answer and returns it.  0, or -1 with errno when jobs_dir cannot
 * be read (a missing jobs_dir has no job). */
int jobdir_each(const char *jobs_dir, int (*fn)(void *ctx, const char *id), void *ctx);

#endif
