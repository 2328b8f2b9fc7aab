/* Single-material-point tests of J2 plasticity, driving the engine's
 * own per-particle update, tlsph_point_update (core/material/material_point.c), with
 * prescribed deformation gradients.  Materials come from scene JSON through the
 * scene parser, so the parameter names tested are the ones users write.
 *
 * Uniaxial stress: F = diag(exp(eps_a), exp(eps_t), exp(eps_t)) with the lateral
 * log strain eps_t solved every increment so that the lateral Cauchy stress
 * vanishes (|sigma_yy| < 1e-7 sigma_xx).  With Hencky elasticity the axial
 * elastic log strain is tau/E (tau = J sigma, Kirchhoff), so the plastic strain
 * follows from kinematics alone, eps_p,kin = eps_a - J sigma/E, independently of
 * the return mapping; the reference is the analytic flow curve at that strain.
 *
 * References and tolerances:
 *  1. flow curves of linear, Johnson-Cook, Swift and Voce hardening up to
 *     eps_p = 1: sigma_xx = sigma_y(eps_p,kin) within 0.5 %, and the stored
 *     eps_p equals eps_p,kin within 1e-6;
 *  2. Johnson-Cook rate term at 10/s and 1000/s (epsdot_0 = 1/s, C = 0.025):
 *     sigma = (A + B eps^n)(1 + C ln(epsdot/epsdot_0)) within 0.5 % at the
 *     applied rate, and the ratio of the two within 0.5 %;
 *  3. adiabatic heating: T - T0 = chi/(rho0 C_p) int J sigma d eps_p (= chi int
 *     sigma d eps_p / (rho C_p) with rho = rho0/J), integrated from the analytic
 *     flow curve by Simpson's rule, within 1 %; with thermal softening on,
 *     sigma = (A + B eps^n)(1 - T*^m) at the current temperature within 0.5 %;
 *  4. plastic incompressibility: at a plastic stretch of e^1 the plastic strain
 *     stays traceless (1e-12) and ln J equals the elastic volumetric strain of
 *     the linear EOS, tau_m/K = J sigma/(3K), within 1e-9 (the elastic
 *     compressibility bound; far below 1e-3 = sigma_y/K);
 *  5. energy consistency on a non-proportional path (stretch, then shear on top):
 *     the work int P : dF / rho0 equals the stored energy psi(H - Ep) plus the
 *     booked plastic work within 1e-4 of the plastic work;
 *  6. objectivity: a rotation superposed on the same path rotates the Cauchy
 *     stress and leaves eps_p unchanged, within 1e-9 relative;
 *  7. the return mapping converges for trial states far outside the yield
 *     surface, for every law and with rate and thermal terms on: Cauchy von
 *     Mises = sigma_y(end state) within 1e-10 relative, in at most 12 iterations. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/mat3.h"
#include "support/point_driver.h"
#include "material/material_point.h"
#include "scene/scene.h"
#include "material/strength/j2_return.h"
#include "material/strength/strength.h"
#include "support/check_main.h"

/* ------------------------------------------------------------------ laws */

struct law {
    const char *name;
    const char *json;
    double (*sigma_y)(double eps);
};

static double linear_law(double e) { return 300e6 + 1e9 * e; }
static double jc_law(double e) { return 499e6 + 382e6 * pow(e, 0.458); }
static double swift_law(double e) { return 800e6 * pow(0.01 + e, 0.2); }
static double voce_law(double e) { return 500e6 - 200e6 * exp(-10.0 * e); }

#define STEEL "\"density\":7850,\"youngs_modulus\":2e11,\"poisson_ratio\":0.3"

