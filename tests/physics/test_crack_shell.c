/* The crack driver on a curved shell (paper 003 §6.4): fibres through the
 * radial thickness of a conforming tube, the tip search, the splits and the
 * facets in the shell's tangent plane, and the inner wall's pressure group
 * shared through the splits (core/crack/crack_driver.c, fibre.c, split.c).
 *
 * The tube: the capped cylinder's wall at a quarter of its length (outer
 * radius 0.246 m, inner 0.206 m, length 0.17 m, spacing S = 0.04/3 m: three
 * shells, 112 rays, 13 layers of DZ = 0.17/13 m, 4368 particles), a pressure
 * of 1 MPa on its inner shell, an axial through pre-crack in the half-plane
 * y = 0, x > 0 from z = 5 DZ to 8 DZ (between the rays at +-pi/112, between
 * layers), both ends declared growing tips.  The damage is set by hand (no
 * step before the driver's), so the path is known: the fibres (layer 8, ray
 * +), (9, +), (10, -), (11, -) at D_J = 0.2 > D_c = 0.1 (ray + / -: theta =
 * +-pi/112), nothing at the lower end.  Expected, by hand:
 *  - four advances of the upper tip, in that order: the first from the
 *    pre-crack's end to (8, +) without a split (45.5 degrees off the axis in
 *    the tangent plane, inside the +-60 degree fan), then (9, +) straight up,
 *    (10, -) diagonally across the pre-crack's plane, (11, -) up again; each
 *    of the last three splits the previous tip fibre (3 particles): 4368 ->
 *    4377 particles; the lower tip never advances;
 *  - across each split: mass, volume and momentum to 1e-14 (relative; of
 *    sum m|v| for the momentum, the tube spun about its axis at 1 rad/s so
 *    that it is not zero); the inner wall's group gains the split fibre's
 *    inner particle and its total reference area vector stays to 1e-14 of
 *    sum |N dA| (split.c share_vectors);
 *  - the halves X1 - X2 = 2 delta: length 2 % of S (1e-12), normal to the
 *    radial direction at the parent (the tangent plane at the tip fibre, on
 *    whose ray the parent lies) and to V2 (1e-12 of |delta|);
 *  - every split half keeps at least 8 neighbours and its fibre mates on its
 *    own side that its parent saw (the other halves of the fibre at the same
 *    +-delta, the next shell: the facets hold the split fibre's ray, and the
 *    halves lie +-delta off them on their own sides, also at the diagonal
 *    hop, whose rectangle folds between the skew radial lines at its ends,
 *    crack_driver.c at_depth);
 *  - then 20 steps pass the stability contract (finite values, det F, the
 *    energy balance). */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crack/crack_driver.h"
#include "crack/fibre.h"
#include "run/integrate.h"
#include "run/model.h"
#include "support/check_main.h"
#include "support/scene_builder.h"

#define S (0.04 / 3.0)
#define DZ (0.17 / 13.0)
#define RAY (M_PI / 112.0)

static struct tlsph_model *tube(void)
{
    char json[4096];
    snprintf(json, sizeof json,
             "{\"dimension\":3,\"time\":{\"end\":1.0,\"max_steps\":1000},"
             "\"materials\":{\"steel\":{\"density\":7830,\"youngs_modulus\":2e11,"
             "\"poisson_ratio\":0.3,\"strength\":{\"type\":\"linear_hardening\","
             "\"yield_stress\":4.55e8,\"hardening_modulus\":5e8},\"damage\":{\"type\":"
             "\"johnson_cook\",\"d1\":0.5,\"d2\":0,\"d3\":0}}},"
             "\"bodies\":[{\"name\":\"wall\",\"material\":\"steel\",\"spacing\":%.17g,"
             "\"placement\":\"conforming\",\"thickness_axis\":\"radial\","
             "\"initial_velocity\":[\"-y\",\"x\",\"0\"],"
             "\"geometry\":{\"difference\":[{\"cylinder\":{\"base\":[0,0,0],\"axis\":[0,0,1],"
             "\"radius\":0.246,\"length\":0.17}},{\"cylinder\":{\"base\":[0,0,-0.01],"
             "\"axis\":[0,0,1],\"radius\":0.206,\"length\":0.19}}]}}],"
             "\"cracks\":[{\"polygon\":[[0.19,0,%.17g],[0.26,0,%.17g],[0.26,0,%.17g],"
             "[0.19,0,%.17g]]}],"
             "\"crack_growth\":{\"tips\":[[0.226,0,%.17g],[0.226,0,%.17g]]},"
             "\"boundary_conditions\":[{\"type\":\"pressure\",\"name\":\"inner_wall\","
             "\"select\":{\"expression\":\"x*x + y*y < 0.0478\"},\"pressure\":1e6}]}",
             S, 5 * DZ, 5 * DZ, 8 * DZ, 8 * DZ, 5 * DZ, 8 * DZ);
    return build_model(json);
}

