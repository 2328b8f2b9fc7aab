/* The crack driver (crack_driver.h). */
#include "crack/crack_driver.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "crack/crack_surface.h"
#include "crack/fibre.h"
#include "crack/fibre_criterion.h"
#include "crack/split.h"
#include "util/clock.h"

/* Initiation (crack_driver.h "Initiation"), defined after the advance. */
static int initiate_setup(struct tlsph_model *m, struct tlsph_errors *err);
static int mark_near(struct tlsph_model *m, size_t b, int r, const double P[3],
                     struct tlsph_errors *err);
static int mark_face(struct tlsph_model *m, size_t b, size_t k, struct tlsph_errors *err);
static int initiate_scan(struct tlsph_model *m, FILE *log, struct tlsph_errors *err);
static void fibre_span(const struct tlsph_model *m, const struct tlsph_fibres *f, size_t k,
                       double *lo, double *hi);

/* |a - b| in the plane (a plate's, or a shell's tangent plane at a). */
static double plane_distance(const struct tlsph_fibres *f, const double a[3], const double b[3])
{
    const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    double v[2];
    tlsph_fibres_local(f, a, d, v);
    return hypot(v[0], v[1]);
}

/* v without its part along the thickness at P (a shell's tangent plane). */
static void tangent(const struct tlsph_fibres *f, const double P[3], const double v[3],
                    double out[3])
{
    if (f->axis != TLSPH_FIBRE_RADIAL) {
        for (int k = 0; k < 3; k++)
            out[k] = k == f->axis ? 0.0 : v[k];
        return;
    }
    double n[3];
    if (tlsph_fibres_normal(f, P, n) != 0) /* on the axis: no thickness direction */
        n[0] = n[1] = n[2] = 0.0;
    const double vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
    for (int k = 0; k < 3; k++)
        out[k] = v[k] - vn * n[k];
}

/* P moved along the thickness to depth (m): a plate's axis coordinate, a
 * shell's radius on P's ray.  The radial lines at the two ends of a diagonal
 * segment are skew, so a rectangle over them folds along its diagonal (two
 * planar triangles): its side at each end stays on that end's ray, the split
 * fibre's ray exactly, and the next rectangle starts on the same line, so the
 * surface is continuous. */
static void at_depth(const struct tlsph_fibres *f, const double P[3], double depth,
                     double out[3])
{
    memcpy(out, P, 3 * sizeof *out);
    if (f->axis != TLSPH_FIBRE_RADIAL) {
        out[f->axis] = depth;
        return;
    }
    double n[3];
    tlsph_fibres_normal(f, P, n);
    const double r = tlsph_fibres_depth(f, P);
    for (int k = 0; k < 3; k++)
        out[k] += (depth - r) * n[k];
}

static double body_spacing(const struct tlsph_model *m, size_t b)
{
    return m->scene.bodies[b].spacing;
}

/* The fibres a tip's search looks at: those within R (all when more than the
 * list holds: ncand = SIZE_MAX). */
static void refresh_candidates(const struct tlsph_model *m, struct tlsph_crack_tip *t)
{
    const struct tlsph_fibres view = tlsph_fibres_view(&m->fibres[t->body], t->region);
    const struct tlsph_fibres *f = &view;
    const double R = m->scene.crack_growth.search_radius * body_spacing(m, t->body);
    const size_t n = tlsph_fibres_within(f, t->T, R * (1.0 + 1e-9), t->cand, TLSPH_CRACK_MAX_CAND);
    t->ncand = n <= TLSPH_CRACK_MAX_CAND ? n : SIZE_MAX;
}

/* ---------------------------------------------------------------- setup */

/* The ends A, B of crack c's trace in the plane of `axis` (the two corners
 * farthest apart there); 0, or -1 when the trace is no segment (a corner off
 * the line A-B by more than 1e-6 of its length: the crack is not through the
 * thickness) or has no length. */
static int trace_ends(const struct tlsph_crack_spec *c, const struct tlsph_fibres *f, double A[3],
                      double B[3])
{
    double best = -1.0;
    int ia = 0, ib = 0;
    for (int a = 0; a < c->ncorners; a++)
        for (int b = a + 1; b < c->ncorners; b++) {
            const double d = plane_distance(f, c->corner[a], c->corner[b]);
            if (d > best) {
                best = d;
                ia = a;
                ib = b;
            }
        }
    if (!(best > 0.0))
        return -1;
    memcpy(A, c->corner[ia], 3 * sizeof *A);
    memcpy(B, c->corner[ib], 3 * sizeof *B);
    const double AB[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]};
    double u[2];
    tlsph_fibres_local(f, A, AB, u);
    const double ux = u[0] / best, uy = u[1] / best;
    for (int k = 0; k < c->ncorners; k++) {
        const double AP[3] = {c->corner[k][0] - A[0], c->corner[k][1] - A[1],
                              c->corner[k][2] - A[2]};
        double pp[2];
        tlsph_fibres_local(f, A, AP, pp);
        const double px = pp[0], py = pp[1];
        if (fabs(px * uy - py * ux) > 1e-6 * best)
            return -1;
    }
    return 0;
}

