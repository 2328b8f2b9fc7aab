#include "support/scene_builder.h"

#include <check.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "material/constitutive.h"
#include "sph/forces.h"
#include "sph/kernel.h"
#include "sph/kinematics.h"

struct tlsph_model *try_build_model(const char *json, char *pointer, size_t size)
{
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tlsph_scene scene;
    struct tlsph_model *m = NULL;
    if (tlsph_scene_parse(json, strlen(json), &scene, &err) == 0)
        tlsph_model_create(&scene, &m, &err);
    for (size_t k = 0; k < err.count; k++)
        fprintf(stderr, "scene error: %s: %s\n", err.items[k].pointer, err.items[k].message);
    if (size > 0)
        snprintf(pointer, size, "%s", err.count > 0 ? err.items[0].pointer : "");
    tlsph_errors_free(&err);
    return m;
}

struct tlsph_model *build_model(const char *json)
{
    char pointer[256];
    struct tlsph_model *m = try_build_model(json, pointer, sizeof pointer);
    ck_assert_msg(m != NULL, "test scene rejected");
    return m;
}

json_t *load_example(const char *name)
{
    const char *top = getenv("top_srcdir");
    char path[4096];
    snprintf(path, sizeof path, "%s/examples/%s.json", top ? top : ".", name);
    json_error_t jerr;
    json_t *root = json_load_file(path, 0, &jerr);
    ck_assert_msg(root != NULL, "cannot read %s: %s", path, jerr.text);
    return root;
}

struct tlsph_model *build_model_json(json_t *root)
{
    char *text = json_dumps(root, JSON_COMPACT);
    json_decref(root);
    ck_assert(text != NULL);
    struct tlsph_model *m = build_model(text);
    free(text);
    return m;
}

struct tlsph_model *build_example(const char *name, double spacing)
{
    json_t *root = load_example(name);
    if (spacing > 0.0)
        json_object_set_new(json_array_get(json_object_get(root, "bodies"), 0), "spacing",
                            json_real(spacing));
    return build_model_json(root);
}

void run_until(struct tlsph_model *m, double t_end)
{
    struct tlsph_diagnostic d;
    while (m->t < t_end * (1.0 - 1e-12)) {
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &d) == 0, "unstable: %s", d.message);
    }
}

int model_has_module(const struct tlsph_model *m, const char *name)
{
    for (int k = 0; k < m->nmodules; k++)
        if (strcmp(m->modules[k], name) == 0)
            return 1;
    return 0;
}

double momentum_scale(const struct tlsph_model *m)
{
    double s = 0.0;
    for (size_t i = 0; i < m->p.n; i++) {
        const double *v = m->p.v + 3 * i;
        s += m->p.mass[i] * sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    }
    return s;
}

void brute_force_stress_force(const struct tlsph_model *m, size_t i, pair_weight_fn weight,
                              void *ctx, double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    for (size_t j = 0; j < m->p.n; j++) {
        if (j == i)
            continue;
        double d[3], r = 0;
        for (int c = 0; c < 3; c++) {
            d[c] = m->p.X[3 * j + c] - m->p.X[3 * i + c];
            r += d[c] * d[c];
        }
        r = sqrt(r);
        const double wij = weight(m, i, j, r, ctx);
        if (wij == 0.0)
            continue;
        double w, dwdr;
        tlsph_kernel(m->scene.kernel, 3, r, 0.5 * (m->p.h[i] + m->p.h[j]), &w, &dwdr);
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++)
                f[a] += wij * m->p.vol0[i] * m->p.vol0[j] *
                        (m->p.P_tilde[9 * i + 3 * a + c] + m->p.P_tilde[9 * j + 3 * a + c]) *
                        dwdr / r * d[c];
    }
}

