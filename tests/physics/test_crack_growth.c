/* The crack driver (core/crack/crack_driver.c): a crack grows in a run.
 *
 * The plate: steel (linear hardening, Johnson-Cook damage with a failure
 * strain of 8 %), 24 x 20 x 3 mm at 1 mm (1440 particles, three layers: the
 * paper's fibres of three), an edge crack in y = 0 from beyond the left edge
 * to x = 0 through the thickness, its tip at (0, 0) growing with the scene's
 * defaults (D_c = 0.1, theta_c = 120 degrees, R = 1.5 spacings).  The rows
 * |y| > 8.5 mm are pulled apart in y (mode I) at up to 5 m/s each side.
 * Contact off: the faces open and do not meet.  cfl 0.3, where the energy
 * bound below was measured.
 *
 * What must hold, and the references:
 *  - the tip advances (more than 5 advances; measured 14, through the right
 *    edge at 1.075e-4 s) and straight ahead: every tip
 *    position within 1 spacing of the pre-crack's line y = 0 (a fibre row is
 *    half a spacing off it: the path may step to the row beside, no
 *    further), every advance forward (x grows), the last tip within 10
 *    degrees of the pre-crack's direction seen from its end;
 *  - across every split (the totals just before and just after the driver's
 *    step): mass and volume to 1e-14 relative, linear momentum to 1e-14 of
 *    sum m|v| (eqs. 21-30; a sum over ~1500 particles in another order
 *    differs by ~n eps = 1e-13 at most; measured: exact or 1 ulp);
 *  - the stability contract every step (finite values, det F, the engine's
 *    energy check) and the energy balance within 2e-3 of the largest energy
 *    term over the run, 1e-3 from the first split on (measured 1.44e-3 with
 *    and without growth, the load's ramp; 3.9e-4 after the first split, the
 *    plate without growth ends at 1.4e-4), no particle lost: the
 *    count = the initial one + the particles split, ids unique;
 *  - the series values: crack_length = the facets' in-plane lengths > 0,
 *    particle count after = before + split;
 *  - a centre crack (x from -2 to 6 mm) growing at both ends: each tip
 *    advances (at least 3 times; measured 8 and 8) away from the other,
 *    within 1 spacing of the crack's line;
 *  - the same plate without "crack_growth" splits nothing (the count and
 *    the modules unchanged).
 * And a unit test of the fibre remap (tlsph_split_particles on a model with
 * two thin bodies): every fibre's list valid after a split (each particle of
 * a thin body in exactly one fibre, ascending along the axis, all at the
 * fibre's in-plane point, centres the mean of X), the halves 2 a new fibre,
 * the second body's fibres shifted with its particles. */
#include <check.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact/state.h"
#include "crack/crack_driver.h"
#include "crack/fibre.h"
#include "crack/split.h"
#include "io/fields.h"
#include "run/integrate.h"
#include "run/model.h"
#include "support/check_main.h"
#include "support/crack_plate.h"
#include "support/scene_builder.h"
#include "util/clock.h"

#define SPACING 0.001
/* |balance| / scale (cfl 0.3): over the whole run 1.44e-3 with and without
 * growth (the load's ramp, before any split); from the first split on
 * 3.9e-4 (the plate without growth ends at 1.4e-4) */
#define ENERGY_BOUND 2e-3
#define ENERGY_BOUND_AFTER 1e-3

static char *plate_json(int grow)
{
    static char text[4096];
    return crack_plate_scene(text, sizeof text, 24.0, 20.0, 1.1e-4, grow);
}

static int cmp_i64(const void *a, const void *b)
{
    const int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return x < y ? -1 : x > y;
}

/* One step, the driver after it, and the stability contract. */
static void step_grow_check(struct tlsph_model *m, struct tlsph_errors *err)
{
    tlsph_model_step(m);
    ck_assert_int_eq(tlsph_crack_driver_step(m, NULL, err), 0);
    struct tlsph_diagnostic d;
    if (tlsph_model_check(m, &d) != 0)
        ck_abort_msg("unstable at step %ld: %s", m->step, d.message);
}

