/* The model object: particles, reference pairs, boundary groups, clocks and
 * diagnostics of one run.  There is no global mutable state in the engine:
 * every function takes the model it works on.
 *
 * Storage is structure-of-arrays.  Vectors are 3 doubles per particle and 3x3
 * tensors 9 doubles (row-major) even in 2-D, where the z components stay zero
 * (plane strain: F_zz = 1).  Symmetric tensors are 6 doubles in the order
 * xx xy xz yy yz zz.  Particles are ordered body by body, and within a body
 * along the reference cell list, so each body is one contiguous index range.
 *
 * Units: SI (m, kg, s, Pa, J). */
#ifndef TLSPH_MODEL_H
#define TLSPH_MODEL_H

#include <stddef.h>
#include <stdint.h>

#include "io/measures.h"
#include "scene/scene.h"

struct tlsph_crack_model; /* sph/crack_treatment.h */
struct tlsph_contact;     /* contact/state.h: the contact phase's state */
struct tlsph_rigid;       /* rigid/state.h: the rigid bodies' state */
struct tlsph_links;       /* sph/virtual_links.h: the virtual links' state */
struct tlsph_crack_surface; /* crack/crack_surface.h: crack facets */
struct tlsph_fibres;        /* crack/fibre.h: a thin body's fibres */
struct tlsph_crack_driver;  /* crack/crack_driver.h: growing cracks */

struct tlsph_particles {
    size_t n;
    size_t cap;       /* particles allocated in every array (>= n; run/particles_grow.h) */
    int64_t *id;      /* stable id: order of generation, body by body */
    int32_t *body;    /* index into scene->bodies */
    double *X;        /* reference position, m [3n] */
    double *x;        /* current position, m [3n] */
    double *v;        /* velocity, m/s [3n] (synchronous, time t) */
    double *f;        /* total force, N [3n] */
    double *vol0;     /* reference volume, m^3 (m^2 x 1 m in 2-D) */
    double *mass;     /* kg */
    double *h;        /* smoothing length, m (support radius = 2h) */
    double *Linv;     /* inverse (or safe pseudo-inverse) of the correction matrix L_i [9n] */
    double *F;        /* deformation gradient, 1 [9n] */
    double *Fdot;     /* its rate at the half step, 1/s [9n] */
    double *P_tilde;  /* P_i L_i^-T: first Piola-Kirchhoff stress folded with the correction, Pa [9n] */
    double *sigma;    /* Cauchy stress, Pa [6n] */
    double *e;        /* specific internal energy, J/kg */
    double *f_hourglass;  /* hourglass-control force of the last evaluation, N [3n]; only with hourglass */
    double *f_viscous;    /* artificial-viscosity force of the last evaluation, N [3n]; only with viscosity */

    /* Plastic history (core/material/material_point.h); allocated only when some material
     * of the scene is plastic (NULL otherwise).  Zero for particles of elastic bodies. */
    double *eps_p;          /* equivalent plastic strain, 1 */
    double *plastic_strain; /* plastic logarithmic strain in the unrotated frame, 1 [6n] */
    double *eps_p_rate;     /* equivalent plastic strain rate of the last step, 1/s */
    double *yield_stress;   /* cached static flow stress at the current state, Pa (0 = unknown) */
    double *hg_scale;       /* hourglass spring modulus / E of the last step, 1 (only with the
                               "tangent" hourglass stiffness and plasticity; NULL otherwise) */
    /* Temperature, K; allocated only when some material has thermal coupling.
     * NaN for particles whose material has no temperature. */
    double *T;
    /* Each particle's own lattice spacing, m; allocated only when some body
     * refines its spacing ("refine", core/scene/graded.c; NULL otherwise: the
     * body's spacing).  h = support_factor / 2 x this. */
    double *spacing;

