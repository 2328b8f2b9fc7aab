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
    const double *lns = k->lns, J = k->J;
    const double G = mat->shear_modulus, G2 = 2.0 * G;
    double Ep[9], Epb[9];
    sym6_to_mat3(s->plastic_strain, Ep);
    mat3_to_basis(k->Q, Ep, Epb);
    const double lnJp = Epb[0] + Epb[4] + Epb[8], lnJ = lns[0] + lns[1] + lns[2];
    double tau[9]; /* trial deviator 2G dev(H - Ep), in the eigenbasis of C */
    for (int c = 0; c < 9; c++)
        tau[c] = -G2 * Epb[c];
    for (int a = 0; a < 3; a++)
        tau[4 * a] += G2 * (lns[a] - lnJ / 3.0 + lnJp / 3.0);
    double t2 = 0.0;
    for (int c = 0; c < 9; c++)
        t2 += tau[c] * tau[c];
    const double q_tr = sqrt(1.5 * t2);
    const struct tlsph_porous_input in = {
        .q_trial = q_tr,
        .omega = g[POR_SHEAR] != POROUS_SHEAR_NONE ? tlsph_porous_omega(tau) : 0.0,
        .J = J,
        .lnJp = lnJp,
        .e = e,
        .G = G,
        .eps_M = s->eps_p,
        .f = s->void_fraction,
        .T = s->T,
        .dt = dt,
        .heating = mat->thermal.enabled
                       ? mat->thermal.taylor_quinney / (mat->density * mat->thermal.specific_heat)
                       : 0.0,
        .yield = s->yield,
    };
    struct tlsph_porous_result out;
    const int plastic = tlsph_porous_return(mat, &in, &out);
    s->yield = out.yield;
    s->rate = 0.0;
    double tau_q = q_tr;
    if (plastic) {
        r->iterations = out.iterations;
        r->converged = out.converged;
        /* the deviator relaxes along its own direction (eq. 84) */
        const double flow = q_tr > 0.0 ? 1.5 * out.b / q_tr : 0.0;
        const double shrink = q_tr > 0.0 ? 1.0 - 3.0 * G * out.b / q_tr : 1.0;
        for (int c = 0; c < 9; c++) {
            Epb[c] += flow * tau[c];
            tau[c] *= shrink;
        }
        for (int a = 0; a < 3; a++)
            Epb[4 * a] += out.a / 3.0;
        mat3_from_basis(k->Q, Epb, Ep);
        mat3_to_sym6(Ep, s->plastic_strain);
        s->eps_p += out.dM;
        s->rate = dt > 0.0 ? out.dM / dt : 0.0;
        if (mat->thermal.enabled)
            s->T = out.T;
        s->void_fraction = out.f;
        s->void_nucleated += out.df_nucleated;
        s->void_shear += out.df_shear;
        r->plastic_work = out.work;
        tau_q = q_tr - 3.0 * G * out.b;
    }
    set_damage(g, s);
    if (tau_q > 0.0)
        r->triaxiality = -out.p * J / tau_q;
    const double Jp = exp(lnJp + out.a);
    if (s->damage >= 1.0) {
        /* fractured: the elastic energy left is released with the failure */
        r->damage_work = tlsph_deviatoric_energy(G, tau_q) +
                         tlsph_volumetric_energy(out.p, J / Jp, Jp);
        tlsph_point_no_stress(r, J, k->min_stretch, out.K_t);
        return;
    }
    for (int a = 0; a < 3; a++)
        tau[4 * a] -= J * out.p;
    tlsph_point_assemble(k, tau, 1, out.K_t, r);
}

void tlsph_porous_point_init(const struct tlsph_material *mat, struct tlsph_point_state *s)
{
    const double *g = mat->damage.params;
    s->void_fraction = g[POR_F0];
    set_damage(g, s);
}
