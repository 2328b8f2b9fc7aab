/* Gurson-Tvergaard-Needleman porous plasticity (paper 000 §5.4, eqs. 46-52).
 *
 * Unlike the initiation criteria, GTN is a yield surface: the stress a point
 * carries is the macroscopic stress of a matrix with void volume fraction f,
 *
 *   Phi = (q / sigma_M)^2 + 2 q1 f* cosh(3/2 q2 sigma_m / sigma_M) - (1 + (q1 f*)^2) <= 0,
 *
 * q the von Mises and sigma_m the mean Cauchy stress, sigma_M the flow stress
 * of the matrix at its own plastic strain eps_M (the material's strength model,
 * undamaged), f* the coalescence function of eq. 47.  Damage is D = q1 f*
 * (eq. 48): D = 1 when f reaches the failure void fraction f_F, where the
 * surface has shrunk to the origin and the point fails (in practice at
 * 1 - D = TLSPH_GTN_FAILURE_RESIDUAL, below).  The return mapping is
 * in material/damage/gtn_return.h, the point update around it in
 * material/damage/gtn_point.c, the parameters and the row in gtn.c.
 *
 * Parameters (scene key, index in m->damage.params):
 *   q1, q2                        Tvergaard's factors (defaults 1.5, 1.0)
 *   initial_void_fraction   f0    in [0, f_c)
 *   critical_void_fraction  f_c   coalescence starts (eq. 47)
 *   failure_void_fraction   f_F   in (f_c, 1): D = 1
 *   shear_coefficient       k_w   Nahshon-Hutchinson shear growth (eq. 51; default 0 = off)
 *   nucleation: {amplitude F_N, mean_strain eps_N, deviation s_N}
 *                                 Chu-Needleman strain-controlled nucleation
 *                                 (eq. 50; absent = off)
 * All dimensionless. */
#ifndef TLSPH_DAMAGE_GTN_H
#define TLSPH_DAMAGE_GTN_H

#include <math.h>

#include "material/material_point.h"
#include "scene/scene.h"

enum { GTN_Q1, GTN_Q2, GTN_F0, GTN_FC, GTN_FF, GTN_KW, GTN_FN, GTN_EN, GTN_SN };

/* Eq. 47: f* = f up to f_c, then linear up to 1/q1 at f_F (and beyond: the
 * point has failed at f_F, the caller sets D = 1). */
static inline double tlsph_gtn_fstar(const double *g, double f)
{
    if (f <= g[GTN_FC])
        return f;
    return g[GTN_FC] + (1.0 / g[GTN_Q1] - g[GTN_FC]) / (g[GTN_FF] - g[GTN_FC]) * (f - g[GTN_FC]);
}

/* A point fails when its residual strength, (1 - D) sigma_M under pure shear,
 * is below this fraction of the matrix flow stress.  The limit D -> 1 itself
 * cannot be reached by a return mapping: the surface shrinks to the origin and
 * the return's conditioning with it (at 1 - D ~ 3e-5 Newton stalls on
 * round-off, measured along proportional paths to failure).  0.1 % of the
 * strength is well inside what the experiments resolve. */
#define TLSPH_GTN_FAILURE_RESIDUAL 1e-3

/* Damage D = q1 f* (eq. 48); 1 (failed) from 1 - D <= TLSPH_GTN_FAILURE_RESIDUAL on,
 * i.e. just before f_F. */
static inline double tlsph_gtn_damage(const double *g, double f)
{
    const double D = g[GTN_Q1] * tlsph_gtn_fstar(g, f);
    return f >= g[GTN_FF] || D >= 1.0 - TLSPH_GTN_FAILURE_RESIDUAL ? 1.0 : D;
}

/* Void fraction nucleated while the matrix strain goes from e0 to e1: the exact
 * integral of eq. 50's normal distribution (written there without its square),
 * F_N/2 [erf((e1 - eps_N)/(s_N sqrt 2)) - erf((e0 - eps_N)/(s_N sqrt 2))]. */
static inline double tlsph_gtn_nucleated(const double *g, double e0, double e1)
{
    if (!(g[GTN_FN] > 0.0))
        return 0.0;
    const double k = 1.0 / (g[GTN_SN] * sqrt(2.0));
    return 0.5 * g[GTN_FN] * (erf((e1 - g[GTN_EN]) * k) - erf((e0 - g[GTN_EN]) * k));
}

/* The damage-model hooks of GTN (damage.h), gtn_point.c. */
void tlsph_gtn_point_update(const struct tlsph_material *mat, const struct tlsph_point_kinematics *k,
                            double e, double dt, struct tlsph_point_state *s,
                            struct tlsph_point_result *r);
void tlsph_gtn_point_init(const struct tlsph_material *mat, struct tlsph_point_state *s);

#endif
