/* Contact between bodies (issue 14; docs/contact.md).
 *
 * A scene with a "contact" block (and at least two bodies) gets a contact
 * phase in its force evaluation, after the pair forces: a search in the
 * current configuration finds the particles of different bodies that may
 * touch, and a contact law pushes every overlapping pair apart along the line
 * of their centres.  A scene without the block allocates nothing here and the
 * step runs no contact code (m->contact is NULL).
 *
 * Laws are a table of descriptors (core/contact/registry.c), one file each:
 * penalty.c (the default: a Hertz-type penalty with damping, no tuning factor)
 * and pinball.c (paper 001 eqs. 31-35).  A law's per-pair physics is a
 * static inline function in its header, which core/contact/forces.c compiles
 * into its own pair loop: the loop is chosen once per evaluation, never per
 * pair.
 *
 * Forces: the force on i from j is -F_ij (x_j - x_i)/r_ij with F_ij >= 0 a
 * function symmetric in i and j, evaluated with the same operations from
 * either side (commutative sums and products only), so f_ij = -f_ji exactly
 * and momentum is conserved to round-off.
 *
 * Energy: the work done against the contact forces is booked in
 * m->energy.contact with the trapezoid of the old and new force at the
 * half-step velocity, the rule the kicks apply to kinetic energy (as for the
 * hourglass and viscous forces): while bodies touch it holds the energy stored
 * in the overlaps, after they part what the contact dissipated.
 *
 * Time step: each law gives the tangent stiffness k of a pair in contact; the
 * evaluation's stable step estimate becomes min(dt_cfl, sqrt(m_eff / k)) over
 * the pairs in contact, m_eff = m_i m_j / (m_i + m_j): 1/omega of the pair's
 * oscillator, half its critical step, since the contact spring acts beside
 * the particles' own bulk springs.
 *
 * Units: SI.  In 2-D (plane strain, unit thickness) masses and forces are per
 * metre of thickness. */
#ifndef TLSPH_CONTACT_H
#define TLSPH_CONTACT_H

#include <stddef.h>
#include <stdint.h>
#include <jansson.h>

#include "scene/keys.h"
#include "scene/scene.h"
#include "util/errors.h"

struct tlsph_model; /* run/model.h */

/* Which compiled pair loop a law uses (core/contact/forces.c). */
enum tlsph_contact_variant {
    TLSPH_CONTACT_PENALTY_LINE,
    TLSPH_CONTACT_PENALTY_POINT,
    TLSPH_CONTACT_PINBALL,
    TLSPH_CONTACT_VARIANTS
};

/* A body's constants for the pair laws, set once at setup by the law. */
struct tlsph_contact_body {
    double radius; /* contact radius R of its particles, m */
    double a, b;   /* meaning fixed by the law (penalty: a = (1 - nu^2)/E, 1/Pa) */
};

struct tlsph_contact_law {
    const char *name;   /* as written in the scene: "contact": {"law": {"type": name}} */
    const char *module; /* its entry in the result's module list */
    /* the pair loop for this scene's settings (s->contact) */
    enum tlsph_contact_variant (*variant)(const struct tlsph_scene *s);
    /* its parameters, at "/contact/law" with the law's name as model: a
     * TLSPH_KEY_MODEL_TYPE row, then one row per parameter into params */
    const struct tlsph_key_table *keys;
    /* Reads obj (absent: NULL, the defaults) into c->params under pointer;
     * 0 or -1 with err. */
    int (*parse)(const json_t *obj, struct tlsph_contact_settings *c, const char *pointer,
                 struct tlsph_errors *err);
    /* The constants of body b's particles (its material, spacing, smoothing
     * length 0.5 support_factor spacing). */
    void (*body)(const struct tlsph_scene *s, size_t b, struct tlsph_contact_body *out);
};

/* The law named name, or NULL; the names in table order, "penalty, pinball". */
const struct tlsph_contact_law *tlsph_contact_find(const char *name);
const char *tlsph_contact_names(void);
/* The default law (a "contact" block without "law"). */
const struct tlsph_contact_law *tlsph_contact_default(void);

/* The validation's estimate of the contact step, before any particle exists
 * (estimate.c): the smallest sqrt(m* / k) of two particles of bodies that
 * can meet, at the deepest overlap the stability contract accepts; s, before
 * the CFL factor; INFINITY without contact.  pair: the two bodies (a <= b). */
double tlsph_contact_step_estimate(const struct tlsph_scene *s, size_t pair[2]);

/* Setup (after the particles exist): per-body constants, the first search.
 * 0, or -1 with err (out of memory). */
int tlsph_contact_create(struct tlsph_model *m, struct tlsph_errors *err);
void tlsph_contact_free(struct tlsph_model *m);

/* The contact phase of a force evaluation at the current positions and
 * half-step velocities, dt the step that led there (0 at setup): searches again
 * when some particle moved more than half the skin since the last search, adds
 * the contact forces to m->p.f, lowers m->dt_cfl to the contacts' stable step,
 * and returns their power at the half-step velocities (trapezoidal, W); the
 * caller books -dt x power into m->energy.contact. */
double tlsph_contact_forces(struct tlsph_model *m, double dt);

/* What the contact phase cost so far (wall-clock, s). */
struct tlsph_contact_cost {
    long searches;         /* searches made (the first at setup included) */
    double search_seconds; /* in the searches */
    double phase_seconds;  /* in the contact phase of the steps, searches included */
};
struct tlsph_contact_cost tlsph_contact_cost(const struct tlsph_model *m);

/* The contact force on body b from the other bodies in the last evaluation,
 * N (N/m in 2-D) [3]: the sum of its particles' contact forces. */
void tlsph_contact_body_force(const struct tlsph_model *m, size_t b, double out[3]);

/* Body pairs with a contact-force series: k < tlsph_contact_pairs(m), the
 * pairs (a, b), a < b, in scene order; none when there would be more than
 * TLSPH_MAX_CONTACT_PAIR_SERIES (scene/limits.h).  The name "<a>--<b>", or
 * NULL when that is not a valid name unique among the bodies and pairs (then
 * the pair has no series).  The force on body a from body b in the last
 * evaluation, N (N/m in 2-D) [3]; on b it is the opposite. */
size_t tlsph_contact_pairs(const struct tlsph_model *m);
const char *tlsph_contact_pair_name(const struct tlsph_model *m, size_t k);
void tlsph_contact_pair_force(const struct tlsph_model *m, size_t k, double out[3]);

/* Pairs in contact (overlapping) in the last evaluation. */
size_t tlsph_contact_active(const struct tlsph_model *m);
/* Searches made so far (the first at setup included). */
long tlsph_contact_searches(const struct tlsph_model *m);
/* Candidate pairs of the current search (each pair counted from both sides). */
size_t tlsph_contact_candidates(const struct tlsph_model *m);
/* The deepest overlap of a pair relative to its contact distance,
 * (R_i + R_j - r) / (R_i + R_j), reached in any evaluation since the last
 * call, which starts the next watch.  The stability contract stops a run
 * whose overlap passed TLSPH_CONTACT_MAX_OVERLAP (scene/limits.h): particles
 * that deep are about to pass through each other. */
double tlsph_contact_take_overlap(struct tlsph_model *m);
/* The ids of the pair of candidates overlapping most now (-1 when none). */
void tlsph_contact_deepest_pair(const struct tlsph_model *m, int64_t ids[2]);

/* 1 when a search ran out of memory (the run must stop: the stability
 * contract reports it as "contact_search"), else 0. */
int tlsph_contact_failed(const struct tlsph_model *m);

#endif
