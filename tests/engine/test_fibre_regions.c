/* Fibres per region ("thickness_regions", crack/fibre.h
 * tlsph_fibres_build_regions) and the crack driver reading a tip's region.
 *
 * The body: a T-section at spacing s = 1 mm (lattice origin at the bounding
 * box's corner, points at (i + 1/2) s): the plate x in [0, 12], y in [0, 9],
 * z in [0, 3] mm (three layers z = 0.5, 1.5, 2.5 mm) and one web under it,
 * y in [3, 6] (three particles across, y = 3.5, 4.5, 5.5 mm), z in [-6, 0]
 * (six layers).  Regions: the plate's box, axis z; the web's box, axis y.
 *
 * What must hold, worked out by hand from the lattice:
 *  - the plate's fibres: 12 x 9 = 108 cells (x, y), each its 3 plate particles
 *    in increasing z; the web's: 12 x 6 = 72 cells (x, z), each its 3
 *    particles in increasing y; 180 fibres, every particle in one.  With the
 *    single "thickness_axis": "z" the 36 cells over the web hold 3 + 6 = 9
 *    (the fibre sum then counts nine particles, the stiffened plate's fault);
 *  - the tip search in the web's view measures in the web's plane (x, z): from
 *    a web fibre with V1 = +x the damaged web fibre one spacing ahead is found;
 *    a plate fibre straight "ahead" in the web's plane (V1 = +z from the top of
 *    the web, the plate's fibres 2 mm above) is no candidate in the web's view
 *    and would be one if the view saw every region;
 *  - the driver: a crack started by hand damage in the web (its particles'
 *    stress sigma_zz set so that the start's direction is +-x) splits its
 *    fibre across z (delta normal to x in the web's plane (x, z): the fibre's
 *    centre moves along z, not y) and its facets span the web's width, y in
 *    [3, 6] mm (the fibre's extent +- s/2 along the web's axis);
 *  - a hand-damaged path in the plate along y = 1.5 mm, with the plate's
 *    region cut at x = 8 mm (the particles at x > 8 mm in no region, no
 *    fibre): the tip advances fibre by fibre to x = 7.5 mm, the region's edge
 *    (fewer than 9 fibres within 1.5 spacings), goes through it and stops;
 *    damaged particles beyond are never reached;
 *  - the fibre sum in each region counts three particles;
 *  - a listed pre-crack tip (crack_growth.tips) grows in the region whose
 *    fibres' cells hold it (crack_driver.c region_holds): a through crack in
 *    the plate in x = 6 mm from beyond the edge y = 0 to y = 1 mm, with the
 *    plate fibres x = 6.5 mm, y = 1.5 .. 8.5 mm damaged (and the web's column
 *    x = 6.5 mm under them too, which the plate's tip must not see), grows
 *    exactly as in the same plate without the web (thickness_axis z, the
 *    same damage): the same events (fibre indices: region 0's fibres come
 *    first and are numbered as the plate's; positions, particles split),
 *    the same facets to the bit, 8 advances (45 degrees onto x = 6.5 mm, then
 *    straight along y over the web) and through the edge y = 9 mm;
 *  - a pre-crack in the web in x = 6 mm from below the web's bottom to
 *    z = -4 mm, the web fibres x = 6.5 mm, z = -3.5 .. -0.5 mm damaged, and
 *    the plate fibre above them: the tip grows in the web's plane (x, z):
 *    V1 without a y part, 4 advances up the web, every event a web fibre at
 *    y = 4.5 mm, through the web's top edge and stopped there (the damaged
 *    plate fibre is another region's), each split's delta along x (normal
 *    to V2 = +z in the web's plane: the split fibre's centre moved along x by
 *    0.01 spacing, not along y), the facets spanning the web's width
 *    y in [3, 6] mm. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crack/crack_driver.h"
#include "crack/crack_surface.h"
#include "crack/fibre.h"
#include "run/model.h"
#include "support/check_main.h"
#include "support/scene_builder.h"

#define S 1e-3

/* The geometries: the T-section, and its plate alone. */
static const char *tee_geometry =
    "{\"union\":[{\"box\":{\"min\":[0,0,0],\"max\":[0.012,0.009,0.003]}},"
    "{\"box\":{\"min\":[0,0.003,-0.006],\"max\":[0.012,0.006,0]}}]}";