/* Is P within a spacing of the box of body b's fibres' particles? */
static int near_fibres_box(const struct tlsph_model *m, size_t b, const double P[3])
{
    const struct tlsph_fibres *f = &m->fibres[b];
    const double s = body_spacing(m, b);
    int inside = 1;
    for (int a = 0; a < 3; a++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t p = 0; p < f->start[f->n]; p++) {
            lo = fmin(lo, m->p.X[3 * f->particle[p] + a]);
            hi = fmax(hi, m->p.X[3 * f->particle[p] + a]);
        }
        inside &= P[a] >= lo - s && P[a] <= hi + s;
    }
    return inside;
}

/* The thin body whose fibres' in-plane box (plus half a spacing) holds P, or
 * nbodies. */
static size_t body_of(const struct tlsph_model *m, const double P[3])
{
    for (size_t b = 0; b < m->scene.nbodies; b++) {
        const struct tlsph_fibres *f = &m->fibres[b];
        if (!f->n)
            continue;
        if (f->axis == TLSPH_FIBRE_RADIAL) { /* a shell: a fibre within a spacing of P */
            if (tlsph_fibres_within(f, P, body_spacing(m, b), NULL, 0) > 0)
                return b;
            continue;
        }
        if (f->nregions) { /* regions: the box of the fibres' particles plus a spacing
                            * (which region holds P is tip_region's question) */
            if (near_fibres_box(m, b, P))
                return b;
            continue;
        }
        int pa[2];
        tlsph_fibre_plane_axes(f->axis, pa);
        const double half = 0.5 * body_spacing(m, b);
        int inside = 1;
        for (int a = 0; a < 2; a++) {
            double lo = INFINITY, hi = -INFINITY;
            for (size_t j = 0; j < f->n; j++) {
                lo = fmin(lo, f->centre[j][pa[a]]);
                hi = fmax(hi, f->centre[j][pa[a]]);
            }
            inside &= P[pa[a]] >= lo - half && P[pa[a]] <= hi + half;
        }
        if (inside)
            return b;
    }
    return m->scene.nbodies;
}

/* Body b has a damage model and the criterion's quantity; else an error at
 * pointer (the damage one ending with `then`).  0 or -1. */
static int body_can_crack(const struct tlsph_model *m, size_t b, const char *pointer,
                          const char *then, struct tlsph_errors *err)
{
    const struct tlsph_body *body = &m->scene.bodies[b];
    if (!m->scene.materials[body->material].damage.model) {
        tlsph_errors_add(err, pointer, "body '%s' has no damage model: its fibres' damage stays "
                         "0 and %s", body->name, then);
        return -1;
    }
    return tlsph_crack_criterion_check(m, b, err);
}

/* Does crack c reach P's depth along the view's axis (its corners on both
 * sides of it, or at it)?  A trace in one region's plane may be another
 * region's crack seen edge-on (a web's crack projects on the plate's plane
 * as a segment too). */
static int spans_depth(const struct tlsph_crack_spec *c, const struct tlsph_fibres *f,
                       const double P[3])
{
    const double z = tlsph_fibres_depth(f, P);
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < c->ncorners; k++) {
        lo = fmin(lo, tlsph_fibres_depth(f, c->corner[k]));
        hi = fmax(hi, tlsph_fibres_depth(f, c->corner[k]));
    }
    return z >= lo && z <= hi;
}

/* Does region r of body b hold P: is P in the cell of one of r's fibres, within
 * half a spacing of its centre along each of r's in-plane axes and within its
 * particles' extent along r's axis plus half a spacing (the plate's faces)?
 * The cells of a region tile its part of the body, so a pre-crack's tip
 * (between lattice rows, half a spacing from the fibres beside it) lies in the
 * cells of the fibres around it, and in one region's cells unless it lies on
 * the face where two regions meet. */
static int region_holds(const struct tlsph_model *m, size_t b, int r, const double P[3])
{
    const struct tlsph_fibres view = tlsph_fibres_view(&m->fibres[b], r);
    const struct tlsph_fibres *f = &view;
    const double half = 0.5 * body_spacing(m, b) * (1.0 + 1e-9), z = tlsph_fibres_depth(f, P);
    for (size_t k = 0; k < f->n; k++) {
        if (!tlsph_fibres_sees(f, k))
            continue;
        const double d[3] = {P[0] - f->centre[k][0], P[1] - f->centre[k][1],
                             P[2] - f->centre[k][2]};
        double v[2];
        tlsph_fibres_local(f, P, d, v);
        if (fabs(v[0]) > half || fabs(v[1]) > half)
            continue;
        double lo = INFINITY, hi = -INFINITY;
        fibre_span(m, f, k, &lo, &hi);
        if (z >= lo - half && z <= hi + half)
            return 1;
    }
    return 0;
}

/* The region of body b (with thickness_regions) that a listed tip P grows in:
 * the one region whose fibres' cells hold it (region_holds).  0 with *region,
 * or -1 with an error at pointer p: in no region's cells, or in two. */