static const struct law laws[] = {
    {"linear_hardening",
     "{" STEEL ",\"strength\":{\"type\":\"linear_hardening\",\"yield_stress\":300e6,"
     "\"hardening_modulus\":1e9}}",
     linear_law},
    {"johnson_cook (Weldox 460E, paper 000 Table 2)",
     "{" STEEL ",\"strength\":{\"type\":\"johnson_cook\",\"yield_stress\":499e6,"
     "\"hardening_coefficient\":382e6,\"hardening_exponent\":0.458}}",
     jc_law},
    {"swift",
     "{" STEEL ",\"strength\":{\"type\":\"swift\",\"strength_coefficient\":800e6,"
     "\"reference_strain\":0.01,\"hardening_exponent\":0.2}}",
     swift_law},
    {"voce",
     "{" STEEL ",\"strength\":{\"type\":\"voce\",\"yield_stress\":300e6,"
     "\"saturation_stress\":500e6,\"saturation_rate\":10}}",
     voce_law},
};

/* ------------------------------------------------------------------ 1 */

START_TEST(flow_curves_match_the_analytic_laws)
{
    const struct law *law = &laws[_i];
    const struct tlsph_material m = material(law->json);
    const double E = m.youngs_modulus;
    struct tlsph_point_state s = {0};
    struct tlsph_point_result r;
    double et = 0.0, worst = 0.0, worst_eps = 0.0, eps_kin = 0.0;
    const double de = 1e-3;
    int samples = 0;
    for (int k = 1; eps_kin < 1.0; k++) {
        const double ea = k * de;
        uniaxial_step(&m, ea, &et, 1e-3, &s, &r);
        eps_kin = ea - r.J * r.sigma[0] / E;
        if (s.eps_p <= 0.0)
            continue;
        const double ref = law->sigma_y(eps_kin);
        worst = fmax(worst, fabs(r.sigma[0] - ref) / ref);
        worst_eps = fmax(worst_eps, fabs(s.eps_p - eps_kin));
        samples++;
        ck_assert_msg(k < 5000, "did not reach eps_p = 1");
    }
    fprintf(stderr, "%s: %d plastic samples to eps_p = %.3f, worst |sigma - sigma_y| %.2e, "
                    "worst |eps_p - eps_p,kin| %.2e\n",
            law->name, samples, eps_kin, worst, worst_eps);
    ck_assert(samples > 900);
    ck_assert_msg(worst < 5e-3, "%s: flow stress off by %.3g %%", law->name, 100 * worst);
    ck_assert_msg(worst_eps < 1e-6, "%s: plastic strain off by %.3g", law->name, worst_eps);
}
END_TEST

/* ------------------------------------------------------------------ 2 */

#define COPPER "\"density\":8960,\"youngs_modulus\":124e9,\"poisson_ratio\":0.34"
static const char *jc_rate =
    "{" COPPER ",\"strength\":{\"type\":\"johnson_cook\",\"yield_stress\":90e6,"
    "\"hardening_coefficient\":292e6,\"hardening_exponent\":0.31,"
    "\"rate_coefficient\":0.025,\"reference_strain_rate\":1.0}}";

static double jc_copper(double e) { return 90e6 + 292e6 * pow(e, 0.31); }

/* Drives uniaxial stress at a constant axial strain rate to eps_p = 0.5;
 * returns sigma at eps_p = 0.2 and 0.5 (interpolation-free: the samples nearest
 * above) with their plastic strains. */
static void rate_run(const struct tlsph_material *m, double rate, double out[2][2])
{
    struct tlsph_point_state s = {0};
    struct tlsph_point_result r;
    const double de = 5e-4, dt = de / rate, targets[2] = {0.2, 0.5};
    double et = 0.0, worst = 0.0;
    int got = 0;
    for (int k = 1; got < 2; k++) {
        uniaxial_step(m, k * de, &et, dt, &s, &r);
        if (s.eps_p > 0.05) {
            /* the plastic rate follows the applied one once the elastic
             * transient is over: within the hardening share H/E */
            const double ref = jc_copper(s.eps_p) * (1.0 + 0.025 * log(rate));
            worst = fmax(worst, fabs(r.sigma[0] - ref) / ref);
        }
        if (s.eps_p >= targets[got]) {
            out[got][0] = s.eps_p;
            out[got][1] = r.sigma[0];
            got++;
        }
        ck_assert(k < 10000);
    }
    fprintf(stderr, "JC at %g/s: worst deviation from (A+B eps^n)(1+C ln rate) %.2e; plastic "
                    "rate %.4g/s\n",
            rate, worst, s.rate);
    ck_assert_msg(worst < 5e-3, "rate %g: %.3g %% off the JC rate law", rate, 100 * worst);
    ck_assert_msg(fabs(s.rate - rate) < 0.01 * rate, "plastic rate %g vs applied %g", s.rate,
                  rate);
}

