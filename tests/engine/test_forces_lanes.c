/* The pair-force loop's packed path (sph/forces.c, pairs in vector lanes)
 * against a plain one-pair-at-a-time loop written here from the formulas of
 * sph/forces.h, sph/hourglass.h and sph/viscosity.h, for every crack
 * treatment, with and without the hourglass's tangent scaling and the
 * artificial viscosity, on a deformed, moving block with random stresses,
 * damages and link damages (failed neighbours included).
 * Reference: the plain loop.  Tolerance: none, bit for bit: the packed path
 * promises each pair the same operations and the sums the same order, which
 * is what keeps scenes bit-identical across the change (no multiply-add is
 * contracted under -std=c11). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "material/constitutive.h"
#include "sph/crack_treatment.h"
#include "sph/damage_aware.h"
#include "sph/forces.h"
#include "sph/kinematics.h"
#include "sph/pseudo_spring.h"
#include "sph/virtual_links.h"
#include "support/check_main.h"
#include "support/scene_builder.h"

/* a 9 x 7 x 6 block (378 particles, 26-54 pairs each: odd and even counts,
 * so the lanes' remainder is taken too); %s: the hourglass's stiffness,
 * the viscosity and damage blocks, the material's extra blocks */
static const char *scene_fmt =
    "{\"dimension\":3,\"time\":{\"end\":1e-6},"
    "\"discretization\":{\"kernel\":\"wendland_c2\",\"support_factor\":2.01,"
    "\"hourglass\":{\"enabled\":true,\"coefficient\":1.0%s}%s},"
    "\"materials\":{\"m\":{\"density\":8960,\"youngs_modulus\":1.24e11,\"poisson_ratio\":0.34%s}},"
    "\"bodies\":[{\"name\":\"b\",\"material\":\"m\",\"spacing\":0.001,"
    "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.0085,0.0065,0.0055]}}}]}";

static const char *jc =
    ",\"strength\":{\"type\":\"johnson_cook\",\"yield_stress\":90e6,"
    "\"hardening_coefficient\":292e6,\"hardening_exponent\":0.31}";
/* the same with Johnson-Cook damage (d1..d3 of OFHC copper, Johnson & Cook 1985) */
static const char *jc_damage =
    ",\"strength\":{\"type\":\"johnson_cook\",\"yield_stress\":90e6,"
    "\"hardening_coefficient\":292e6,\"hardening_exponent\":0.31},"
    "\"damage\":{\"type\":\"johnson_cook\",\"d1\":0.54,\"d2\":4.89,\"d3\":-3.03}";

static double uniform(void)
{
    return rand() / (double)RAND_MAX;
}

/* The viscous pair force's c (f_i += c x_ij, before the factor m_i): paper 001
 * eq. 18 in viscosity.h's order of operations */
static double plain_viscosity(const struct tlsph_model *m, size_t i, size_t j, int64_t k,
                              const double x[3], const double d[3])
{
    const struct tlsph_particles *p = &m->p;
    const struct tlsph_material *mat = &m->scene.materials[0];
    double vx = 0.0, r2 = 0.0, R2 = 0.0;
    for (int a = 0; a < 3; a++) {
        const double term = x[a] * (p->v[3 * j + a] - p->v[3 * i + a]);
        vx = a == 0 ? term : vx + term;
        r2 = a == 0 ? x[a] * x[a] : r2 + x[a] * x[a];
        R2 = a == 0 ? d[a] * d[a] : R2 + d[a] * d[a];
    }
    if (vx >= 0.0)
        return 0.0;
    const double h = 0.5 * (p->h[i] + p->h[j]);
    const double mu = h * vx / (r2 + 0.01 * h * h);
    const double b1 = m->scene.viscosity_linear, b2 = m->scene.viscosity_quadratic;
    const double pi = (-b1 * mat->wave_speed * mu + b2 * mu * mu) / mat->density;
    return p->mass[j] * pi * m->pairs.dw[k] * sqrt(R2) / sqrt(r2);
}

/* The plain loop: force_particle of sph/forces.c one pair at a time; weights
 * as the treatment gives them. */
