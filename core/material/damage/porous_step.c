#include "material/damage/porous_step.h"

#include <math.h>
#include <string.h>

#include "material/strength/strength.h"
#include "util/mat3.h"

void tlsph_porous_trial(const struct tlsph_material *mat, const struct tlsph_point_kinematics *k,
                        double e, double dt, const struct tlsph_point_state *s,
                        struct tlsph_porous_trial *t, struct tlsph_porous_input *in)
{
    const double *lns = k->lns;
    const double G = mat->shear_modulus, G2 = 2.0 * G;
    double Ep[9];
    sym6_to_mat3(s->plastic_strain, Ep);
    mat3_to_basis(k->Q, Ep, t->Epb);
    const double lnJp = t->Epb[0] + t->Epb[4] + t->Epb[8], lnJ = lns[0] + lns[1] + lns[2];
    for (int c = 0; c < 9; c++)
        t->tau[c] = -G2 * t->Epb[c];
    for (int a = 0; a < 3; a++)
        t->tau[4 * a] += G2 * (lns[a] - lnJ / 3.0 + lnJp / 3.0);
    double t2 = 0.0;
    for (int c = 0; c < 9; c++)
        t2 += t->tau[c] * t->tau[c];
    t->q = sqrt(1.5 * t2);
    *in = (struct tlsph_porous_input){
        .q_trial = t->q,
        .J = k->J,
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
}

double tlsph_porous_commit(const struct tlsph_material *mat, const struct tlsph_point_kinematics *k,
                           double dt, const struct tlsph_porous_flow *fl,
                           struct tlsph_porous_trial *t, struct tlsph_point_state *s,
                           struct tlsph_point_result *r)
{
    const double G = mat->shear_modulus, q_tr = t->q;
    r->iterations = fl->iterations;
    r->converged = fl->converged;
    const double flow = q_tr > 0.0 ? 1.5 * fl->dq / q_tr : 0.0;
    const double shrink = q_tr > 0.0 ? 1.0 - 3.0 * G * fl->dq / q_tr : 1.0;
    for (int c = 0; c < 9; c++) {
        t->Epb[c] += flow * t->tau[c];
        t->tau[c] *= shrink;
    }
    for (int a = 0; a < 3; a++)
        t->Epb[4 * a] += fl->dv / 3.0;
    double Ep[9];
    mat3_from_basis(k->Q, t->Epb, Ep);
    mat3_to_sym6(Ep, s->plastic_strain);
    s->eps_p += fl->dM;
    s->rate = dt > 0.0 ? fl->dM / dt : 0.0;
    if (mat->thermal.enabled)
        s->T = fl->T;
    s->void_fraction = fl->f;
    r->plastic_work = fl->work;
    return q_tr - 3.0 * G * fl->dq;
}

void tlsph_porous_finish(const struct tlsph_point_kinematics *k, double G, double lnJp_end,
                         double tau_q, double p, double K_t, int failed,
                         struct tlsph_porous_trial *t, struct tlsph_point_result *r)
{
    const double J = k->J;
    if (tau_q > 0.0)
        r->triaxiality = -p * J / tau_q;
    if (failed) {
        /* the elastic energy left is released with the failure */
        const double Je = J * exp(-lnJp_end);
        r->damage_work = tlsph_deviatoric_energy(G, tau_q) +
                         tlsph_volumetric_energy(p, Je, exp(lnJp_end));
        tlsph_point_no_stress(r, J, k->min_stretch, K_t);
        return;
    }
    for (int a = 0; a < 3; a++)
        t->tau[4 * a] -= J * p;
    tlsph_point_assemble(k, t->tau, 1, K_t, r);
}

struct tlsph_porous_input tlsph_porous_scaled_trial(const struct tlsph_porous_input *in, double s)
{
    struct tlsph_porous_input sub = *in;
    const double lnJ = log(in->J);
    sub.q_trial = s * in->q_trial;
    sub.lnJp = lnJ - s * (lnJ - in->lnJp);
    return sub;
}

double tlsph_porous_strain_scale(const struct tlsph_porous_input *in, double p)
{
    return (in->q_trial + in->J * fabs(p)) / (3.0 * in->G);
}

double tlsph_porous_frozen_root(double top, double two_D, double q1, double q2, double fs,
                                double x_tr, double y_tr, double cG, double cK, double *x_out)
{
    /* cap: x(y) = 0 at cosh(3/2 q2 y) = top/two_D */
    const double cap = two_D > 0.0 ? (top > two_D ? acosh(top / two_D) / (1.5 * q2) : 0.0)
                                   : INFINITY;
    const double side = y_tr >= 0.0 ? 1.0 : -1.0;
    double a = 0.0, b = side * fmin(fabs(y_tr), cap);
#define SURFACE_X(y) sqrt(fmax(top - two_D * cosh(1.5 * q2 * (y)), 0.0))
#define NORMAL_G(y, x)                                                                             \
    (2.0 * (x) * (y_tr - (y)) * cK - (x_tr - (x)) * 3.0 * q1 * q2 * fs * sinh(1.5 * q2 * (y)) * cG)
    double xa = SURFACE_X(a), xb = SURFACE_X(b);
    double ga = NORMAL_G(a, xa), gb = NORMAL_G(b, xb);
    double y = b, x = xb;
    if (ga * gb < 0.0) {
        for (int it = 0; it < 60; it++) {
            y = (a * gb - b * ga) / (gb - ga);
            x = SURFACE_X(y);
            const double gy = NORMAL_G(y, x);
            if (gy * gb < 0.0) {
                a = b;
                ga = gb;
            } else {
                ga *= 0.5; /* Illinois: the end kept twice counts half */
            }
            b = y;
            gb = gy;
            if (gy == 0.0 || fabs(b - a) <= 1e-12 * fmax(fabs(y), 1e-3))
                break;
        }
    } else if (ga == 0.0 || fabs(ga) < fabs(gb)) {
        y = a, x = xa;
    }
#undef SURFACE_X
#undef NORMAL_G
    *x_out = x;
    return y;
}

/* Newton from u with a backtracking line search; returns 1 when converged
 * (state: the state at u). */
static int newton(const struct tlsph_porous_solver *sv, const struct tlsph_material *m,
                  const struct tlsph_porous_input *in, double scale, double *u, void *state,
                  void *trial, int *evals)
{
    const struct tlsph_porous_iterate *e = state, *t = trial;
    sv->admissible(m, in, scale, u);
    sv->evaluate(m, in, scale, u, state);
    int used = 1, ok = e->ok;
    while (ok && !e->done) {
        double d[4];
        if (used >= sv->budget || !sv->direction(state, d)) {
            ok = 0;
            break;
        }
        /* backtracking: halve the step until |R|^2 decreases (Armijo); a step
         * that finds no decrease at all ends the iteration unconverged */
        double lambda = 1.0;
        int moved = 0;
        while (used < sv->budget && lambda >= 1e-6) {
            double v[4];
            for (int k = 0; k < sv->n; k++)
                v[k] = u[k] + lambda * d[k];
            sv->admissible(m, in, scale, v);
            sv->evaluate(m, in, scale, v, trial);
            used++;
            if (t->ok && isfinite(t->merit) && t->merit <= (1.0 - 1e-4 * lambda) * e->merit) {
                for (int k = 0; k < sv->n; k++)
                    u[k] = v[k];
                memcpy(state, trial, sv->size);
                moved = 1;
                break;
            }
            lambda *= 0.5;
        }
        ok = moved;
    }
    *evals += used;
    return ok;
}

double tlsph_porous_trial_phi(const struct tlsph_porous_solver *sv,
                              const struct tlsph_material *m,
                              const struct tlsph_porous_input *in, double *yield, double *p,
                              double *K_t)
{
    *yield = in->yield;
    if (!(*yield > 0.0)) {
        struct tlsph_flow fl;
        m->strength->flow(m, in->eps_M, 0.0, in->T, &fl);
        *yield = fl.stress;
    }
    return sv->trial_phi(m, in, *yield, p, K_t);
}

int tlsph_porous_solve(const struct tlsph_porous_solver *sv, const struct tlsph_material *m,
                       const struct tlsph_porous_input *in, double yield, double p_tr,
                       double K_tr, double *u, void *state, void *scratch, int *evals)
{
    sv->first_guess(m, in, yield, p_tr, K_tr, u);
    if (newton(sv, m, in, tlsph_porous_strain_scale(in, p_tr), u, state, scratch, evals))
        return 1;
    /* A large increment (many yield strains in one step, strong void growth)
     * can defeat Newton from the frozen guess: reach the same end-of-step
     * system through trial states scaled by k/n. */
    for (int n = 4; n <= 64; n *= 4) {
        double v[4] = {0.0, 0.0, 0.0, 0.0};
        int flowing = 0, ok = 1;
        for (int k = 1; k <= n && ok; k++) {
            const struct tlsph_porous_input sub = tlsph_porous_scaled_trial(in, (double)k / n);
            double p, K_t;
            if (!(sv->trial_phi(m, &sub, yield, &p, &K_t) > 0.0))
                continue; /* elastic at this scale */
            if (!flowing)
                sv->first_guess(m, &sub, yield, p, K_t, v);
            flowing = 1;
            ok = newton(sv, m, &sub, tlsph_porous_strain_scale(&sub, p), v, state, scratch, evals);
        }
        if (ok) {
            for (int i = 0; i < sv->n; i++)
                u[i] = v[i];
            return 1;
        }
    }
    return 0;
}
