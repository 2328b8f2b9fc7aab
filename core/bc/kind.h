/* Boundary-condition kinds as a table of descriptors.
 *
 * A kind (fixed, velocity, wall, symmetry, body_force, pressure) lives whole in one file,
 * core/bc/<name>.c, which defines its descriptor; core/bc/registry.c lists the
 * descriptors, one row each.  The scene names a row by its "type"; the scene
 * parser (core/scene/parse_bcs.c), the step (core/bc/boundary.c), the module
 * list, the output and the gauges read only the descriptor, so adding a kind is
 * its file, its row, its schema entry (schemas/scene.schema.json) and its docs
 * (docs/scene.md); its key table is what tests/engine/scene_keys.sh compares
 * them with.
 *
 * Machinery shared by the kinds: selectors (core/bc/selector.h), planes
 * (core/bc/plane.h), velocity constraints and their impulses
 * (core/bc/impulse.h), particle groups and reactions (core/bc/groups.c),
 * surface area vectors (core/bc/surface.h).
 *
 * Energy account.  The work of the conditions on the bodies is booked in
 * m->energy.external_work (J), so that kinetic + internal + dissipated -
 * external work stays constant; each hook below says what it books.
 *
 * Hot loops: the step calls a hook once per condition; the hook runs its own
 * plain loop over its particles (no dispatch per particle). */
#ifndef TLSPH_BC_KIND_H
#define TLSPH_BC_KIND_H

#include <stddef.h>
#include <stdint.h>
#include <jansson.h>

#include "scene/keys.h"
#include "scene/scene.h"
#include "util/errors.h"

struct tlsph_model; /* core/run/model.h */
struct tlsph_group;

/* What a condition does to one velocity component of its group's particles. */
enum tlsph_bc_prescription {
    TLSPH_BC_FREE,     /* leaves it alone */
    TLSPH_BC_CONSTANT, /* holds it at one value for the whole run */
    TLSPH_BC_VARYING   /* makes it follow a function of time */
};

/* Longest "type" (a kind's name), with its NUL. */
#define TLSPH_BC_TYPE_SIZE 32

/* The first two rows of every kind's key table.  core/scene/parse_bcs.c reads
 * both before it knows the kind: "type" to find it, "name" (with the reader,
 * into bc->name; absent: bc<index>) so that a name is checked even when the type
 * is not valid. */
/* clang-format off */
#define TLSPH_BC_KEYS                                                                          \
    {.name = "type", .kind = TLSPH_KEY_STRING, .flags = TLSPH_KEY_REQUIRED | TLSPH_KEY_CALLER, \
     .size = TLSPH_BC_TYPE_SIZE, .description = "the kind of condition"},                      \
    {.name = "name", .kind = TLSPH_KEY_STRING, .flags = TLSPH_KEY_NAME, .size = TLSPH_NAME_MAX, \
     .offset = offsetof(struct tlsph_bc, name), .noun = "boundary condition name",             \
     .description = "unique among the boundary conditions; names its output series; "          \
                    "absent = bc<index>"}
/* clang-format on */

struct tlsph_bc_kind {
    const char *name;   /* as written in the scene: {"type": name, ...} */
    const char *module; /* its entry in the result's module list, "bc:<name>" */
    int carries_load;   /* its group's reaction is a support load: written as a time
                           series (core/io/fields.c) and usable by gauges */
    int reports_torque; /* a rigid surface with no particle group (a wall): its reaction
                           and its torque about bc->point (collected in g->torque_impulse
                           by its hooks) are written as the "walls" series */
    /* Every key its scene object accepts, at "/boundary_conditions/<i>" with the
     * kind's name as model: TLSPH_BC_KEYS, then the kind's own keys, which its
     * parse reads.  "Unknown field" messages list the rows in this order. */
    const struct tlsph_key_table *keys;

    /* Reads the kind's own keys from obj ("type" and "name" are done, bc->kind
     * set, unknown keys reported) into bc, reporting every problem under pointer.
     * In 2-D the z components of points and normals are ignored (zeroed), and a
     * z velocity or acceleration must be 0.  Returns 0 or -1. */
    int (*parse)(const json_t *obj, struct tlsph_scene *s, struct tlsph_bc *bc,
                 const char *pointer, struct tlsph_errors *err);

