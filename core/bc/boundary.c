/* The step's boundary phases: one dispatch per condition and phase, in scene
 * order; the kinds' hooks run their own particle loops. */
#include "bc/boundary.h"

void tlsph_boundary_constrain(struct tlsph_model *m, double t, double t_mid)
{
    /* summed over all conditions, then booked once */
    double work = 0.0;
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        struct tlsph_bc *bc = &m->scene.bcs[k];
        if (bc->kind->constrain)
            bc->kind->constrain(m, bc, &m->groups[k], t, t_mid, &work);
    }
    m->energy.external_work += work;
}

void tlsph_boundary_before_drift(struct tlsph_model *m, double dt)
{
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        struct tlsph_bc *bc = &m->scene.bcs[k];
        if (bc->kind->before_drift)
            bc->kind->before_drift(m, bc, &m->groups[k], dt);
    }
}

double tlsph_boundary_forces(struct tlsph_model *m)
{
    double power = 0.0;
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        struct tlsph_bc *bc = &m->scene.bcs[k];
        if (bc->kind->force)
            bc->kind->force(m, bc, &m->groups[k], &power);
    }
    return power;
}

void tlsph_boundary_end_step(struct tlsph_model *m, double dt)
{
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        struct tlsph_bc *bc = &m->scene.bcs[k];
        struct tlsph_group *g = &m->groups[k];
        if (bc->kind->end_step)
            bc->kind->end_step(m, bc, g, dt);
        for (int c = 0; c < 3; c++) {
            g->reaction[c] = g->impulse[c] / dt;
            g->impulse[c] = 0.0;
            g->torque[c] = g->torque_impulse[c] / dt;
            g->torque_impulse[c] = 0.0;
        }
    }
}