START_TEST(johnson_cook_rate_term)
{
    const struct tlsph_material m = material(jc_rate);
    double slow[2][2], fast[2][2];
    rate_run(&m, 10.0, slow);
    rate_run(&m, 1000.0, fast);
    const double expect = (1.0 + 0.025 * log(1000.0)) / (1.0 + 0.025 * log(10.0));
    for (int k = 0; k < 2; k++) {
        /* compare at equal plastic strain: scale out the (small) difference */
        const double ratio = (fast[k][1] / jc_copper(fast[k][0])) / (slow[k][1] / jc_copper(slow[k][0]));
        fprintf(stderr, "eps_p %.3f: sigma(1000/s)/sigma(10/s) = %.5f, JC %.5f\n", fast[k][0],
                ratio, expect);
        ck_assert_msg(fabs(ratio / expect - 1.0) < 5e-3, "rate ratio %.5f vs %.5f", ratio, expect);
    }
}
END_TEST

/* ------------------------------------------------------------------ 3 */

/* J of uniaxial stress sigma with the linear EOS: ln J = J sigma / (3K). */
static double uniaxial_J(double sigma, double K)
{
    double J = 1.0;
    for (int k = 0; k < 50; k++)
        J = exp(J * sigma / (3.0 * K));
    return J;
}

START_TEST(adiabatic_temperature_rise)
{
    const char *json =
        "{" COPPER ",\"thermal\":{\"specific_heat\":383,\"initial_temperature\":298,"
        "\"taylor_quinney\":0.9},"
        "\"strength\":{\"type\":\"johnson_cook\",\"yield_stress\":90e6,"
        "\"hardening_coefficient\":292e6,\"hardening_exponent\":0.31}}";
    const struct tlsph_material m = material(json);
    struct tlsph_point_state s = {0};
    s.T = 298.0;
    struct tlsph_point_result r;
    double et = 0.0, work = 0.0;
    for (int k = 1; s.eps_p < 1.0; k++) {
        uniaxial_step(&m, k * 1e-3, &et, 1e-6, &s, &r);
        work += r.plastic_work;
    }
    /* Simpson integral of J sigma_y over [0, eps_p] */
    const int nint = 2000;
    const double h = s.eps_p / nint;
    double integral = 0.0;
    for (int k = 0; k <= nint; k++) {
        const double e = k * h, sy = jc_copper(e);
        const double w = (k == 0 || k == nint) ? 1.0 : (k % 2 ? 4.0 : 2.0);
        integral += w * uniaxial_J(sy, m.bulk_modulus) * sy;
    }
    integral *= h / 3.0;
    const double rise_ref = 0.9 * integral / (8960.0 * 383.0);
    const double rise = s.T - 298.0;
    fprintf(stderr, "adiabatic rise at eps_p %.3f: %.4f K, reference %.4f K (%.2e); booked work "
                    "%.6g J/m^3 vs integral %.6g\n",
            s.eps_p, rise, rise_ref, rise / rise_ref - 1.0, work, integral);
    ck_assert_msg(fabs(rise / rise_ref - 1.0) < 0.01, "temperature rise %.4f K vs %.4f K", rise,
                  rise_ref);
    /* the heat is exactly chi/(rho0 C_p) of the plastic work booked */
    ck_assert(fabs(rise - 0.9 * work / (8960.0 * 383.0)) < 1e-9 * rise);
}
END_TEST