static int tip_region(const struct tlsph_model *m, size_t b, const double P[3], const char *p,
                      int *region, struct tlsph_errors *err)
{
    const struct tlsph_fibres *f = &m->fibres[b];
    int held[2], n = 0;
    for (int r = 0; r < f->nregions; r++)
        if (region_holds(m, b, r, P) && n++ < 2)
            held[n - 1] = r;
    const char *name = m->scene.bodies[b].name;
    if (n == 0) {
        tlsph_errors_add(err, p,
                         "the tip (%g, %g, %g) m lies among no region's fibres of body "
                         "'%s' (thickness_regions): a tip grows in the region whose fibres' "
                         "cells hold it, within half a spacing of a fibre in the region's plane "
                         "and within its thickness",
                         P[0], P[1], P[2], name);
        return -1;
    }
    if (n > 1) {
        tlsph_errors_add(err, p,
                         "the tip (%g, %g, %g) m lies among the fibres of regions %d "
                         "and %d of body '%s' (thickness_regions/%d and /%d, where they meet): "
                         "which region's plane it grows in is ambiguous; move it into one "
                         "region",
                         P[0], P[1], P[2], held[0], held[1], name, held[0], held[1]);
        return -1;
    }
    *region = held[0];
    return 0;
}

static int setup_tip(struct tlsph_model *m, size_t j, struct tlsph_crack_tip *t,
                     struct tlsph_errors *err)
{
    const double *P = m->scene.crack_growth.tip[j];
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_index(p, sizeof p, "/crack_growth/tips", j);
    const size_t b = body_of(m, P);
    if (b == m->scene.nbodies) {
        tlsph_errors_add(err, p, "the tip (%g, %g, %g) m is in no body with fibres "
                         "(\"thickness_axis\"): a crack grows from fibre to fibre",
                         P[0], P[1], P[2]);
        return -1;
    }
    const struct tlsph_body *body = &m->scene.bodies[b];
    if (body_can_crack(m, b, p, "the crack cannot grow", err) != 0)
        return -1;
    int region = 0;
    if (m->fibres[b].nregions && tip_region(m, b, P, p, &region, err) != 0)
        return -1;
    /* the tip's region's view (the body's fibres without regions) */
    const struct tlsph_fibres view = tlsph_fibres_view(&m->fibres[b], region);
    const struct tlsph_fibres *f = &view;
    for (size_t c = 0; c < m->scene.ncracks; c++) {
        double A[3], B[3];
        if (trace_ends(&m->scene.cracks[c], f, A, B) != 0 ||
            (f->nregions && !spans_depth(&m->scene.cracks[c], f, P)))
            continue;
        const double len = plane_distance(f, A, B);
        const double *end = plane_distance(f, P, A) <= 1e-6 * len   ? A
                            : plane_distance(f, P, B) <= 1e-6 * len ? B
                                                                    : NULL;
        if (!end)
            continue;
        const double *other = end == A ? B : A;
        t->body = b;
        t->fibre = -1;
        t->region = region;
        const double V[3] = {end[0] - other[0], end[1] - other[1], end[2] - other[2]};
        tangent(f, end, V, t->V1);
        for (int k = 0; k < 3; k++)
            t->T[k] = t->end[k] = P[k];
        refresh_candidates(m, t);
        return 0;
    }
    tlsph_errors_add(err, p, "the tip (%g, %g, %g) m is no end of a through-thickness crack's "
                     "trace in the plane of body '%s' (a crack polygon containing the "
                     "thickness direction, ending there)", P[0], P[1], P[2], body->name);
    return -1;
}

int tlsph_crack_driver_setup(struct tlsph_model *m, struct tlsph_errors *err)
{
    const struct tlsph_crack_growth *g = &m->scene.crack_growth;
    if (!g->on)
        return 0;
    struct tlsph_crack_driver *d = calloc(1, sizeof *d);
    if (!d) {
        tlsph_errors_add(err, "/crack_growth", "out of memory");
        return -1;
    }
    m->crack_driver = d;
    if (!m->fibres || (!m->crack_surface && !g->initiate)) {
        tlsph_errors_add(err, "/crack_growth", "a growing crack needs a body with fibres and a "
                         "pre-crack");
        return -1;
    }
    if (g->initiate && initiate_setup(m, err) != 0)
        return -1;
    for (size_t j = 0; j < g->ntips; j++)
        if (setup_tip(m, j, &d->tip[j], err) != 0)
            return -1;
    if (!m->p.damage) { /* setup_tip and initiate checked the materials: cannot happen */
        tlsph_errors_add(err, "/crack_growth", "no damage model: the crack cannot grow");
        return -1;
    }
    d->ntips = g->ntips;
    return 0;
}

/* ---------------------------------------------------------------- advance */

/* Adds the rectangle over the in-plane segment P-Q spanning [lo, hi] along
 * the axis (a shell: along the radius, at_depth) as two triangles; *length
 * += its in-plane length.  0 or -1. */