static void plain_forces(const struct tlsph_model *m, double *f, double *f_hg)
{
    const struct tlsph_particles *p = &m->p;
    const enum tlsph_approximation v = m->crack->variant;
    const struct tlsph_material *mat = &m->scene.materials[0];
    const double coeff = 0.5 * m->scene.hourglass_coefficient * mat->youngs_modulus;
    for (size_t i = 0; i < p->n; i++) {
        const int damaged = v == TLSPH_APPROX_DAMAGE_AWARE || v == TLSPH_APPROX_PSEUDO_SPRING;
        const double Di = damaged ? p->damage[i] : 0.0;
        double fs[3] = {0}, h[3] = {0}, q[3] = {0};
        const int64_t end = damaged && Di >= 1.0 ? m->pairs.start[i] : m->pairs.start[i + 1];
        for (int64_t k = m->pairs.start[i]; k < end; k++) {
            const size_t j = (size_t)m->pairs.j[k];
            struct tlsph_pair_weights wt = {1.0, 1.0, 1.0};
            if (v == TLSPH_APPROX_DAMAGE_AWARE)
                wt = tlsph_damage_aware_force_weights(Di, p->damage[j]);
            else if (v == TLSPH_APPROX_PSEUDO_SPRING)
                wt = tlsph_pseudo_spring_force_weights(Di, p->damage[j]);
            else if (v == TLSPH_APPROX_VIRTUAL_LINKS)
                wt = tlsph_virtual_links_force_weights(m->links->D[k]);
            double d[3], x[3];
            for (int a = 0; a < 3; a++) {
                d[a] = p->X[3 * j + a] - p->X[3 * i + a];
                x[a] = p->x[3 * j + a] - p->x[3 * i + a];
            }
            const double s = p->vol0[j] * m->pairs.dw[k];
            const double *Pi = p->P_tilde + 9 * i, *Pj = p->P_tilde + 9 * j;
            for (int r = 0; r < 3; r++) {
                double t = 0.0;
                for (int c = 0; c < 3; c++) {
                    const double term = (wt.wi * Pi[3 * r + c] + wt.wj * Pj[3 * r + c]) * d[c];
                    t = c == 0 ? term : t + term;
                }
                fs[r] += s * t;
            }
            if (!(wt.stab > 0.0))
                continue;
            if (m->scene.viscosity) {
                const double c = wt.stab * plain_viscosity(m, i, j, k, x, d);
                for (int a = 0; a < 3; a++)
                    q[a] += c * x[a];
            }
            const double *Fi = p->F + 9 * i, *Fj = p->F + 9 * j;
            double Fd[3], r2 = 0.0, R2 = 0.0, e = 0.0;
            for (int r = 0; r < 3; r++) {
                Fd[r] = (Fi[3 * r] + Fj[3 * r]) * d[0];
                Fd[r] = Fd[r] + (Fi[3 * r + 1] + Fj[3 * r + 1]) * d[1];
                Fd[r] = Fd[r] + (Fi[3 * r + 2] + Fj[3 * r + 2]) * d[2];
            }
            for (int a = 0; a < 3; a++) {
                r2 = a == 0 ? x[a] * x[a] : r2 + x[a] * x[a];
                R2 = a == 0 ? d[a] * d[a] : R2 + d[a] * d[a];
                e = a == 0 ? (Fd[a] - 2.0 * x[a]) * x[a] : e + (Fd[a] - 2.0 * x[a]) * x[a];
            }
            const double stiff = p->hg_scale ? 0.5 * (p->hg_scale[i] + p->hg_scale[j]) : 1.0;
            const double c = wt.stab * stiff * (-coeff * p->vol0[j] * m->pairs.w[k] / R2 * (e / r2));
            for (int a = 0; a < 3; a++)
                h[a] += c * x[a];
        }
        for (int a = 0; a < 3; a++) {
            f_hg[3 * i + a] = h[a] * p->vol0[i];
            /* + the viscous term (0 * m_i without viscosity, as the engine adds it) */
            f[3 * i + a] = p->vol0[i] * fs[a] + f_hg[3 * i + a] + q[a] * p->mass[i];
        }
    }
}

/* Builds the scene, deforms it (x = 1.01 X + jitter), sets random damage
 * (one particle in eight failed) or link damage (one link in eight broken) and
 * hourglass scales, evaluates the stresses and compares the engine's forces
 * with the plain loop's, bit for bit. */
