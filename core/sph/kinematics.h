/* Kinematics: deformation gradient and its rate (paper 000 eqs. 26-27) with the
 * corrected kernel gradient, one gather pass over the reference pairs. */
#ifndef TLSPH_KINEMATICS_H
#define TLSPH_KINEMATICS_H

#include "run/model.h"

/* F_i    = I + [sum_j V_j (u_j - u_i) (x) grad W_i(X_ij)] L_i^-1   (positions x)
 * Fdot_i =     [sum_j V_j (v_j - v_i) (x) grad W_i(X_ij)] L_i^-1   (velocities v)
 * and the first half of the trapezoidal internal-energy update,
 * e_i += dt/2 / rho0 * P_i(old) : Fdot_i, using P_tilde of the previous step
 * (P:Fdot = P_tilde : G_dot, so L_i never has to be re-applied).
 *
 * With damage the model's crack treatment (m->crack, sph/crack_treatment.h)
 * chooses the pass: damage-aware (eqs. 33-34, sph/damage_aware.h) or
 * pseudo-spring (sph/pseudo_spring.c).  A failed particle (D = 1) gets
 * Fdot = 0 and no update. */
void tlsph_kinematics(struct tlsph_model *m, double dt);

/* Whether the kinematics may share a parallel loop with the stress update
 * (tlsph_constitutive_with_kinematics): true when the treatment's gather of a
 * particle reads no field that the update of another particle writes.  The
 * intact and virtual-link gathers read x and v (and the links' own D_ij);
 * the damage-aware and pseudo-spring ones read the neighbours' D, which the
 * update writes, so they keep their own pass.  Also false for a porous model,
 * whose constitutive phase is timed alone (cost.material_phase_share), and
 * when the bodies' ranges do not cover the particles. */
int tlsph_kinematics_fusable(const struct tlsph_model *m);

/* The gather of particles [lo, hi), called by every thread of a parallel
 * region: each thread does its share (tlsph_static_share, util/parallel.h) and
 * goes on without waiting; outside a parallel region it does them all.  A loop
 * that follows over the shares of the same range in the same region gives
 * each thread the same particles, so it may read what this wrote for its own
 * particles without a barrier.  Only when tlsph_kinematics_fusable(m). */
void tlsph_kinematics_for(struct tlsph_model *m, size_t lo, size_t hi, double dt);

/* The start of particle i's gather, shared by every treatment: what each of
 * its pairs is measured against, i's reference position X_i (m), displacement
 * u_i = x_i - X_i (m) and velocity v_i (m/s).  This and tlsph_pair_delta are
 * always inlined, so the pair loops stay plain, and each difference is taken in
 * one place, so every treatment rounds it alike. */
struct tlsph_gather_origin {
    double X[3], u[3], v[3];
};

static inline __attribute__((always_inline)) struct tlsph_gather_origin
tlsph_gather_origin(const struct tlsph_particles *p, size_t i)
{
    const double *Xi = p->X + 3 * i, *xi = p->x + 3 * i, *vi = p->v + 3 * i;
    struct tlsph_gather_origin o;
    for (int a = 0; a < 3; a++) {
        o.X[a] = Xi[a];
        o.u[a] = xi[a] - Xi[a];
        o.v[a] = vi[a];
    }
    return o;
}

/* Pair (i, j) of i's gather: the differences j - i of reference position
 * d = X_j - X_i (m), displacement du = u_j - u_i (m) and velocity
 * dv = v_j - v_i (m/s). */
struct tlsph_pair_delta {
    double d[3], du[3], dv[3];
};

static inline __attribute__((always_inline)) struct tlsph_pair_delta
tlsph_pair_delta(const struct tlsph_particles *p, const struct tlsph_gather_origin *o, size_t j)
{
    const double *Xj = p->X + 3 * j, *xj = p->x + 3 * j, *vj = p->v + 3 * j;
    struct tlsph_pair_delta q;
    for (int a = 0; a < 3; a++) {
        q.d[a] = Xj[a] - o->X[a];
        q.du[a] = xj[a] - Xj[a] - o->u[a];
        q.dv[a] = vj[a] - o->v[a];
    }
    return q;
}

/* The end of particle i's gather, shared by every treatment: G and Gd are the
 * uncorrected sums of V_j (u_j - u_i) (x) grad W and V_j (v_j - v_i) (x) grad W.
 * Books the first half of the trapezoidal energy update with the old P_tilde,
 * then sets F_i = I + G L_i^-1 and Fdot_i = Gd L_i^-1 (with the current p.Linv;
 * after a split, F_i = G_c + G L_i^-1 G_c with p.Linv = L_i^-1 G_c and G_c =
 * p.F_carry: crack/split_carry.h). */
static inline void tlsph_kinematics_finish(struct tlsph_particles *p, size_t i, double dt,
                                           const double G[9], const double Gd[9])
{
    double power = 0.0;
    for (int a = 0; a < 9; a++)
        power += p->P_tilde[9 * i + a] * Gd[a];
    p->e[i] += 0.5 * dt * power * p->vol0[i] / p->mass[i];

    const double *Li = p->Linv + 9 * i;
    double *Fi = p->F + 9 * i, *Fdi = p->Fdot + 9 * i;
    /* the part carried through splits (model.h F_carry): I without crack growth */
    static const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double *Gc = p->F_carry ? p->F_carry + 9 * i : identity;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            Fi[3 * r + c] = Gc[3 * r + c] + G[3 * r] * Li[c] + G[3 * r + 1] * Li[3 + c] +
                            G[3 * r + 2] * Li[6 + c];
            Fdi[3 * r + c] =
                Gd[3 * r] * Li[c] + Gd[3 * r + 1] * Li[3 + c] + Gd[3 * r + 2] * Li[6 + c];
        }
}

#endif
