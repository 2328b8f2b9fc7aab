/* Internal interface between the scene parser's files (core/scene/parse*.c,
 * geometry.c, condition.c).  Not part of the engine's API: the engine sees only
 * core/scene/scene.h. */
#ifndef TLSPH_SCENE_PARSE_INTERNAL_H
#define TLSPH_SCENE_PARSE_INTERNAL_H

#include <jansson.h>

#include "scene/scene.h"
#include "scene/json_check.h"
#include "scene/keys.h"

/* scene_keys.c: the tables the section parsers read with (the root is
 * tlsph_scene_keys, keys.h). */
extern const struct tlsph_key_table tlsph_material_keys; /* "/materials/<name>" */
extern const struct tlsph_key_table tlsph_body_keys;     /* "/bodies/<i>" */
extern const struct tlsph_key_table tlsph_refine_keys;   /* "/bodies/<i>/refine/<k>" (refine.c) */
extern const struct tlsph_key_table tlsph_thickness_region_keys; /* "/bodies/<i>/thickness_regions/<k>" */
extern const struct tlsph_key_table tlsph_gauge_keys;    /* "/output/gauges/<i>" */
extern const struct tlsph_key_table tlsph_section_keys;  /* "/output/sections/<i>" */
extern const struct tlsph_key_table tlsph_probe_keys;    /* "/output/probes/<i>" */
extern const struct tlsph_key_table tlsph_extent_keys;   /* "/output/extents/<i>" */
extern const struct tlsph_key_table tlsph_contact_keys;  /* "/contact" */
extern const struct tlsph_key_table tlsph_rigid_body_keys; /* "/rigid_bodies/<i>" */

/* parse.c: shared helpers */
/* Compiles a number (as its %.17g text) or an expression string at pointer;
 * allow_conditions enables <, <=, >, >=, &&, || (see condition.c). */
int tlsph_scene_expr(struct tlsph_expr *ex, const json_t *v, const char *const *free_vars,
                     int nfree, int allow_conditions, const struct tlsph_scene *s,
                     const char *pointer, struct tlsph_errors *err);
/* Index of the body named name, or -1. */
int tlsph_scene_find_body(const struct tlsph_scene *s, const char *name);
/* A material block (thermal, damage) whose physics needs plastic flow: when
 * m's strength model is not plastic, reports at pointer that `block` needs one
 * because `why`, and returns 1; else 0. */
int tlsph_require_plastic(const struct tlsph_material *m, const char *block, const char *why,
                          const char *pointer, struct tlsph_errors *err);

/* parse_geometry.c */
/* "/bodies/<i>/geometry": one row per primitive, each with its table, and the
 * union and difference arrays. */
extern const struct tlsph_key_table tlsph_geometry_keys;
int tlsph_parse_geometry(const json_t *v, int dimension, int depth, const char *pointer,
                         struct tlsph_geometry *g, struct tlsph_errors *err);
void tlsph_geometry_free(struct tlsph_geometry *g);
/* A 3-vector at obj[key], any non-zero length, normalised into out (z zeroed
 * in 2-D); -1 with an error at pointer/key otherwise. */
int tlsph_parse_direction(const json_t *obj, const char *key, int dimension, const char *pointer,
                          double out[3], struct tlsph_errors *err);

/* precision.c: body b's spacing against its largest coordinate (geometry and
 * origin; TLSPH_MIN_RELATIVE_SPACING); 0, or -1 with an error under pointer
 * ("/bodies/<i>"). */
int tlsph_check_body_precision(const struct tlsph_body *b, int dimension, const char *pointer,
                               struct tlsph_errors *err);

/* parse_bodies.c: fills s->bodies (s->materials and s->params already parsed). */
int tlsph_parse_bodies(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err);
/* Counts each body's lattice points against s->max_particles. */
int tlsph_check_particle_counts(struct tlsph_scene *s, struct tlsph_errors *err);

/* parse_contact.c: fills s->contact (bodies already parsed). */
int tlsph_parse_contact(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err);