void check_forces_match_brute_force(struct tlsph_model *m, pair_weight_fn weight, void *ctx)
{
    for (size_t k = 0; k < 3 * m->p.n; k++)
        m->p.x[k] = m->p.X[k] * 1.01 + 2e-5 * (rand() / (double)RAND_MAX - 0.5);
    tlsph_kinematics(m, 0.0);
    tlsph_constitutive(m, 0.0);
    tlsph_forces(m);
    double fmaxabs = 0.0, err = 0.0;
    for (size_t i = 0; i < m->p.n; i++) {
        double f[3];
        brute_force_stress_force(m, i, weight, ctx, f);
        for (int a = 0; a < 3; a++) {
            fmaxabs = fmax(fmaxabs, fabs(f[a]));
            err = fmax(err, fabs(f[a] - m->p.f[3 * i + a]));
        }
    }
    ck_assert(fmaxabs > 0.0);
    ck_assert_msg(err <= 1e-12 * fmaxabs, "pair loop differs from brute force by %.3g (max %.3g)",
                  err, fmaxabs);
}

void check_affine_patch(struct tlsph_model *m, const double A[9], const double B[9])
{
    const double b[3] = {0.3e-3, -0.2e-3, 0.1e-3};
    for (size_t i = 0; i < m->p.n; i++) {
        const double *X = m->p.X + 3 * i;
        for (int r = 0; r < 3; r++) {
            m->p.x[3 * i + r] = (m->dim == 2 && r == 2) ? 0.0 : b[r];
            m->p.v[3 * i + r] = 0.0;
            for (int c = 0; c < 3; c++) {
                m->p.x[3 * i + r] += A[3 * r + c] * X[c];
                m->p.v[3 * i + r] += B[3 * r + c] * X[c];
            }
        }
    }
    tlsph_kinematics(m, 0.0);
    double worst = 0.0, worstd = 0.0;
    for (size_t i = 0; i < m->p.n; i++)
        for (int k = 0; k < 9; k++) {
            worst = fmax(worst, fabs(m->p.F[9 * i + k] - A[k]));
            worstd = fmax(worstd, fabs(m->p.Fdot[9 * i + k] - B[k]));
        }
    ck_assert_msg(worst < 1e-10, "max |F - A| = %.3g", worst);
    ck_assert_msg(worstd < 1e-10 * 100.0, "max |Fdot - B| = %.3g (|B| ~ 100/s)", worstd);
}

double band_mean_x(const struct tlsph_model *m, double X0)
{
    double s = 0;
    int n = 0;
    for (size_t i = 0; i < m->p.n; i++)
        if (fabs(m->p.X[3 * i] - X0) < 0.0004) {
            s += m->p.x[3 * i];
            n++;
        }
    return s / n;
}

void check_momentum_kept(struct tlsph_model *m, int steps)
{
    double p0[3], p[3];
    tlsph_model_momentum(m, p0);
    const double scale = momentum_scale(m);
    for (int s = 0; s < steps; s++)
        tlsph_model_step(m);
    tlsph_model_momentum(m, p);
    for (int c = 0; c < 3; c++)
        ck_assert_msg(fabs(p[c] - p0[c]) <= 1e-12 * scale,
                      "momentum component %d drifted by %.3g (scale %.3g)", c, p[c] - p0[c], scale);
    /* the run did something: the body deformed */
    ck_assert(m->energy.internal > 1e-6 * m->energy.kinetic);
}

void check_patch(struct tlsph_model *m)
{
    static const double A3[9] = {1.02, 0.03, -0.01, 0.015, 0.97, 0.02, -0.02, 0.01, 1.05};
    static const double B3[9] = {10, -30, 5, 20, 40, -15, 7, 3, -60};
    static const double A2[9] = {1.03, -0.02, 0, 0.01, 0.96, 0, 0, 0, 1};
    static const double B2[9] = {15, -8, 0, 4, 25, 0, 0, 0, 0};
    check_affine_patch(m, m->dim == 2 ? A2 : A3, m->dim == 2 ? B2 : B3);
}

double pair_in_support(const struct tlsph_model *m, size_t i, size_t j, double r, void *ctx)
{
    (void)ctx;
    return r < m->p.h[i] + m->p.h[j] ? 1.0 : 0.0;
}

void check_stress_forces(const char *json, unsigned seed)
{
    struct tlsph_model *m = build_model(json);
    m->scene.hourglass = 0;
    m->scene.viscosity = 0;
    srand(seed);
    check_forces_match_brute_force(m, pair_in_support, NULL);
    tlsph_model_free(m);
}