static int add_rect(struct tlsph_model *m, const struct tlsph_fibres *f, const double P[3],
                    const double Q[3], double lo, double hi, double spacing, double *length,
                    struct tlsph_errors *err)
{
    const double l = plane_distance(f, P, Q);
    if (!(l > 1e-9 * spacing))
        return 0;
    double c[4][3];
    at_depth(f, P, lo, c[0]);
    at_depth(f, Q, lo, c[1]);
    at_depth(f, Q, hi, c[2]);
    at_depth(f, P, hi, c[3]);
    const double T1[3][3] = {{c[0][0], c[0][1], c[0][2]}, {c[1][0], c[1][1], c[1][2]},
                             {c[2][0], c[2][1], c[2][2]}};
    const double T2[3][3] = {{c[0][0], c[0][1], c[0][2]}, {c[2][0], c[2][1], c[2][2]},
                             {c[3][0], c[3][1], c[3][2]}};
    if (tlsph_crack_surface_add(m->crack_surface, T1) != TLSPH_CRACK_OK ||
        tlsph_crack_surface_add(m->crack_surface, T2) != TLSPH_CRACK_OK) {
        tlsph_errors_add(err, "", "crack growth: cannot add a facet (out of memory or out of "
                         "the surface's grid)");
        return -1;
    }
    *length += l;
    return 0;
}

/* Widens [lo, hi] by fibre k's particles along the axis. */
static void fibre_span(const struct tlsph_model *m, const struct tlsph_fibres *f, size_t k,
                       double *lo, double *hi)
{
    for (size_t p = f->start[k]; p < f->start[k + 1]; p++) {
        const double z = tlsph_fibres_depth(f, m->p.X + 3 * f->particle[p]);
        *lo = fmin(*lo, z);
        *hi = fmax(*hi, z);
    }
}

/* Splits fibre k of body b (copied list: the split reallocates the fibres). */
static int split_fibre(struct tlsph_model *m, size_t b, size_t k, const double V1[3],
                       const double V2[3], const double delta[3], size_t first_facet,
                       size_t *count, struct tlsph_errors *err)
{
    const struct tlsph_fibres *f = &m->fibres[b];
    const size_t n = f->start[k + 1] - f->start[k];
    size_t *index = malloc((n ? n : 1) * sizeof *index);
    if (!index) {
        tlsph_errors_add(err, "", "crack growth: out of memory");
        return -1;
    }
    memcpy(index, f->particle + f->start[k], n * sizeof *index);
    struct tlsph_split sp = {.index = index, .n = n};
    memcpy(sp.V1, V1, sizeof sp.V1);
    memcpy(sp.V2, V2, sizeof sp.V2);
    memcpy(sp.delta, delta, sizeof sp.delta);
    int rc = tlsph_split_particles(m, &sp, m->crack_surface, first_facet, NULL, NULL, err);
    if (rc == 0 && m->crack_driver->near) /* initiation: k is a crack's face now */
        rc = mark_face(m, b, k, err);
    free(index);
    *count += n;
    return rc;
}

/* Is fibre k at the body's edge (fewer than 8 fibres within 1.5 spacings)? */
static int at_edge(const struct tlsph_fibres *f, size_t k, double spacing)
{
    return tlsph_fibres_within(f, f->centre[k], 1.5 * spacing * (1.0 + 1e-9), NULL, 0) < 9;
}

static int record(struct tlsph_crack_driver *d, const struct tlsph_model *m, size_t tip,
                  size_t split, struct tlsph_errors *err)
{
    if (d->nevents == d->event_cap) {
        const size_t cap = d->event_cap ? 2 * d->event_cap : 16;
        struct tlsph_crack_event *e = realloc(d->event, cap * sizeof *e);
        if (!e) {
            tlsph_errors_add(err, "", "crack growth: out of memory");
            return -1;
        }
        d->event = e;
        d->event_cap = cap;
    }
    const struct tlsph_crack_tip *t = &d->tip[tip];
    struct tlsph_crack_event *e = &d->event[d->nevents++];
    *e = (struct tlsph_crack_event){.step = m->step, .time = m->t, .tip = tip,
                                    .fibre = t->fibre, .split = split, .particles = m->p.n};
    memcpy(e->position, t->T, sizeof e->position);
    return 0;
}

