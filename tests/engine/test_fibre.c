/* Fibres and the crack-tip search (core/crack/fibre.h, paper 003 §3.1, eq. 20),
 * with hand-placed particles and damage; every expected answer is worked out
 * by hand in the comment next to it.
 *
 * The lattice: spacing s = 1 mm, in-plane cells (i, j), i = -3..3, j = -3..3,
 * three layers z = 0.5, 1.5, 2.5 mm (a plate 3 mm thick, axis z), listed in a
 * scrambled order so that the build must sort them. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crack/fibre.h"
#include "run/model.h"
#include "support/check_main.h"
#include "support/scene_builder.h"

#define S 1e-3
#define NI 7
#define NL 3
#define NP (NI * NI * NL)

struct plate {
    double X[3 * NP];
    size_t index[NP];
    double D[NP];
};

/* Particle p of the lattice: cell (i, j) and layer l from p's digits, the
 * in-plane coordinates of cell (i, j) = (i S, j S) with i, j in -3..3. */
static void make_plate(struct plate *pl, int axis)
{
    for (size_t p = 0; p < NP; p++) {
        const int l = (int)(p % NL), i = (int)(p / NL % NI) - 3, j = (int)(p / NL / NI) - 3;
        double *x = pl->X + 3 * p;
        const int a0 = axis == 0 ? 1 : 0, a1 = axis == 2 ? 1 : 2;
        x[a0] = i * S;
        x[a1] = j * S;
        x[axis] = (0.5 + l) * S;
        pl->D[p] = 0.0;
    }
    /* scrambled: a permutation by a stride coprime with NP (147 = 3 * 7 * 7) */
    for (size_t k = 0; k < NP; k++)
        pl->index[k] = (k * 38) % NP;
}

/* The fibre holding cell (i, j), found by its centre (axis z). */
static long fibre_at(const struct tlsph_fibres *f, int i, int j)
{
    for (size_t k = 0; k < f->n; k++)
        if (fabs(f->centre[k][0] - i * S) < 1e-12 && fabs(f->centre[k][1] - j * S) < 1e-12)
            return (long)k;
    return -1;
}

/* Sets fibre (i, j)'s damage to d: its particles d/4, d/4, d/2 (scalings by
 * powers of two, so the sum is d exactly). */
static void damage_fibre(struct plate *pl, const struct tlsph_fibres *f, int i, int j, double d)
{
    const long k = fibre_at(f, i, j);
    ck_assert_int_ge(k, 0);
    const double share[NL] = {0.25, 0.25, 0.5};
    for (size_t p = f->start[k]; p < f->start[k + 1]; p++)
        pl->D[f->particle[p]] = share[p - f->start[k]] * d;
}

START_TEST(fibres_stack_the_layers)
{
    for (int axis = 0; axis < 3; axis++) {
        static struct plate pl;
        make_plate(&pl, axis);
        struct tlsph_fibres f;
        ck_assert_int_eq(tlsph_fibres_build(&f, pl.X, pl.index, NP, S, axis, NULL),
                         TLSPH_FIBRE_OK);
        /* 7 x 7 fibres of 3 particles, each ordered along the axis, at one
         * in-plane point */
        ck_assert_uint_eq(f.n, NI * NI);
        for (size_t k = 0; k < f.n; k++) {
            ck_assert_uint_eq(f.start[k + 1] - f.start[k], NL);
            for (size_t p = f.start[k]; p < f.start[k + 1]; p++) {
                const double *x = pl.X + 3 * f.particle[p];
                ck_assert_double_eq_tol(x[axis], (0.5 + (double)(p - f.start[k])) * S, 1e-15);
                for (int a = 0; a < 3; a++)
                    if (a != axis)
                        ck_assert_double_eq_tol(x[a], f.centre[k][a], 1e-15);
            }
            ck_assert_double_eq_tol(f.centre[k][axis], 1.5 * S, 1e-15);
        }
        tlsph_fibres_release(&f);
    }
}
END_TEST