/* parse_links.c: fills s->links (materials and the scene's sections already
 * parsed). */
int tlsph_parse_links(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err);

/* parse_rigid.c: fills s->rigid ("rigid_bodies"). */
int tlsph_parse_rigid_bodies(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err);

/* parse_cracks.c: fills s->cracks ("cracks"; the dimension already read). */
extern const struct tlsph_key_table tlsph_crack_keys; /* "/cracks/<i>" */
extern const struct tlsph_key_table tlsph_crack_growth_keys; /* "/crack_growth" */
int tlsph_parse_cracks(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err);
/* "crack_growth" (after the bodies and cracks). */
int tlsph_parse_crack_growth(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err);

/* parse_bcs.c: fills s->bcs (bodies already parsed). */
int tlsph_parse_bcs(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err);

/* lattice.c: lattice index range of body b over its geometry bounds
 * (i in [lo[d], hi[d]], empty when hi < lo) and the number of candidate
 * points (product of the ranges, as a double so that it cannot overflow). */
double tlsph_lattice_range(const struct tlsph_scene *s, size_t b, long lo[3], long hi[3]);
/* *count = the number of lattice points of body b inside its geometry (its
 * shell points when its placement is conforming); 0, or -1 when out of memory. */
int tlsph_lattice_count(const struct tlsph_scene *s, size_t b, size_t *count);
/* Objects (primitives, unions and differences) in geometry g, g included. */
size_t tlsph_geometry_count(const struct tlsph_geometry *g);
/* Calls visit at each lattice point X (m) of body b inside its geometry (a
 * conforming body: at each shell point, in the order of tlsph_body_lattice,
 * lo and hi unused), within
 * the index range lo..hi of tlsph_lattice_range, x fastest (the order of
 * tlsph_body_lattice); stops at the first non-zero return and returns it (visitors return
 * positive values); -1 when out of memory. */
int tlsph_lattice_visit(const struct tlsph_scene *s, size_t b, const long lo[3], const long hi[3],
                        int (*visit)(const double X[3], void *ctx), void *ctx);

/* refine.c: body b's "refine" array (its geometry and spacing parsed) into
 * b->refine; 0, or -1 with errors under pointer ("/bodies/<i>"). */
int tlsph_parse_refine(const json_t *obj, int dimension, struct tlsph_body *b, const char *pointer,
                       struct tlsph_errors *err);
/* parse_geometry.c: a box object {"min": [..], "max": [..]} (m) with key table t
 * at pointer P into lo, hi; refused at P/max/<k> when max[k] <= min[k] for k <
 * naxes ("<what> max[k] = ... must be greater than ...").  0 or -1. */
int tlsph_parse_box_corners(const json_t *o, const struct tlsph_key_table *t, int naxes,
                            const char *what, const char *P, double lo[3], double hi[3],
                            struct tlsph_errors *err);
/* A body's "thickness_regions" (thickness_regions.c): into b->thickness_region,
 * b->thickness_axis = TLSPH_THICKNESS_REGIONS when given.  0 or -1. */
int tlsph_parse_thickness_regions(const json_t *obj, int dimension, struct tlsph_body *b,
                                  const char *pointer, struct tlsph_errors *err);
void tlsph_refine_free(struct tlsph_body *b);

/* graded.c: a body with refine regions.  Calls visit at each leaf cell's
 * centre X (m) inside the geometry with the leaf's size (its particle's
 * spacing, m); stops at the first non-zero return and returns it, or
 * TLSPH_GRADED_TOO_MANY once more than budget cells were visited. */
#define TLSPH_GRADED_TOO_MANY (-2)
int tlsph_graded_visit(const struct tlsph_scene *s, size_t b, size_t budget,
                       int (*visit)(const double X[3], double size, void *ctx), void *ctx);
/* The finest particle spacing of body (its spacing / 2^k), m. */
double tlsph_graded_finest(const struct tlsph_body *body);

