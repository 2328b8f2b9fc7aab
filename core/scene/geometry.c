/* Scene geometry: point membership, bounding boxes and the simple cubic lattice
 * that turns a body's geometry into particle positions.
 *
 * Membership is closed (a point on a primitive's surface is inside), except for
 * the notch cutter of the notched bar, which removes points strictly inside its
 * circle, so the notch root (rho = r at the notch position) belongs to the bar.
 * The lattice is origin + (i + 1/2) h per axis; index ranges come from
 * floor/ceil of the bounds so that positions never accumulate rounding. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/parse_internal.h"

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Axial coordinate s and squared radial distance of X for an axis through base. */
static void axial(const double *a, const double X[3], double *s, double *rho2)
{
    const double d[3] = {X[0] - a[0], X[1] - a[1], X[2] - a[2]};
    *s = dot3(d, a + 3);
    *rho2 = dot3(d, d) - *s * *s;
    if (*rho2 < 0.0)
        *rho2 = 0.0;
}

int tlsph_geometry_contains(const struct tlsph_geometry *g, const double X[3])
{
    const double *a = g->a;
    switch (g->type) {
    case TLSPH_GEOM_BOX:
        for (int k = 0; k < 3; k++)
            if (X[k] < a[k] || X[k] > a[3 + k])
                return 0;
        return 1;
    case TLSPH_GEOM_CYLINDER: {
        double s, rho2;
        axial(a, X, &s, &rho2);
        return s >= 0.0 && s <= a[7] && rho2 <= a[6] * a[6];
    }
    case TLSPH_GEOM_SPHERE: {
        const double d[3] = {X[0] - a[0], X[1] - a[1], X[2] - a[2]};
        return dot3(d, d) <= a[3] * a[3];
    }
    case TLSPH_GEOM_PLATE: {
        /* u = a[9..11] (stored by the parser), w = n x u. */
        const double d[3] = {X[0] - a[0], X[1] - a[1], X[2] - a[2]};
        double w[3];
        cross3(a + 3, a + 9, w);
        return fabs(dot3(d, a + 3)) <= 0.5 * a[6] && fabs(dot3(d, a + 9)) <= 0.5 * a[7] &&
               fabs(dot3(d, w)) <= 0.5 * a[8];
    }
    case TLSPH_GEOM_NOTCHED_BAR: {
        double s, rho2;
        axial(a, X, &s, &rho2);
        if (s < 0.0 || s > a[7] || rho2 > a[6] * a[6])
            return 0;
        /* Circular root of radius R centred at rho = r + R; when the notch is
         * deeper than R (a U-notch) straight flanks 2R apart run out to the
         * surface. */
        const double rc = a[8] + a[9], dr = sqrt(rho2) - rc, dz = s - a[10];
        if (dr > 0.0 && fabs(dz) < a[9])
            return 0;
        return dr * dr + dz * dz >= a[9] * a[9];
    }
    case TLSPH_GEOM_UNION:
        for (size_t i = 0; i < g->nchildren; i++)
            if (tlsph_geometry_contains(&g->children[i], X))
                return 1;
        return 0;
    case TLSPH_GEOM_DIFFERENCE:
        if (g->nchildren == 0 || !tlsph_geometry_contains(&g->children[0], X))
            return 0;
        for (size_t i = 1; i < g->nchildren; i++)
            if (tlsph_geometry_contains(&g->children[i], X))
                return 0;
        return 1;
    }
    return 0;
}

/* Tight box of a cylinder of radius r from base along unit axis for length L:
 * the end discs extend r sqrt(1 - axis_k^2) along axis k. */
static void cylinder_bounds(const double *a, double r, double L, double lo[3], double hi[3])
{
    for (int k = 0; k < 3; k++) {
        const double e = r * sqrt(fmax(0.0, 1.0 - a[3 + k] * a[3 + k]));
        const double p0 = a[k], p1 = a[k] + L * a[3 + k];
        lo[k] = fmin(p0, p1) - e;
        hi[k] = fmax(p0, p1) + e;
    }
}

void tlsph_geometry_bounds(const struct tlsph_geometry *g, double lo[3], double hi[3])
{
    const double *a = g->a;
    switch (g->type) {
    case TLSPH_GEOM_BOX:
        for (int k = 0; k < 3; k++) {
            lo[k] = a[k];
            hi[k] = a[3 + k];
        }
        return;
    case TLSPH_GEOM_CYLINDER:
    case TLSPH_GEOM_NOTCHED_BAR:
        cylinder_bounds(a, a[6], a[7], lo, hi);
        return;
    case TLSPH_GEOM_SPHERE:
        for (int k = 0; k < 3; k++) {
            lo[k] = a[k] - a[3];
            hi[k] = a[k] + a[3];
        }
        return;
    case TLSPH_GEOM_PLATE: {
        double w[3];
        cross3(a + 3, a + 9, w);
        for (int k = 0; k < 3; k++) {
            const double e = 0.5 * (fabs(a[3 + k]) * a[6] + fabs(a[9 + k]) * a[7] +
                                    fabs(w[k]) * a[8]);
            lo[k] = a[k] - e;
            hi[k] = a[k] + e;
        }
        return;
    }
    case TLSPH_GEOM_UNION:
        for (int k = 0; k < 3; k++) {
            lo[k] = INFINITY;
            hi[k] = -INFINITY;
        }
        for (size_t i = 0; i < g->nchildren; i++) {
            double l[3], h[3];
            tlsph_geometry_bounds(&g->children[i], l, h);
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], l[k]);
                hi[k] = fmax(hi[k], h[k]);
            }
        }
        if (g->nchildren == 0)
            for (int k = 0; k < 3; k++)
                lo[k] = hi[k] = 0.0;
        return;
    case TLSPH_GEOM_DIFFERENCE:
        if (g->nchildren > 0) {
            tlsph_geometry_bounds(&g->children[0], lo, hi);
        } else {
            for (int k = 0; k < 3; k++)
                lo[k] = hi[k] = 0.0;
        }
        return;
    }
}