static const char *plate_geometry = "{\"box\":{\"min\":[0,0,0],\"max\":[0.012,0.009,0.003]}}";

/* A steel body of spacing 1 mm with the given body key text (thickness_axis or
 * regions) and geometry, and the rest of the scene's keys (cracks, crack_growth). */
static struct tlsph_model *section(const char *thin, const char *geometry, const char *rest)
{
    char json[4096];
    snprintf(json, sizeof json,
             "{\"dimension\":3,\"time\":{\"end\":1e-5},\"contact\":{\"enabled\":false},"
             "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2.1e11,"
             "\"poisson_ratio\":0.3,\"strength\":{\"type\":\"linear_hardening\","
             "\"yield_stress\":3e8,\"hardening_modulus\":5e8},"
             "\"damage\":{\"type\":\"johnson_cook\",\"d1\":0.08,\"d2\":0,\"d3\":0}}},"
             "\"bodies\":[{\"name\":\"tee\",\"material\":\"steel\",\"spacing\":0.001,%s,"
             "\"geometry\":%s}],%s}",
             thin, geometry, rest);
    return build_model(json);
}

/* The T-section with the given body key text; initiation on with D_c = 1.5 on
 * the damage. */
static struct tlsph_model *tee(const char *thin)
{
    return section(thin, tee_geometry,
                   "\"crack_growth\":{\"initiate\":true,\"critical_damage\":1.5}");
}

static const char *regions_full =
    "\"thickness_regions\":[{\"axis\":\"z\",\"box\":{\"min\":[0,0,0],\"max\":[0.012,0.009,"
    "0.003]}},{\"axis\":\"y\",\"box\":{\"min\":[0,0.003,-0.006],\"max\":[0.012,0.006,0]}}]";
static const char *regions_cut =
    "\"thickness_regions\":[{\"axis\":\"z\",\"box\":{\"min\":[0,0,0],\"max\":[0.008,0.009,"
    "0.003]}},{\"axis\":\"y\",\"box\":{\"min\":[0,0.003,-0.006],\"max\":[0.012,0.006,0]}}]";

/* The fibre of region r whose centre is (x, y, z) (m); fails when none. */
static size_t fibre_at(const struct tlsph_fibres *f, int r, double x, double y, double z)
{
    for (size_t k = 0; k < f->n; k++)
        if (tlsph_fibres_region_of(f, k) == r && fabs(f->centre[k][0] - x) < 1e-9 &&
            fabs(f->centre[k][1] - y) < 1e-9 && fabs(f->centre[k][2] - z) < 1e-9)
            return k;
    ck_abort_msg("no fibre of region %d at (%g, %g, %g) mm", r, 1e3 * x, 1e3 * y, 1e3 * z);
    return 0;
}

/* Fibre k's particles: damage d each, sigma_jj = s (Pa) for the start's
 * direction (the largest principal stress along j: the crack runs across it). */
static void load_fibre(struct tlsph_model *m, size_t k, double d, int jj, double s)
{
    const struct tlsph_fibres *f = &m->fibres[0];
    static const int diag[3] = {0, 3, 5}; /* xx yy zz in the 6-component stress */
    for (size_t p = f->start[k]; p < f->start[k + 1]; p++) {
        m->p.damage[f->particle[p]] = d;
        m->p.sigma[6 * f->particle[p] + diag[jj]] = s;
    }
}

