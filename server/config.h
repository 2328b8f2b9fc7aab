/* tlsphd configuration (server/config.c): embedded defaults, then the config
 * file (--config FILE: "key = value" lines, '#' comments), then command-line
 * flags, each overriding the previous.
 *
 * Keys (file) / flags:
 *   listen = ADDR:PORT        --listen        127.0.0.1:8080 ([::1]:8080 for IPv6)
 *   data_dir = DIR            --data-dir      $XDG_STATE_HOME/tlsphd if XDG_STATE_HOME is set,
 *                                             else ./tlsphd-data
 *   engine = PATH             --engine        tlsph-run next to the tlsphd executable, else
 *                                             TLSPH_ENGINE_DEFAULT ($bindir/tlsph-run)
 *   schemas_dir = DIR         --schemas-dir   where openapi.json is read from (see config.c)
 *   max_jobs = N              --max-jobs      1
 *   cores = N                 --cores         the CPUs tlsphd may run on (sched_getaffinity):
 *                                             the thread budget of the local executor
 *                                             (thread_budget.h)
 *   threads_per_job = N       --threads-per-job  local executor: cores / max_jobs, at least 1,
 *                                             and lowered to that with a warning
 *                                             (budget_warning) when threads_per_job x
 *                                             max_jobs > cores; slurm: cores (at most
 *                                             TLSPH_MAX_THREADS either way)
 *   wall_limit = S            --wall-limit    3600
 *   max_particles = N         --max-particles the engine's default, TLSPH_DEFAULT_MAX_PARTICLES
 *                                             (2000000; at most TLSPH_MAX_PARTICLES)
 *   max_children = N          --max-children  1000 (study size)
 *   body_limit = BYTES        --body-limit    8388608
 *   connection_limit = N      --connection-limit 512
 *   per_ip_limit = N          --per-ip-limit  64 (0 = none)
 *   connection_timeout = S    --connection-timeout 30 (idle)
 *   header_timeout = S        --header-timeout 10 (a request's headers, from its start)
 *   body_timeout = S          --body-timeout  120 (a request's body, from its start)
 *   heavy_threads = N         --heavy-threads 2 (threads for job lists and result reads;
 *                                             routes.h's lanes)
 *   memory_limit_mb = N       --memory-limit-mb 0 (RLIMIT_AS per engine; 0 = none)
 *   kill_grace = S            --kill-grace    5
 *   max_attempts = N          --max-attempts  3
 *   min_free_mb = N           --min-free-mb   256 (free-space floor of the data directory;
 *                                             0 = none; storage.h)
 *   max_output_mb = N         --max-output-mb 16384 (quota on a job's estimated result
 *                                             file; 0 = none; output_size.h)
 *   disk_reserve_mb = N       --disk-reserve-mb 8 (the reserve file; 0 = none; storage.h)
 *   token_sha256 = HEX        (repeatable)    SHA-256 of an accepted bearer token
 *   token_file = FILE         --token-file    plaintext tokens, one per line (hashed at load)
 *   executor = local|slurm    --executor      local (supervised fork/exec on this machine);
 *                                             slurm: every run is a Slurm batch job
 *                                             (executor.h, executor_slurm.c)
 *   shared_dir = DIR          --shared-dir    the job directories, on a file system that
 *                                             the compute nodes share ("" = data_dir/jobs)
 *   slurm_partition = NAME    (file only)     sbatch --partition ("" = the cluster's default)
 *   slurm_account = NAME      (file only)     sbatch --account ("" = the user's default)
 *   slurm_options = OPTS      (file only)     more sbatch options, split at blanks
 *   slurm_poll = S            (file only)     2 (s between looks at squeue)
 *   slurm_particles_per_cpu = N  (file only)  20000 (cpus-per-task = particles / N, at
 *                                             least 1, at most threads_per_job)
 *   slurm_bytes_per_particle = B (file only)  4096 (the engine's cost record
 *                                             bytes_per_particle, with room)
 *   slurm_mem_margin = X      (file only)     1.5 (memory = margin x particles x B + base)
 *   slurm_mem_base_mb = N     (file only)     256 (the engine's libraries, HDF5 buffers)
 *   slurm_array_limit = N     (file only)     0 (a study's array %limit when its request
 *                                             sets no max_parallel; 0 = none)
 *   test_hold_heavy = FILE    (file only)     TESTING ONLY: heavy requests (job lists,
 *                                             result reads) wait while FILE exists
 *
 * And, on the command line only, --recover: start on a data directory that
 * does not pass the start-up checks by rebuilding it (startup.h).
 *
 * Layout under data_dir: tlsphd.sqlite (+ -wal, -shm), tlsphd.reserve and
 * jobs/<id>/. */
#ifndef TLSPHD_CONFIG_H
#define TLSPHD_CONFIG_H

#include <stddef.h>
#include <stdio.h>
#include <sys/socket.h>

#include "auth.h"

struct tcfg {
    char listen[128];        /* as given */
    struct sockaddr_storage addr;
    socklen_t addrlen;
    int loopback;            /* the address is a loopback address */
    char data_dir[1024];
    char db_path[1100];
    char jobs_dir[1100];
    char engine[1024];
    char schemas_dir[1024];
    int max_jobs;
    int threads_per_job;
    int cores;               /* the local executor's thread budget (thread_budget.h) */
    char budget_warning[256]; /* why tcfg_load changed threads_per_job, "" none (logged) */
    double wall_limit;
    long max_particles;
    long max_children;
    size_t body_limit;
    int connection_limit;
    int per_ip_limit;
    int connection_timeout;
    int header_timeout;      /* s for a request's headers, from its start (http_conns.h) */
    int body_timeout;        /* s for its body, from its start */
    int heavy_threads;       /* threads of the heavy lane (routes.h) */
    long memory_limit_mb;
    double kill_grace;
    int max_attempts;
    long min_free_mb;        /* free-space floor, MiB (0 = none) */
    long max_output_mb;      /* per-job quota on the estimated result file, MiB (0 = none) */
    long disk_reserve_mb;    /* the reserve file, MiB (0 = none) */
    int recover;             /* --recover was given */
    char executor[16];       /* "local" or "slurm" */
    char shared_dir[1024];   /* "" = data_dir/jobs */
    char slurm_partition[128], slurm_account[128];
    char slurm_options[1024];
    double slurm_poll;       /* s */
    long slurm_particles_per_cpu;
    double slurm_bytes_per_particle; /* B */
    double slurm_mem_margin;
    long slurm_mem_base_mb;
    int slurm_array_limit;   /* 0 = none */
    char test_hold_heavy[1024]; /* testing only, "" = off (http_config.hold_path) */
    struct tauth auth;       /* token hashes (empty = no authentication) */
};

enum tcfg_rc {
    TCFG_OK,
    TCFG_HELP, /* --help: print the usage and exit 0 */
    TCFG_ERROR /* a usage error; err says why */
};

/* Fills cfg from defaults, the config file and argv. */
enum tcfg_rc tcfg_load(struct tcfg *cfg, int argc, char **argv, char *err, size_t errsize);
void tcfg_free(struct tcfg *cfg);
void tcfg_usage(FILE *f);

#endif
