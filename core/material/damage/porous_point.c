/* The material point of the Gurson family (porous.h): the damage model's point
 * update and initial state, on the return of porous_return.h.
 *
 * As for paper 000's GTN (gtn_point.c): the point carries the macroscopic
 * stress of the porous material, on or inside the surface, with no (1 - D)
 * factor and undegraded elastic moduli (the voids act through the surface);
 * the plastic strain has a trace, the plastic volume change a, and the EOS sees
 * the elastic volume ratio J exp(-tr Ep). */
#include <math.h>

#include "material/damage/porous.h"
#include "material/damage/porous_return.h"
#include "material/damage/porous_step.h"
#include "util/mat3.h"

#define OMEGA_ROUNDOFF 1e-12

double tlsph_porous_omega(const double s[9])
{
    double t2 = 0.0;
    for (int c = 0; c < 9; c++)
        t2 += s[c] * s[c];
    const double q = sqrt(1.5 * t2);
    if (!(q > 0.0))
        return 0.0; /* no deviator: hydrostatic, no shear growth */
    const double xi = 13.5 * mat3_det(s) / (q * q * q);
    /* |xi| <= 1 up to round-off.  An axisymmetric state computed through the
     * engine's kinematics has omega up to ~2e-14, not 0: the eigenvalues of C
     * are resolved to ~sqrt(ulp) when two of them coincide, and omega is
     * quadratic in that error (measured along the axisymmetric path of
     * test_gurson).  Below OMEGA_ROUNDOFF it is that round-off and counts as
     * the exact 0 of eq. 50 (the shear growth it would give, k_w f omega
     * d eps_q, is below 1e-14 f per unit strain). */
    const double w = 1.0 - xi * xi;
    return w <= OMEGA_ROUNDOFF ? 0.0 : fmin(w, 1.0);
}

/* Whether the point has fractured: the scene's criterion, or a surface shrunk
 * to (almost) nothing. */
static int fractured(const double *g, const struct tlsph_point_state *s)
{
    const double r = TLSPH_POROUS_FAILURE_RESIDUAL;
    if (tlsph_porous_shear_strength2(g, s->void_fstar) <= r * r)
        return 1;
    if (g[POR_CRITERION] == POROUS_FRACTURE_PLASTIC_STRAIN)
        return s->eps_p >= g[POR_EC];
    return s->void_fraction >= g[POR_FP];
}

/* A point whose strength under pure shear, sqrt(1 + q3 f*^2 - 2 q1 f*) sigma_M,
 * is below this fraction of sigma_M and whose return has no solution
 * fractures: the void growth the step needs closes the surface within the
 * step.  With q3 < q1^2 (Table 1: 3.25 < 6.25) the strength vanishes like the
 * square root of the distance to the collapse, and a step that dilates
 * strongly (trial J 1.14 in a sheared block of gtn_aravas, f 0.1287 against
 * a collapse at 0.1289, strength 3 % left) has no root at all. */
#define COLLAPSING 0.1

/* D, D_init and f* from the state's f and eps_M. */
static void set_damage(const double *g, struct tlsph_point_state *s)
{
    s->void_fstar = tlsph_porous_fstar(g, s->void_fraction);
    s->damage_init = g[POR_CRITERION] == POROUS_FRACTURE_PLASTIC_STRAIN
                         ? s->eps_p / g[POR_EC]
                         : s->void_fraction / g[POR_FP];
    s->damage = fractured(g, s)
                    ? 1.0
                    : 1.0 - sqrt(fmax(tlsph_porous_shear_strength2(g, s->void_fstar), 0.0));
}

void tlsph_porous_point_update(const struct tlsph_material *mat,
                               const struct tlsph_point_kinematics *k, double e, double dt,
                               struct tlsph_point_state *s, struct tlsph_point_result *r)
{
    const double *g = mat->damage.params;
    const double G = mat->shear_modulus;
    struct tlsph_porous_trial t;
    struct tlsph_porous_input in;
    tlsph_porous_trial(mat, k, e, dt, s, &t, &in);
    if (g[POR_SHEAR] != POROUS_SHEAR_NONE)
        in.omega = tlsph_porous_omega(t.tau);
    struct tlsph_porous_result out;
    const int plastic = tlsph_porous_return(mat, &in, &out);
    s->yield = out.yield;
    s->rate = 0.0;
    double tau_q = t.q;
    if (plastic) {
        /* the deviator relaxes along its own direction (eq. 84) */
        tau_q = tlsph_porous_commit(mat, k, dt, &out.flow, &t, s, r);
        s->void_nucleated += out.df_nucleated;
        s->void_shear += out.df_shear;
    }
    set_damage(g, s);
    if (plastic && !out.flow.converged &&
        tlsph_porous_shear_strength2(g, s->void_fstar) <= COLLAPSING * COLLAPSING) {
        /* no end-of-step state exists: the void growth the step needs shrinks
         * the surface to nothing; the point fractures (not a solver failure) */
        s->damage = 1.0;
        r->converged = 1;
    }
    tlsph_porous_finish(k, G, in.lnJp + out.flow.dv, tau_q, out.p, out.K_t, s->damage >= 1.0, &t, r);
}

void tlsph_porous_point_init(const struct tlsph_material *mat, struct tlsph_point_state *s)
{
    const double *g = mat->damage.params;
    s->void_fraction = g[POR_F0];
    set_damage(g, s);
}
