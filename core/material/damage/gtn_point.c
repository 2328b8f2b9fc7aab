/* The GTN material point (paper 000 §5.4): the damage model's point update
 * and initial state (damage.h hooks), on the return mapping of gtn_return.h.
 *
 * The point carries the macroscopic stress of the porous material, on or
 * inside the GTN surface.  No (1 - D) factor on top: the voids act through the
 * yield surface and D = q1 f* only enters the approximation (eqs. 33-35).  The
 * elastic moduli are not degraded either (Algorithm 2's 2G(1 - D) would count
 * the voids twice).  The plastic strain has a trace, the plastic volume change
 * of void growth, so the EOS sees the elastic volume ratio J exp(-tr Ep). */
#include <math.h>

#include "material/damage/gtn.h"
#include "material/damage/gtn_return.h"
#include "util/mat3.h"

void tlsph_gtn_point_update(const struct tlsph_material *mat, const struct tlsph_point_kinematics *k,
                            double e, double dt, struct tlsph_point_state *s,
                            struct tlsph_point_result *r)
{
    const double *g = mat->damage.params;
    const double *lns = k->lns, J = k->J;
    const double G = mat->shear_modulus, G2 = 2.0 * G;
    double Ep[9], Epb[9];
    sym6_to_mat3(s->plastic_strain, Ep);
    mat3_to_basis(k->Q, Ep, Epb);
    const double lnJp = Epb[0] + Epb[4] + Epb[8], lnJ = lns[0] + lns[1] + lns[2];
    double tau[9]; /* trial deviator 2G dev(H - Ep) */
    for (int c = 0; c < 9; c++)
        tau[c] = -G2 * Epb[c];
    for (int a = 0; a < 3; a++)
        tau[4 * a] += G2 * (lns[a] - lnJ / 3.0 + lnJp / 3.0);
    double t2 = 0.0;
    for (int c = 0; c < 9; c++)
        t2 += tau[c] * tau[c];
    const double q_tr = sqrt(1.5 * t2);
    double omega = 0.0;
    if (g[GTN_KW] > 0.0 && q_tr > 0.0) {
        const double xi = 13.5 * mat3_det(tau) / (q_tr * q_tr * q_tr);
        omega = fmin(fmax(1.0 - xi * xi, 0.0), 1.0); /* |xi| <= 1 up to round-off */
    }
    const struct tlsph_gtn_input in = {
        .q_trial = q_tr,
        .omega = omega,
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
    struct tlsph_gtn_result out;
    const int plastic = tlsph_gtn_return(mat, &in, &out);
    s->yield = out.yield;
    s->rate = 0.0;
    double tau_q = q_tr;
    if (plastic) {
        r->iterations = out.iterations;
        r->converged = out.converged;
        const double flow = q_tr > 0.0 ? 1.5 * out.dq / q_tr : 0.0;
        const double shrink = q_tr > 0.0 ? 1.0 - 3.0 * G * out.dq / q_tr : 1.0;
        for (int c = 0; c < 9; c++) {
            Epb[c] += flow * tau[c];
            tau[c] *= shrink;
        }
        for (int a = 0; a < 3; a++)
            Epb[4 * a] += out.dv / 3.0;
        mat3_from_basis(k->Q, Epb, Ep);
        mat3_to_sym6(Ep, s->plastic_strain);
        s->eps_p += out.dM;
        s->rate = dt > 0.0 ? out.dM / dt : 0.0;
        if (mat->thermal.enabled)
            s->T = out.T;
        s->void_fraction = out.f;
        r->plastic_work = out.work;
        tau_q = q_tr - 3.0 * G * out.dq;
    }
    s->damage = tlsph_gtn_damage(g, s->void_fraction);
    s->damage_init = s->void_fraction / g[GTN_FC];
    if (tau_q > 0.0)
        r->triaxiality = -out.p * J / tau_q;
    if (s->damage >= 1.0) {
        /* the surface has shrunk to the origin: what elastic energy is left is
         * released with the failure */
        const double Je = J * exp(-(lnJp + out.dv));
        r->damage_work = tlsph_deviatoric_energy(G, tau_q) +
                         tlsph_volumetric_energy(out.p, Je, exp(lnJp + out.dv));
        tlsph_point_no_stress(r, J, k->min_stretch, out.K_t);
        return;
    }
    for (int a = 0; a < 3; a++)
        tau[4 * a] -= J * out.p;
    tlsph_point_assemble(k, tau, 1, out.K_t, r);
}

void tlsph_gtn_point_init(const struct tlsph_material *mat, struct tlsph_point_state *s)
{
    /* GTN starts from its initial voids: D = q1 f0 > 0 already */
    const double *g = mat->damage.params;
    s->void_fraction = g[GTN_F0];
    s->damage = tlsph_gtn_damage(g, g[GTN_F0]);
    s->damage_init = g[GTN_F0] / g[GTN_FC];
}