enum { HG_SCALE = 1, DAMAGE = 2, LINKS = 4, VISC = 8 }; /* what the scene must carry */

static void check_lanes(const char *stiffness, const char *extra, const char *material,
                        unsigned expect, unsigned seed)
{
    char json[2048];
    snprintf(json, sizeof json, scene_fmt, stiffness, extra, material);
    struct tlsph_model *m = build_model(json);
    struct tlsph_particles *p = &m->p;
    ck_assert_int_eq(!!p->hg_scale, !!(expect & HG_SCALE));
    ck_assert_int_eq(!!p->damage, !!(expect & DAMAGE));
    ck_assert_int_eq(!!m->links, !!(expect & LINKS));
    ck_assert_int_eq(!!m->scene.viscosity, !!(expect & VISC));
    srand(seed);
    for (size_t k = 0; k < 3 * p->n; k++)
        p->x[k] = p->X[k] * 1.01 + 2e-5 * (uniform() - 0.5);
    /* pairs approaching and separating: the viscosity acts on the first only */
    for (size_t k = 0; k < 3 * p->n; k++)
        p->v[k] = 50.0 * (uniform() - 0.5);
    tlsph_kinematics(m, 0.0);
    tlsph_constitutive(m, 0.0);
    if (p->damage)
        for (size_t i = 0; i < p->n; i++)
            p->damage[i] = rand() % 8 == 0 ? 1.0 : uniform();
    if (m->links)
        for (size_t k = 0; k < m->pairs.npairs; k++)
            m->links->D[k] = rand() % 8 == 0 ? 1.0 : uniform();
    if (p->hg_scale)
        for (size_t i = 0; i < p->n; i++)
            p->hg_scale[i] = 0.05 + uniform();
    tlsph_forces(m);
    double *f = malloc(3 * p->n * sizeof *f), *f_hg = malloc(3 * p->n * sizeof *f_hg);
    ck_assert_ptr_nonnull(f);
    ck_assert_ptr_nonnull(f_hg);
    plain_forces(m, f, f_hg);
    size_t differ = 0;
    for (size_t k = 0; k < 3 * p->n; k++)
        differ += memcmp(&f[k], &p->f[k], sizeof f[k]) != 0 ||
                  memcmp(&f_hg[k], &p->f_hourglass[k], sizeof f[k]) != 0;
    ck_assert_msg(differ == 0, "%zu of %zu force components differ from the plain loop", differ,
                  3 * p->n);
    free(f);
    free(f_hg);
    tlsph_model_free(m);
}

static const char *visc = ",\"viscosity\":{\"enabled\":true,\"linear\":1.0,\"quadratic\":1.0}";

START_TEST(intact_elastic)
{
    check_lanes("", "", "", 0, 1);
}
END_TEST

START_TEST(intact_elastic_viscous)
{
    check_lanes("", visc, "", VISC, 6);
}
END_TEST

START_TEST(intact_tangent_hourglass)
{
    check_lanes(",\"stiffness\":\"tangent\"", "", jc, HG_SCALE, 2);
}
END_TEST

/* with viscosity */
START_TEST(damage_aware)
{
    char extra[256];
    snprintf(extra, sizeof extra, "%s,\"damage\":{\"treatment\":\"damage_aware\"}", visc);
    check_lanes("", extra, jc_damage, HG_SCALE | DAMAGE | VISC, 3);
}
END_TEST

START_TEST(pseudo_spring)
{
    check_lanes("", ",\"damage\":{\"treatment\":\"pseudo_spring\"}", jc_damage,
                HG_SCALE | DAMAGE, 4);
}
END_TEST

/* with viscosity */
START_TEST(virtual_links)
{
    char extra[256];
    snprintf(extra, sizeof extra,
             "%s,\"damage\":{\"treatment\":\"virtual_links\","
             "\"links\":{\"type\":\"plastic_strain\",\"threshold\":0.17}}",
             visc);
    check_lanes("", extra, jc, HG_SCALE | LINKS | VISC, 5);
}
END_TEST

TLSPH_CHECK_MAIN("forces_lanes", 60, intact_elastic, intact_elastic_viscous,
                 intact_tangent_hourglass, damage_aware, pseudo_spring, virtual_links)
