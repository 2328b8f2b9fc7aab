#include "material/material_point.h"

#include <math.h>
#include <string.h>

#include "material/eos/eos.h"
#include "util/mat3.h"
#include "material/damage/damage.h"
#include "material/strength/j2_return.h"
#include "material/strength/strength.h"

/* (ln a - ln b)/(a - b) for eigenvalues a, b > 0 of C whose logarithms are
 * already known (ln a = 2 lns_a): the difference of the logs loses no more
 * than 1e-13 when a/b - 1 > 1e-3; closer, the series of log1p(x)/x. */
static inline double log_divided_difference(double a, double b, double lna, double lnb)
{
    const double x = a / b - 1.0;
    if (fabs(x) < 1e-3)
        return (1.0 - x * (0.5 - x * (1.0 / 3.0 - x * (0.25 - 0.2 * x)))) / b;
    return (lna - lnb) / (a - b);
}

/* Returns the plastic work per unit reference volume; tau (eigenbasis of C,
 * deviatoric trial on entry) is returned to the yield surface in place.  tau is
 * the effective (undamaged) stress: the damaged return is the same one scaled
 * by (1 - D), so only the heat, (1 - D) of the effective work, sees D. */
static double plastic_correction(const struct tlsph_material *mat, const double *Q, double J,
                                 double dt, double intact, struct tlsph_point_state *s,
                                 double tau[9], const double Ep_basis[9],
                                 struct tlsph_point_result *r, double *dgamma)
{
    double t2 = 0.0;
    for (int k = 0; k < 9; k++)
        t2 += tau[k] * tau[k];
    const double G = mat->shear_modulus;
    const struct tlsph_j2_input in = {
        .q_trial = sqrt(1.5 * t2),
        .J = J,
        .G = G,
        .eps_p = s->eps_p,
        .T = s->T,
        .dt = dt,
        .heating = mat->thermal.enabled ? intact * mat->thermal.taylor_quinney /
                                              (mat->density * mat->thermal.specific_heat)
                                        : 0.0,
        .yield = s->yield,
        .guess = s->rate * dt,
    };
    struct tlsph_j2_result out;
    const int plastic = tlsph_j2_return(mat, &in, &out);
    s->yield = out.yield;
    *dgamma = 0.0;
    if (!plastic) {
        s->rate = 0.0;
        return 0.0;
    }
    r->iterations = out.iterations;
    r->converged = out.converged;
    /* normal n = 3/2 tau_trial / q; dEp = dgamma n; tau = (1 - 3G dgamma / q) tau_trial */
    const double flow = 1.5 * out.dgamma / in.q_trial;
    const double shrink = 1.0 - 3.0 * G * out.dgamma / in.q_trial;
    double Epb[9], Ep[9];
    for (int k = 0; k < 9; k++) {
        Epb[k] = Ep_basis[k] + flow * tau[k];
        tau[k] *= shrink;
    }
    mat3_from_basis(Q, Epb, Ep);
    mat3_to_sym6(Ep, s->plastic_strain);
    s->eps_p += out.dgamma;
    s->rate = dt > 0.0 ? out.dgamma / dt : 0.0;
    if (mat->thermal.enabled)
        s->T = out.T;
    *dgamma = out.dgamma;
    return intact * out.dgamma * (in.q_trial - 3.0 * G * out.dgamma);
}

/* The step's stretch of a point that flowed this step (material_point.h:
 * wave_stretch).  A J2 point in plastic flow has the continuum tangent
 *   C_ep = K 1(x)1 + 2G I_dev - 2G (3G / (3G + H)) N (x) N,   N = dev tau / |dev tau|,
 * so a longitudinal wave along the principal direction a meets the modulus
 *   M_a = K_t + 4/3 G - 2G N_aa^2 3G / (3G + H)  >=  K_t + 4/3 G - 2G N_aa^2 (H = 0):
 * in uniaxial flow along a (N_aa^2 = 2/3) the bulk modulus alone, across it the
 * elastic one.  H (the hardening slope, <= 1 % of 3G for metals) is left out,
 * which errs by under 1 % of the step in the unsafe direction; the CFL factor
 * covers it.  Elastic unloading in the next step would see M_el: measured
 * against the linearised step operator (tests/physics/test_stable_step.c,
 * docs/performance.md "The stable step"), the limit of a flowing Taylor foot is
 * 1.2-1.4x this estimate, and 1.24-1.59x with the elastic tangent alone.  The
 * floor M_el/3 is the bulk-only modulus at Poisson's ratio 0, and keeps an EOS
 * in tension (K_t <= 0) from giving an unbounded step.  tau:
 * Kirchhoff stress in the eigenbasis of C (its diagonal is along the principal
 * directions); lam: eigenvalues of C. */