static int advance(struct tlsph_model *m, size_t tip, size_t J, FILE *log,
                   struct tlsph_errors *err)
{
    struct tlsph_crack_driver *d = m->crack_driver;
    struct tlsph_crack_tip *t = &d->tip[tip];
    const size_t b = t->body;
    /* the tip's region (valid until the first split below: after it only the
     * geometry of the view, its axis, is read; fibres from m->fibres again) */
    const struct tlsph_fibres view = tlsph_fibres_view(&m->fibres[b], t->region);
    const struct tlsph_fibres *f = &view;
    const int axis = f->axis;
    const double s = body_spacing(m, b);
    double CJ[3], V2[3], u2[3], delta[3], n2[3] = {0, 0, 0};
    memcpy(CJ, f->centre[J], sizeof CJ);
    const double TJ[3] = {CJ[0] - t->T[0], CJ[1] - t->T[1], CJ[2] - t->T[2]};
    tangent(f, t->T, TJ, V2);
    const double L2 = sqrt(V2[0] * V2[0] + V2[1] * V2[1] + V2[2] * V2[2]);
    for (int k = 0; k < 3; k++)
        u2[k] = V2[k] / L2;
    /* n2 = e_axis x u2: in the plane, normal to V2 (a shell: the radial
     * direction at the tip for e_axis, the tangent plane there) */
    if (axis == TLSPH_FIBRE_RADIAL) {
        double nt[3];
        tlsph_fibres_normal(f, t->T, nt);
        n2[0] = nt[1] * u2[2] - nt[2] * u2[1];
        n2[1] = nt[2] * u2[0] - nt[0] * u2[2];
        n2[2] = nt[0] * u2[1] - nt[1] * u2[0];
    } else {
        n2[(axis + 1) % 3] = -u2[(axis + 2) % 3];
        n2[(axis + 2) % 3] = u2[(axis + 1) % 3];
    }
    const double dm = TLSPH_CRACK_DELTA * s;
    for (int k = 0; k < 3; k++)
        delta[k] = dm * n2[k];
    double lo = INFINITY, hi = -INFINITY;
    fibre_span(m, f, J, &lo, &hi);
    if (t->fibre >= 0)
        fibre_span(m, f, (size_t)t->fibre, &lo, &hi);
    lo -= 0.5 * s;
    hi += 0.5 * s;
    const int edge = at_edge(f, J, s);
    size_t split = 0;
    if (t->fibre >= 0) {
        double CI[3], stop[3];
        memcpy(CI, m->fibres[b].centre[t->fibre], sizeof CI);
        for (int k = 0; k < 3; k++)
            stop[k] = CJ[k] - dm * u2[k];
        const size_t first = m->crack_surface->nfacets;
        double V1[3]; /* a shell: the old direction in the tangent plane at the tip */
        memcpy(V1, t->V1, sizeof V1);
        if (axis == TLSPH_FIBRE_RADIAL)
            tangent(f, t->T, t->V1, V1);
        if (add_rect(m, f, t->end, CI, lo, hi, s, &t->length, err) != 0 ||
            add_rect(m, f, CI, stop, lo, hi, s, &t->length, err) != 0 ||
            split_fibre(m, b, (size_t)t->fibre, V1, V2, delta, first, &split, err) != 0)
            return -1;
        memcpy(t->end, stop, sizeof stop);
    }
    memcpy(t->T, CJ, sizeof CJ);
    memcpy(t->V1, V2, sizeof V2);
    t->fibre = (long)J;
    t->advances++;
    if (edge) { /* through the edge: split the edge fibre straight, facets past it */
        double past[3];
        for (int k = 0; k < 3; k++)
            past[k] = CJ[k] + s * u2[k];
        const size_t first = m->crack_surface->nfacets;
        if (add_rect(m, f, t->end, past, lo, hi, s, &t->length, err) != 0 ||
            split_fibre(m, b, J, u2, u2, delta, first, &split, err) != 0)
            return -1;
        memcpy(t->end, past, sizeof past);
        t->stopped = 1;
    }
    d->particles_split += split;
    if (record(d, m, tip, split, err) != 0)
        return -1;
    if (d->near && mark_near(m, b, t->region, CJ, err) != 0)
        return -1;
    for (size_t q = 0; q < d->ntips + d->nstarted; q++)
        refresh_candidates(m, &d->tip[q]);
    if (log)
        fprintf(log,
                "tlsph: crack tip %zu -> fibre %ld at (%g, %g, %g) m, step %ld, t = %g s: %zu "
                "particles split, %zu particles, grown %g m%s\n",
                tip, t->fibre, CJ[0], CJ[1], CJ[2], m->step, m->t, split, m->p.n, t->length,
                t->stopped ? ", through the edge" : "");
    return 0;
}

/* ---------------------------------------------------------------- initiation */

/* Near flags: 0 free, NEAR a crack (no start there), NEAR_FACE a fibre a split
 * made or split (a crack's face: a tip that would step onto it stops). */
enum { NEAR = 1, NEAR_FACE = 2 };

/* Body b's near flags cover its fibres; entries added since (the halves a
 * split appended: faces of a crack) are near.  0 or -1. */
static int near_cover(struct tlsph_model *m, size_t b, struct tlsph_errors *err)
{
    struct tlsph_crack_driver *d = m->crack_driver;
    const size_t n = m->fibres[b].n;
    if (n <= d->near_cap[b])
        return 0;
    const size_t cap = n > 2 * d->near_cap[b] ? n : 2 * d->near_cap[b];
    unsigned char *q = realloc(d->near[b], cap);
    if (!q) {
        tlsph_errors_add(err, "", "crack initiation: out of memory");
        return -1;
    }
    memset(q + d->near_cap[b], NEAR_FACE, cap - d->near_cap[b]);
    d->near[b] = q;
    d->near_cap[b] = cap;
    return 0;
}

/* Marks body b's fibres within TLSPH_CRACK_CLEAR spacings of P near (a scan
 * of the body's fibres: once per advance or start, not per step). */
static int mark_near(struct tlsph_model *m, size_t b, int r, const double P[3],
                     struct tlsph_errors *err)
{
    if (near_cover(m, b, err) != 0)
        return -1;
    const struct tlsph_fibres view = tlsph_fibres_view(&m->fibres[b], r);
    const struct tlsph_fibres *f = &view;
    const double radius = TLSPH_CRACK_CLEAR * body_spacing(m, b) * (1.0 + 1e-9);
    unsigned char *near = m->crack_driver->near[b];
    for (size_t k = 0; k < f->n; k++)
        if (tlsph_fibres_sees(f, k) && plane_distance(f, P, f->centre[k]) <= radius &&
            !near[k])
            near[k] = NEAR;
    return 0;
}

/* Fibre k of body b has been split: a crack's face (the fibres the split
 * appended are faces from birth, near_cover). */
