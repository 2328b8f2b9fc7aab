/* The rigid bodies' run state (rigid.h), shared by core/rigid/ only: the
 * motion (motion.c) moves the bodies, the contact phase (contact.c) searches
 * and pushes the particles, rigid.c sets up and reports. */
#ifndef TLSPH_RIGID_STATE_H
#define TLSPH_RIGID_STATE_H

#include <stddef.h>
#include <stdint.h>

#include "rigid/rigid.h"

struct tlsph_rigid_body {
    const struct tlsph_rigid_spec *spec;
    int free;                  /* moves under the particles' forces */
    double c[3];               /* reference point, m */
    double Q[9];               /* orientation, world from the t = 0 frame */
    double V[3];               /* velocity of c, m/s (half-step during the force evaluation) */
    double W[3];               /* angular velocity, rad/s (likewise) */
    double L[3];               /* free: angular momentum about c, kg m^2/s */
    double mass;               /* free: kg */
    double Iinv0[9];           /* free: inverse inertia in the t = 0 frame, 1/(kg m^2) */
    double extent;             /* radius about c holding the shape, m (INFINITY: plane) */
    double F[3], T[3];         /* the particles' force and torque about c (last evaluation) */
    double F_old[3], T_old[3]; /* those of the evaluation before (trapezoidal work) */
    /* at the last search */
    double c_search[3], Q_search[9];
    double reach; /* largest |x - c| over the particles that could come in contact, m */
};

struct tlsph_rigid {
    size_t nb;
    struct tlsph_rigid_body *b; /* [nb] */
    double *radius;             /* contact radius R of each scene body's particles, m */
    double *stiffness;          /* their contact stiffness against a rigid body, N/m (N/m^2 2-D) */
    /* candidates: the particles of body k are cand[start[k] .. start[k+1]-1] */
    int64_t *start; /* [nb + 1] */
    int32_t *cand;
    size_t cap;
    double *x_search; /* particle positions at the last search, m [3n] */
    double *f;        /* each particle's rigid contact force, this evaluation, N [3n] */
    double *f_old;    /* the evaluation before, N [3n] */
    double skin;      /* m */
    double max_radius;
    double max_overlap; /* deepest delta / R since the stability contract looked */
    size_t active;      /* particle-body contacts in the last evaluation */
    int failed;         /* a search ran out of memory */
    long searches;        /* searches made (the first at setup included) */
    double phase_seconds; /* wall-clock in the rigid phase of the steps, s */
};

/* Searches again when the particles and bodies moved too far since the last
 * search (or when force is set).  0, or -1 out of memory. */
int tlsph_rigid_search(struct tlsph_model *m, struct tlsph_rigid *r, int force);
/* The signed distance (m) of x from body k's surface and the outward normal n
 * (world), by its shape (not for hot loops: one dispatch per call). */
double tlsph_rigid_distance(const struct tlsph_rigid_body *k, const double x[3], double n[3]);
/* The bodies' state at t = 0 (motion.c). */
void tlsph_rigid_create_motion(struct tlsph_model *m);
/* Body k's inverse inertia in the world now: Q Iinv0 Q^T. */
void tlsph_rigid_inverse_inertia(const struct tlsph_rigid_body *k, double out[9]);

#endif