START_TEST(thermal_softening_follows_temperature)
{
    const char *json =
        "{" COPPER ",\"thermal\":{\"specific_heat\":383,\"initial_temperature\":298},"
        "\"strength\":{\"type\":\"johnson_cook\",\"yield_stress\":90e6,"
        "\"hardening_coefficient\":292e6,\"hardening_exponent\":0.31,"
        "\"thermal_exponent\":1.09,\"reference_temperature\":298,\"melting_temperature\":1356}}";
    const struct tlsph_material m = material(json);
    ck_assert(m.thermal.enabled && fabs(m.thermal.taylor_quinney - 0.9) < 1e-15);
    struct tlsph_point_state s = {0};
    s.T = 298.0;
    struct tlsph_point_result r;
    double et = 0.0, worst = 0.0, work = 0.0;
    for (int k = 1; s.eps_p < 1.0; k++) {
        uniaxial_step(&m, k * 1e-3, &et, 1e-6, &s, &r);
        work += r.plastic_work;
        if (s.eps_p <= 0.0)
            continue;
        const double Ts = (s.T - 298.0) / (1356.0 - 298.0);
        const double ref = jc_copper(s.eps_p) * (1.0 - pow(Ts, 1.09));
        worst = fmax(worst, fabs(r.sigma[0] - ref) / ref);
    }
    fprintf(stderr, "thermal softening: T = %.2f K at eps_p %.3f, worst deviation %.2e\n", s.T,
            s.eps_p, worst);
    ck_assert(s.T > 330.0); /* the softening really acted */
    ck_assert_msg(worst < 5e-3, "softened flow stress off by %.3g %%", 100 * worst);
    ck_assert(fabs(s.T - 298.0 - 0.9 * work / (8960.0 * 383.0)) < 1e-9 * (s.T - 298.0));
}
END_TEST

/* ------------------------------------------------------------------ 4 */

START_TEST(plastic_flow_is_isochoric)
{
    const struct tlsph_material m = material(laws[0].json);
    struct tlsph_point_state s = {0};
    struct tlsph_point_result r;
    double et = 0.0, worst_tr = 0.0, worst_J = 0.0, worst_lnJ = 0.0;
    for (int k = 1; k <= 1000; k++) { /* axial log strain 1: stretch e = 2.718 */
        uniaxial_step(&m, k * 1e-3, &et, 1e-3, &s, &r);
        const double *Ep = s.plastic_strain;
        worst_tr = fmax(worst_tr, fabs(Ep[0] + Ep[3] + Ep[5]));
        const double bound = r.J * r.sigma[0] / (3.0 * m.bulk_modulus);
        worst_J = fmax(worst_J, fabs(log(r.J) - bound));
        worst_lnJ = fmax(worst_lnJ, fabs(log(r.J)));
    }
    fprintf(stderr, "stretch e^1: eps_p %.3f, det F %.6f, |tr Ep| %.2e, |ln J - tau/3K| %.2e, "
                    "max |ln J| %.2e (sigma_y/K = %.2e)\n",
            s.eps_p, r.J, worst_tr, worst_J, worst_lnJ, r.sigma[0] / m.bulk_modulus);
    ck_assert(s.eps_p > 0.99);
    ck_assert_msg(worst_tr < 1e-12, "plastic strain has a trace %g", worst_tr);
    ck_assert_msg(worst_J < 1e-9, "ln J departs from the elastic volume strain by %g", worst_J);
    ck_assert(worst_lnJ < r.sigma[0] / m.bulk_modulus);
}
END_TEST

/* ------------------------------------------------------------------ 5, 6 */

/* Path: uniaxial extension to 0.2 with lateral contraction 0.1 (0 <= t <= 1),
 * then simple shear gamma up to 0.8 on top (1 < t <= 2). */
static void path_F(double t, double *F)
{
    const double a = fmin(t, 1.0);
    double U[9] = {exp(0.2 * a), 0, 0, 0, exp(-0.1 * a), 0, 0, 0, exp(-0.1 * a)};
    const double g = t > 1.0 ? 0.8 * (t - 1.0) : 0.0;
    const double S[9] = {1, g, 0, 0, 1, 0, 0, 0, 1};
    mat3_mul(S, U, F);
}