/* conforming.c: the shells of a body with placement conforming.  The sphere
 * or cylinder they follow: g itself or the first object of a difference; NULL
 * when g has none. */
const struct tlsph_geometry *tlsph_conforming_base(const struct tlsph_geometry *g);
/* Number of shell points of body b inside its geometry. */
size_t tlsph_conforming_count(const struct tlsph_scene *s, size_t b);
/* Fills X (3 per point, m) and vol (m^3, or m^2 in 2-D; when non-NULL) with
 * the tlsph_conforming_count(s, b) points. */
void tlsph_conforming_fill(const struct tlsph_scene *s, size_t b, double *X, double *vol);

/* check_values.c: the scene's expressions are finite where the engine evaluates
 * them.  The fastest initial speed of a body and where it is. */
struct tlsph_initial_speed {
    double speed; /* m/s */
    double X[3];  /* m */
};
/* Evaluates each body's initial velocity at every lattice point of the body (a
 * constant once), reporting a non-finite value at its pointer, and fills
 * fastest[b] for each body.  After the particle counts. */
int tlsph_check_initial_velocities(struct tlsph_scene *s, struct tlsph_initial_speed *fastest,
                                   struct tlsph_errors *err);
/* Evaluates ex, an expression of t, at t = k end / N, k = 0..N (N =
 * TLSPH_TIME_SAMPLES; t = 0 only when s->end_time is not valid), reporting the
 * first non-finite value at pointer as "<what> '<expression>' is ...". */
int tlsph_check_expr_of_time(struct tlsph_expr *ex, const struct tlsph_scene *s,
                             const char *what, const char *pointer, struct tlsph_errors *err);

/* time_vector.c: obj's member `key`, which must be an array of 3 items, each a
 * number or an expression string of t (s) in `unit`, or null (null_means says
 * what null does, for the error text).  Compiles each given item into ex[k]
 * (owned by the caller, freed with tlsph_expr_free) and sets set[k]; an item
 * with off_plane[k] must be null or the constant 0 and is not kept.  The caller
 * checks that key is present.  Returns the number of items set, or -1 after
 * reporting at pointer/key or its items. */
int tlsph_scene_time_vector(const json_t *obj, const char *key, const char *unit,
                            const char *null_means, const int off_plane[3],
                            const struct tlsph_scene *s, struct tlsph_expr ex[3], int set[3],
                            const char *pointer, struct tlsph_errors *err);

/* check_steps.c: the first time step and the step count (see the file). */
/* P-wave speed of m at its reference state (J = 1, e = 0), m/s. */
double tlsph_reference_wave_speed(const struct tlsph_material *m);
/* The initial speeds against the speed limit, a fixed step against the frame
 * interval, and the estimated step count against TLSPH_MAX_STEPS; sets
 * s->estimated_dt and s->estimated_steps. */
int tlsph_check_steps(struct tlsph_scene *s, const struct tlsph_initial_speed *fastest,
                      struct tlsph_errors *err);
/* tlsph_check_initial_velocities, then tlsph_check_steps: the last checks of a
 * scene, run when everything else is valid. */
int tlsph_check_run_start(struct tlsph_scene *s, struct tlsph_errors *err);

/* parse_damage.c: a material's "damage" block (after its strength and thermal
 * blocks). */
int tlsph_parse_material_damage(const json_t *mat, struct tlsph_material *m, const char *pointer,
                                struct tlsph_errors *err);

/* parse_measures.c: "/output/gauges" and "/output/sections" (boundary
 * conditions already parsed). */
int tlsph_parse_measures(const json_t *root, struct tlsph_scene *s, struct tlsph_errors *err);

/* condition.c: rewrites comparisons (<, <=, >, >=) and logical &&, || into
 * libmatheval arithmetic with step(); returns a malloc'ed string, NULL on
 * allocation failure or when the text is not a well-formed condition (msg
 * then says why, unless it is an allocation failure). */
char *tlsph_condition_rewrite(const char *text, char *msg, size_t msg_size);


#endif