START_TEST(each_region_stacks_along_its_axis)
{
    struct tlsph_model *m = tee(regions_full);
    const struct tlsph_fibres *f = &m->fibres[0];
    ck_assert_int_eq(f->nregions, 2);
    ck_assert_uint_eq(f->n, 180);
    ck_assert_uint_eq(f->start[f->n], m->p.n); /* every particle in one fibre */
    size_t per[2] = {0, 0};
    for (size_t k = 0; k < f->n; k++) {
        const int r = tlsph_fibres_region_of(f, k);
        const int a = r == 0 ? 2 : 1;
        const double first = r == 0 ? 0.5e-3 : 3.5e-3;
        per[r]++;
        ck_assert_uint_eq(f->start[k + 1] - f->start[k], 3);
        for (size_t p = f->start[k]; p < f->start[k + 1]; p++)
            ck_assert_double_eq_tol(m->p.X[3 * f->particle[p] + a],
                                    first + (double)(p - f->start[k]) * S, 1e-12);
    }
    ck_assert_uint_eq(per[0], 108);
    ck_assert_uint_eq(per[1], 72);
    /* the fibre sum counts three particles in each region */
    for (size_t i = 0; i < m->p.n; i++)
        m->p.damage[i] = 0.25;
    for (size_t k = 0; k < f->n; k++)
        ck_assert_double_eq_tol(tlsph_fibre_damage(f, k, m->p.damage), 0.75, 1e-15);
    tlsph_model_free(m);

    /* one axis for the whole body: the cells over the web hold nine */
    m = tee("\"thickness_axis\":\"z\"");
    f = &m->fibres[0];
    size_t nine = 0;
    ck_assert_uint_eq(f->n, 108);
    for (size_t k = 0; k < f->n; k++)
        nine += f->start[k + 1] - f->start[k] == 9;
    ck_assert_uint_eq(nine, 36);
    tlsph_model_free(m);
}
END_TEST

START_TEST(the_web_searches_in_its_plane)
{
    struct tlsph_model *m = tee(regions_full);
    const struct tlsph_fibres *f = &m->fibres[0];
    double *D = m->p.damage;
    const struct tlsph_fibres web = tlsph_fibres_view(f, 1), plate = tlsph_fibres_view(f, 0);
    ck_assert_int_eq(web.axis, 1);
    ck_assert_int_eq(plate.axis, 2);
    /* along x in the web: the next web fibre */
    const size_t a = fibre_at(f, 1, 5.5e-3, 4.5e-3, -3.5e-3);
    const size_t b = fibre_at(f, 1, 6.5e-3, 4.5e-3, -3.5e-3);
    load_fibre(m, b, 1.0, 2, 0.0);
    struct tlsph_tip_search q = {.radius = 1.5 * S, .theta_c = 2.0 * M_PI / 3.0, .D_c = 1.5};
    memcpy(q.tip, f->centre[a], sizeof q.tip);
    q.direction[0] = 1.0;
    ck_assert_int_eq(tlsph_fibre_next_tip(&web, D, &q), (long)b);
    ck_assert_uint_eq(tlsph_fibres_within(&web, f->centre[a], 1.5 * S * (1 + 1e-9), NULL, 0), 9);
    /* up from the web's top: the plate's fibre 2 mm above is another region's */
    const size_t top = fibre_at(f, 1, 5.5e-3, 4.5e-3, -0.5e-3);
    const size_t over = fibre_at(f, 0, 5.5e-3, 0.5e-3, 1.5e-3);
    load_fibre(m, over, 1.0, 2, 0.0);
    memcpy(q.tip, f->centre[top], sizeof q.tip);
    q.direction[0] = 0.0;
    q.direction[2] = 1.0;
    q.radius = 2.5 * S;
    ck_assert_int_eq(tlsph_fibre_next_tip(&web, D, &q), -1);
    struct tlsph_fibres all = web; /* the web's plane, every region's fibres */
    all.only = 0;
    ck_assert_int_eq(tlsph_fibre_next_tip(&all, D, &q), (long)over);
    tlsph_model_free(m);
}
END_TEST

/* Runs the driver (no model step) until nothing changes for 3 calls or 40. */
static void drive(struct tlsph_model *m)
{
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    size_t quiet = 0, last = m->crack_driver->nevents;
    for (int k = 0; k < 40 && quiet < 3; k++) {
        ck_assert_int_eq(tlsph_crack_driver_step(m, NULL, &err), 0);
        quiet = m->crack_driver->nevents == last ? quiet + 1 : 0;
        last = m->crack_driver->nevents;
    }
    tlsph_errors_free(&err);
}