static int mark_face(struct tlsph_model *m, size_t b, size_t k, struct tlsph_errors *err)
{
    if (near_cover(m, b, err) != 0)
        return -1;
    m->crack_driver->near[b][k] = NEAR_FACE;
    return 0;
}

/* Marks body b's fibres within TLSPH_CRACK_CLEAR spacings of the in-plane
 * segment A-B near (a pre-crack's trace). */
static void mark_near_segment(struct tlsph_model *m, size_t b, const struct tlsph_fibres *f,
                              const double A[3], const double B[3])
{
    const double r = TLSPH_CRACK_CLEAR * body_spacing(m, b) * (1.0 + 1e-9);
    const double AB[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]};
    double u[2];
    tlsph_fibres_local(f, A, AB, u);
    const double L2 = u[0] * u[0] + u[1] * u[1];
    for (size_t k = 0; k < f->n; k++) {
        if (!tlsph_fibres_sees(f, k))
            continue;
        const double AC[3] = {f->centre[k][0] - A[0], f->centre[k][1] - A[1],
                              f->centre[k][2] - A[2]};
        double c[2];
        tlsph_fibres_local(f, A, AC, c);
        double t = L2 > 0.0 ? (c[0] * u[0] + c[1] * u[1]) / L2 : 0.0;
        t = fmin(1.0, fmax(0.0, t));
        if (hypot(c[0] - t * u[0], c[1] - t * u[1]) <= r)
            m->crack_driver->near[b][k] = NEAR;
    }
}

static int initiate_setup(struct tlsph_model *m, struct tlsph_errors *err)
{
    struct tlsph_crack_driver *d = m->crack_driver;
    const char *P = "/crack_growth/initiate";
    if (!(m->scene.crack_growth.fan_angle < 180.0)) {
        tlsph_errors_add(err, "/crack_growth/fan_angle", "a started crack's tips sit between "
                         "their fibre's halves, which a fan of %g degrees (180 or more) would "
                         "take: below 180 with initiate", m->scene.crack_growth.fan_angle);
        return -1;
    }
    const size_t nb = m->scene.nbodies;
    d->near = calloc(nb, sizeof *d->near);
    d->near_cap = calloc(nb, sizeof *d->near_cap);
    if (!d->near || !d->near_cap) {
        tlsph_errors_add(err, P, "out of memory");
        return -1;
    }
    for (size_t b = 0; b < nb; b++) {
        const struct tlsph_fibres *f = &m->fibres[b];
        if (!f->n)
            continue;
        if (body_can_crack(m, b, P, "no crack can start there", err) != 0)
            return -1;
        d->near[b] = calloc(f->n, 1);
        if (!d->near[b]) {
            tlsph_errors_add(err, P, "out of memory");
            return -1;
        }
        d->near_cap[b] = f->n;
        for (int r = 0; r < (f->nregions ? f->nregions : 1); r++) { /* each region's plane */
            const struct tlsph_fibres view = tlsph_fibres_view(f, r);
            for (size_t c = 0; c < m->scene.ncracks; c++) {
                double A[3], B[3];
                if (trace_ends(&m->scene.cracks[c], &view, A, B) == 0)
                    mark_near_segment(m, b, &view, A, B);
            }
        }
    }
    if (!m->crack_surface) { /* no pre-crack: an empty surface (cells as precrack.c) */
        double cell = 0.0;
        for (size_t i = 0; i < m->p.n; i++)
            cell = fmax(cell, 2.0 * m->p.h[i]);
        m->crack_surface = calloc(1, sizeof *m->crack_surface);
        if (!m->crack_surface ||
            tlsph_crack_surface_init(m->crack_surface, cell) != TLSPH_CRACK_OK) {
            tlsph_errors_add(err, P, "cannot make the crack surface (out of memory or no "
                             "particle)");
            return -1;
        }
    }
    return 0;
}

/* u: the crack's direction at fibre k of body b (unit, in the plane at C):
 * normal to the largest principal stress of the fibre's mean Cauchy stress
 * projected on the plane. */
static void start_direction(const struct tlsph_model *m, const struct tlsph_fibres *f, size_t k,
                            double u[3])
{
    const double *C = f->centre[k];
    double e[2][3] = {{0, 0, 0}, {0, 0, 0}};
    if (f->axis == TLSPH_FIBRE_RADIAL) {
        double n[3];
        tlsph_fibres_normal(f, C, n);
        e[0][0] = f->dir[1] * n[2] - f->dir[2] * n[1];
        e[0][1] = f->dir[2] * n[0] - f->dir[0] * n[2];
        e[0][2] = f->dir[0] * n[1] - f->dir[1] * n[0];
        memcpy(e[1], f->dir, sizeof e[1]);
    } else {
        int pa[2];
        tlsph_fibre_plane_axes(f->axis, pa);
        e[0][pa[0]] = e[1][pa[1]] = 1.0;
    }
    static const int sym[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}}; /* xx xy xz yy yz zz */
    double S[2][2] = {{0, 0}, {0, 0}};
    for (size_t p = f->start[k]; p < f->start[k + 1]; p++) {
        const double *sg = m->p.sigma + 6 * f->particle[p];
        for (int a = 0; a < 2; a++)
            for (int c = 0; c < 2; c++)
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++)
                        S[a][c] += e[a][i] * sg[sym[i][j]] * e[c][j];
    }
    const double th = 0.5 * atan2(2.0 * S[0][1], S[0][0] - S[1][1]); /* largest's axis */
    for (int i = 0; i < 3; i++)
        u[i] = -sin(th) * e[0][i] + cos(th) * e[1][i];
}

