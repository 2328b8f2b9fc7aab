/* Rigid bodies (issue 14; docs/contact.md "Rigid bodies").
 *
 * A scene's "rigid_bodies" array holds surfaces the particles cannot pass: a
 * plane, a box, a sphere, a cylinder with its end caps or a cone with its base
 * cap, each moving as prescribed (velocity and angular velocity as
 * expressions of t) or freely (mass and inertia, driven by the particles'
 * contact forces).  A scene without the array allocates and runs nothing here
 * (m->rigid is NULL).
 *
 * Frames.  Every shape is described in its own frame, origin at its reference
 * point c (the centroid; a plane: its point) and local z along its axis (a
 * plane's normal, a cylinder's or cone's axis; a box: its rotated z edge).
 * The columns of `axes` are the local axes in the world at t = 0; the body's
 * orientation Q (world from reference, Q = I at t = 0) carries them along, so
 * a particle at x sits at y = (Q axes)^T (x - c) in the shape's frame.
 *
 * 2-D (plane strain, unit thickness): particles lie in z = 0 and every shape
 * is its section by that plane: a sphere is a disc, a cylinder (axis in the
 * plane) a rectangle 2r x length, a cone (axis in the plane) a triangle, a
 * box (rotation about z only) a rectangle; z components of points are
 * ignored, an axis must have an in-plane part, and masses, forces and inertia
 * are per metre of thickness.
 *
 * Units: SI.  Ownership: the scene owns its specs (tlsph_rigid_specs_free);
 * the model owns its state (tlsph_rigid_free). */
#ifndef TLSPH_RIGID_H
#define TLSPH_RIGID_H

#include <stddef.h>
#include <stdint.h>
#include <jansson.h>

#include "scene/keys.h"
#include "scene/limits.h"
#include "util/errors.h"
#include "util/expr.h"

struct tlsph_model; /* run/model.h */
struct tlsph_scene; /* scene/scene.h */

/* Which compiled contact loop a shape uses (core/rigid/contact.c). */
enum tlsph_rigid_shape_id {
    TLSPH_RIGID_PLANE,
    TLSPH_RIGID_BOX,
    TLSPH_RIGID_SPHERE,
    TLSPH_RIGID_CYLINDER,
    TLSPH_RIGID_CONE,
    TLSPH_RIGID_SHAPES
};

enum tlsph_rigid_motion { TLSPH_RIGID_PRESCRIBED, TLSPH_RIGID_FREE };

/* One entry of "rigid_bodies", validated. */
struct tlsph_rigid_spec {
    char name[TLSPH_NAME_MAX];
    const struct tlsph_rigid_shape *shape;
    double centre[3]; /* reference point c at t = 0 (centroid; plane: its point), m */
    double axes[9];   /* the shape frame's axes at t = 0, columns (row-major 3x3), 1 */
    /* the shape's sizes (meaning fixed by the shape, shapes.h), m */
    double size[3];
    double friction; /* Coulomb coefficient mu, 1 */
    double damping;  /* fraction zeta of the critical damping of a particle's contact, 1 */

    enum tlsph_rigid_motion motion;
    /* prescribed: velocity of c (m/s) and angular velocity (rad/s), expressions
     * of t; a component not given is 0 (set[] = 0) */
    struct tlsph_expr velocity[3], angular_velocity[3];
    int velocity_set[3], angular_set[3];
    /* free: initial velocity and angular velocity, the mass (kg; kg/m in 2-D)
     * and the inertia tensor about c in the t = 0 frame (kg m^2; kg m^2/m in
     * 2-D, where only zz is used) */
    double v0[3], w0[3];
    double mass;
    double inertia[9];
};

/* A shape: one file each (core/rigid/<name>.c), one row in core/rigid/registry.c. */
struct tlsph_rigid_shape {
    const char *name; /* as in the scene: "shape": {"type": name, ...} */
    enum tlsph_rigid_shape_id id;
    int has_volume; /* 0: a plane (a half-space), which cannot move freely */
    /* its keys at "/rigid_bodies/<i>/shape": TLSPH_KEY_MODEL_TYPE, then its own */
    const struct tlsph_key_table *keys;
    /* Reads obj into r's centre, axes and size (dimension 2 or 3); reports
     * under pointer; 0 or -1. */
    int (*parse)(const json_t *obj, int dimension, struct tlsph_rigid_spec *r, const char *pointer,
                 struct tlsph_errors *err);
    /* Volume (m^3; area x 1 m in 2-D) and the inertia about c per unit mass in
     * the shape's frame, diagonal (m^2; in 2-D only [2], about z). */
    double (*mass_properties)(const struct tlsph_rigid_spec *r, int dimension, double inertia[3]);
    /* Radius of a sphere about c holding the shape, m (INFINITY: a plane). */
    double (*extent)(const struct tlsph_rigid_spec *r);
};

/* Key rows of the shapes' and motions' tables: a length > 0 read by the key
 * reader into size[slot]; an optional vector read by the caller. */
/* clang-format off */
#define TLSPH_RIGID_LENGTH(key, slot, what)                                                     \
    {.name = (key), .kind = TLSPH_KEY_NUMBER, .flags = TLSPH_KEY_REQUIRED,                      \
     .range = {0.0, 0.0, JC_OPEN, JC_NONE}, .unit = "m", .offset = TLSPH_PARAM(slot),          \
     .description = (what)}
#define TLSPH_RIGID_VECTOR(key, unit_, what)                                                    \
    {.name = (key), .kind = TLSPH_KEY_ARRAY, .flags = TLSPH_KEY_CALLER, .unit = (unit_),        \
     .description = (what)}