START_TEST(mode_one_crack_grows_straight)
{
    struct tlsph_model *m = build_model(plate_json(1));
    ck_assert_ptr_nonnull(m->crack_driver);
    ck_assert(model_has_module(m, "crack:growth"));
    const size_t n0 = m->p.n;
    double worst_balance = 0.0, worst_after = 0.0, worst_mass = 0.0, worst_vol = 0.0, worst_mom = 0.0;
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    const double wall0 = tlsph_monotonic_seconds();
    while (m->t < m->scene.end_time * (1.0 - 1e-12)) {
        tlsph_model_step(m);
        const size_t before_events = m->crack_driver->nevents, before_n = m->p.n;
        const struct crack_totals a = crack_totals(m);
        ck_assert_int_eq(tlsph_crack_driver_step(m, NULL, &err), 0);
        if (m->crack_driver->nevents != before_events) {
            const struct crack_totals b = crack_totals(m);
            worst_mass = fmax(worst_mass, fabs(b.mass - a.mass) / a.mass);
            worst_vol = fmax(worst_vol, fabs(b.vol - a.vol) / a.vol);
            for (int c = 0; c < 3; c++)
                worst_mom = fmax(worst_mom, fabs(b.mom[c] - a.mom[c]) / a.scale);
            const struct tlsph_crack_event *e =
                &m->crack_driver->event[m->crack_driver->nevents - 1];
            ck_assert_uint_eq(m->p.n, before_n + e->split);
        }
        struct tlsph_diagnostic d;
        if (tlsph_model_check(m, &d) != 0)
            ck_abort_msg("unstable at step %ld: %s", m->step, d.message);
        const double bal = fabs(tlsph_energy_balance(&m->energy)) / m->energy.scale;
        worst_balance = fmax(worst_balance, bal);
        if (m->crack_driver->particles_split)
            worst_after = fmax(worst_after, bal);
    }
    printf("final balance %.3e, worst after the first split %.3e of the scale\n",
           tlsph_energy_balance(&m->energy) / m->energy.scale, worst_after);
    const double wall = tlsph_monotonic_seconds() - wall0;
    const struct tlsph_crack_driver *cd = m->crack_driver;
    printf("crack growth: %ld steps, %zu advances, %zu particles split, %zu -> %zu particles, "
           "grown %.4g m; mass %.2e, volume %.2e, momentum %.2e; worst balance %.3e of the "
           "scale; driver %.4f s of %.3f s (%.2f %%)\n",
           m->step, cd->nevents, cd->particles_split, n0, m->p.n,
           tlsph_crack_driver_length(m), worst_mass, worst_vol, worst_mom, worst_balance,
           cd->seconds, wall, 100.0 * cd->seconds / wall);
    for (size_t k = 0; k < cd->nevents; k++)
        printf("  step %ld t %.3e tip (%.4g, %.4g) mm fibre %ld split %zu\n", cd->event[k].step,
               cd->event[k].time, 1e3 * cd->event[k].position[0],
               1e3 * cd->event[k].position[1], cd->event[k].fibre, cd->event[k].split);
    ck_assert_uint_gt(cd->nevents, 5);
    double last_x = -1.0;
    for (size_t k = 0; k < cd->nevents; k++) {
        ck_assert(fabs(cd->event[k].position[1]) <= SPACING * (1.0 + 1e-9));
        ck_assert(cd->event[k].position[0] > last_x);
        last_x = cd->event[k].position[0];
    }
    const double *P = cd->event[cd->nevents - 1].position;
    ck_assert(fabs(atan2(P[1], P[0])) <= 10.0 * M_PI / 180.0);
    ck_assert(worst_mass <= 1e-14 && worst_vol <= 1e-14 && worst_mom <= 1e-14);
    ck_assert(worst_balance <= ENERGY_BOUND);
    ck_assert(worst_after <= ENERGY_BOUND_AFTER);
    ck_assert_uint_eq(m->p.n, n0 + cd->particles_split);
    ck_assert_double_gt(tlsph_crack_driver_length(m), 0.0);
    /* the series the result file gets: the crack_tips family and the globals */
    const struct tlsph_series_family *fam = &tlsph_series_families[TLSPH_FAMILY_CRACK_TIPS];
    ck_assert_uint_eq(fam->count(m), 1);
    ck_assert_str_eq(fam->item(m, 0), "tip0");
    double row[5];
    fam->values(m, 0, row);
    for (int c = 0; c < 3; c++)
        ck_assert(row[c] == P[c]);
    ck_assert(row[3] == (double)cd->nevents && row[4] == tlsph_crack_driver_length(m));
    int64_t *ids = malloc(m->p.n * sizeof *ids);
    ck_assert_ptr_nonnull(ids);
    memcpy(ids, m->p.id, m->p.n * sizeof *ids);
    qsort(ids, m->p.n, sizeof *ids, cmp_i64);
    for (size_t i = 1; i < m->p.n; i++)
        ck_assert(ids[i] != ids[i - 1]);
    free(ids);
    tlsph_errors_free(&err);
    tlsph_model_free(m);
}
END_TEST