START_TEST(a_web_crack_cuts_across_the_web)
{
    struct tlsph_model *m = tee(regions_full);
    const struct tlsph_fibres *f = &m->fibres[0];
    const size_t k = fibre_at(f, 1, 5.5e-3, 4.5e-3, -3.5e-3);
    double C0[3];
    memcpy(C0, f->centre[k], sizeof C0);
    load_fibre(m, k, 1.0, 2, 1e8); /* sigma_zz: the crack runs along x */
    const size_t n0 = m->crack_surface ? m->crack_surface->nfacets : 0;
    drive(m);
    const struct tlsph_crack_driver *d = m->crack_driver;
    ck_assert_uint_eq(d->starts, 1);
    ck_assert_uint_eq(d->event[0].fibre, k);
    f = &m->fibres[0];
    /* the +delta halves stay fibre k: its centre moved by delta along z */
    ck_assert_double_eq_tol(f->centre[k][1], C0[1], 1e-12);
    ck_assert_double_eq_tol(fabs(f->centre[k][2] - C0[2]), TLSPH_CRACK_DELTA * S, 1e-12);
    ck_assert_int_eq(tlsph_fibres_region_of(f, f->n - 1), 1); /* the new face's fibre */
    /* the facets span the web's width along y and lie in the plane z = C0 */
    ck_assert_uint_gt(m->crack_surface->nfacets, n0);
    double lo = INFINITY, hi = -INFINITY;
    for (size_t t = n0; t < m->crack_surface->nfacets; t++)
        for (int v = 0; v < 3; v++) {
            lo = fmin(lo, m->crack_surface->facet[t][v][1]);
            hi = fmax(hi, m->crack_surface->facet[t][v][1]);
            ck_assert_double_eq_tol(m->crack_surface->facet[t][v][2], C0[2], 1e-12);
        }
    ck_assert_double_eq_tol(lo, 3e-3, 1e-12);
    ck_assert_double_eq_tol(hi, 6e-3, 1e-12);
    tlsph_model_free(m);
}
END_TEST

START_TEST(a_path_stops_at_the_region_edge)
{
    struct tlsph_model *m = tee(regions_cut);
    const struct tlsph_fibres *f = &m->fibres[0];
    ck_assert_uint_eq(f->n, 8 * 9 + 72); /* plate cells x = 0.5 .. 7.5 mm */
    /* the start at (2.5, 1.5) mm, sigma_yy: running along x */
    load_fibre(m, fibre_at(f, 0, 2.5e-3, 1.5e-3, 1.5e-3), 1.0, 1, 1e8);
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    ck_assert_int_eq(tlsph_crack_driver_step(m, NULL, &err), 0); /* the start */
    /* the path, one fibre ahead of the tip per driver call (each within the
     * clearance of the tip's last fibre: no start of its own) */
    for (int i = 3; i < 8; i++) {
        f = &m->fibres[0];
        load_fibre(m, fibre_at(f, 0, (i + 0.5) * S, 1.5e-3, 1.5e-3), 1.0, 1, 0.0);
        ck_assert_int_eq(tlsph_crack_driver_step(m, NULL, &err), 0);
    }
    tlsph_errors_free(&err);
    /* the plate's particles beyond the region at y = 1.5 mm, damaged */
    size_t beyond = 0;
    for (size_t i = 0; i < m->p.n; i++)
        if (m->p.X[3 * i] > 8e-3 && fabs(m->p.X[3 * i + 1] - 1.5e-3) < 1e-9 &&
            m->p.X[3 * i + 2] > 0.0) {
            m->p.damage[i] = 1.0;
            beyond++;
        }
    ck_assert_uint_eq(beyond, 4 * 3);
    drive(m);
    const struct tlsph_crack_driver *d = m->crack_driver;
    ck_assert_uint_eq(d->starts, 1);
    const struct tlsph_crack_tip *ahead = NULL;
    for (size_t t = 0; t < d->nstarted; t++)
        if (d->tip[d->ntips + t].V1[0] > 0.0)
            ahead = &d->tip[d->ntips + t];
    ck_assert_ptr_nonnull(ahead);
    ck_assert_int_eq(ahead->stopped, 1);
    ck_assert_uint_eq(ahead->advances, 5); /* 3.5, 4.5, 5.5, 6.5, 7.5 mm */
    ck_assert_double_eq_tol(ahead->T[0], 7.5e-3, 1e-12);
    ck_assert_double_eq_tol(ahead->T[1], 1.5e-3, 1e-12);
    for (size_t e = 0; e < d->nevents; e++)
        ck_assert(d->event[e].position[0] < 8e-3);
    /* through the edge: the cut runs a spacing past the last fibre, and no
     * particle beyond the region was split (the count grew by the fibres'
     * particles only: 6 fibres of 3) */
    ck_assert_double_eq_tol(ahead->end[0], 8.5e-3, 1e-12);
    ck_assert_uint_eq(d->particles_split, 6 * 3);
    tlsph_model_free(m);
}
END_TEST