/* A shape's descriptor from its file's static table, parse, mass_properties
 * and extent: tlsph_rigid_<id>, named "id". */
#define TLSPH_RIGID_SHAPE(id_, ID, volume)                                                      \
    const struct tlsph_rigid_shape tlsph_rigid_##id_ = {                                        \
        .name = #id_, .id = (ID), .has_volume = (volume), .keys = &table, .parse = parse,       \
        .mass_properties = mass_properties, .extent = extent}
/* clang-format on */

/* For the shapes' parse: reports the keys of obj that t does not list, reads
 * the point at key into point (m) and t's lengths into r->size; 0, or -1
 * after an error (all of them reported). */
int tlsph_rigid_read_shape(const json_t *obj, const struct tlsph_key_table *t, const char *key,
                           double point[3], struct tlsph_rigid_spec *r, const char *pointer,
                           struct tlsph_errors *err);

/* The shape named name, or NULL; the names in table order. */
const struct tlsph_rigid_shape *tlsph_rigid_shape_find(const char *name);
const char *tlsph_rigid_shape_names(void);

/* The motion types, for the key tables: {"type": name, ...} at
 * "/rigid_bodies/<i>/motion". */
struct tlsph_rigid_motion_type {
    const char *name;
    const struct tlsph_key_table *keys;
};
const struct tlsph_rigid_motion_type *tlsph_rigid_motion_find(const char *name);
const char *tlsph_rigid_motion_names(void);
/* Reads "motion" of the entry obj (absent: prescribed at rest) into r (shape
 * parsed first: a free body's mass properties come from it); parameters and
 * dimension from s.  0 or -1 with errors under pointer ("/rigid_bodies/<i>"). */
int tlsph_rigid_parse_motion(const json_t *obj, const struct tlsph_scene *s,
                             struct tlsph_rigid_spec *r, const char *pointer,
                             struct tlsph_errors *err);

/* Releases the expressions of n specs and the array. */
void tlsph_rigid_specs_free(struct tlsph_rigid_spec *r, size_t n);

/* ------------------------------------------------------------------ engine */

/* Setup, after the particles exist: the bodies' state at t = 0, the first
 * search, and the check that no particle overlaps a rigid body (reported at
 * /rigid_bodies/<k>).  0, or -1 with err. */
int tlsph_rigid_create(struct tlsph_model *m, struct tlsph_errors *err);
void tlsph_rigid_free(struct tlsph_model *m);

/* Half kick of the free bodies (momentum and angular momentum += half x the
 * force and torque of the last evaluation), then the prescribed bodies'
 * velocities at time t (s). */
void tlsph_rigid_kick(struct tlsph_model *m, double half, double t);
/* Moves every body over the step dt (s) starting at t: free bodies with their
 * half-step velocities, prescribed ones with theirs at t + dt/2; the rotation
 * is exact for the angular velocity held over the step (core/rigid/motion.c). */
void tlsph_rigid_drift(struct tlsph_model *m, double t, double dt);
/* The contact phase against the rigid bodies at the current positions and
 * half-step velocities (dt the step that led there, 0 at setup): adds the
 * forces to m->p.f, collects each body's reaction, lowers m->dt_cfl, and books
 * the work: the interface's (stored + dissipated, trapezoidal) into
 * m->energy.contact, the prescribed bodies' into m->energy.external_work. */
void tlsph_rigid_forces(struct tlsph_model *m, double dt);
/* Kinetic energy of the free bodies (translation + rotation), J. */
double tlsph_rigid_kinetic_energy(const struct tlsph_model *m);
/* Linear momentum of the free bodies, kg m/s [3] (added to out). */
void tlsph_rigid_momentum(const struct tlsph_model *m, double out[3]);

/* Output and checks: body k's state (k < scene.nrigid). */
struct tlsph_rigid_report {
    double position[3];         /* its reference point c, m */
    double velocity[3];         /* of c, m/s */
    double angular_velocity[3]; /* rad/s */
    double force[3];            /* what the particles exert on it (last evaluation), N */
    double torque[3];           /* of that force about c, N m */
    double angular_momentum[3]; /* about c (free bodies; 0 for prescribed), kg m^2/s */
    double orientation[9];      /* Q, world from reference, 1 */
};
void tlsph_rigid_report(const struct tlsph_model *m, size_t k, struct tlsph_rigid_report *out);

/* The deepest overlap / R of a particle on a rigid body in any evaluation
 * since the last call, which starts the next watch; *id and *body the
 * particle (id) and the rigid body (index) overlapping most now, looked for
 * only when the overlap passed TLSPH_CONTACT_MAX_OVERLAP (else -1).  The
 * stability contract stops a run past that bound (rigid_penetration). */
double tlsph_rigid_take_overlap(struct tlsph_model *m, int64_t *id, long *body);
/* What the rigid-body phase cost so far: searches (the first at setup
 * included), and the wall-clock seconds of the phase, searches included. */
struct tlsph_rigid_cost {
    long searches;
    double phase_seconds;
};
struct tlsph_rigid_cost tlsph_rigid_cost(const struct tlsph_model *m);

/* Particles in contact with a rigid body in the last evaluation. */
size_t tlsph_rigid_active(const struct tlsph_model *m);
/* 1 when a search ran out of memory (the run must stop: the stability
 * contract reports it as "rigid_search"), else 0. */
int tlsph_rigid_failed(const struct tlsph_model *m);

#endif
