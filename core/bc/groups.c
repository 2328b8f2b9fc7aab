/* Each condition's particle group: chosen once by its kind's select hook, then
 * summarised for the time series (mass, mean displacement). */
#include <stdio.h>

#include "bc/boundary.h"

int tlsph_boundary_select(struct tlsph_model *m, struct tlsph_errors *err)
{
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        struct tlsph_bc *bc = &m->scene.bcs[k];
        struct tlsph_group *g = &m->groups[k];
        if (!bc->kind->select)
            continue;
        const size_t count = bc->kind->select(m, bc, NULL);
        char ptr[64];
        snprintf(ptr, sizeof ptr, "/boundary_conditions/%zu", k);
        if (count == 0) {
            tlsph_errors_add(err, ptr, "boundary condition '%s' selects no particle", bc->name);
            return -1;
        }
        g->index = tlsph_alloc(m, count, sizeof *g->index);
        if (!g->index) {
            tlsph_errors_add(err, ptr, "out of memory");
            return -1;
        }
        g->n = bc->kind->select(m, bc, g->index);
        for (size_t a = 0; a < g->n; a++)
            g->mass += m->p.mass[g->index[a]];
        if (bc->kind->prepare && bc->kind->prepare(m, bc, g, ptr, err) != 0)
            return -1;
    }
    return 0;
}

void tlsph_boundary_displacements(struct tlsph_model *m)
{
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        struct tlsph_group *g = &m->groups[k];
        double u[3] = {0, 0, 0};
        for (size_t a = 0; a < g->n; a++) {
            const size_t i = (size_t)g->index[a];
            for (int c = 0; c < 3; c++)
                u[c] += m->p.x[3 * i + c] - m->p.X[3 * i + c];
        }
        for (int c = 0; c < 3; c++)
            g->displacement[c] = g->n ? u[c] / (double)g->n : 0.0;
    }
}
