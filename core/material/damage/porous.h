/* The Gurson family of paper 003 (Ren & Li 2012, §4): porous plasticity with
 * the implicit Aravas-type update of its Appendices A-B (porous_return.h).
 *
 * One yield surface (eq. 43, with f* of eq. 45 in place of f where the model
 * has coalescence),
 *
 *   Phi = (sigma_e/sigma_M)^2 + 2 q1 f* cosh(3/2 q2 sigma_m/sigma_M) - (1 + q3 f*^2) <= 0,
 *
 * sigma_e the von Mises and sigma_m the mean Cauchy stress, sigma_M the flow
 * stress of the matrix at its own plastic strain eps_M (the material's strength
 * model), and one void-growth law,
 *
 *   df = (1 - f) d eps_v          growth (eq. 44), eps_v the plastic volume strain
 *      + A_N(eps_M) d eps_M       strain-controlled nucleation (eqs. 46-48)
 *      + k_w f omega0 d eps_q     shear (eqs. 49-53; s:d^p/sigma_e = d eps_q),
 *
 * with omega0 = omega(sigma) (eq. 50, Nahshon-Hutchinson) or omega(sigma) Omega(T)
 * (eqs. 53-54, Nielsen-Tvergaard), T = sigma_m/sigma_e the triaxiality.  The
 * four models of the family are rows that fill the same parameter layout:
 *
 *   gurson      q1 = q2 = q3 = 1, f* = f, growth only         (gurson.c)
 *   gtn_aravas  q1 q2 q3, f*, nucleation                      (gtn_aravas.c)
 *   sm_gurson   + shear term with omega(sigma)                (sm_gurson.c)
 *   m_gurson    + shear term with omega(sigma) Omega(T)       (m_gurson.c)
 *
 * (paper 000's `gtn`, gtn.h, is the same physics with q3 = q1^2 in its own
 * three-unknown return; tests/physics/test_gurson.c checks they agree.)
 *
 * Fracture (the paper's crack criterion D_c, §3 and §6.1): the point fails
 * when f reaches fracture_void_fraction (f_p, models 1-4 of the paper) or, with
 * "fracture_criterion": "plastic_strain", when the matrix plastic strain eps_M
 * reaches fracture_plastic_strain (the paper's fifth variant).  It also fails
 * when the surface has (almost) shrunk to the origin, whatever the criterion.
 *
 * Damage: D = 1 - sqrt(1 + q3 f*^2 - 2 q1 f*), the loss of strength under pure
 * shear (sigma_e/sigma_M on the surface at sigma_m = 0); with q3 = q1^2 it is
 * paper 000's D = q1 f*.  D = 1 on fracture.  D_init = f/f_p or eps_M/eps_c,
 * the fracture indicator (1 at fracture).
 *
 * All parameters dimensionless. */
#ifndef TLSPH_DAMAGE_POROUS_H
#define TLSPH_DAMAGE_POROUS_H

#include <math.h>

#include <jansson.h>

#include "material/material_point.h"
#include "scene/scene.h"
#include "util/errors.h"

/* m->damage.params of every porous model of the family. */
enum {
    POR_Q1, POR_Q2, POR_Q3,  /* yield-surface factors (eq. 43) */
    POR_F0,                  /* initial void fraction */
    POR_FC, POR_FF,          /* f* of eq. 45: coalescence from f_c, f* = 1/q1 at f_f */
    POR_KW,                  /* shear coefficient k_w (eqs. 49, 52); 0 = no shear term */
    POR_T1, POR_T2,          /* triaxiality switch of eq. 54 (m_gurson) */
    POR_FN, POR_EN, POR_SN,  /* nucleation f_N, eps_N, s_N (eq. 48); f_N = 0: none */
    POR_FP,                  /* fracture void fraction f_p */
    POR_EC,                  /* fracture matrix plastic strain eps_c */
    POR_CRITERION,           /* POROUS_FRACTURE_* (the scene's choice, as a double) */
    POR_SHEAR,               /* POROUS_SHEAR_*: set by the model's row, not a key */
    POR_COUNT
};

