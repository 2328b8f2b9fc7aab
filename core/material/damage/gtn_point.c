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
#include "material/damage/porous_step.h"
#include "util/mat3.h"

void tlsph_gtn_point_update(const struct tlsph_material *mat, const struct tlsph_point_kinematics *k,
                            double e, double dt, struct tlsph_point_state *s,
                            struct tlsph_point_result *r)
{
    const double *g = mat->damage.params;
    const double G = mat->shear_modulus;
    struct tlsph_porous_trial t;
    struct tlsph_porous_input in;
    tlsph_porous_trial(mat, k, e, dt, s, &t, &in);
    const double q_tr = t.q;
    if (g[GTN_KW] > 0.0 && q_tr > 0.0) {
        const double xi = 13.5 * mat3_det(t.tau) / (q_tr * q_tr * q_tr);
        in.omega = fmin(fmax(1.0 - xi * xi, 0.0), 1.0); /* |xi| <= 1 up to round-off */
    }
    struct tlsph_gtn_result out;
    const int plastic = tlsph_gtn_return(mat, &in, &out);
    s->yield = out.yield;
    s->rate = 0.0;
    double tau_q = q_tr;
    if (plastic)
        tau_q = tlsph_porous_commit(mat, k, dt, &out.flow, &t, s, r);
    s->damage = tlsph_gtn_damage(g, s->void_fraction);
    s->damage_init = s->void_fraction / g[GTN_FC];
    /* at D = 1 the surface has shrunk to the origin */
    tlsph_porous_finish(k, G, in.lnJp + out.flow.dv, tau_q, out.p, out.K_t, s->damage >= 1.0, &t, r);
}

void tlsph_gtn_point_init(const struct tlsph_material *mat, struct tlsph_point_state *s)
{
    /* GTN starts from its initial voids: D = q1 f0 > 0 already */
    const double *g = mat->damage.params;
    s->void_fraction = g[GTN_F0];
    s->damage = tlsph_gtn_damage(g, g[GTN_F0]);
    s->damage_init = g[GTN_F0] / g[GTN_FC];
}
