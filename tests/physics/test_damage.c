/* Single-material-point tests of the damage models (paper 000 §5),
 * driving the engine's own tlsph_point_update under uniaxial stress (lateral
 * Cauchy stress solved to zero, tests/support/point_driver.c), with the Weldox
 * parameters of the paper's Tables 1-3.
 *
 * References and tolerances:
 *  1. Johnson-Cook initiation under proportional uniaxial stress (triaxiality
 *     1/3, no rate or thermal term): D_init reaches 1 at
 *     eps_p = D1 + D2 exp(D3/3) = 1.3556 (460E), 1.2300 (700E), 1.0948 (900E),
 *     within 0.5 %; the triaxiality the point sees is 1/3 within 1e-6.
 *  2. Cockcroft-Latham initiation: D_init reaches 1 where int <sigma_1> d eps_p
 *     = W_cr; under uniaxial stress sigma_1 = sigma_y(eps_p) = A + B eps^n, so
 *     the reference strain solves A e + B e^(n+1)/(n+1) = W_cr (bisection to
 *     1e-12), within 0.5 %.
 *  3. Evolution (eq. 45, factor 10): D = 10 (D_init - 1), so with JC the point
 *     fails (D = 1) at eps_p = 1.1 eps_f (0.5 %); on the way the axial stress is
 *     (1 - D) sigma_y(eps_p) (1e-6 relative); once failed it carries no stress
 *     at any further strain.
 *  4. Energy: along the whole path to failure, the work int P : dF (trapezoid)
 *     equals the booked plastic work plus the booked damage energy (nothing is
 *     stored at failure), within 1e-3 of the work: damage dissipation is what
 *     the drop of the stress releases, nothing more or less.
 *  5. Rankine on the particle (paper 001 eq. 40 maximised over directions):
 *     an elastic point (yield stress 100 GPa, never reached) under uniaxial
 *     stress fails (D from 0 to 1) where its largest principal stretch minus
 *     1 = exp(axial log strain) - 1 reaches the threshold 0.0044: not at 1e-9
 *     below it, at 1e-9 above; no plastic flow; the released energy is the
 *     stored energy (E eps^2 / 2 to 1 %, measured 1.1e-4: the log-strain
 *     energy of the Hencky model) and the failed point carries no stress. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "support/point_driver.h"
#include "support/check_main.h"

struct alloy {
    const char *name;
    double A, B, n;      /* JC strength, Pa, Pa, 1 (Table 2) */
    double wcr;          /* CL critical work, Pa (Table 3) */
    double d1, d2, d3;   /* JC failure (Table 3) */
    double eps_f;        /* d1 + d2 exp(d3/3), the uniaxial failure strain */
};

static const struct alloy alloys[] = {
    {"460E", 499e6, 382e6, 0.458, 1219e6, 0.636, 1.936, -2.969, 1.3556},
    {"700E", 859e6, 329e6, 0.579, 1424e6, 0.361, 4.768, -5.107, 1.2300},
    {"900E", 992e6, 364e6, 0.568, 1510e6, 0.294, 5.149, -5.583, 1.0948},
};

static struct tlsph_material weldox(const struct alloy *a, const char *damage)
{
    char json[1024];
    snprintf(json, sizeof json,
             "{\"density\":7850,\"youngs_modulus\":2.1e11,\"poisson_ratio\":0.33,"
             "\"strength\":{\"type\":\"johnson_cook\",\"yield_stress\":%.17g,"
             "\"hardening_coefficient\":%.17g,\"hardening_exponent\":%.17g},"
             "\"damage\":%s}",
             a->A, a->B, a->n, damage);
    return material(json);
}

/* Drives uniaxial stress in axial log-strain steps of de until the point
 * fails or ea reaches ea_max; returns the plastic strain where D_init crossed 1
 * (linear interpolation between steps) and, in *at_failure, where D reached 1. */
struct path {
    double eps_init, eps_fail;
    double work, plastic, damage; /* J/m^3 */
    double worst_stress_error;    /* max |sigma_xx - (1-D) sigma_y| / sigma_y after initiation */
    double worst_triax_error;     /* max |triaxiality - 1/3| while flowing */
    int failed_carries_stress;    /* set when a failed point returned stress */
};

