/* The Slurm executor (server/executor_slurm.c): every run a Slurm batch job.
 *
 * Assumption: the job directories (shared_dir, config.h) are on a file system
 * that the daemon's host and every compute node see under the same path, and
 * tlsph-run (engine) is installed under the same path on the nodes.  The
 * SQLite queue stays on the daemon's local disk (WAL needs one); only the job
 * directories are shared.  Without a shared file system the engine on the
 * node cannot read scene.json: the script's first line fails, the job ends
 * FAILED with no exit status, and the run fails saying so
 * (docs/deployment.md, "Running the jobs on a Slurm cluster").
 *
 * Why sbatch and not slurmrestd: the commands are on every submit host and
 * need nothing beyond munge, which a submit host already has; slurmrestd is
 * an optional daemon that many sites do not run, and needs a JWT or a local
 * socket set up per user.  One sbatch per run or per study, one squeue per
 * poll (slurm_poll s) for all of the user's jobs, one scancel per cancel:
 * the controller sees a few RPCs a second at most, whatever the queue holds.
 *
 * The life of a run:
 *   claim      tq_claim_next; a study child takes its accepted siblings
 *              along (tq_claim_siblings) into one job array, %limit from the
 *              study's max_parallel (else slurm_array_limit)
 *   record     before sbatch, each job directory's slurm_job file
 *              (slurm_record.h) says "NAME TASK -" (written durably); after
 *              it, "NAME TASK ID".
 *              NAME is tlsph-<first job id>-<attempt>, unique per submission
 *   sbatch     slurm_submit.h; a refusal requeues the runs (an attempt each)
 *              and no claim is made for SUBMIT_BACKOFF s
 *   poll       squeue for the state (slurm_state.h): the message says
 *              "Slurm job ID: PENDING (reason)" or "RUNNING on NODE";
 *              progress.jsonl is read from where the last read stopped
 *   end        slurm_verdict (slurm_state.h): the exit_status file is the
 *              truth when the engine wrote it (exit codes 0, 2, 3, 4 end the
 *              run at once); Slurm's state
 *              when Slurm ended the job (TIMEOUT, OUT_OF_MEMORY, CANCELLED,
 *              NODE_FAIL, PREEMPTED, ...); either way the final state is
 *              engine_outcome's, as for a local run
 *   cancel     scancel ID; the run ends dismissed when Slurm says CANCELLED
 *   stop       the daemon stops; the Slurm jobs go on
 *   restart    every run the queue has as running is adopted again from its
 *              slurm_job file: with an id it is watched as before; with "-"
 *              (the daemon died around sbatch) it is looked up by NAME in
 *              squeue, and adopted if Slurm has it; a run without a file, or
 *              unknown to Slurm and without an exit status, never reached a
 *              node and is requeued.  So nothing is lost, and nothing is
 *              submitted twice: a run is submitted again only when Slurm
 *              does not know its submission.
 *
 * Where Slurm has no accounting (no slurmdbd, so no sacct), the executor
 * needs none: squeue shows ended jobs for MinJobAge (300 s by default), and
 * after that the exit_status file on the shared directory is the truth.  A
 * run that Slurm forgot before the daemon saw its end (the daemon was down
 * for longer than MinJobAge) and that left no exit status is run again. */
#ifndef TLSPHD_EXECUTOR_SLURM_H
#define TLSPHD_EXECUTOR_SLURM_H

struct texec_host;
struct tcfg;

/* Adopts the runs an earlier daemon left with Slurm, then submits, watches
 * and ends runs until *h->stop is set.  cfg: the slurm_* settings (must
 * outlive the call). */
void texec_slurm_run(const struct texec_host *h, const struct tcfg *cfg);

#endif
