/* Damage and failure models (paper 000 §5).  One file per model, one row per
 * model in material/damage/registry.c; a material names a row:
 *   "damage": {"type": name, ...model parameters, "evolution": {"factor": 10}}
 *
 * Two variables per particle: the damage-initiation variable D_init (0 at the
 * start, damage starts when it reaches 1) and the damage D in [0, 1] (1 =
 * failed: the particle carries no stress).  An initiation model (Cockcroft-
 * Latham, Johnson-Cook) says how much D_init grows in a step of plastic flow;
 * the evolution law (material/damage/evolution.c, eq. 45) turns D_init into D.
 *
 * Damage couples into the constitutive update (core/material/material_point.c): the
 * deviatoric stress and the flow stress carry (1 - D) (eq. 38, 2G(1 - D)),
 * the tensile pressure carries (1 - D) (eq. 37), and the criteria read the
 * effective (undamaged-matrix) stress.  It couples into the approximation
 * through the crack treatment (core/sph/crack_treatment.h; eqs. 33-35 in
 * core/sph/damage_aware.h).
 *
 * A porous-plasticity model (GTN) is a yield surface rather than a
 * criterion: it brings its own point update, initial state and per-particle
 * fields through the hooks below, and sets D itself.
 *
 * A new model provides, in its own file(s), a descriptor tlsph_damage_<name>
 * with name, module, parse, and either initiation (a criterion) or
 * point_update (porous, with porous = 1), plus the optional hooks; and one row
 * ROW(<name>) in registry.c's DAMAGE_MODELS (which also makes the list of
 * accepted names).  Nothing outside this folder names a model.
 *
 * Units: SI (Pa, 1/s, K). */
#ifndef TLSPH_DAMAGE_H
#define TLSPH_DAMAGE_H

#include <jansson.h>
#include <math.h>

#include "util/errors.h"
#include "scene/scene.h"

struct tlsph_point_kinematics; /* material/material_point.h */
struct tlsph_point_state;
struct tlsph_point_result;

/* Per-particle arrays a model needs beyond D and D_init (run/model.h). */
#define TLSPH_DAMAGE_FIELD_VOID_FRACTION 1u /* p.void_fraction: the state's void_fraction */
/* p.void_fstar, p.void_nucleated, p.void_shear: the Gurson family's (porous.h) */
#define TLSPH_DAMAGE_FIELD_POROUS 2u

/* Most extra module labels one material's damage model reports. */
#define TLSPH_DAMAGE_MAX_MODULES 4

/* What an initiation criterion sees of one step of plastic flow at a point. */
struct tlsph_damage_step {
    double deps_p;      /* equivalent plastic strain increment of the step (> 0), 1 */
    double rate;        /* equivalent plastic strain rate, 1/s */
    double T;           /* temperature, K (only with the material's thermal block) */
    double triaxiality; /* sigma_m / sigma_eq of the effective stress at the end of the step, 1 */
    double sigma1;      /* largest principal effective Cauchy stress, Pa (models with
                           needs_sigma1 only; 0 otherwise) */
    double stretch1;    /* largest principal stretch minus 1, sqrt of C's largest eigenvalue
                           minus 1 (models with state_based only; 0 otherwise) */
};

struct tlsph_key_table; /* core/scene/keys.h */

struct tlsph_damage_model {
    const char *name;   /* as written in the scene */
    const struct tlsph_key_table *keys; /* its parameters: what parse reads (core/scene/keys.h) */
    const char *module; /* "damage:<name>", for the run's list of active modules */
    int needs_sigma1;   /* the criterion reads the largest principal stress */
    /* 1 for a porous-plasticity model (GTN, material/damage/gtn.h): it replaces the J2
     * return by its own yield surface (point_update) and sets D itself, so it
     * has no initiation criterion and no eq. 45 evolution (the scene parser
     * refuses an "evolution" block). */
    int porous;
    /* 1 for a criterion whose particle fails outright when D_init reaches 1
     * (D from 0 to 1, no eq. 45 evolution, "evolution" refused): its parse sets
     * m->damage.evolution_factor = INFINITY and the caller reads no evolution
     * block (paper 003's accumulated Johnson-Cook damage). */
    int sudden;
    /* 1 for a criterion of the strain state rather than of plastic flow (Rankine):
     * it runs every step, plastic or not, its initiation returns the value of
     * D_init at this state (not an increment; the point keeps the maximum over
     * its history) and deps_p may be 0. */
    int state_based;
    unsigned fields;    /* TLSPH_DAMAGE_FIELD_* arrays it needs allocated */
    /* Reads the model's parameters (its "type" and "evolution" keys are handled
     * by the caller) into m->damage.params / m->damage.terms.  m's elastic
     * constants, thermal block and strength are already parsed.  Returns 0 or -1. */
    int (*parse)(const json_t *obj, struct tlsph_material *m, const char *pointer,
                 struct tlsph_errors *err);
    /* Increment of D_init over one step of plastic flow, >= 0; eq. 45 then gives
     * D (the run reports damage:evolution_linear).  NULL when porous. */
    double (*initiation)(const struct tlsph_material *m, const struct tlsph_damage_step *step);
    /* Porous models: the whole update of a point that has not failed, in place
     * of the J2 return and the (1 - D) scaling (as tlsph_point_update, with the
     * kinematics of C done; material_point.h has the shared pieces).  It
     * updates the whole state s, D and D_init included.  NULL for criteria. */
    void (*point_update)(const struct tlsph_material *m, const struct tlsph_point_kinematics *k,
                         double e, double dt, struct tlsph_point_state *s,
                         struct tlsph_point_result *r);
    /* Sets the damage part of a point's state at t = 0 (D, D_init and the
     * model's fields) in s, which holds zeros.  NULL: all zero. */
    void (*point_init)(const struct tlsph_material *m, struct tlsph_point_state *s);
    /* Writes the labels of the optional mechanisms m's parameters switch on
     * ("damage:<name>_<mechanism>", static strings) to out and returns how
     * many.  NULL: none. */
    int (*modules)(const struct tlsph_material *m, const char *out[TLSPH_DAMAGE_MAX_MODULES]);
};

const struct tlsph_damage_model *tlsph_damage_find(const char *name);
/* Comma-separated list of names, for error messages. */
const char *tlsph_damage_names(void);

/* Eq. 45 with its factor as a parameter: D = 0 for D_init < 1, D = min(1,
 * factor (D_init - 1)) beyond.  D = 1 is failure, and it is the model's
 * definition, not a clamp: D is a volume fraction of cracked material.  An
 * infinite factor (a sudden criterion) fails the point at D_init = 1. */
static inline double tlsph_damage_evolution(const struct tlsph_damage *d, double D_init)
{
    if (D_init < 1.0)
        return 0.0;
    if (d->evolution_factor == INFINITY)
        return 1.0;
    const double D = d->evolution_factor * (D_init - 1.0);
    return D < 1.0 ? D : 1.0;
}

/* Parses "evolution": {"factor": >0} (optional; default 10, the paper's value)
 * with the table tlsph_damage_evolution_keys. */
extern const struct tlsph_key_table tlsph_damage_evolution_keys;
int tlsph_damage_parse_evolution(const json_t *obj, struct tlsph_material *m, const char *pointer,
                                 struct tlsph_errors *err);

/* A porous model's refusal of an "evolution" block: reports it (naming the
 * model and why: "'evolution' does not apply to <what>") when obj has one.
 * Returns -1 then, else 0. */
int tlsph_damage_refuse_evolution(const json_t *obj, const char *pointer, const char *what,
                                  struct tlsph_errors *err);

#endif