/* psi = G |dev H - Ep|^2 + K (ln J)^2 / 2 per unit reference volume. */
static double stored_energy(const struct tlsph_material *m, const double *F,
                            const struct tlsph_point_state *s)
{
    double C[9], lam[3], Q[9], lnU[3], H[6], Ep[9], E6[6];
    mat3_mul_at(F, F, C);
    sym3_eigen(C, lam, Q);
    for (int a = 0; a < 3; a++)
        lnU[a] = 0.5 * log(lam[a]);
    const double lnJ = lnU[0] + lnU[1] + lnU[2];
    for (int a = 0; a < 3; a++)
        lnU[a] -= lnJ / 3.0;
    sym3_compose(Q, lnU, H);
    sym6_to_mat3(s->plastic_strain, Ep);
    mat3_to_sym6(Ep, E6);
    double dev2 = 0.0;
    for (int c = 0; c < 6; c++) {
        const double d = H[c] - E6[c];
        dev2 += (c == 1 || c == 2 || c == 4 ? 2.0 : 1.0) * d * d;
    }
    return m->shear_modulus * dev2 + 0.5 * m->bulk_modulus * lnJ * lnJ;
}

START_TEST(work_equals_stored_energy_plus_dissipation)
{
    const struct tlsph_material m = material(laws[1].json);
    struct tlsph_point_state s = {0};
    struct tlsph_point_result r;
    const int n = 4000;
    double F0[9], F1[9], Pold[9] = {0}, work = 0.0, dissipation = 0.0;
    path_F(0.0, F0);
    for (int k = 1; k <= n; k++) {
        path_F(2.0 * k / n, F1);
        tlsph_point_update(&m, F1, 0.0, 1e-6, &s, &r);
        ck_assert(r.converged);
        for (int c = 0; c < 9; c++)
            work += 0.5 * (Pold[c] + r.P[c]) * (F1[c] - F0[c]); /* trapezoid, F linear per step */
        dissipation += r.plastic_work;
        memcpy(Pold, r.P, sizeof Pold);
        memcpy(F0, F1, sizeof F0);
    }
    const double psi = stored_energy(&m, F1, &s);
    const double gap = work - psi - dissipation;
    fprintf(stderr, "non-proportional path: work %.6g, stored %.6g, plastic %.6g J/m^3, gap %.2e "
                    "of the plastic work (eps_p %.3f)\n",
            work, psi, dissipation, gap / dissipation, s.eps_p);
    ck_assert(s.eps_p > 0.5 && psi > 0.0);
    ck_assert_msg(fabs(gap) < 1e-4 * dissipation, "energy gap %.3g of the plastic work",
                  gap / dissipation);
}
END_TEST

START_TEST(superposed_rotation_rotates_the_stress)
{
    const struct tlsph_material m = material(laws[1].json);
    struct tlsph_point_state a = {0}, b = {0};
    struct tlsph_point_result ra, rb;
    const int n = 1000;
    double worst = 0.0, smax = 0.0;
    for (int k = 1; k <= n; k++) {
        const double t = 2.0 * k / n;
        double F[9], FR[9], R[9];
        path_F(t, F);
        const double th = 2.5 * t; /* up to 286 degrees about a skew axis */
        const double ax[3] = {0.48, -0.6, 0.64};
        const double C = cos(th), S = sin(th), T = 1 - C;
        const double x = ax[0], y = ax[1], z = ax[2];
        const double Rm[9] = {C + x * x * T,     x * y * T - z * S, x * z * T + y * S,
                              y * x * T + z * S, C + y * y * T,     y * z * T - x * S,
                              z * x * T - y * S, z * y * T + x * S, C + z * z * T};
        memcpy(R, Rm, sizeof R);
        mat3_mul(R, F, FR);
        tlsph_point_update(&m, F, 0.0, 1e-6, &a, &ra);
        tlsph_point_update(&m, FR, 0.0, 1e-6, &b, &rb);
        double sa[9], sb[9], rot[9];
        sym6_to_mat3(ra.sigma, sa);
        sym6_to_mat3(rb.sigma, sb);
        mat3_from_basis(R, sa, rot); /* R sigma R^T */
        for (int c = 0; c < 9; c++) {
            worst = fmax(worst, fabs(rot[c] - sb[c]));
            smax = fmax(smax, fabs(sa[c]));
        }
        ck_assert(fabs(a.eps_p - b.eps_p) <= 1e-9 * fmax(a.eps_p, 1e-12));
    }
    fprintf(stderr, "superposed rotation: max |R sigma R^T - sigma(RF)| = %.2e of %.3g Pa\n",
            worst, smax);
    ck_assert(a.eps_p > 0.5);
    ck_assert_msg(worst < 1e-9 * smax, "stress not objective: %g Pa", worst);
}
END_TEST

