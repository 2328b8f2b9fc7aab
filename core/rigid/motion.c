/* Motion of the rigid bodies (rigid.h), in the step's kick-drift-kick.
 *
 * Free body: the kicks add half a step of the particles' force to its momentum
 * M V and of their torque about c to its angular momentum L (world frame), so
 * what the particles lose the body gains: the force on the body is minus the
 * sum of the particles' contact forces of the same evaluation, and both are
 * applied with the same dt/2 (F_n + F_n+1): total momentum is conserved to
 * round-off.  The drift moves c by dt V and turns the body by the exact
 * rotation for a constant angular velocity over the step, R = exp(dt [w])
 * (Rodrigues), with w the angular velocity at the middle of the turn:
 * w0 = I(Q)^-1 L, Q_half = exp(dt/2 [w0]) Q, w = I(Q_half)^-1 L (the explicit
 * midpoint rule on the rotations, second order), I(Q) = Q I0 Q^T the inertia
 * carried with the body.  L is untouched by the drift, so a torque-free body
 * keeps its angular momentum exactly; its energy 1/2 w.L drifts at second
 * order in the step (docs/contact.md).
 *
 * Prescribed body: the kick sets V and w from the expressions at the time
 * given (the half-step time before the drift, the step's end after the second
 * kick); the drift moves and turns it with the half-step values. */
#include <math.h>
#include <string.h>

#include "rigid/frame.h"
#include "rigid/state.h"
#include "run/model.h"
#include "util/mat3.h"

void tlsph_rigid_inverse_inertia(const struct tlsph_rigid_body *k, double out[9])
{
    double t[9];
    mat3_mul(k->Q, k->Iinv0, t);
    mat3_mul_bt(t, k->Q, out);
}

static void angular_velocity(const struct tlsph_rigid_body *k, double w[3])
{
    double Ii[9];
    tlsph_rigid_inverse_inertia(k, Ii);
    for (int i = 0; i < 3; i++)
        w[i] = Ii[3 * i] * k->L[0] + Ii[3 * i + 1] * k->L[1] + Ii[3 * i + 2] * k->L[2];
}

/* Q <- exp(dt [w]) Q */
static void turn(double Q[9], const double w[3], double dt)
{
    const double a[3] = {dt * w[0], dt * w[1], dt * w[2]};
    double R[9], t[9];
    rigid_rotation(a, R);
    mat3_mul(R, Q, t);
    memcpy(Q, t, sizeof t);
}

static void prescribed(struct tlsph_rigid_body *k, double t)
{
    struct tlsph_rigid_spec *s = (struct tlsph_rigid_spec *)k->spec; /* evaluators hold state */
    for (int c = 0; c < 3; c++) {
        k->V[c] = s->velocity_set[c] ? tlsph_expr_eval(&s->velocity[c], &t) : 0.0;
        k->W[c] = s->angular_set[c] ? tlsph_expr_eval(&s->angular_velocity[c], &t) : 0.0;
    }
}

void tlsph_rigid_kick(struct tlsph_model *m, double half, double t)
{
    struct tlsph_rigid *r = m->rigid;
    for (size_t j = 0; j < r->nb; j++) {
        struct tlsph_rigid_body *k = &r->b[j];
        if (!k->free) {
            prescribed(k, t);
            continue;
        }
        for (int c = 0; c < 3; c++) {
            k->V[c] += half * k->F[c] / k->mass;
            k->L[c] += half * k->T[c];
        }
        angular_velocity(k, k->W);
    }
}

void tlsph_rigid_drift(struct tlsph_model *m, double t, double dt)
{
    (void)t;
    struct tlsph_rigid *r = m->rigid;
    for (size_t j = 0; j < r->nb; j++) {
        struct tlsph_rigid_body *k = &r->b[j];
        for (int c = 0; c < 3; c++)
            k->c[c] += dt * k->V[c];
        if (!k->free) {
            turn(k->Q, k->W, dt);
            continue;
        }
        struct tlsph_rigid_body half = *k;
        turn(half.Q, k->W, 0.5 * dt);
        angular_velocity(&half, k->W); /* the mid-turn angular velocity */
        turn(k->Q, k->W, dt);
    }
}

void tlsph_rigid_create_motion(struct tlsph_model *m)
{
    struct tlsph_rigid *r = m->rigid;
    for (size_t j = 0; j < r->nb; j++) {
        struct tlsph_rigid_body *k = &r->b[j];
        const struct tlsph_rigid_spec *s = k->spec;
        memcpy(k->c, s->centre, sizeof k->c);
        for (int i = 0; i < 9; i++)
            k->Q[i] = i % 4 == 0 ? 1.0 : 0.0;
        k->free = s->motion == TLSPH_RIGID_FREE;
        if (!k->free) {
            prescribed(k, 0.0);
            continue;
        }
        k->mass = s->mass;
        if (m->dim == 2) {
            memset(k->Iinv0, 0, sizeof k->Iinv0);
            k->Iinv0[8] = 1.0 / s->inertia[8];
        } else {
            mat3_inverse(s->inertia, k->Iinv0);
        }
        memcpy(k->V, s->v0, sizeof k->V);
        memcpy(k->W, s->w0, sizeof k->W);
        /* L = I0 w0 */
        const double *I = m->dim == 2 ? NULL : s->inertia;
        for (int i = 0; i < 3; i++)
            k->L[i] = I ? I[3 * i] * s->w0[0] + I[3 * i + 1] * s->w0[1] + I[3 * i + 2] * s->w0[2]
                        : (i == 2 ? s->inertia[8] * s->w0[2] : 0.0);
    }
}

double tlsph_rigid_kinetic_energy(const struct tlsph_model *m)
{
    const struct tlsph_rigid *r = m->rigid;
    double e = 0.0;
    for (size_t j = 0; j < r->nb; j++) {
        const struct tlsph_rigid_body *k = &r->b[j];
        if (!k->free)
            continue;
        e += 0.5 * k->mass * (k->V[0] * k->V[0] + k->V[1] * k->V[1] + k->V[2] * k->V[2]);
        e += 0.5 * (k->W[0] * k->L[0] + k->W[1] * k->L[1] + k->W[2] * k->L[2]);
    }
    return e;
}

void tlsph_rigid_momentum(const struct tlsph_model *m, double out[3])
{
    const struct tlsph_rigid *r = m->rigid;
    for (size_t j = 0; j < r->nb; j++)
        if (r->b[j].free)
            for (int c = 0; c < 3; c++)
                out[c] += r->b[j].mass * r->b[j].V[c];
}
