/* What one run asks Slurm for, see slurm_resources.h. */
#include "slurm_resources.h"

#include <math.h>
#include <string.h>

#include "config.h"
#include "errmsg.h"
#include "output_size.h"
#include "scene/scene.h"

int slurm_resources_of(const char *scene_json, const struct tcfg *cfg, long threads,
                       double wall_limit, struct slurm_resources *out, char *err,
                       size_t errsize)
{
    memset(out, 0, sizeof *out);
    struct tlsph_scene sc;
    memset(&sc, 0, sizeof sc);
    struct tlsph_errors e;
    tlsph_errors_init(&e);
    struct output_size size;
    int rc = tlsph_scene_parse(scene_json, strlen(scene_json), &sc, &e);
    if (rc == 0) {
        rc = output_size_estimate(&sc, &size, &e);
        tlsph_scene_free(&sc);
    }
    if (rc != 0) {
        errmsg_set(err, errsize, "the scene does not lay out: %s",
                   e.count > 0 ? e.items[0].message : "invalid");
        tlsph_errors_free(&e);
        return -1;
    }
    tlsph_errors_free(&e);
    const double n = (double)size.particles;
    out->particles = size.particles;
    out->cpus = (long)ceil(n / (double)cfg->slurm_particles_per_cpu);
    if (out->cpus > threads)
        out->cpus = threads;
    if (out->cpus < 1)
        out->cpus = 1;
    out->mem_mb = (long)ceil(cfg->slurm_mem_margin * n * cfg->slurm_bytes_per_particle / 1048576.0) +
                  cfg->slurm_mem_base_mb;
    out->time_min = (long)ceil(wall_limit / 60.0);
    if (out->time_min < 1)
        out->time_min = 1;
    return 0;
}

void slurm_resources_max(struct slurm_resources *acc, const struct slurm_resources *r)
{
    if (r->particles > acc->particles)
        acc->particles = r->particles;
    if (r->cpus > acc->cpus)
        acc->cpus = r->cpus;
    if (r->mem_mb > acc->mem_mb)
        acc->mem_mb = r->mem_mb;
    if (r->time_min > acc->time_min)
        acc->time_min = r->time_min;
}
