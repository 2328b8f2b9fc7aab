/* What one run asks Slurm for (server/slurm_resources.c).
 *
 *   cpus-per-task = ceil(N / slurm_particles_per_cpu), in 1..threads (the
 *                   engine's OpenMP threads: the batch script passes
 *                   SLURM_CPUS_PER_TASK to tlsph-run --threads)
 *   mem (MiB)     = ceil(slurm_mem_margin x N x slurm_bytes_per_particle / 2^20)
 *                   + slurm_mem_base_mb
 *   time (min)    = ceil(wall_limit / 60), at least 1 (Slurm counts minutes)
 *
 * N is the engine's own lattice count of the scene (output_size.h, the count
 * the run will have).  slurm_bytes_per_particle is the engine's cost record
 * bytes_per_particle (its allocations over its particles, in every finished
 * job's cost and result.h5) with room for what it does not count (the
 * neighbour lists grow with damage and contact); docs/deployment.md has the
 * measured values.  A study's array asks for the largest of its children. */
#ifndef TLSPHD_SLURM_RESOURCES_H
#define TLSPHD_SLURM_RESOURCES_H

#include <stddef.h>

struct tcfg;

struct slurm_resources {
    size_t particles;
    long cpus;
    long mem_mb;
    long time_min;
};

/* The resources of a scene (JSON text) run with at most threads threads and
 * the wall-clock limit wall_limit (s): 0, or -1 with err (a scene the engine
 * cannot lay out: it would fail validation on the node too). */
int slurm_resources_of(const char *scene_json, const struct tcfg *cfg, long threads,
                       double wall_limit, struct slurm_resources *out, char *err,
                       size_t errsize);
/* acc = the member-wise largest of acc and r. */
void slurm_resources_max(struct slurm_resources *acc, const struct slurm_resources *r);

#endif
