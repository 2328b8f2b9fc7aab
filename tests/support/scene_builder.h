/* Test support: build a model from a scene given as JSON text, failing the
 * test (with every validation error printed) when the scene is rejected. */
#ifndef TLSPH_TEST_SCENE_BUILDER_H
#define TLSPH_TEST_SCENE_BUILDER_H

#include <jansson.h>

#include "run/model.h"

struct tlsph_model *build_model(const char *json);
/* The same without failing: the model, or NULL with the first error's JSON
 * pointer in pointer (every error printed). */
struct tlsph_model *try_build_model(const char *json, char *pointer, size_t size);
/* examples/<name>.json (under $top_srcdir, else ".") as JSON, a new reference;
 * fails the test when it cannot be read. */
json_t *load_example(const char *name);
/* build_model of root's text; takes over root's reference. */
struct tlsph_model *build_model_json(json_t *root);
/* The model of examples/<name>.json (under $top_srcdir, else "."), with the
 * first body's spacing (m) replaced when spacing > 0. */
struct tlsph_model *build_example(const char *name, double spacing);
/* Runs steps until m->t >= t_end, calling the stability check every step;
 * fails the test if the model goes unstable. */
void run_until(struct tlsph_model *m, double t_end);
/* 1 when the model's list of active modules names name, else 0. */
int model_has_module(const struct tlsph_model *m, const char *name);
/* sum_i m_i |v_i|, kg m/s: the scale momentum drift is measured against. */
double momentum_scale(const struct tlsph_model *m);
/* The weight of pair (i, j) at reference distance r (m) in a brute-force sum:
 * 0 for no pair. */
typedef double (*pair_weight_fn)(const struct tlsph_model *m, size_t i, size_t j, double r,
                                 void *ctx);
/* The stress force on particle i (N) by an O(n) loop over every particle j:
 * sum_j weight V_i V_j (P~_i + P~_j) grad W(X_ij), the kernel evaluated
 * directly at the mean smoothing length; what the pair loop must reproduce. */
void brute_force_stress_force(const struct tlsph_model *m, size_t i, pair_weight_fn weight,
                              void *ctx, double f[3]);
/* Deforms m (x = 1.01 X plus a random jitter of 2e-5 m from rand(): seed it
 * first), evaluates kinematics, stress and pair forces, and fails the test
 * unless every particle's force is brute_force_stress_force's within 1e-12 of
 * the largest. */
void check_forces_match_brute_force(struct tlsph_model *m, pair_weight_fn weight, void *ctx);
/* The patch test: moves m to x = A X + b with velocity v = B X (A, B row-major
 * 3x3), evaluates the kinematics and fails the test unless F = A within 1e-10
 * and Fdot = B within 1e-8 (|B| ~ 100/s) at every particle. */
void check_affine_patch(struct tlsph_model *m, const double A[9], const double B[9]);
/* check_affine_patch with the standard A and B of m's dimension (a general
 * stretch-shear, plane in 2-D). */
void check_patch(struct tlsph_model *m);
/* Every pair inside the kernel's support (r < h_i + h_j), at full weight. */
double pair_in_support(const struct tlsph_model *m, size_t i, size_t j, double r, void *ctx);
/* check_forces_match_brute_force on the model of json with hourglass and
 * viscosity off, after srand(seed); frees the model. */
void check_stress_forces(const char *json, unsigned seed);
/* Mean current x (m) of the particles whose reference x is within 0.4 mm of X0. */
double band_mean_x(const struct tlsph_model *m, double X0);
/* Runs steps steps of a free body and fails the test unless every momentum
 * component stays within 1e-12 of momentum_scale and the body deformed
 * (internal energy above 1e-6 of the kinetic). */
void check_momentum_kept(struct tlsph_model *m, int steps);

#endif