/* ------------------------------------------------------------------ 7 */

START_TEST(return_mapping_converges_far_outside)
{
    const char *extra[] = {
        /* JC with rate and thermal terms at once, n < 1 (infinite slope at eps = 0) */
        "{" COPPER ",\"thermal\":{\"specific_heat\":383,\"initial_temperature\":298},"
        "\"strength\":{\"type\":\"johnson_cook\",\"yield_stress\":90e6,"
        "\"hardening_coefficient\":292e6,\"hardening_exponent\":0.31,\"rate_coefficient\":0.025,"
        "\"thermal_exponent\":1.09,\"reference_temperature\":298,\"melting_temperature\":1356}}",
    };
    const int nlaws = (int)(sizeof laws / sizeof *laws);
    for (int l = 0; l <= nlaws; l++) {
        const struct tlsph_material m = material(l < nlaws ? laws[l].json : extra[0]);
        const double steps[3] = {1e-9, 1e-6, 1e-3}; /* dt: huge to tiny plastic rates */
        for (int d = 0; d < 3; d++)
            for (int start = 0; start < 2; start++) {
                struct tlsph_point_state s = {0};
                s.eps_p = start ? 0.3 : 0.0;
                s.T = 298.0;
                /* trial strain 0.3 in one step: q_trial ~ 100 sigma_y */
                double F[9];
                diag_F(0.3, -0.15, F);
                struct tlsph_point_result r;
                tlsph_point_update(&m, F, 0.0, steps[d], &s, &r);
                struct tlsph_flow f;
                m.strength->flow(&m, s.eps_p, s.rate, s.T, &f);
                const double vm = von_mises(r.sigma);
                ck_assert_msg(r.converged && r.iterations <= 12,
                              "law %d dt %g: converged %d after %d iterations", l, steps[d],
                              r.converged, r.iterations);
                ck_assert_msg(fabs(vm - f.stress) <= 1e-10 * f.stress,
                              "law %d dt %g: von Mises %.12g vs sigma_y %.12g", l, steps[d], vm,
                              f.stress);
            }
    }
}
END_TEST

START_TEST(elastic_step_has_no_plastic_flow)
{
    const struct tlsph_material m = material(laws[0].json);
    struct tlsph_point_state s = {0};
    struct tlsph_point_result r;
    double F[9];
    diag_F(1e-4, -0.3e-4, F); /* sigma ~ 20 MPa < 300 MPa */
    tlsph_point_update(&m, F, 0.0, 1e-6, &s, &r);
    ck_assert(s.eps_p == 0.0 && r.iterations == 0 && r.plastic_work == 0.0);
    for (int c = 0; c < 6; c++)
        ck_assert(s.plastic_strain[c] == 0.0);
}
END_TEST

int main(void)
{
    Suite *su = suite_create("plasticity");
    TCase *tc = tcase_create("material point");
    tcase_set_timeout(tc, 300);
    tcase_add_loop_test(tc, flow_curves_match_the_analytic_laws, 0,
                        (int)(sizeof laws / sizeof *laws));
    tcase_add_test(tc, johnson_cook_rate_term);
    tcase_add_test(tc, adiabatic_temperature_rise);
    tcase_add_test(tc, thermal_softening_follows_temperature);
    tcase_add_test(tc, plastic_flow_is_isochoric);
    tcase_add_test(tc, work_equals_stored_energy_plus_dissipation);
    tcase_add_test(tc, superposed_rotation_rotates_the_stress);
    tcase_add_test(tc, return_mapping_converges_far_outside);
    tcase_add_test(tc, elastic_step_has_no_plastic_flow);
    suite_add_tcase(su, tc);
    return tlsph_check_run(su);
}