START_TEST(off_lattice_sets_are_refused)
{
    static struct plate pl;
    make_plate(&pl, 2);
    struct tlsph_fibres f;
    /* particle 40 moved by 1e-4 spacings in x: off its cell's point */
    pl.X[3 * 40] += 1e-4 * S;
    size_t bad = 0;
    ck_assert_int_eq(tlsph_fibres_build(&f, pl.X, pl.index, NP, S, 2, &bad),
                     TLSPH_FIBRE_NOT_LATTICE);
    ck_assert_uint_eq(bad, 40);
    ck_assert_ptr_null(f.start);
    /* 1e-9 spacings (round-off of a generated lattice) is on it */
    pl.X[3 * 40] -= 1e-4 * S - 1e-9 * S;
    ck_assert_int_eq(tlsph_fibres_build(&f, pl.X, pl.index, NP, S, 2, NULL), TLSPH_FIBRE_OK);
    tlsph_fibres_release(&f);
    ck_assert_int_eq(tlsph_fibres_build(&f, pl.X, pl.index, NP, 0.0, 2, NULL),
                     TLSPH_FIBRE_BAD_INPUT);
    ck_assert_int_eq(tlsph_fibres_build(&f, pl.X, pl.index, NP, S, 3, NULL),
                     TLSPH_FIBRE_BAD_INPUT);
    ck_assert_int_eq(tlsph_fibres_build(&f, pl.X, pl.index, 0, S, 2, NULL),
                     TLSPH_FIBRE_BAD_INPUT);
}
END_TEST

START_TEST(fibre_damage_is_the_sum)
{
    static struct plate pl;
    make_plate(&pl, 2);
    struct tlsph_fibres f;
    ck_assert_int_eq(tlsph_fibres_build(&f, pl.X, pl.index, NP, S, 2, NULL), TLSPH_FIBRE_OK);
    const long k = fibre_at(&f, 1, 0);
    /* 0.01 + 0.02 + 0.04 = 0.07 */
    pl.D[f.particle[f.start[k]]] = 0.01;
    pl.D[f.particle[f.start[k] + 1]] = 0.02;
    pl.D[f.particle[f.start[k] + 2]] = 0.04;
    ck_assert_double_eq_tol(tlsph_fibre_damage(&f, (size_t)k, pl.D), 0.07, 1e-16);
    ck_assert_double_eq(tlsph_fibre_damage(&f, (size_t)fibre_at(&f, 0, 0), pl.D), 0.0);
    tlsph_fibres_release(&f);
}
END_TEST

/* The tip at fibre (0, 0), the crack coming from -x (V1 = +x), R = 2.5 S,
 * theta_c = 90 degrees (the fan +-45 degrees about +x), D_c = 0.1. */
static struct tlsph_tip_search search(void)
{
    return (struct tlsph_tip_search){.tip = {0, 0, 1.5 * S},
                                     .direction = {1, 0, 0},
                                     .radius = 2.5 * S,
                                     .theta_c = M_PI / 2,
                                     .D_c = 0.1};
}

