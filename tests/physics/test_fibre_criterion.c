/* The crack driver's fibre criterion (core/crack/fibre_criterion.h,
 * crack_growth.criterion): which particle quantity a fibre sums for eq. 20.
 *
 * The plate: Table 1's Normal Strength steel of paper 003 (E 200 GPa, nu 0.3,
 * 270 MPa + 833 MPa eps_M) with the M-Gurson row (Table 1 defaults: f0 =
 * 0.0025), 12 x 8 x 3 mm at 1 mm (288 particles, fibres of three along z),
 * an edge crack in y = 0 from beyond the left edge to x = 0, its tip at
 * (0, 0) growing with D_c = 0.0135 (the paper's f_p, §6.1).  Nothing is
 * stepped: the fields are set by hand and the driver's search is asked once,
 * so every answer is known exactly.
 *
 * References, by hand:
 *  - the field the search sums is p.damage, p.void_fraction or p.eps_p for
 *    "damage", "void_fraction", "plastic_strain" (the model's own arrays);
 *  - at the start every fibre's void-fraction sum is 3 f0 = 0.0075 < 0.0135:
 *    no advance; but the porous damage D = 1 - sqrt(1 + q3 f*^2 - 2 q1 f*)
 *    is 0.0062597 per particle at f0 (q1 2.5, q3 3.25), a fibre sum of 0.0188:
 *    under "damage" the tip moves at the first search (why the Gurson runs
 *    need the void-fraction criterion);
 *  - the fibre at (0.5, 0.5) mm (45 degrees ahead of the tip, inside the fan
 *    of +-60 degrees, within R = 1.5 mm) with its three particles at f = 0.0045
 *    at f = 0.0045 (1 + 1e-9) sums past D_c (eq. 20): the tip moves there
 *    under "void_fraction", and not under "plastic_strain" (eps_p = 0); at
 *    f = 0.0045 (1 - 1e-9) it stays (1e-9: the sum of three 0.0045 rounds
 *    to one ulp below 0.0135);
 *  - the same with eps_p set on that fibre (0.35/3 each): the tip moves under
 *    "plastic_strain" only;
 *  - "void_fraction" for a Johnson-Cook material (no void fraction) and an
 *    unknown name are refused at /crack_growth/criterion. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "crack/crack_driver.h"
#include "crack/fibre_criterion.h"
#include "run/model.h"
#include "support/check_main.h"
#include "support/scene_builder.h"

#define DC 0.0135

static const char *GURSON = "{\"density\":7800,\"youngs_modulus\":2e11,\"poisson_ratio\":0.3,"
                            "\"strength\":{\"type\":\"linear_hardening\",\"yield_stress\":2.7e8,"
                            "\"hardening_modulus\":8.33e8},\"damage\":{\"type\":\"m_gurson\"}}";
static const char *JC = "{\"density\":7800,\"youngs_modulus\":2e11,\"poisson_ratio\":0.3,"
                        "\"strength\":{\"type\":\"linear_hardening\",\"yield_stress\":2.7e8,"
                        "\"hardening_modulus\":8.33e8},\"damage\":{\"type\":\"johnson_cook\","
                        "\"d1\":0.08,\"d2\":0,\"d3\":0}}";

static char *scene(const char *material, const char *criterion, double dc)
{
    static char text[4096];
    snprintf(text, sizeof text,
             "{\"dimension\":3,\"time\":{\"end\":1e-5},\"contact\":{\"enabled\":false},"
             "\"materials\":{\"steel\":%s},"
             "\"bodies\":[{\"name\":\"plate\",\"material\":\"steel\",\"spacing\":0.001,"
             "\"thickness_axis\":\"z\",\"geometry\":{\"box\":{\"min\":[-0.004,-0.004,0],"
             "\"max\":[0.008,0.004,0.003]}}}],"
             "\"cracks\":[{\"polygon\":[[-0.005,0,-0.001],[0,0,-0.001],[0,0,0.004],"
             "[-0.005,0,0.004]]}],"
             "\"crack_growth\":{\"tips\":[[0,0,0.0015]],\"criterion\":\"%s\","
             "\"critical_damage\":%.17g}}",
             material, criterion, dc);
    return text;
}

/* Sets field[i] = value for the three particles of the fibre at (x, y) mm. */
static int set_fibre(struct tlsph_model *m, double *field, double x, double y, double value)
{
    int n = 0;
    for (size_t i = 0; i < m->p.n; i++)
        if (fabs(m->p.X[3 * i] - 1e-3 * x) < 1e-6 && fabs(m->p.X[3 * i + 1] - 1e-3 * y) < 1e-6) {
            field[i] = value;
            n++;
        }
    return n;
}