/* The fibre at layer l (centre z = (l + 1/2) DZ) on the ray at azimuth phi. */
static long fibre_at(const struct tlsph_fibres *f, int l, double phi)
{
    for (size_t j = 0; j < f->n; j++) {
        const double *c = f->centre[j];
        if (fabs(c[2] - (l + 0.5) * DZ) < 1e-9 && fabs(atan2(c[1], c[0]) - phi) < 1e-9)
            return (long)j;
    }
    return -1;
}

struct totals {
    double mass, vol, mom[3], scale, area[3], area_scale;
    size_t group;
};

static struct totals totals(const struct tlsph_model *m)
{
    struct totals t = {0};
    for (size_t i = 0; i < m->p.n; i++) { /* mass, volume, momentum and sum m|v| */
        const double mi = m->p.mass[i], *v = m->p.v + 3 * i;
        t.mass += mi;
        t.vol += m->p.vol0[i];
        t.scale += mi * sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (int c = 0; c < 3; c++)
            t.mom[c] += mi * v[c];
    }
    const struct tlsph_group *g = &m->groups[0];
    t.group = g->n;
    for (size_t a = 0; a < g->n; a++)
        for (int c = 0; c < 3; c++) {
            t.area[c] += g->area[3 * a + c];
            t.area_scale += fabs(g->area[3 * a + c]);
        }
    return t;
}