    /* Damage (core/material/damage/damage.h); allocated only when some material of the
     * scene has a damage model (NULL otherwise), zero for the others. */
    double *damage;         /* D in [0, 1]; 1 = failed, 1 */
    double *damage_init;    /* damage-initiation variable D_init, 1 (GTN: f / f_c) */
    /* Void volume fraction f, 1; allocated only when some material's damage model
     * needs it (TLSPH_DAMAGE_FIELD_VOID_FRACTION, material/damage/damage.h: GTN),
     * zero for the others. */
    double *void_fraction;
    /* The Gurson family (TLSPH_DAMAGE_FIELD_POROUS, material/damage/porous.h) only:
     * f* (eq. 45) and the parts of f nucleated and grown by shear so far, 1 */
    double *void_fstar, *void_nucleated, *void_shear;
    /* Damage-aware treatment only (sph/damage_aware.h): sum_j V_j sum_steps D_j
     * (du_j - du_i) (x) grad W_i, the part of the displacement gradient (before
     * L_i^-1) that damaged neighbours did not transmit, so that F follows eq. 34 [9n]. */
    double *crack_gradient;
    /* Crack growth only (crack/split_carry.h): the part G_i of F carried through
     * the splits, F_i = G_i + [sum_j ...] L_i^-1 G_i, where p.Linv holds L_i^-1 G_i;
     * the identity until a split rebuilds i's support, 1 [9n].  NULL otherwise. */
    double *F_carry;
};

/* Reference neighbour pairs in CSR form, built once: the pairs of i are
 * start[i] .. start[i+1]-1.  The list is symmetric (j in i's list <=> i in j's). */
struct tlsph_pairs {
    size_t npairs;
    int64_t *start;   /* [n+1] */
    int32_t *j;       /* neighbour index */
    double *dw;       /* W'(|X_ij|)/|X_ij|, 1/m^(d+2): grad W_i(X_ij) = dw * (X_j - X_i) */
    double *w;        /* W(|X_ij|), 1/m^d (hourglass control only; NULL otherwise) */
};

/* One boundary condition's particle group and its running totals. */
struct tlsph_group {
    size_t n;
    int32_t *index;           /* particle indices */
    double impulse[3];        /* constraint impulse accumulated during the current step, N s */
    double reaction[3];       /* force exerted by the support on the group (last step), N */
    /* Walls (kinds with reports_torque): the angular impulse about the condition's
     * point collected during the current step, N m s, and its rate over the last
     * step, the torque the support exerts about that point, N m. */
    double torque_impulse[3];
    double torque[3];
    double displacement[3];   /* mean displacement of the group, m */
    double mass;              /* kg */
    /* Kinds that load a surface (pressure): each particle's reference area vector
     * N dA (outward), m^2 (m per metre of thickness in 2-D) [3n]; NULL otherwise. */
    double *area;
    double *load;             /* and the force of the last evaluation, N [3n] */
};

struct tlsph_energy {
    double kinetic;           /* J */
    double internal;          /* stored (strain + thermal) energy, J */
    double external_work;     /* work done on the body by boundary conditions and body forces, J */
    double hourglass;         /* work done against hourglass-control forces, J */
    double viscous;           /* work done against artificial-viscosity forces, J */
    double contact;           /* work done against contact forces: stored in the overlaps
                                 plus dissipated (0 without contact), J */
    double plastic_work;      /* plastic dissipation (part of internal), J */
    double damage_work;       /* energy released by damage growth (part of internal), J */
    double initial;           /* kinetic + internal at t = 0, J */
    double scale;             /* largest |term| seen so far, J: the drift reference */
};

/* Why a run was stopped by the stability contract. */
struct tlsph_diagnostic {
    long step;
    double time;
    char quantity[64];        /* "nan", "det_F", "energy_balance", "speed", ... */
    double value;             /* the offending value */
    double limit;             /* the bound it crossed */
    size_t nids;
    int64_t ids[16];          /* first offending particle ids */
    char message[256];
};

#define TLSPH_MAX_MODULES 32

struct tlsph_model {
    struct tlsph_scene scene;   /* owned */
    int dim;
    struct tlsph_particles p;
    struct tlsph_pairs pairs;
    size_t *body_begin, *body_end; /* particle ranges per body */
    struct tlsph_group *groups;    /* one per scene->bcs entry (empty for walls: they have no group) */
    struct tlsph_measures measures; /* gauges and sections of scene.output */
    const struct tlsph_crack_model *crack; /* how damage enters the approximation, chosen
                                              once at setup (intact without damage) */
    struct tlsph_contact *contact;  /* contact between bodies (contact/contact.h); NULL
                                       when the scene has none: nothing allocated or run */
    struct tlsph_rigid *rigid;      /* rigid bodies (rigid/rigid.h); NULL without
                                       "rigid_bodies": nothing allocated or run */
    struct tlsph_links *links;      /* link damage (sph/virtual_links.h); NULL unless the
                                       treatment is virtual_links */
    struct tlsph_crack_surface *crack_surface; /* the scene's "cracks" as facets
                                       (crack/precrack.h), owned; NULL without cracks:
                                       nothing allocated or run.  A growing crack adds
                                       its facets here. */
    struct tlsph_fibres *fibres;    /* [nbodies]: each thin body's fibres (crack/fibre.h;
                                       empty for the others), owned; NULL when no body
                                       has a "thickness_axis" */
    struct tlsph_crack_driver *crack_driver; /* growing cracks (crack/crack_driver.h),
                                       owned; NULL without "crack_growth": nothing
                                       allocated or run */