/* One search; the new tip's in-plane position (mm) when the tip moved. */
static int search(struct tlsph_model *m, double tip[2])
{
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    const size_t before = m->crack_driver->nevents;
    ck_assert_int_eq(tlsph_crack_driver_step(m, NULL, &err), 0);
    tlsph_errors_free(&err);
    if (m->crack_driver->nevents == before)
        return 0;
    tip[0] = 1e3 * m->crack_driver->tip[0].T[0];
    tip[1] = 1e3 * m->crack_driver->tip[0].T[1];
    return 1;
}

START_TEST(each_criterion_reads_its_field)
{
    const char *names[] = {"damage", "void_fraction", "plastic_strain"};
    for (int c = 0; c < 3; c++) {
        struct tlsph_model *m = build_model(scene(GURSON, names[c], DC));
        const double *want[] = {m->p.damage, m->p.void_fraction, m->p.eps_p};
        ck_assert_ptr_nonnull(want[c]);
        ck_assert_ptr_eq(tlsph_crack_criterion_field(m), want[c]);
        ck_assert_int_eq(m->scene.crack_growth.criterion, c);
        tlsph_model_free(m);
    }
}
END_TEST

/* The void fraction at the start (f0 everywhere), then on one fibre. */
START_TEST(the_void_fraction_sum_moves_the_tip)
{
    const char *names[] = {"damage", "void_fraction", "plastic_strain"};
    for (int c = 0; c < 3; c++) {
        struct tlsph_model *m = build_model(scene(GURSON, names[c], DC));
        double tip[2];
        for (size_t i = 0; i < m->p.n; i++) {
            ck_assert_double_eq(m->p.void_fraction[i], 0.0025); /* f0, Table 1 */
            ck_assert_double_eq_tol(m->p.damage[i], 0.0062597, 1e-6);
        }
        if (c == 0) { /* D(f0) summed: 0.01878 >= D_c at once */
            ck_assert_int_eq(search(m, tip), 1);
            tlsph_model_free(m);
            continue;
        }
        ck_assert_int_eq(search(m, tip), 0); /* 0.0075 < D_c */
        ck_assert_int_eq(set_fibre(m, m->p.void_fraction, 0.5, 0.5, DC / 3 * (1 - 1e-9)), 3);
        ck_assert_int_eq(search(m, tip), 0); /* just below D_c */
        ck_assert_int_eq(set_fibre(m, m->p.void_fraction, 0.5, 0.5, DC / 3 * (1 + 1e-9)), 3);
        const int moved = search(m, tip);
        ck_assert_int_eq(moved, c == 1);
        if (moved) {
            ck_assert_double_eq_tol(tip[0], 0.5, 1e-9);
            ck_assert_double_eq_tol(tip[1], 0.5, 1e-9);
        }
        tlsph_model_free(m);
    }
}
END_TEST

START_TEST(the_plastic_strain_sum_moves_the_tip)
{
    const char *names[] = {"damage", "void_fraction", "plastic_strain"};
    for (int c = 0; c < 3; c++) {
        struct tlsph_model *m = build_model(scene(GURSON, names[c], 0.35));
        double tip[2];
        for (size_t i = 0; i < m->p.n; i++)
            m->p.damage[i] = 0.0; /* D(f0) = 0.0063 x 3 < 0.35 anyway; by hand: none */
        ck_assert_int_eq(search(m, tip), 0);
        ck_assert_int_eq(set_fibre(m, m->p.eps_p, 0.5, -0.5, 0.35 / 3 * (1 + 1e-9)), 3);
        const int moved = search(m, tip);
        ck_assert_int_eq(moved, c == 2);
        if (moved) {
            ck_assert_double_eq_tol(tip[0], 0.5, 1e-9);
            ck_assert_double_eq_tol(tip[1], -0.5, 1e-9);
        }
        tlsph_model_free(m);
    }
}
END_TEST

START_TEST(a_quantity_the_material_lacks_is_refused)
{
    char pointer[256];
    ck_assert_ptr_null(try_build_model(scene(JC, "void_fraction", DC), pointer, sizeof pointer));
    ck_assert_str_eq(pointer, "/crack_growth/criterion");
    ck_assert_ptr_null(try_build_model(scene(GURSON, "triaxiality", DC), pointer, sizeof pointer));
    ck_assert_str_eq(pointer, "/crack_growth/criterion");
    struct tlsph_model *m = build_model(scene(JC, "plastic_strain", 0.35));
    ck_assert_ptr_eq(tlsph_crack_criterion_field(m), m->p.eps_p);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("fibre_criterion", 0, each_criterion_reads_its_field,
                 the_void_fraction_sum_moves_the_tip, the_plastic_strain_sum_moves_the_tip,
                 a_quantity_the_material_lacks_is_refused)