START_TEST(a_crack_grows_along_the_shell)
{
    struct tlsph_model *m = tube();
    ck_assert_ptr_nonnull(m->crack_driver);
    ck_assert_uint_eq(m->p.n, 4368);
    const struct tlsph_fibres *f = &m->fibres[0];
    ck_assert_int_eq(f->axis, TLSPH_FIBRE_RADIAL);
    const long path[4] = {fibre_at(f, 8, RAY), fibre_at(f, 9, RAY), fibre_at(f, 10, -RAY),
                          fibre_at(f, 11, -RAY)};
    for (int k = 0; k < 4; k++) {
        ck_assert_int_ge(path[k], 0);
        for (size_t p = f->start[path[k]]; p < f->start[path[k] + 1]; p++)
            m->p.damage[f->particle[p]] = 0.2 / 3.0;
    }
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tlsph_crack_driver *d = m->crack_driver;
    for (int round = 0; round < 8; round++) {
        const struct tlsph_crack_tip *t = &d->tip[1];
        const long tip_fibre = t->fibre;
        size_t parent[8] = {0}, k = 0;
        if (tip_fibre >= 0)
            for (size_t p = f->start[tip_fibre]; p < f->start[tip_fibre + 1]; p++)
                parent[k++] = f->particle[p];
        const size_t n0 = m->p.n, ev0 = d->nevents;
        int mate[8][8] = {{0}}; /* parent q saw parent r before the split */
        for (size_t q = 0; q < k; q++)
            for (int64_t r = m->pairs.start[parent[q]]; r < m->pairs.start[parent[q] + 1]; r++)
                for (size_t u = 0; u < k; u++)
                    mate[q][u] |= (size_t)m->pairs.j[r] == parent[u];
        const struct totals a = totals(m);
        ck_assert_int_eq(tlsph_crack_driver_step(m, NULL, &err), 0);
        if (d->nevents == ev0)
            continue;
        ck_assert_uint_eq(d->nevents, ev0 + 1);
        const struct tlsph_crack_event *e = &d->event[ev0];
        ck_assert_uint_eq(e->tip, 1);
        ck_assert_int_eq(e->fibre, path[ev0]);
        ck_assert_uint_eq(e->split, ev0 ? 3 : 0);
        ck_assert_uint_eq(m->p.n, n0 + e->split);
        const struct totals b = totals(m);
        ck_assert(fabs(b.mass - a.mass) <= 1e-14 * a.mass);
        ck_assert(fabs(b.vol - a.vol) <= 1e-14 * a.vol);
        for (int c = 0; c < 3; c++) {
            ck_assert(fabs(b.mom[c] - a.mom[c]) <= 1e-14 * a.scale);
            ck_assert_msg(fabs(b.area[c] - a.area[c]) <= 1e-14 * a.area_scale,
                          "area %d: %g vs %g", c, b.area[c], a.area[c]);
        }
        ck_assert_uint_eq(b.group, a.group + (e->split ? 1 : 0));
        for (size_t s = 0; s < e->split; s++) {
            const size_t h1 = parent[s], h2 = n0 + s;
            double dd[3], mid[3], n[3], len = 0.0, dn = 0.0, dv = 0.0;
            for (int c = 0; c < 3; c++) {
                dd[c] = m->p.X[3 * h1 + c] - m->p.X[3 * h2 + c];
                mid[c] = 0.5 * (m->p.X[3 * h1 + c] + m->p.X[3 * h2 + c]); /* the parent's X */
            }
            ck_assert_int_eq(tlsph_fibres_normal(&m->fibres[0], mid, n), 0);
            for (int c = 0; c < 3; c++) {
                len += dd[c] * dd[c];
                dn += dd[c] * n[c];
                dv += dd[c] * t->V1[c]; /* V1 is now this split's V2 */
            }
            len = sqrt(len);
            ck_assert_double_eq_tol(len, 2.0 * TLSPH_CRACK_DELTA * S, 1e-12);
            ck_assert_msg(fabs(dn) <= 1e-12 * len && fabs(dv) <= 1e-12 * len *
                          sqrt(t->V1[0] * t->V1[0] + t->V1[1] * t->V1[1] + t->V1[2] * t->V1[2]),
                          "delta off the tangent plane or not normal to V2: %g %g", dn, dv);
            for (size_t h = 0; h < 2; h++) {
                const size_t i = h ? h2 : h1;
                ck_assert_msg(m->pairs.start[i + 1] - m->pairs.start[i] >= 8,
                              "half %zu has %lld neighbours", i,
                              (long long)(m->pairs.start[i + 1] - m->pairs.start[i]));
                /* its fibre mates on its own side (the same ray, delta off the
                 * facets) are still its neighbours */
                for (size_t q = 0; q < e->split; q++) {
                    const size_t j = h ? n0 + q : parent[q];
                    if (j == i || !mate[s][q])
                        continue;
                    int found = 0;
                    for (int64_t r = m->pairs.start[i]; r < m->pairs.start[i + 1]; r++)
                        found |= (size_t)m->pairs.j[r] == j;
                    ck_assert_msg(found, "split %zu: half %zu lost its fibre mate %zu", ev0, i,
                                  j);
                }
            }
        }
    }
    ck_assert_uint_eq(d->nevents, 4);
    ck_assert_uint_eq(d->tip[0].advances, 0);
    ck_assert_uint_eq(m->p.n, 4377);
    tlsph_errors_free(&err);
    struct tlsph_diagnostic dg;
    for (int s = 0; s < 20; s++) {
        tlsph_model_step(m);
        ck_assert_msg(tlsph_model_check(m, &dg) == 0, "step %ld: %s", m->step, dg.message);
    }
    tlsph_model_free(m);
}
END_TEST

TLSPH_CHECK_MAIN("crack_shell", 120, a_crack_grows_along_the_shell)