/* A crack starts at fibre k of body b (crack_driver.h "Initiation"). */
static int start_crack(struct tlsph_model *m, size_t b, size_t k, FILE *log,
                       struct tlsph_errors *err)
{
    struct tlsph_crack_driver *d = m->crack_driver;
    const int region = tlsph_fibres_region_of(&m->fibres[b], k);
    /* k's region (valid until k's split below: after it only its axis is read) */
    const struct tlsph_fibres view = tlsph_fibres_view(&m->fibres[b], region);
    const struct tlsph_fibres *f = &view;
    const double s = body_spacing(m, b);
    const int edge = at_edge(f, k, s);
    if (d->ntips + d->nstarted + (edge ? 1 : 2) > TLSPH_CRACK_MAX_TIPS) {
        d->full = 1;
        if (log)
            fprintf(log, "tlsph: crack initiation stops at step %ld: %d tips, the most the "
                    "driver holds\n", m->step, TLSPH_CRACK_MAX_TIPS);
        return 0;
    }
    double C[3], u[3], n2[3] = {0, 0, 0}, delta[3];
    memcpy(C, f->centre[k], sizeof C);
    start_direction(m, f, k, u);
    if (edge) { /* inward: towards the mean of the neighbours' centres */
        size_t nb[TLSPH_CRACK_MAX_CAND];
        const size_t cnt = tlsph_fibres_within(f, C, 1.5 * s * (1.0 + 1e-9), nb,
                                               TLSPH_CRACK_MAX_CAND);
        double w = 0.0;
        for (size_t q = 0; q < cnt && q < TLSPH_CRACK_MAX_CAND; q++)
            for (int i = 0; i < 3; i++)
                w += (f->centre[nb[q]][i] - C[i]) * u[i];
        if (w < 0.0)
            for (int i = 0; i < 3; i++)
                u[i] = -u[i];
    }
    if (f->axis == TLSPH_FIBRE_RADIAL) { /* n2 = n x u, as advance */
        double nt[3];
        tlsph_fibres_normal(f, C, nt);
        n2[0] = nt[1] * u[2] - nt[2] * u[1];
        n2[1] = nt[2] * u[0] - nt[0] * u[2];
        n2[2] = nt[0] * u[1] - nt[1] * u[0];
    } else {
        n2[(f->axis + 1) % 3] = -u[(f->axis + 2) % 3];
        n2[(f->axis + 2) % 3] = u[(f->axis + 1) % 3];
    }
    for (int i = 0; i < 3; i++)
        delta[i] = TLSPH_CRACK_DELTA * s * n2[i];
    double lo = INFINITY, hi = -INFINITY;
    fibre_span(m, f, k, &lo, &hi);
    lo -= 0.5 * s;
    hi += 0.5 * s;
    const double back = edge ? s : 0.5 * s;
    double P0[3], P1[3];
    for (int i = 0; i < 3; i++) {
        P0[i] = C[i] - back * u[i];
        P1[i] = C[i] + 0.5 * s * u[i];
    }
    struct tlsph_crack_tip *ta = &d->tip[d->ntips + d->nstarted];
    *ta = (struct tlsph_crack_tip){.body = b, .fibre = -1, .region = region};
    const size_t first = m->crack_surface->nfacets;
    size_t split = 0;
    if (add_rect(m, f, P0, P1, lo, hi, s, &ta->length, err) != 0 ||
        split_fibre(m, b, k, u, u, delta, first, &split, err) != 0)
        return -1;
    memcpy(ta->T, C, sizeof C);
    memcpy(ta->V1, u, sizeof u);
    /* the tips' surfaces end at C, as a pre-crack's at its end: a first advance
     * that goes through the edge runs its facets end -> past the edge fibre
     * along C -> C_J, through C_J between its halves (from C +- s/2 u they
     * would miss C_J when u and C_J - C differ, leaving the halves 2 delta
     * apart in one support: measured, the run turned non-finite) */
    memcpy(ta->end, C, sizeof C);
    const size_t first_tip = d->ntips + d->nstarted;
    d->nstarted++;
    if (!edge) {
        struct tlsph_crack_tip *tb = &d->tip[d->ntips + d->nstarted];
        *tb = (struct tlsph_crack_tip){.body = b, .fibre = -1, .region = region};
        memcpy(tb->T, C, sizeof C);
        memcpy(tb->end, C, sizeof C);
        for (int i = 0; i < 3; i++)
            tb->V1[i] = -u[i];
        d->nstarted++;
    }
    d->starts++;
    d->particles_split += split;
    for (size_t q = first_tip; q < d->ntips + d->nstarted; q++)
        refresh_candidates(m, &d->tip[q]);
    if (record(d, m, first_tip, split, err) != 0)
        return -1;
    d->event[d->nevents - 1].fibre = (long)k;
    d->event[d->nevents - 1].started = 1;
    if (mark_near(m, b, region, C, err) != 0)
        return -1;
    if (log)
        fprintf(log,
                "tlsph: crack starts at fibre %zu of body '%s' at (%g, %g, %g) m, step %ld, "
                "t = %g s, direction (%.3f, %.3f, %.3f)%s: tips %zu%s, %zu particles split, %zu "
                "particles\n",
                k, m->scene.bodies[b].name, C[0], C[1], C[2], m->step, m->t, u[0], u[1], u[2],
                edge ? " (edge, inward)" : "", first_tip, edge ? "" : " and the next", split,
                m->p.n);
    return 0;
}