double tlsph_lattice_range(const struct tlsph_scene *s, size_t b, long lo[3], long hi[3])
{
    const struct tlsph_body *body = &s->bodies[b];
    const double h = body->spacing;
    double glo[3], ghi[3];
    tlsph_geometry_bounds(&body->geometry, glo, ghi);
    double total = 1.0;
    for (int k = 0; k < 3; k++) {
        if (k == 2 && s->dimension == 2) {
            lo[k] = hi[k] = 0; /* the single plane z = 0 */
            continue;
        }
        /* origin + (i + 1/2) h in [glo, ghi]  <=>  i in [(glo-o)/h - 1/2, (ghi-o)/h - 1/2] */
        const double fl = ceil((glo[k] - body->origin[k]) / h - 0.5);
        const double fh = floor((ghi[k] - body->origin[k]) / h - 0.5);
        if (!(fh >= fl) || !isfinite(fl) || !isfinite(fh)) {
            lo[k] = 0;
            hi[k] = -1;
            total = 0.0;
            continue;
        }
        const double n = fh - fl + 1.0;
        total *= n;
        /* Keep the indices representable; callers refuse such ranges by the count. */
        if (fabs(fl) > 1e15 || fabs(fh) > 1e15 || n > 1e15) {
            lo[k] = 0;
            hi[k] = -1;
            total = INFINITY;
            continue;
        }
        lo[k] = (long)fl;
        hi[k] = (long)fh;
    }
    return total;
}

int tlsph_lattice_visit(const struct tlsph_scene *s, size_t b, const long lo[3], const long hi[3],
                        int (*visit)(const double X[3], void *ctx), void *ctx)
{
    const struct tlsph_body *body = &s->bodies[b];
    const double h = body->spacing;
    for (long k = lo[2]; k <= hi[2]; k++) {
        const double z = s->dimension == 2 ? 0.0 : body->origin[2] + ((double)k + 0.5) * h;
        for (long j = lo[1]; j <= hi[1]; j++) {
            const double y = body->origin[1] + ((double)j + 0.5) * h;
            for (long i = lo[0]; i <= hi[0]; i++) {
                const double X[3] = {body->origin[0] + ((double)i + 0.5) * h, y, z};
                if (!tlsph_geometry_contains(&body->geometry, X))
                    continue;
                const int r = visit(X, ctx);
                if (r)
                    return r;
            }
        }
    }
    return 0;
}

struct walk {
    double *out; /* NULL: count only */
    size_t cap, n;
};

static int store_point(const double X[3], void *ctx)
{
    struct walk *w = ctx;
    if (w->out && w->n < w->cap)
        memcpy(w->out + 3 * w->n, X, 3 * sizeof *X);
    w->n++;
    return 0;
}

/* Stores up to cap points in out (when non-NULL) and returns the number of
 * points inside. */
static size_t lattice_walk(const struct tlsph_scene *s, size_t b, const long lo[3],
                           const long hi[3], double *out, size_t cap)
{
    struct walk w = {.out = out, .cap = cap};
    tlsph_lattice_visit(s, b, lo, hi, store_point, &w);
    return w.n;
}

size_t tlsph_lattice_count(const struct tlsph_scene *s, size_t b)
{
    long lo[3], hi[3];
    const double total = tlsph_lattice_range(s, b, lo, hi);
    if (!(total > 0.0) || !isfinite(total))
        return 0;
    return lattice_walk(s, b, lo, hi, NULL, 0);
}

int tlsph_body_lattice(const struct tlsph_scene *s, size_t b, long max_points, double **out,
                       size_t *n, struct tlsph_errors *err)
{
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_index(p, sizeof p, "/bodies", b);
    *out = NULL;
    *n = 0;
    long lo[3], hi[3];
    const double total = tlsph_lattice_range(s, b, lo, hi);
    /* Candidates are bounded like the parser's estimate (10x the particle limit). */
    if (!isfinite(total) || total > 10.0 * (double)max_points) {
        tlsph_errors_add(err, p,
                         "body '%s': its bounding box holds about %.3g lattice points at spacing "
                         "%g m, more than 10 x the limit of %ld particles",
                         s->bodies[b].name, total, s->bodies[b].spacing, max_points);
        return -1;
    }
    const size_t count = total > 0.0 ? lattice_walk(s, b, lo, hi, NULL, 0) : 0;
    if (count > (size_t)max_points) {
        tlsph_errors_add(err, p, "body '%s' has %zu particles, more than the limit of %ld",
                         s->bodies[b].name, count, max_points);
        return -1;
    }
    if (count == 0)
        return 0;
    double *x = malloc(3 * count * sizeof *x);
    if (!x) {
        tlsph_errors_add(err, p, "out of memory for %zu particles of body '%s'", count,
                         s->bodies[b].name);
        return -1;
    }
    const size_t again = lattice_walk(s, b, lo, hi, x, count);
    if (again != count) { /* cannot happen: the walk is deterministic */
        free(x);
        tlsph_errors_add(err, p, "internal error: lattice count changed");
        return -1;
    }
    *out = x;
    *n = count;
    return 0;
}