static double flowing_wave_stretch(const double tau[9], const double lam[3], double K_t, double G)
{
    const double mean = (tau[0] + tau[4] + tau[8]) / 3.0;
    double d2 = 0.0;
    for (int k = 0; k < 9; k++) {
        const double d = tau[k] - (k % 4 == 0 ? mean : 0.0);
        d2 += d * d;
    }
    const double M_el = fmax(K_t + 4.0 / 3.0 * G, 4.0 / 3.0 * G);
    double s = INFINITY;
    for (int a = 0; a < 3; a++) {
        const double n = tau[4 * a] - mean, N2 = d2 > 0.0 ? n * n / d2 : 0.0;
        const double M_a = fmax(M_el - 2.0 * G * N2, M_el / 3.0);
        s = fmin(s, sqrt(lam[a] * M_el / M_a));
    }
    return s;
}

/* Largest eigenvalue of the symmetric 3x3 matrix A (row-major). */
static double largest_eigenvalue(const double A[9])
{
    double lam[3], Q[9];
    sym3_eigen(A, lam, Q);
    return fmax(lam[0], fmax(lam[1], lam[2]));
}

/* Grows the damage of a point that flowed plastically by dgamma this step (or
 * of any point, for a state_based criterion) and returns the energy released
 * (J/m^3).  tau_dev: effective deviatoric Kirchhoff stress after the return (any
 * basis); p: effective pressure (Pa); lns_max: log of the largest principal stretch. */
static double damage_growth(const struct tlsph_material *mat, double dgamma, double J, double p,
                            const double tau_dev[9], double triax, double lns_max,
                            struct tlsph_point_state *s)
{
    const struct tlsph_damage_model *model = mat->damage.model;
    struct tlsph_damage_step step = {
        .deps_p = dgamma, .rate = s->rate, .T = s->T, .triaxiality = triax, .sigma1 = 0.0};
    if (model->needs_sigma1)
        step.sigma1 = largest_eigenvalue(tau_dev) / J - p;
    if (model->state_based) {
        step.stretch1 = expm1(lns_max);
        s->damage_init = fmax(s->damage_init, model->initiation(mat, &step));
    } else {
        s->damage_init += model->initiation(mat, &step);
    }
    const double D0 = s->damage, D1 = fmax(D0, tlsph_damage_evolution(&mat->damage, s->damage_init));
    if (D1 == D0)
        return 0.0;
    s->damage = D1;
    double t2 = 0.0;
    for (int k = 0; k < 9; k++)
        t2 += tau_dev[k] * tau_dev[k];
    /* effective stored energy; its volumetric part splits into the tensile part,
     * which damage degrades, and the compressive part, which only failure removes */
    const double psi_dev = tlsph_deviatoric_energy(mat->shear_modulus, sqrt(1.5 * t2));
    const double psi_vol = tlsph_volumetric_energy(p, J, 1.0);
    const double tensile = p < 0.0 ? psi_vol : 0.0;
    double released = (psi_dev + tensile) * (D1 - D0);
    if (D1 >= 1.0 && p >= 0.0)
        released += psi_vol;
    return released;
}

void tlsph_point_no_stress(struct tlsph_point_result *r, double J, double min_stretch, double K_t)
{
    for (int k = 0; k < 9; k++)
        r->P[k] = 0.0;
    for (int k = 0; k < 6; k++)
        r->sigma[k] = 0.0;
    r->J = J;
    r->min_stretch = min_stretch;
    r->wave_stretch = min_stretch;
    r->K_t = K_t;
}

static void assemble(const double F[9], const double tau[9], const double lam[3],
                     const double lns[3], const double Q[9], int general, double J, double smin,
                     double K_t, struct tlsph_point_result *r)
{
    double S[9];
    if (general) {
        double Sb[9];
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                Sb[3 * a + b] =
                    tau[3 * a + b] * (a == b ? 1.0 / lam[a]
                                             : log_divided_difference(lam[a], lam[b], 2.0 * lns[a],
                                                                      2.0 * lns[b]));
        mat3_from_basis(Q, Sb, S);
    } else {
        /* elastic: tau is diagonal in the eigenbasis (coaxial with C), S = U^-1 tau U^-1 */
        const double d[3] = {tau[0] / lam[0], tau[4] / lam[1], tau[8] / lam[2]};
        double S6[6];
        sym3_compose(Q, d, S6);
        sym6_to_mat3(S6, S);
    }
    mat3_mul(F, S, r->P);

    double sig[9];
    mat3_mul_bt(r->P, F, sig);
    const double rJ = 1.0 / J;
    r->sigma[0] = sig[0] * rJ;
    r->sigma[1] = 0.5 * (sig[1] + sig[3]) * rJ;
    r->sigma[2] = 0.5 * (sig[2] + sig[6]) * rJ;
    r->sigma[3] = sig[4] * rJ;
    r->sigma[4] = 0.5 * (sig[5] + sig[7]) * rJ;
    r->sigma[5] = sig[8] * rJ;
    r->J = J;
    r->min_stretch = smin;
    r->wave_stretch = smin;
    r->K_t = K_t;
}