/* The T-section (regions_full) or the plate alone (thickness_axis z) with a
 * through crack (its corners, mm) and its tip (mm); no initiation, D_c 1.5. */
static struct tlsph_model *cracked(int web, const double corner[4][3], const double tip[3])
{
    char rest[1024];
    int at = snprintf(rest, sizeof rest, "\"cracks\":[{\"polygon\":[");
    for (int c = 0; c < 4; c++)
        at += snprintf(rest + at, sizeof rest - (size_t)at, "%s[%.17g,%.17g,%.17g]", c ? "," : "",
                       1e-3 * corner[c][0], 1e-3 * corner[c][1], 1e-3 * corner[c][2]);
    snprintf(rest + at, sizeof rest - (size_t)at,
             "]}],\"crack_growth\":{\"critical_damage\":1.5,\"tips\":[[%.17g,%.17g,%.17g]]}",
             1e-3 * tip[0], 1e-3 * tip[1], 1e-3 * tip[2]);
    return section(web ? regions_full : "\"thickness_axis\":\"z\"",
                   web ? tee_geometry : plate_geometry, rest);
}

/* Equal coordinates of the two lattices: in the plate's plane (x, y) to the
 * bit, along z to the round-off of the lattice's origin (the T-section's
 * lowest point is z = -6 mm, the plate's 0: the same point z = 1.5 mm is
 * -6e-3 + 7.5e-3 in one and 1.5e-3 in the other, 2e-19 m apart). */
static int same(double a, double b, int k)
{
    return k < 2 ? a == b : fabs(a - b) <= 1e-15;
}

START_TEST(a_plate_precrack_grows_as_without_the_web)
{
    static const double corner[4][3] = {{6, -1, -1}, {6, 1, -1}, {6, 1, 4}, {6, -1, 4}};
    static const double tip[3] = {6, 1, 1.5};
    struct tlsph_model *m[2] = {cracked(1, corner, tip), cracked(0, corner, tip)};
    ck_assert_uint_eq(m[0]->fibres[0].n, 180);
    ck_assert_uint_eq(m[1]->fibres[0].n, 108);
    for (int w = 0; w < 2; w++) {
        const struct tlsph_fibres *f = &m[w]->fibres[0];
        ck_assert_int_eq(m[w]->crack_driver->tip[0].region, 0);
        for (int i = 1; i < 9; i++)
            load_fibre(m[w], fibre_at(f, 0, 6.5e-3, (i + 0.5) * S, 1.5e-3), 1.0, 0, 0.0);
        if (w == 0) /* the web's column under the path: another region's */
            for (int i = 0; i < 6; i++)
                load_fibre(m[w], fibre_at(f, 1, 6.5e-3, 4.5e-3, -(i + 0.5) * S), 1.0, 0, 0.0);
        drive(m[w]);
    }
    const struct tlsph_crack_driver *a = m[0]->crack_driver, *b = m[1]->crack_driver;
    printf("plate pre-crack with the web: %zu advances, %zu particles split, %zu facets; "
           "without: %zu, %zu, %zu\n",
           a->nevents, a->particles_split, m[0]->crack_surface->nfacets, b->nevents,
           b->particles_split, m[1]->crack_surface->nfacets);
    ck_assert_uint_eq(a->nevents, 8);
    ck_assert_uint_eq(b->nevents, 8);
    ck_assert_int_eq(a->tip[0].stopped, 1);
    ck_assert_int_eq(b->tip[0].stopped, 1);
    for (size_t e = 0; e < a->nevents; e++) {
        ck_assert_int_eq(a->event[e].fibre, b->event[e].fibre);
        ck_assert_uint_eq(a->event[e].split, b->event[e].split);
        ck_assert_int_eq(tlsph_fibres_region_of(&m[0]->fibres[0], (size_t)a->event[e].fibre), 0);
        for (int k = 0; k < 3; k++)
            ck_assert_msg(same(a->event[e].position[k], b->event[e].position[k], k),
                          "event %zu axis %d: %.17g vs %.17g", e, k, a->event[e].position[k],
                          b->event[e].position[k]);
        ck_assert_double_eq_tol(a->event[e].position[0], 6.5e-3, 1e-12);
        ck_assert_double_eq_tol(a->event[e].position[1], (e + 1.5) * S, 1e-12);
    }
    ck_assert_uint_eq(a->particles_split, b->particles_split);
    ck_assert(a->tip[0].length == b->tip[0].length);
    /* the same cut: every facet, in the plane to the bit */
    const struct tlsph_crack_surface *sa = m[0]->crack_surface, *sb = m[1]->crack_surface;
    ck_assert_uint_eq(sa->nfacets, sb->nfacets);
    for (size_t t = 0; t < sa->nfacets; t++)
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++)
                ck_assert(same(sa->facet[t][v][k], sb->facet[t][v][k], k));
    tlsph_model_free(m[0]);
    tlsph_model_free(m[1]);
}
END_TEST

