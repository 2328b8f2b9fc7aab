/* The Slurm executor's files in a job directory (server/slurm_record.c):
 *
 *   slurm_job    "NAME TASK ID": the submission that runs the job: NAME the
 *                Slurm job name (tlsph-<first job id>-<attempt>, unique per
 *                submission), TASK its array index ("-" for a single job), ID
 *                its Slurm id ("123" or "123_4"; "-" until sbatch answered).
 *                Written durably (durable.h) before sbatch and again after,
 *                so that a restarted daemon knows every submission it may
 *                have made (executor_slurm.h, "restart").
 *   exit_status  the engine's exit status, one line, written by the batch
 *                script (slurm_submit.h) */
#ifndef TLSPHD_SLURM_RECORD_H
#define TLSPHD_SLURM_RECORD_H

#include <stddef.h>

#define SLURM_NAME_MAX 96 /* buffers of slurm_record_read */
#define SLURM_TASK_MAX 24
#define SLURM_ID_MAX 64

/* Writes job id's record: 0, or -1 with err. */
int slurm_record_write(const char *jobs_dir, const char *id, const char *name, const char *task,
                       const char *slurm, char *err, size_t errsize);
/* Reads it: 1 with name, task and slurm, 0 when there is none, -1 unreadable. */
int slurm_record_read(const char *jobs_dir, const char *id, char name[SLURM_NAME_MAX],
                      char task[SLURM_TASK_MAX], char slurm[SLURM_ID_MAX]);
/* The exit status the batch script wrote (0..255), -1 none (yet). */
int slurm_exit_read(const char *jobs_dir, const char *id);

#endif