    /* Setup.  Writes the indices of the condition's particles, in increasing
     * order, to index (NULL: count only) and returns their number; called twice
     * (count, then fill).  NULL: the kind has no particle group (a wall acts on
     * whichever particle reaches it); otherwise selecting no particle is a scene
     * error. */
    size_t (*select)(const struct tlsph_model *m, struct tlsph_bc *bc, int32_t *index);

    /* Setup checks, after every group is selected (core/bc/contradictions.c):
     * what the condition prescribes for velocity component c (0..2) of its
     * group's particles (TLSPH_BC_CONSTANT: *value, m/s), so that no particle
     * gets two prescriptions of one component that can differ (the later
     * condition would silently win).  NULL: it prescribes nothing. */
    enum tlsph_bc_prescription (*prescribes)(struct tlsph_bc *bc, int c, double *value);
    /* Checks that need the particles at t = 0 (a wall: none behind it);
     * reports at pointer and returns -1, or 0.  NULL: none. */
    int (*check)(const struct tlsph_model *m, const struct tlsph_bc *bc, const char *pointer,
                 struct tlsph_errors *err);

    /* Setup, after select (pairs and correction matrices built): the kind's
     * per-particle data of group g (a pressure: each particle's reference area
     * vector), allocated with tlsph_alloc into g's fields and freed with the
     * model.  Reports at pointer and returns -1, or 0.  NULL: none. */
    int (*prepare)(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                   const char *pointer, struct tlsph_errors *err);

    /* The step's phases, in the order they come (core/run/integrate.c); NULL =
     * the kind does not act then.  Within a phase the conditions act in scene
     * order.  g is the condition's group; g->impulse (N s) collects the momentum
     * the support gives the bodies during the step. */

    /* After each half kick (and once at setup): imposes the kind's constraint on
     * the velocities, with prescribed values taken at time t (s).  Books the
     * constraint's momentum change in g->impulse and adds its work to *work (J),
     * which the caller adds to the external work once, after every condition:
     * the work of an impulse is the impulse times the prescribed velocity at the
     * middle of the step, t_mid (s) (counting the kinetic energy the reset
     * removes instead would book as external work the dt^2 |f|^2 / 4m each half
     * kick adds to a held particle).  A support that does not move (fixed,
     * symmetry, a wall holding a resting particle) does no work; a wall books
     * here the end of an arrival (core/bc/wall.c), for which the kick just
     * made is m->dt / 2 (m->dt is 0 at setup) with the forces m->p.f. */
    void (*constrain)(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                      double t, double t_mid, double *work);

    /* After the first kick's constraints, before the drift x += dt v (dt in s);
     * m->p.f still holds the forces of that kick.  Changes velocities so the
     * drift respects the condition (a wall stops particles on its plane), books
     * the change in g->impulse and its own work directly in
     * m->energy.external_work (a wall: the kinetic energy an arriving particle
     * loses down to the drift velocity, booked as negative work; the rest is
     * booked by its constrain hook). */
    void (*before_drift)(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                         double dt);

    /* During force evaluation, after the pair forces: adds the condition's
     * forces (N) to m->p.f and their power at the current (half-step)
     * velocities to *power (W); the caller books dt * power as external work.
     * (A kind whose force varies in time books instead, in its constrain hook,
     * the work of each half kick at the mean of the velocities before and
     * after it: a pressure.) */
    void (*force)(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                  double *power);

    /* At the end of the step, after the second kick's constraints and before
     * g->impulse becomes the reaction g->reaction = impulse / dt and is cleared.
     * Books any work it does directly in m->energy.external_work. */
    void (*end_step)(struct tlsph_model *m, struct tlsph_bc *bc, struct tlsph_group *g,
                     double dt);
};

/* The kind named name (as in the scene), or NULL. */
const struct tlsph_bc_kind *tlsph_bc_find(const char *name);

/* Writes the names of the kinds, in table order, into buf (size bytes): all
 * of them, or only those that carry load when load_only; each between quote,
 * separated by ", " except the last pair, which is separated by last_sep
 * ("a, b, c" or "'a', 'b' or 'c'").  For error messages. */
void tlsph_bc_names(char *buf, size_t size, int load_only, const char *quote,
                    const char *last_sep);

#endif