START_TEST(the_fan_picks_the_damaged_fibre_ahead)
{
    static struct plate pl;
    make_plate(&pl, 2);
    struct tlsph_fibres f;
    ck_assert_int_eq(tlsph_fibres_build(&f, pl.X, pl.index, NP, S, 2, NULL), TLSPH_FIBRE_OK);
    struct tlsph_tip_search q = search();

    /* nothing damaged: none */
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, pl.D, &q), -1);
    /* fibres that must be ignored, all far above D_c:
     *   (0, 0) the tip itself; (-1, 0) behind (theta = 180 deg);
     *   (1, 2) outside the angle (theta = atan 2 = 63 deg > 45);
     *   (0, 1) beside (theta = 90 deg); (3, 0) beyond R (3 S > 2.5 S);
     *   (2, 2) inside the angle (45 deg) but beyond R (2.83 S) */
    damage_fibre(&pl, &f, 0, 0, 0.9);
    damage_fibre(&pl, &f, -1, 0, 0.9);
    damage_fibre(&pl, &f, 1, 2, 0.9);
    damage_fibre(&pl, &f, 0, 1, 0.9);
    damage_fibre(&pl, &f, 3, 0, 0.9);
    damage_fibre(&pl, &f, 2, 2, 0.9);
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, pl.D, &q), -1);
    /* below D_c ahead: none (0.099 < 0.1) */
    damage_fibre(&pl, &f, 1, 0, 0.099);
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, pl.D, &q), -1);
    /* exactly D_c: eq. 20's ">=" takes it */
    damage_fibre(&pl, &f, 2, 0, 0.1);
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, pl.D, &q), fibre_at(&f, 2, 0));
    /* on the fan's edge (1, 1), theta = 45 deg, more damaged: taken */
    damage_fibre(&pl, &f, 1, 1, 0.3);
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, pl.D, &q), fibre_at(&f, 1, 1));
    /* the most damaged wins: (1, 0) at 0.5 */
    damage_fibre(&pl, &f, 1, 0, 0.5);
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, pl.D, &q), fibre_at(&f, 1, 0));
    /* equal damage: the nearer ((1, 0) at S against (2, 1) at 2.24 S) */
    damage_fibre(&pl, &f, 2, 1, 0.5);
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, pl.D, &q), fibre_at(&f, 1, 0));
    /* the crack coming from +x instead (V1 = -x): only (-1, 0) qualifies */
    q.direction[0] = -1;
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, pl.D, &q), fibre_at(&f, -1, 0));
    /* a narrower fan, theta_c = 60 deg (+-30) about +x: (1, 1) at 45 deg and
     * (2, 1) at 26.6 deg: (2, 1) is in, (1, 1) out; (1, 0) cleared */
    q = search();
    q.theta_c = M_PI / 3;
    damage_fibre(&pl, &f, 1, 0, 0.0);
    damage_fibre(&pl, &f, 2, 0, 0.0);
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, pl.D, &q), fibre_at(&f, 2, 1));
    /* V1 along the thickness only: no in-plane direction, none */
    q.direction[0] = 0;
    q.direction[2] = 1;
    ck_assert_int_eq(tlsph_fibre_next_tip(&f, pl.D, &q), -1);
    tlsph_fibres_release(&f);
}
END_TEST

/* The fibres of a generated lattice body declared thin: a plate 12 x 8 x 3 mm,
 * spacing 1 mm, "thickness_axis": "z": 12 x 8 fibres of 3 particles, built at
 * setup in m->fibres; the same body without the key has none. */
START_TEST(a_thin_plate_has_its_fibres)
{
    const char *fmt =
        "{\"dimension\":3,\"time\":{\"end\":1e-5},\"materials\":{\"steel\":{\"density\":7850,"
        "\"youngs_modulus\":2.1e11,\"poisson_ratio\":0.3}},\"bodies\":[{\"name\":\"plate\","
        "\"material\":\"steel\",\"spacing\":0.001,\"geometry\":{\"box\":{\"min\":[0,0,0],"
        "\"max\":[0.012,0.008,0.003]}}%s}]}";
    char json[1024];
    snprintf(json, sizeof json, fmt, ",\"thickness_axis\":\"z\"");
    struct tlsph_model *m = build_model(json);
    ck_assert_ptr_nonnull(m->fibres);
    ck_assert(model_has_module(m, "crack:fibres"));
    const struct tlsph_fibres *f = &m->fibres[0];
    ck_assert_int_eq(f->axis, 2);
    ck_assert_uint_eq(f->n, 96);
    for (size_t k = 0; k < f->n; k++) {
        ck_assert_uint_eq(f->start[k + 1] - f->start[k], 3);
        for (size_t p = f->start[k]; p < f->start[k + 1]; p++)
            ck_assert_double_eq_tol(m->p.X[3 * f->particle[p] + 2],
                                    (0.5 + (double)(p - f->start[k])) * 1e-3, 1e-12);
    }
    tlsph_model_free(m);
    snprintf(json, sizeof json, fmt, "");
    m = build_model(json);
    ck_assert_ptr_null(m->fibres);
    ck_assert(!model_has_module(m, "crack:fibres"));
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("fibre", 60, fibres_stack_the_layers, off_lattice_sets_are_refused,
                 fibre_damage_is_the_sum, the_fan_picks_the_damaged_fibre_ahead,
                 a_thin_plate_has_its_fibres)
