/* Contradictions between boundary conditions and the bodies, refused at setup
 * (so at validation: tlsph-run --validate builds the model): each kind's own
 * check of the particles at t = 0 (a wall with a body behind it), then that no
 * velocity component of any particle is prescribed by two conditions that can
 * disagree -- `fixed` and `velocity` on the same particles, or two velocity
 * conditions -- where the later condition would silently win and the
 * reactions of both would be wrong.  Prescriptions that cannot differ (fixed
 * with a symmetry plane, or with a velocity component held at 0) are fine. */
#include <stdio.h>
#include <stdlib.h>

#include "bc/boundary.h"

static const char *const axis[] = {"x", "y", "z"};

/* Whether two prescriptions of one component can disagree. */
static int disagree(enum tlsph_bc_prescription a, double va, enum tlsph_bc_prescription b,
                    double vb)
{
    return !(a == TLSPH_BC_CONSTANT && b == TLSPH_BC_CONSTANT && va == vb);
}

/* The first conflict of condition k with an earlier one. */
struct conflict {
    size_t other, particle, count;
    int component;
};

static int check_prescriptions(struct tlsph_model *m, struct tlsph_errors *err)
{
    struct tlsph_scene *s = &m->scene;
    const size_t n = m->p.n;
    /* owner[3 i + c]: the first condition prescribing component c of particle i */
    int32_t *owner = malloc(3 * (n ? n : 1) * sizeof *owner);
    if (!owner) {
        tlsph_errors_add(err, "/boundary_conditions", "out of memory");
        return -1;
    }
    for (size_t i = 0; i < 3 * n; i++)
        owner[i] = -1;
    int bad = 0;
    for (size_t k = 0; k < s->nbcs; k++) {
        struct tlsph_bc *bc = &s->bcs[k];
        const struct tlsph_group *g = &m->groups[k];
        if (!bc->kind->prescribes)
            continue;
        enum tlsph_bc_prescription p[3];
        double v[3] = {0, 0, 0};
        for (int c = 0; c < 3; c++)
            p[c] = bc->kind->prescribes(bc, c, &v[c]);
        struct conflict first = {0, 0, 0, -1};
        for (size_t a = 0; a < g->n; a++) {
            const size_t i = (size_t)g->index[a];
            for (int c = 0; c < 3; c++) {
                if (p[c] == TLSPH_BC_FREE)
                    continue;
                const int32_t o = owner[3 * i + c];
                if (o < 0) {
                    owner[3 * i + c] = (int32_t)k;
                    continue;
                }
                struct tlsph_bc *ob = &s->bcs[o];
                double ov = 0.0;
                const enum tlsph_bc_prescription op = ob->kind->prescribes(ob, c, &ov);
                if (!disagree(op, ov, p[c], v[c]))
                    continue;
                if (first.component < 0) {
                    first = (struct conflict){(size_t)o, i, 0, c};
                }
                if ((size_t)o == first.other && c == first.component)
                    first.count++;
            }
        }
        if (first.component < 0)
            continue;
        const struct tlsph_bc *ob = &s->bcs[first.other];
        const double *X = m->p.X + 3 * first.particle;
        char ptr[64];
        snprintf(ptr, sizeof ptr, "/boundary_conditions/%zu", k);
        tlsph_errors_add(err, ptr,
                         "boundary conditions '%s' (%s, /boundary_conditions/%zu) and '%s' (%s) "
                         "both prescribe the %s velocity of %zu particles (e.g. the one at (%g, "
                         "%g, %g) m) with values that can differ; a velocity component may follow "
                         "one condition only: make the selections disjoint or leave the "
                         "component free (null)",
                         ob->name, ob->kind->name, first.other, bc->name, bc->kind->name,
                         axis[first.component], first.count, X[0], X[1], X[2]);
        bad = 1;
    }
    free(owner);
    return bad ? -1 : 0;
}

int tlsph_boundary_check(struct tlsph_model *m, struct tlsph_errors *err)
{
    int bad = 0;
    for (size_t k = 0; k < m->scene.nbcs; k++) {
        const struct tlsph_bc *bc = &m->scene.bcs[k];
        if (!bc->kind->check)
            continue;
        char ptr[64];
        snprintf(ptr, sizeof ptr, "/boundary_conditions/%zu", k);
        bad |= bc->kind->check(m, bc, ptr, err) != 0;
    }
    bad |= check_prescriptions(m, err) != 0;
    return bad ? -1 : 0;
}