/* A centre crack from x = -2 to 6 mm with both ends growing: each tip
 * advances away from the other along the crack's line. */
START_TEST(through_crack_grows_at_both_tips)
{
    char text[4096];
    json_t *root = json_loads(crack_plate_scene(text, sizeof text, 24.0, 20.0, 1.1e-4, 1), 0, NULL);
    ck_assert_ptr_nonnull(root);
    json_object_set_new(root, "cracks",
                        json_pack("[{s:[[f,i,f],[f,i,f],[f,i,f],[f,i,f]]}]", "polygon", -0.002, 0,
                                  -0.001, 0.006, 0, -0.001, 0.006, 0, 0.004, -0.002, 0, 0.004));
    json_object_set_new(json_object_get(root, "crack_growth"), "tips",
                        json_pack("[[f,i,f],[f,i,f]]", -0.002, 0, 0.0015, 0.006, 0, 0.0015));
    struct tlsph_model *m = build_model_json(root);
    const size_t n0 = m->p.n;
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    while (m->t < m->scene.end_time * (1.0 - 1e-12)) {
        step_grow_check(m, &err);
    }
    const struct tlsph_crack_driver *cd = m->crack_driver;
    double last[2] = {0.002, 0.002}; /* distance from the crack's centre x = 2 mm */
    size_t count[2] = {0, 0};
    for (size_t k = 0; k < cd->nevents; k++) {
        const struct tlsph_crack_event *e = &cd->event[k];
        const double r = fabs(e->position[0] - 0.002);
        ck_assert(e->tip == 0 ? e->position[0] < -0.002 : e->position[0] > 0.006);
        ck_assert(r > last[e->tip]);
        ck_assert(fabs(e->position[1]) <= SPACING * (1.0 + 1e-9));
        last[e->tip] = r;
        count[e->tip]++;
    }
    printf("two tips: %zu and %zu advances, %zu -> %zu particles, grown %.4g m\n", count[0],
           count[1], n0, m->p.n, tlsph_crack_driver_length(m));
    ck_assert(count[0] >= 3 && count[1] >= 3);
    tlsph_errors_free(&err);
    tlsph_model_free(m);
}
END_TEST

START_TEST(no_growth_without_the_key)
{
    struct tlsph_model *m = build_model(plate_json(0));
    ck_assert_ptr_null(m->crack_driver);
    ck_assert(!model_has_module(m, "crack:growth"));
    const size_t n0 = m->p.n;
    double worst_balance = 0.0;
    while (m->t < m->scene.end_time * (1.0 - 1e-12)) {
        tlsph_model_step(m);
        struct tlsph_diagnostic d;
        if (tlsph_model_check(m, &d) != 0)
            ck_abort_msg("unstable at step %ld: %s", m->step, d.message);
        worst_balance =
            fmax(worst_balance, fabs(tlsph_energy_balance(&m->energy)) / m->energy.scale);
    }
    printf("no growth: %ld steps, worst balance %.3e, final %.3e of the scale\n", m->step,
           worst_balance, tlsph_energy_balance(&m->energy) / m->energy.scale);
    ck_assert_uint_eq(m->p.n, n0);
    tlsph_model_free(m);
}
END_TEST

/* Every thin body's fibres: a partition of its particles, each fibre at one
 * in-plane point, ascending along the axis, its centre the mean of X. */
