#include "material/failure.h"

#include "util/parallel.h"

/* Still carries the stress of its last step, or moved relative to its
 * neighbours in this one (see failure.h). */
static inline int still_loaded(const struct tlsph_particles *p, size_t i)
{
    const double *Pt = p->P_tilde + 9 * i, *Fd = p->Fdot + 9 * i;
    for (int c = 0; c < 9; c++)
        if (Pt[c] != 0.0 || Fd[c] != 0.0)
            return 1;
    return 0;
}

void tlsph_failure(struct tlsph_model *m)
{
    struct tlsph_particles *p = &m->p;
    const int arrest = m->scene.failed_motion == TLSPH_FAILED_ARREST;
    size_t failed = 0;
    double arrested = 0.0;
    for (size_t b = 0; p->damage && b < m->scene.nbodies; b++) {
        if (!m->scene.materials[m->scene.bodies[b].material].damage.model)
            continue;
#pragma omp parallel for schedule(static) reduction(+ : failed, arrested)                      \
    if (m->body_end[b] - m->body_begin[b] >= TLSPH_PARALLEL_MIN_ITEMS)
        for (size_t i = m->body_begin[b]; i < m->body_end[b]; i++) {
            if (!(p->damage[i] >= 1.0))
                continue;
            failed++;
            if (!still_loaded(p, i))
                continue; /* failed before: released then */
            for (int c = 0; c < 6; c++)
                p->sigma[6 * i + c] = 0.0;
            for (int c = 0; c < 9; c++)
                p->P_tilde[9 * i + c] = 0.0;
            if (arrest) {
                double *v = p->v + 3 * i;
                arrested += 0.5 * p->mass[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
                v[0] = v[1] = v[2] = 0.0;
            }
        }
    }
    m->failed = failed;
    m->energy.external_work -= arrested; /* kinetic energy taken out by arresting failed particles */
}
