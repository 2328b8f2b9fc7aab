/* Setup, teardown and reports of the rigid bodies (rigid.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rigid/state.h"
#include "run/model.h"

/* At t = 0 no particle may overlap a rigid body: its centre must be at least
 * its contact radius R = spacing/2 from the surface (up to round-off), the
 * lattice cell touching the surface at most.  An overlapping particle would
 * start with a contact force no motion caused. */
static int check_start(const struct tlsph_model *m, struct tlsph_errors *err)
{
    const struct tlsph_rigid *r = m->rigid;
    int bad = 0;
    for (size_t j = 0; j < r->nb; j++) {
        const struct tlsph_rigid_body *k = &r->b[j];
        size_t count = 0, worst_i = 0;
        double worst = 0.0;
        for (int64_t a = r->start[j]; a < r->start[j + 1]; a++) {
            const size_t i = (size_t)r->cand[a];
            const double R = r->radius[m->p.body[i]];
            double n[3];
            const double depth = (R - tlsph_rigid_distance(k, m->p.x + 3 * i, n)) / R;
            if (depth <= 1e-9)
                continue;
            if (count++ == 0 || depth > worst) {
                worst = depth;
                worst_i = i;
            }
        }
        if (count == 0)
            continue;
        char ptr[64];
        snprintf(ptr, sizeof ptr, "/rigid_bodies/%zu", j);
        const double *X = m->p.x + 3 * worst_i;
        tlsph_errors_add(err, ptr,
                         "rigid body '%s' overlaps body '%s' at t = 0: %zu particles are closer "
                         "to its surface than half their spacing or inside it (the deepest "
                         "%.3g of half a spacing, at (%g, %g, %g) m); bodies must start apart "
                         "from a rigid body or touching it",
                         k->spec->name, m->scene.bodies[m->p.body[worst_i]].name, count, worst,
                         X[0], X[1], X[2]);
        bad = 1;
    }
    return bad ? -1 : 0;
}

int tlsph_rigid_create(struct tlsph_model *m, struct tlsph_errors *err)
{
    const struct tlsph_scene *s = &m->scene;
    const size_t n = m->p.n;
    struct tlsph_rigid *r = calloc(1, sizeof *r);
    if (!r) {
        tlsph_errors_add(err, "/rigid_bodies", "out of memory for the rigid bodies");
        return -1;
    }
    m->rigid = r;
    m->bytes_allocated += sizeof *r;
    r->nb = s->nrigid;
    r->b = tlsph_alloc(m, r->nb, sizeof *r->b);
    r->radius = tlsph_alloc(m, s->nbodies, sizeof *r->radius);
    r->stiffness = tlsph_alloc(m, s->nbodies, sizeof *r->stiffness);
    r->start = tlsph_alloc(m, r->nb + 1, sizeof *r->start);
    r->x_search = tlsph_alloc(m, 3 * n, sizeof *r->x_search);
    r->f = tlsph_alloc(m, 3 * n, sizeof *r->f);
    r->f_old = tlsph_alloc(m, 3 * n, sizeof *r->f_old);
    if (!r->b || !r->radius || !r->stiffness || !r->start || !r->x_search || !r->f || !r->f_old) {
        tlsph_errors_add(err, "/rigid_bodies", "out of memory for the rigid bodies");
        return -1;
    }
    double spacing = 0.0;
    for (size_t b = 0; b < s->nbodies; b++) {
        const struct tlsph_body *bd = &s->bodies[b];
        const struct tlsph_material *mat = &s->materials[bd->material];
        const double estar = mat->youngs_modulus / (1.0 - mat->poisson_ratio * mat->poisson_ratio);
        r->radius[b] = 0.5 * bd->spacing;
        /* the penalty law's line form against a rigid partner (contact.c) */
        r->stiffness[b] = 0.25 * M_PI * estar * (m->dim == 3 ? bd->spacing : 1.0);
        r->max_radius = fmax(r->max_radius, r->radius[b]);
        spacing = fmax(spacing, bd->spacing);
    }
    r->skin = 0.5 * spacing;
    for (size_t j = 0; j < r->nb; j++) {
        r->b[j].spec = &s->rigid[j];
        r->b[j].extent = s->rigid[j].shape->extent(&s->rigid[j]);
    }
    tlsph_rigid_create_motion(m);
    if (tlsph_rigid_search(m, r, 1) != 0) {
        tlsph_errors_add(err, "/rigid_bodies", "out of memory for the rigid-body search");
        return -1;
    }
    return check_start(m, err);
}

void tlsph_rigid_free(struct tlsph_model *m)
{
    struct tlsph_rigid *r = m->rigid;
    if (!r)
        return;
    free(r->b);
    free(r->radius);
    free(r->stiffness);
    free(r->start);
    free(r->cand);
    free(r->x_search);
    free(r->f);
    free(r->f_old);
    free(r);
    m->rigid = NULL;
}

void tlsph_rigid_report(const struct tlsph_model *m, size_t j, struct tlsph_rigid_report *out)
{
    const struct tlsph_rigid_body *k = &m->rigid->b[j];
    memcpy(out->position, k->c, sizeof out->position);
    memcpy(out->velocity, k->V, sizeof out->velocity);
    memcpy(out->angular_velocity, k->W, sizeof out->angular_velocity);
    memcpy(out->force, k->F, sizeof out->force);
    memcpy(out->torque, k->T, sizeof out->torque);
    memcpy(out->angular_momentum, k->L, sizeof out->angular_momentum);
    memcpy(out->orientation, k->Q, sizeof out->orientation);
}

double tlsph_rigid_take_overlap(struct tlsph_model *m, int64_t *id, long *body)
{
    struct tlsph_rigid *r = m->rigid;
    const double seen = r->max_overlap;
    r->max_overlap = 0.0;
    *id = -1;
    *body = -1;
    if (!(seen > TLSPH_CONTACT_MAX_OVERLAP))
        return seen; /* who overlaps most matters only to a run that stops */
    double deepest = 0.0;
    for (size_t j = 0; j < r->nb; j++)
        for (int64_t a = r->start[j]; a < r->start[j + 1]; a++) {
            const size_t i = (size_t)r->cand[a];
            const double R = r->radius[m->p.body[i]];
            double n[3];
            const double depth = (R - tlsph_rigid_distance(&r->b[j], m->p.x + 3 * i, n)) / R;
            if (depth > deepest) {
                deepest = depth;
                *id = m->p.id[i];
                *body = (long)j;
            }
        }
    return seen;
}

struct tlsph_rigid_cost tlsph_rigid_cost(const struct tlsph_model *m)
{
    const struct tlsph_rigid *r = m->rigid;
    return (struct tlsph_rigid_cost){r->searches, r->phase_seconds};
}

size_t tlsph_rigid_active(const struct tlsph_model *m)
{
    return m->rigid->active;
}

int tlsph_rigid_failed(const struct tlsph_model *m)
{
    return m->rigid->failed;
}