static void check_fibres(const struct tlsph_model *m)
{
    int *seen = calloc(m->p.n, sizeof *seen);
    ck_assert_ptr_nonnull(seen);
    for (size_t b = 0; b < m->scene.nbodies; b++) {
        const struct tlsph_fibres *f = &m->fibres[b];
        if (m->scene.bodies[b].thickness_axis < 0) {
            ck_assert_uint_eq(f->n, 0);
            continue;
        }
        const int ax = f->axis, a0 = ax == 0 ? 1 : 0, a1 = ax == 2 ? 1 : 2;
        ck_assert_uint_eq(f->start[f->n], m->body_end[b] - m->body_begin[b]);
        for (size_t j = 0; j < f->n; j++) {
            ck_assert_uint_lt(f->start[j], f->start[j + 1]);
            double c[3] = {0, 0, 0};
            const double cnt = (double)(f->start[j + 1] - f->start[j]);
            for (size_t p = f->start[j]; p < f->start[j + 1]; p++) {
                const size_t i = f->particle[p];
                ck_assert(i >= m->body_begin[b] && i < m->body_end[b]);
                ck_assert_int_eq(seen[i]++, 0);
                if (p > f->start[j])
                    ck_assert(m->p.X[3 * i + ax] > m->p.X[3 * f->particle[p - 1] + ax]);
                const size_t i0 = f->particle[f->start[j]];
                ck_assert(fabs(m->p.X[3 * i + a0] - m->p.X[3 * i0 + a0]) < 1e-12);
                ck_assert(fabs(m->p.X[3 * i + a1] - m->p.X[3 * i0 + a1]) < 1e-12);
                for (int a = 0; a < 3; a++)
                    c[a] += m->p.X[3 * i + a] / cnt;
            }
            for (int a = 0; a < 3; a++)
                ck_assert(fabs(c[a] - f->centre[j][a]) < 1e-15);
        }
    }
    free(seen);
}

START_TEST(fibres_follow_a_split)
{
    struct tlsph_model *m = build_model(
        "{\"dimension\":3,\"time\":{\"end\":1e-6},\"contact\":{\"enabled\":false},"
        "\"materials\":{\"m\":{\"density\":2700,\"youngs_modulus\":7e10,\"poisson_ratio\":0.33}},"
        "\"bodies\":[{\"name\":\"plate\",\"material\":\"m\",\"spacing\":0.001,"
        "\"thickness_axis\":\"z\",\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.010,0.008,0.003]}}},"
        "{\"name\":\"block\",\"material\":\"m\",\"spacing\":0.001,"
        "\"geometry\":{\"box\":{\"min\":[0.02,0,0],\"max\":[0.024,0.004,0.003]}}},"
        "{\"name\":\"strip\",\"material\":\"m\",\"spacing\":0.001,\"thickness_axis\":\"y\","
        "\"geometry\":{\"box\":{\"min\":[0,0.02,0],\"max\":[0.006,0.023,0.004]}}}]}");
    check_fibres(m);
    const size_t nf0 = m->fibres[0].n, nf2 = m->fibres[2].n, begin2 = m->body_begin[2];
    const size_t first2 = m->fibres[2].particle[0];
    /* fibre 13 of the plate: (3.5, 1.5) mm, three particles */
    const size_t J = 13;
    const size_t k = m->fibres[0].start[J + 1] - m->fibres[0].start[J];
    ck_assert_uint_eq(k, 3);
    size_t index[3];
    memcpy(index, m->fibres[0].particle + m->fibres[0].start[J], sizeof index);
    struct tlsph_crack_surface cs;
    ck_assert_int_eq(tlsph_crack_surface_init(&cs, 0.0024), TLSPH_CRACK_OK);
    const double yc = m->fibres[0].centre[J][1], xc = m->fibres[0].centre[J][0];
    const double T1[3][3] = {{-0.001, yc, -0.001}, {xc, yc, -0.001}, {xc, yc, 0.004}};
    const double T2[3][3] = {{-0.001, yc, -0.001}, {xc, yc, 0.004}, {-0.001, yc, 0.004}};
    ck_assert_int_eq(tlsph_crack_surface_add(&cs, T1), TLSPH_CRACK_OK);
    ck_assert_int_eq(tlsph_crack_surface_add(&cs, T2), TLSPH_CRACK_OK);
    struct tlsph_split sp = {.index = index, .n = k, .V1 = {1, 0, 0}, .V2 = {1, 0, 0},
                             .delta = {0, 1e-5, 0}};
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    ck_assert_int_eq(tlsph_split_particles(m, &sp, &cs, 0, NULL, NULL, &err), 0);
    check_fibres(m);
    ck_assert_uint_eq(m->fibres[0].n, nf0 + 1);
    ck_assert_uint_eq(m->fibres[2].n, nf2);
    ck_assert_uint_eq(m->fibres[2].particle[0], first2 + k);
    ck_assert_uint_eq(m->body_begin[2], begin2 + k);
    /* the parent fibre keeps its index at +delta, the halves 2 are the last fibre */
    const struct tlsph_fibres *f = &m->fibres[0];
    ck_assert(fabs(f->centre[J][1] - (yc + 1e-5)) < 1e-15);
    ck_assert(fabs(f->centre[nf0][1] - (yc - 1e-5)) < 1e-15);
    for (size_t s = 0; s < k; s++) {
        ck_assert_uint_eq(f->particle[f->start[J] + s], index[s]);
        ck_assert_uint_eq(f->particle[f->start[nf0] + s], m->body_end[0] - k + s);
    }
    /* the damage sum of each new fibre counts its own particles only */
    double *D = calloc(m->p.n, sizeof *D);
    ck_assert_ptr_nonnull(D);
    for (size_t i = 0; i < m->p.n; i++)
        D[i] = 0.01;
    ck_assert(fabs(tlsph_fibre_damage(f, J, D) - 0.03) < 1e-15);
    ck_assert(fabs(tlsph_fibre_damage(f, nf0, D) - 0.03) < 1e-15);
    free(D);
    tlsph_crack_surface_release(&cs);
    tlsph_errors_free(&err);
    tlsph_model_free(m);
}
END_TEST