static struct path drive(const struct tlsph_material *m, const struct alloy *a, double de,
                         double ea_max)
{
    struct path out = {NAN, NAN, 0, 0, 0, 0, 0, 0};
    struct tlsph_point_state s = {0};
    struct tlsph_point_result r;
    double et = 0.0, ea = 0.0, P_old[9] = {0}, F_old[9];
    diag_F(0.0, 0.0, F_old);
    double prev_eps = 0.0, prev_init = 0.0;
    int after_failure = 0;
    while (ea < ea_max && after_failure < 20) {
        ea += de;
        uniaxial_step(m, ea, &et, 1e-6, &s, &r);
        double F[9];
        diag_F(ea, et, F);
        for (int k = 0; k < 9; k++)
            out.work += 0.5 * (P_old[k] + r.P[k]) * (F[k] - F_old[k]);
        memcpy(P_old, r.P, sizeof P_old);
        memcpy(F_old, F, sizeof F_old);
        out.plastic += r.plastic_work;
        out.damage += r.damage_work;
        if (r.iterations > 0 && s.damage < 1.0)
            out.worst_triax_error = fmax(out.worst_triax_error, fabs(r.triaxiality - 1.0 / 3.0));
        if (isnan(out.eps_init) && s.damage_init >= 1.0)
            out.eps_init = prev_eps + (1.0 - prev_init) * (s.eps_p - prev_eps) /
                                          (s.damage_init - prev_init);
        if (s.damage > 0.0 && s.damage < 1.0) {
            const double sy = a->A + a->B * pow(s.eps_p, a->n);
            out.worst_stress_error =
                fmax(out.worst_stress_error, fabs(r.sigma[0] - (1.0 - s.damage) * sy) / sy);
        }
        if (s.damage >= 1.0) {
            if (isnan(out.eps_fail))
                out.eps_fail = s.eps_p;
            else if (fabs(r.sigma[0]) + fabs(r.P[0]) > 0.0)
                out.failed_carries_stress = 1;
            after_failure++;
        }
        prev_eps = s.eps_p;
        prev_init = s.damage_init;
    }
    return out;
}

START_TEST(johnson_cook_initiates_at_the_failure_strain)
{
    const struct alloy *a = &alloys[_i];
    const double eps_f = a->d1 + a->d2 * exp(a->d3 / 3.0);
    ck_assert_msg(fabs(eps_f - a->eps_f) < 5e-5, "%s: table value %g vs formula %g", a->name,
                  a->eps_f, eps_f);
    char dmg[256];
    snprintf(dmg, sizeof dmg, "{\"type\":\"johnson_cook\",\"d1\":%.17g,\"d2\":%.17g,\"d3\":%.17g}",
             a->d1, a->d2, a->d3);
    const struct tlsph_material m = weldox(a, dmg);
    const struct path p = drive(&m, a, 1e-3, 3.0);
    printf("JC %s: initiation at eps_p = %.5f (ref %.5f, %+.2e), failure at %.5f (ref %.5f), "
           "triaxiality error %.1e\n",
           a->name, p.eps_init, eps_f, p.eps_init / eps_f - 1.0, p.eps_fail, 1.1 * eps_f,
           p.worst_triax_error);
    ck_assert_msg(fabs(p.eps_init / eps_f - 1.0) < 5e-3, "%s: initiation at %g, expected %g",
                  a->name, p.eps_init, eps_f);
    ck_assert_msg(p.worst_triax_error < 1e-6, "triaxiality off by %g", p.worst_triax_error);
    ck_assert_msg(fabs(p.eps_fail / (1.1 * eps_f) - 1.0) < 5e-3, "%s: failure at %g, expected %g",
                  a->name, p.eps_fail, 1.1 * eps_f);
    ck_assert_msg(p.worst_stress_error < 1e-6, "damaged stress off by %g", p.worst_stress_error);
    ck_assert_msg(!p.failed_carries_stress, "a failed point carried stress");
}
END_TEST

/* A e + B e^(n+1)/(n+1) = W_cr by bisection. */
static double cl_reference(const struct alloy *a)
{
    double lo = 0.0, hi = 10.0;
    for (int k = 0; k < 200; k++) {
        const double e = 0.5 * (lo + hi);
        const double w = a->A * e + a->B * pow(e, a->n + 1.0) / (a->n + 1.0);
        if (w < a->wcr)
            lo = e;
        else
            hi = e;
    }
    return 0.5 * (lo + hi);
}

START_TEST(cockcroft_latham_initiates_at_the_critical_work)
{
    const struct alloy *a = &alloys[_i];
    const double ref = cl_reference(a);
    char dmg[256];
    snprintf(dmg, sizeof dmg, "{\"type\":\"cockcroft_latham\",\"critical_work\":%.17g}", a->wcr);
    const struct tlsph_material m = weldox(a, dmg);
    const struct path p = drive(&m, a, 1e-3, 3.0);
    printf("CL %s: initiation at eps_p = %.5f (ref %.5f, %+.2e), failure at %.5f\n", a->name,
           p.eps_init, ref, p.eps_init / ref - 1.0, p.eps_fail);
    ck_assert_msg(fabs(p.eps_init / ref - 1.0) < 5e-3, "%s: initiation at %g, expected %g",
                  a->name, p.eps_init, ref);
    ck_assert_msg(p.eps_fail > p.eps_init, "failure before initiation");
    ck_assert_msg(!p.failed_carries_stress, "a failed point carried stress");
}
END_TEST