    /* run state */
    long step;
    double t, dt;
    /* The frame schedule, kept by the run loop (run.c): a step that would pass
     * more than one frame time ends at the next one instead (tlsph_next_dt).
     * frame_interval 0 = no schedule (a model stepped without tlsph_run). */
    double frame_interval;        /* end / frames, s */
    double next_frame_time;       /* the first frame time not yet written, s */
    double dt_cfl;                /* stable step estimate of the last force evaluation (s), before the CFL factor */
    double max_wave_speed;        /* largest P-wave speed of the last evaluation, m/s */
    size_t inverted;              /* particles with det F <= 0 or non-finite in the last evaluation */
    int64_t first_inverted_id;    /* id of one of them */
    double min_detF;              /* smallest det F of the last evaluation */
    size_t return_failures;       /* point updates whose return mapping did not converge, whole run */
    long long plastic_point_steps; /* return mappings that found plastic flow, whole run */
    long long return_iterations;  /* their residual evaluations, whole run (cost of plasticity) */
    double material_seconds;      /* wall-clock in the constitutive phase, whole run, s */
    int64_t first_return_failure_id;
    size_t failed;                /* particles with D = 1 (after the last evaluation) */
    struct tlsph_energy energy;

    /* setup statistics */
    size_t deficient_supports;    /* particles whose L_i needed the safe inverse */
    double max_L_condition;       /* largest condition number of L_i accepted */
    size_t isolated;              /* particles with no neighbour at all */
    size_t cut_pairs;             /* reference pairs the scene's cracks removed (0 without) */

    /* modules (effects) active in this run, for the metadata */
    const char *modules[TLSPH_MAX_MODULES];
    int nmodules;

    /* cost record */
    double wall_seconds;
    size_t bytes_allocated;       /* engine arrays, bytes */
};

/* Particle i's lattice spacing, m: its own when its body is graded, else its
 * body's. */
static inline double tlsph_particle_spacing(const struct tlsph_model *m, size_t i)
{
    return m->p.spacing ? m->p.spacing[i] : m->scene.bodies[m->p.body[i]].spacing;
}

/* Takes ownership of *scene (leaves it empty).  Generates particles, builds pairs
 * and the correction matrices, selects groups and modules. Returns 0 or -1 with err. */
int tlsph_model_create(struct tlsph_scene *scene, struct tlsph_model **out,
                       struct tlsph_errors *err);
void tlsph_model_free(struct tlsph_model *m);

/* Advances one time step. */
void tlsph_model_step(struct tlsph_model *m);
/* Stability contract; returns 0 when healthy, -1 and fills d otherwise. */
int tlsph_model_check(struct tlsph_model *m, struct tlsph_diagnostic *d);
/* Before a step: simulated time must advance (the next step positive and
 * t + dt > t) and, without time.max_steps, the steps taken plus those the rest
 * of the run needs at the stable step (tlsph_stable_dt) must stay within TLSPH_MAX_STEPS
 * (scene/limits.h).  Returns 0, or -1 with d (quantity "time_step", the
 * particles that limit the step). */
int tlsph_time_check(struct tlsph_model *m, struct tlsph_diagnostic *d);
/* The output writer refused a value that is not finite (dataset, value, ids:
 * struct tlsph_output_refusal, io/output/output.h): the stability contract's
 * diagnostic when it finds something, else one for the refused value
 * (quantity "non_finite_output"). */
void tlsph_refusal_diagnostic(struct tlsph_model *m, const char *dataset, double value,
                              const int64_t *ids, size_t nids, struct tlsph_diagnostic *d);
/* Total linear momentum (particles and free rigid bodies), kg m/s. */
void tlsph_model_momentum(const struct tlsph_model *m, double out[3]);
/* kinetic + internal + hourglass + viscous + contact - external work - initial energy, J:
 * 0 when energy is conserved (the stability contract bounds it). */
double tlsph_energy_balance(const struct tlsph_energy *e);

/* Tracked allocation helpers (count bytes into m->bytes_allocated). */
void *tlsph_alloc(struct tlsph_model *m, size_t count, size_t size);

#endif