/* Contact on (the default): the faces a split makes take part in contact
 * within the body, and the two halves of one split particle (2 delta apart,
 * one material point on both faces) are never a contact pair.  Before they
 * were excluded, the halves were candidates overlapped by 98 % of their contact
 * distance and the plate stopped on contact_penetration at its second advance
 * (examples/crack-growth-plate.json: step 400, 0.977 against the limit 0.5).
 * Reference: the same bounds as without contact (the crack runs straight
 * ahead, more than 5 advances, the balance within ENERGY_BOUND). */
START_TEST(faces_take_part_in_contact)
{
    char *json = plate_json(1);
    char *off = strstr(json, "\"contact\":{\"enabled\":false},");
    ck_assert_ptr_nonnull(off);
    memmove(off, off + strlen("\"contact\":{\"enabled\":false},"),
            strlen(off + strlen("\"contact\":{\"enabled\":false},")) + 1);
    struct tlsph_model *m = build_model(json);
    ck_assert_ptr_nonnull(m->contact);
    ck_assert_ptr_nonnull(m->contact->touch);
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    double worst_balance = 0.0;
    size_t half_pairs = 0, face_pairs = 0;
    while (m->t < m->scene.end_time * (1.0 - 1e-12)) {
        step_grow_check(m, &err);
        worst_balance = fmax(worst_balance, fabs(tlsph_energy_balance(&m->energy)) / m->energy.scale);
        const struct tlsph_contact *c = m->contact;
        for (size_t i = 0; i < m->p.n; i++)
            for (int64_t k = c->start[i]; k < c->start[i + 1]; k++) {
                const size_t j = (size_t)c->j[k];
                if (m->p.body[i] != m->p.body[j])
                    continue;
                half_pairs += tlsph_contact_split_halves(&m->p, i, j);
                face_pairs += m->crack_driver->particles_split && tlsph_contact_cut_pair(m, i, j);
            }
    }
    const struct tlsph_crack_driver *cd = m->crack_driver;
    printf("with contact: %zu advances, %zu particles split, worst balance %.3e of the scale, "
           "candidate pair-steps across the faces %zu, between halves %zu\n",
           cd->nevents, cd->particles_split, worst_balance, face_pairs, half_pairs);
    ck_assert_uint_gt(cd->nevents, 5);
    for (size_t k = 0; k < cd->nevents; k++)
        ck_assert(fabs(cd->event[k].position[1]) <= SPACING * (1.0 + 1e-9));
    ck_assert_uint_eq(half_pairs, 0);
    ck_assert_uint_gt(face_pairs, 0);
    ck_assert(worst_balance <= ENERGY_BOUND);
    tlsph_errors_free(&err);
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("crack_growth", 300, fibres_follow_a_split, no_growth_without_the_key,
                 mode_one_crack_grows_straight, through_crack_grows_at_both_tips,
                 faces_take_part_in_contact)