START_TEST(work_is_plastic_plus_damage_dissipation)
{
    const struct alloy *a = &alloys[0];
    char dmg[256];
    snprintf(dmg, sizeof dmg,
             "{\"type\":\"johnson_cook\",\"d1\":%.17g,\"d2\":%.17g,\"d3\":%.17g,"
             "\"evolution\":{\"factor\":2}}",
             a->d1, a->d2, a->d3);
    const struct tlsph_material m = weldox(a, dmg);
    const struct path p = drive(&m, a, 2e-4, 3.0);
    ck_assert(isfinite(p.eps_fail));
    const double booked = p.plastic + p.damage;
    printf("energy to failure: work %.6e J/m^3, plastic %.6e, damage %.6e (%.2f %%), "
           "mismatch %.2e\n",
           p.work, p.plastic, p.damage, 100.0 * p.damage / p.work, (p.work - booked) / p.work);
    ck_assert_msg(p.damage > 0.0, "no damage energy booked");
    ck_assert_msg(fabs(p.work - booked) <= 1e-3 * p.work, "work %g vs plastic + damage %g",
                  p.work, booked);
}
END_TEST

START_TEST(damage_needs_plastic_flow_to_grow)
{
    /* elastic loading below yield: no initiation at all */
    const struct alloy *a = &alloys[0];
    const struct tlsph_material m = weldox(a, "{\"type\":\"cockcroft_latham\",\"critical_work\":1}");
    struct tlsph_point_state s = {0};
    struct tlsph_point_result r;
    double et = 0.0;
    for (int k = 1; k <= 10; k++)
        uniaxial_step(&m, 2e-4 * k, &et, 1e-6, &s, &r); /* up to 2e-3 < A/E = 2.4e-3 */
    ck_assert(s.eps_p == 0.0);
    ck_assert(s.damage_init == 0.0 && s.damage == 0.0);
}
END_TEST

START_TEST(rankine_fails_at_the_threshold_stretch)
{
    const double E = 1.9e11, limit = 0.0044, ea_fail = log1p(limit);
    const struct tlsph_material m =
        material("{\"density\":8000,\"youngs_modulus\":1.9e11,\"poisson_ratio\":0.3,"
                 "\"strength\":{\"type\":\"linear_hardening\",\"yield_stress\":1e11,"
                 "\"hardening_modulus\":0},"
                 "\"damage\":{\"type\":\"rankine\",\"stretch\":0.0044}}");
    struct tlsph_point_state s = {0};
    struct tlsph_point_result r;
    double et = 0.0;
    for (int k = 1; k <= 10; k++)
        uniaxial_step(&m, 0.1 * k * ea_fail * (1.0 - 1e-9), &et, 1e-9, &s, &r);
    printf("Rankine: below the threshold D_init = %.12f, D = %g, eps_p = %g\n", s.damage_init,
           s.damage, s.eps_p);
    ck_assert_msg(s.damage == 0.0 && s.damage_init < 1.0, "failed below the threshold");
    ck_assert_msg(fabs(s.damage_init - 1.0) < 1e-8, "D_init %.12f, expected 1 - 1e-9",
                  s.damage_init);
    const double stored = 0.5 * E * ea_fail * ea_fail;
    uniaxial_step(&m, ea_fail * (1.0 + 1e-9), &et, 1e-9, &s, &r);
    printf("Rankine: above D = %g, released %.6g J/m^3 (E eps^2/2 = %.6g)\n", s.damage,
           r.damage_work, stored);
    ck_assert_msg(s.damage == 1.0, "not failed above the threshold (D = %g)", s.damage);
    ck_assert(s.eps_p == 0.0);
    ck_assert_msg(fabs(r.damage_work / stored - 1.0) < 0.01, "released %g, stored %g",
                  r.damage_work, stored);
    uniaxial_step(&m, 2.0 * ea_fail, &et, 1e-9, &s, &r);
    ck_assert(r.sigma[0] == 0.0 && r.P[0] == 0.0);
}
END_TEST

int main(void)
{
    Suite *su = suite_create("damage");
    TCase *tc = tcase_create("point");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, johnson_cook_initiates_at_the_failure_strain, 0, 3);
    tcase_add_loop_test(tc, cockcroft_latham_initiates_at_the_critical_work, 0, 3);
    tcase_add_test(tc, work_is_plastic_plus_damage_dissipation);
    tcase_add_test(tc, damage_needs_plastic_flow_to_grow);
    tcase_add_test(tc, rankine_fails_at_the_threshold_stretch);
    suite_add_tcase(su, tc);
    return tlsph_check_run(su);
}