START_TEST(a_web_precrack_grows_in_the_web_plane)
{
    static const double corner[4][3] = {{6, 2, -7}, {6, 7, -7}, {6, 7, -4}, {6, 2, -4}};
    static const double tip[3] = {6, 4.5, -4};
    struct tlsph_model *m = cracked(1, corner, tip);
    const struct tlsph_fibres *f = &m->fibres[0];
    const struct tlsph_crack_tip *t = &m->crack_driver->tip[0];
    ck_assert_int_eq(t->region, 1);
    ck_assert(t->V1[1] == 0.0 && t->V1[2] > 0.0 && t->V1[0] == 0.0);
    size_t path[4];
    double C0[4][3];
    for (int i = 0; i < 4; i++) {
        path[i] = fibre_at(f, 1, 6.5e-3, 4.5e-3, -(3.5 - i) * S);
        memcpy(C0[i], f->centre[path[i]], sizeof C0[i]);
        load_fibre(m, path[i], 1.0, 0, 0.0);
    }
    load_fibre(m, fibre_at(f, 0, 6.5e-3, 4.5e-3, 1.5e-3), 1.0, 0, 0.0); /* the plate above */
    const size_t n0 = m->crack_surface->nfacets;
    drive(m);
    const struct tlsph_crack_driver *d = m->crack_driver;
    f = &m->fibres[0];
    printf("web pre-crack: %zu advances, %zu particles split, %zu facets added\n", d->nevents,
           d->particles_split, m->crack_surface->nfacets - n0);
    ck_assert_uint_eq(d->nevents, 4);
    ck_assert_int_eq(t->stopped, 1);
    for (size_t e = 0; e < d->nevents; e++) {
        ck_assert_int_eq(d->event[e].fibre, (long)path[e]);
        ck_assert_int_eq(tlsph_fibres_region_of(f, path[e]), 1);
        ck_assert_double_eq_tol(d->event[e].position[1], 4.5e-3, 1e-12);
    }
    /* each path fibre split with delta along x (normal to +z in the web's plane) */
    for (int i = 0; i < 4; i++) {
        ck_assert_double_eq_tol(f->centre[path[i]][1], C0[i][1], 1e-12);
        ck_assert_double_eq_tol(f->centre[path[i]][2], C0[i][2], 1e-12);
        ck_assert_double_eq_tol(fabs(f->centre[path[i]][0] - C0[i][0]), TLSPH_CRACK_DELTA * S,
                                1e-12);
    }
    /* the facets span the web's width along y */
    ck_assert_uint_gt(m->crack_surface->nfacets, n0);
    for (size_t q = n0; q < m->crack_surface->nfacets; q++)
        for (int v = 0; v < 3; v++) {
            const double y = m->crack_surface->facet[q][v][1];
            ck_assert_msg(fabs(y - 3e-3) < 1e-12 || fabs(y - 6e-3) < 1e-12, "facet y %g", y);
            ck_assert(m->crack_surface->facet[q][v][2] <= 0.5e-3 + 1e-12);
        }
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("fibre_regions", 60, each_region_stacks_along_its_axis,
                 the_web_searches_in_its_plane, a_web_crack_cuts_across_the_web,
                 a_path_stops_at_the_region_edge, a_plate_precrack_grows_as_without_the_web,
                 a_web_precrack_grows_in_the_web_plane)