/* After a step: every thin body's fibres in index order (crack_driver.h). */
static int initiate_scan(struct tlsph_model *m, FILE *log, struct tlsph_errors *err)
{
    struct tlsph_crack_driver *d = m->crack_driver;
    const double t0 = tlsph_monotonic_seconds();
    const double Dc = m->scene.crack_growth.critical_damage;
    double starting = 0.0; /* the starts themselves (splits): not the scan's cost */
    int rc = 0;
    for (size_t b = 0; b < m->scene.nbodies && rc == 0 && !d->full; b++) {
        const size_t n0 = m->fibres[b].n; /* fibres a start appends are halves: near */
        if (!n0 || (rc = near_cover(m, b, err)) != 0)
            continue;
        for (size_t k = 0; k < n0 && rc == 0 && !d->full; k++) {
            if (d->near[b][k])
                continue;
            /* the field and the fibres move with every split: read them here */
            if (tlsph_fibre_damage(&m->fibres[b], k, tlsph_crack_criterion_field(m)) >= Dc) {
                const double t1 = tlsph_monotonic_seconds();
                rc = start_crack(m, b, k, log, err);
                starting += tlsph_monotonic_seconds() - t1;
            }
        }
    }
    d->scan_seconds += tlsph_monotonic_seconds() - t0 - starting;
    return rc;
}

/* Is fibre J of body b another tip's fibre (two cracks meeting there)? */
static int tip_fibre_of_other(const struct tlsph_crack_driver *d, size_t self, size_t b, long J)
{
    for (size_t q = 0; q < d->ntips + d->nstarted; q++)
        if (q != self && d->tip[q].body == b && d->tip[q].fibre == J)
            return 1;
    return 0;
}

int tlsph_crack_driver_step(struct tlsph_model *m, FILE *log, struct tlsph_errors *err)
{
    struct tlsph_crack_driver *d = m->crack_driver;
    if (!d)
        return 0;
    const double t0 = tlsph_monotonic_seconds();
    const struct tlsph_crack_growth *g = &m->scene.crack_growth;
    int rc = 0;
    for (size_t k = 0; k < d->ntips + d->nstarted && rc == 0; k++) {
        struct tlsph_crack_tip *t = &d->tip[k];
        if (t->stopped)
            continue;
        const struct tlsph_fibres view = tlsph_fibres_view(&m->fibres[t->body], t->region);
        const struct tlsph_fibres *f = &view;
        struct tlsph_tip_search q = {.radius = g->search_radius * body_spacing(m, t->body),
                                     .theta_c = g->fan_angle * M_PI / 180.0,
                                     .D_c = g->critical_damage};
        memcpy(q.tip, t->T, sizeof q.tip);
        memcpy(q.direction, t->V1, sizeof q.direction);
        const double *D = tlsph_crack_criterion_field(m);
        const long J = t->ncand == SIZE_MAX
                           ? tlsph_fibre_next_tip(f, D, &q)
                           : tlsph_fibre_next_tip_among(f, D, &q, t->cand, t->ncand);
        if (J >= 0 && d->near && (rc = near_cover(m, t->body, err)) == 0 &&
            (d->near[t->body][J] == NEAR_FACE || tip_fibre_of_other(d, k, t->body, J))) {
            /* initiation: the next fibre is a crack's face, this crack meets
             * another (or its own): it stops there (not joined, crack_driver.h) */
            t->stopped = 1;
            if (log)
                fprintf(log, "tlsph: crack tip %zu at (%g, %g, %g) m meets a crack (fibre %ld, a "
                        "face or another tip's), step %ld: it stops\n", k, t->T[0], t->T[1], t->T[2], J, m->step);
            continue;
        }
        if (J >= 0 && rc == 0)
            rc = advance(m, k, (size_t)J, log, err);
    }
    if (rc == 0 && d->near)
        rc = initiate_scan(m, log, err);
    d->seconds += tlsph_monotonic_seconds() - t0;
    return rc;
}

double tlsph_crack_driver_length(const struct tlsph_model *m)
{
    const struct tlsph_crack_driver *d = m->crack_driver;
    double sum = 0.0;
    for (size_t k = 0; d && k < d->ntips + d->nstarted; k++)
        sum += d->tip[k].length;
    return sum;
}

void tlsph_crack_driver_release(struct tlsph_model *m)
{
    if (!m->crack_driver)
        return;
    struct tlsph_crack_driver *d = m->crack_driver;
    for (size_t b = 0; d->near && b < m->scene.nbodies; b++)
        free(d->near[b]);
    free(d->near);
    free(d->near_cap);
    free(d->event);
    free(d);
    m->crack_driver = NULL;
}
