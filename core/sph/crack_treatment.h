/* Crack treatments: how damage enters the particle approximation (paper 000
 * §3.1).  A table of descriptors in sph/crack_treatment.c; the model picks one
 * row once at setup (tlsph_crack_select) and keeps it in m->crack:
 *   intact          no material damages: the plain eqs. 26-27 and 31
 *   damage_aware    eqs. 33-35, sph/damage_aware.h
 *   pseudo_spring   kernels scaled per pair, sph/pseudo_spring.h (comparison only)
 *   virtual_links   paper 001: immediate neighbours, damage per link, sph/virtual_links.h
 *                   (selected by the scene alone: its criteria are the links')
 * The scene's /discretization/damage/treatment names a row (parsed into enum
 * tlsph_crack_treatment, scene.h).
 *
 * The pair loops stay specialised at compile time: a row's `variant` indexes
 * the variant tables of kinematics.c (one gather pass per variant) and
 * forces.c (one force loop per variant and optional term), and those loops
 * call the treatment's per-pair pieces, static inline functions in its header,
 * with the variant as a constant, so the choice folds away at compile time:
 * no pair loop carries a function pointer or a branch on the treatment.
 *
 * A new treatment provides: its header with the per-pair pieces (at least
 * its force weights, struct tlsph_pair_weights) and its .c with its row; a
 * value of enum tlsph_approximation; its entries in the variant tables of
 * kinematics.c and forces.c, and its case in forces.c's pair_weights; and its
 * row in crack_treatment.c (plus the scene's name for it in scene.h and
 * core/scene/parse_damage.c). */
#ifndef TLSPH_CRACK_TREATMENT_H
#define TLSPH_CRACK_TREATMENT_H

#include "scene/scene.h"
#include "util/errors.h"

struct tlsph_model;

/* The compile-time variant of the pair loops. */
enum tlsph_approximation {
    TLSPH_APPROX_INTACT,
    TLSPH_APPROX_DAMAGE_AWARE,
    TLSPH_APPROX_PSEUDO_SPRING,
    TLSPH_APPROX_VIRTUAL_LINKS,
    TLSPH_APPROX_COUNT
};

/* Per-particle arrays a treatment needs beyond D and D_init (model.h). */
#define TLSPH_CRACK_FIELD_GRADIENT 1u /* p.crack_gradient: the untransmitted gradient, eq. 34 */

struct tlsph_crack_model {
    const char *name;   /* as written in the scene ("intact" for the row without damage) */
    const char *module; /* "approximation:<name>" for the run's list of modules; NULL: none */
    enum tlsph_crack_treatment scene; /* the scene value that selects the row (not read for
                                         the intact row) */
    enum tlsph_approximation variant; /* which specialised pair loops run */
    unsigned fields;    /* TLSPH_CRACK_FIELD_* arrays to allocate */
    /* Optional hooks of a treatment with state of its own (NULL: none), none of
     * them in a pair loop: setup runs once after the reference pairs are built
     * and before the correction matrices (it may narrow the pairs: m->pairs.j
     * and start are compacted in place), update once per force evaluation
     * after the stress update (run/integrate.c), release at tlsph_model_free
     * (also after a failed setup). */
    int (*setup)(struct tlsph_model *m, struct tlsph_errors *err);
    void (*update)(struct tlsph_model *m);
    void (*release)(struct tlsph_model *m);
};

/* The row for this scene: virtual_links when the scene names it (its links
 * carry the damage; validation refuses material damage models with it), else
 * intact when no material has a damage model, else the scene's treatment.
 * Never NULL. */
const struct tlsph_crack_model *tlsph_crack_select(const struct tlsph_scene *s);

/* Weights of one pair's stress force f_i += s [w_i P~_i + w_j P~_j] (X_j - X_i)
 * and of its stabilisation (hourglass and viscous forces times stab), from the
 * damages of both particles. */
struct tlsph_pair_weights {
    double wi, wj, stab;
};

#endif