void tlsph_point_assemble(const struct tlsph_point_kinematics *k, const double tau[9], int general,
                          double K_t, struct tlsph_point_result *r)
{
    assemble(k->F, tau, k->lam, k->lns, k->Q, general, k->J, k->min_stretch, K_t, r);
}

void tlsph_point_update(const struct tlsph_material *mat, const double F[9], double e, double dt,
                        struct tlsph_point_state *s, struct tlsph_point_result *r)
{
    double C[9], lam[3], Q[9];
    mat3_mul_at(F, F, C);
    sym3_eigen(C, lam, Q);
    tlsph_point_update_eigen(mat, F, lam, Q, e, dt, s, r);
}

void tlsph_point_update_eigen(const struct tlsph_material *mat, const double F[9],
                              const double lam[3], const double Q[9], double e, double dt,
                              struct tlsph_point_state *s, struct tlsph_point_result *r)
{
    const int damaging = s && mat->damage.model;
    r->plastic_work = 0.0;
    r->damage_work = 0.0;
    r->iterations = 0;
    r->converged = 1;
    r->triaxiality = NAN;
    if (damaging && s->damage >= 1.0) {
        /* failed: no stress; its F is no longer a strain of material (see kinematics.c) */
        tlsph_point_no_stress(r, 1.0, 1.0, 0.0);
        return;
    }
    double lns[3], smin = INFINITY;
    for (int a = 0; a < 3; a++) {
        const double st = sqrt(lam[a]);
        lns[a] = log(st);
        smin = fmin(smin, st);
    }
    const double J = mat3_det(F);
    const double lnJ = lns[0] + lns[1] + lns[2];
    const double G2 = 2.0 * mat->shear_modulus;
    if (damaging && mat->damage.model->point_update) {
        /* a porous model: its own yield surface and damage */
        struct tlsph_point_kinematics k = {.F = F, .J = J, .min_stretch = smin};
        memcpy(k.lam, lam, sizeof k.lam);
        memcpy(k.lns, lns, sizeof lns);
        memcpy(k.Q, Q, sizeof k.Q);
        mat->damage.model->point_update(mat, &k, e, dt, s, r);
        return;
    }
    const double intact = damaging ? 1.0 - s->damage : 1.0;

    /* tau: the effective stress conjugate to H, in the eigenbasis of C (row-major 3x3). */
    double tau[9] = {0};
    for (int a = 0; a < 3; a++)
        tau[4 * a] = G2 * (lns[a] - lnJ / 3.0);
    double dgamma = 0.0;
    if (s) {
        double Ep[9], Epb[9];
        sym6_to_mat3(s->plastic_strain, Ep);
        mat3_to_basis(Q, Ep, Epb);
        for (int c = 0; c < 9; c++)
            tau[c] -= G2 * Epb[c];
        r->plastic_work = plastic_correction(mat, Q, J, dt, intact, s, tau, Epb, r, &dgamma);
    }

    double p, K_t;
    if (s && mat->thermal.enabled && mat->thermal.expansion > 0.0) {
        /* paper 003 eq. 58: the heat's thermal strain d^t = gamma dT I takes
         * exp(3 gamma (T - T0)) of the volume; the EOS sees the rest.  Only
         * the pressure changes: the thermal strain has no deviator. */
        const double Je =
            J * exp(-3.0 * mat->thermal.expansion * (s->T - mat->thermal.initial_temperature));
        mat->eos->pressure(mat, Je, e, &p, &K_t);
    } else {
        mat->eos->pressure(mat, J, e, &p, &K_t);
    }
    double scale = 1.0, p_carried = p;
    if (damaging) {
        double t2 = 0.0;
        for (int c = 0; c < 9; c++)
            t2 += tau[c] * tau[c];
        const double q = sqrt(1.5 * t2) / J; /* Cauchy von Mises */
        if (q > 0.0)
            r->triaxiality = -p / q;
        if (dgamma > 0.0 || mat->damage.model->state_based)
            r->damage_work = damage_growth(mat, dgamma, J, p, tau, r->triaxiality,
                                           fmax(lns[0], fmax(lns[1], lns[2])), s);
        if (s->damage >= 1.0) {
            tlsph_point_no_stress(r, J, smin, K_t);
            return;
        }
        scale = 1.0 - s->damage;
        if (p < 0.0)
            p_carried = scale * p;
        if (scale < 1.0)
            for (int c = 0; c < 9; c++)
                tau[c] *= scale;
    }
    for (int a = 0; a < 3; a++)
        tau[4 * a] -= J * p_carried;
    assemble(F, tau, lam, lns, Q, s != NULL, J, smin, K_t, r);
    if (dgamma > 0.0)
        r->wave_stretch = flowing_wave_stretch(tau, lam, K_t, mat->shear_modulus);
}