enum { POROUS_FRACTURE_VOID_FRACTION = 0, POROUS_FRACTURE_PLASTIC_STRAIN = 1 };
enum { POROUS_SHEAR_NONE = 0, POROUS_SHEAR_NH = 1, POROUS_SHEAR_SWITCHED = 2 };

/* The point fails when its strength under pure shear, sqrt(1 + q3 f*^2 - 2 q1 f*)
 * sigma_M, is below this fraction of sigma_M: the surface has shrunk to the
 * origin and a return cannot be solved there (the same limit as gtn.h's
 * TLSPH_GTN_FAILURE_RESIDUAL, for the same reason). */
#define TLSPH_POROUS_FAILURE_RESIDUAL 1e-3

/* Eq. 45: f* = f up to f_c, linear to 1/q1 at f_f, 1/q1 beyond.  Models
 * without coalescence (gurson) have f_c = f_f = 1: f* = f. */
static inline double tlsph_porous_fstar(const double *g, double f)
{
    if (f <= g[POR_FC])
        return f;
    if (f >= g[POR_FF])
        return 1.0 / g[POR_Q1];
    return g[POR_FC] + (1.0 / g[POR_Q1] - g[POR_FC]) / (g[POR_FF] - g[POR_FC]) * (f - g[POR_FC]);
}

/* The slope of f* in f (eq. 96; the paper prints f - f_c for f_f - f_c in the
 * denominator). */
static inline double tlsph_porous_fstar_slope(const double *g, double f)
{
    if (f <= g[POR_FC])
        return 1.0;
    if (f >= g[POR_FF])
        return 0.0;
    return (1.0 / g[POR_Q1] - g[POR_FC]) / (g[POR_FF] - g[POR_FC]);
}

/* 1 + q3 f*^2 - 2 q1 f*: (sigma_e/sigma_M)^2 on the surface at sigma_m = 0. */
static inline double tlsph_porous_shear_strength2(const double *g, double fs)
{
    return 1.0 + g[POR_Q3] * fs * fs - 2.0 * g[POR_Q1] * fs;
}

/* Omega(T) of eq. 54 and its slope; models without the switch have Omega = 1. */
static inline double tlsph_porous_switch(const double *g, double T, double *slope)
{
    *slope = 0.0;
    if (g[POR_SHEAR] != POROUS_SHEAR_SWITCHED || T < g[POR_T1])
        return 1.0;
    if (T > g[POR_T2])
        return 0.0;
    *slope = 1.0 / (g[POR_T1] - g[POR_T2]);
    return (T - g[POR_T2]) / (g[POR_T1] - g[POR_T2]);
}

/* omega(sigma) of eq. 50 from the deviator s (any multiple of it: Cauchy or
 * Kirchhoff), with xi = 27 J3 / (2 sigma_e^3), J3 = det s (the paper prints
 * "|s|" and "sigma_3^3"): 0 for axisymmetric states, 1 in pure shear. */
double tlsph_porous_omega(const double s[9]);

/* The damage-model hooks shared by the family (porous_point.c). */
void tlsph_porous_point_update(const struct tlsph_material *mat,
                               const struct tlsph_point_kinematics *k, double e, double dt,
                               struct tlsph_point_state *s, struct tlsph_point_result *r);
void tlsph_porous_point_init(const struct tlsph_material *mat, struct tlsph_point_state *s);

/* The checks one key cannot make alone, shared by the rows (porous_parse.c):
 * f0 below f_p and f_c, f_c < f_f, f_c < 1/q1, T1 < T2.  Returns 0 or -1. */
int tlsph_porous_check(const struct tlsph_material *m, const char *pointer,
                       struct tlsph_errors *err);

#endif
