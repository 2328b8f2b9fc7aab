/* Graded particle spacing: the particles of a body with "refine" regions.
 *
 * Choice: a balanced octree (quadtree in 2-D) of the body's lattice cells.
 * Each cell of the uniform lattice (size h, centre origin + (i + 1/2) h) is
 * split into 2^d children of half its size while its size exceeds the target
 * spacing anywhere within one cell size of it (the cell grown by its size on
 * every side); a leaf whose centre lies inside the geometry is a particle of
 * volume (leaf size)^d and spacing = leaf size.  Why this one:
 *  - the leaves tile the lattice cells exactly, so the volumes sum to what the
 *    uniform lattice would give at each leaf's size (a body whose faces lie
 *    on the cell faces, such as a box from the default origin, exactly);
 *  - looking one cell size around a cell keeps neighbouring leaves within one
 *    level (2:1): if a leaf of size c touched a leaf of size c/4, that leaf's
 *    parent (size c/2, within c/2 of our leaf) was split because the target
 *    is below c/2 within c/2 of it, which is within c of our leaf, so our leaf
 *    would have been split.  Neighbours are thus one or two spacings apart,
 *    every support is a full lattice on each side, and the corrected gradient
 *    (L_i) stays well conditioned across a transition;
 *  - no random numbers or relaxation: deterministic and fast.
 * The target spacing is min(h, min over regions of s_r + (g_r - 1) d_r(X));
 * its minimum over a cell uses a lower bound of the distance of the grown cell
 * to the region (exact for box and sphere regions; for a cylinder the
 * distance of the cell's centre less the grown cell's half diagonal), so the
 * refinement may reach a little further than asked, never less far.
 *
 * Cells are visited base cell by base cell (x fastest, over the lattice range
 * grown by one cell on each side, since a cell centred just outside the
 * geometry's box may hold children inside it), children in z, y, x order. */
#include <math.h>

#include "scene/parse_internal.h"

static double sq(double a)
{
    return a * a;
}

/* Distance of the point X from region g (box, sphere or cylinder), m. */
static double point_distance(const struct tlsph_geometry *g, const double X[3], int naxes)
{
    const double *a = g->a;
    switch (g->type) {
    case TLSPH_GEOM_BOX: {
        double d2 = 0.0;
        for (int k = 0; k < naxes; k++)
            d2 += sq(fmax(0.0, fmax(a[k] - X[k], X[k] - a[3 + k])));
        return sqrt(d2);
    }
    case TLSPH_GEOM_SPHERE: {
        double d2 = 0.0;
        for (int k = 0; k < naxes; k++)
            d2 += sq(X[k] - a[k]);
        return fmax(0.0, sqrt(d2) - a[3]);
    }
    case TLSPH_GEOM_CYLINDER: {
        const double d[3] = {X[0] - a[0], X[1] - a[1], X[2] - a[2]};
        const double s = d[0] * a[3] + d[1] * a[4] + d[2] * a[5];
        const double rho = sqrt(fmax(0.0, d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - s * s));
        return hypot(fmax(0.0, fmax(-s, s - a[7])), fmax(0.0, rho - a[6]));
    }
    default: return 0.0; /* the parser admits no other region */
    }
}

/* A lower bound of the distance of region g from the box centre +- half, m. */
static double box_distance(const struct tlsph_geometry *g, const double centre[3], double half,
                           int naxes)
{
    const double *a = g->a;
    double d2 = 0.0;
    switch (g->type) {
    case TLSPH_GEOM_BOX:
        for (int k = 0; k < naxes; k++)
            d2 += sq(fmax(0.0, fmax(a[k] - (centre[k] + half), (centre[k] - half) - a[3 + k])));
        return sqrt(d2);
    case TLSPH_GEOM_SPHERE:
        /* the box's nearest point to the sphere's centre */
        for (int k = 0; k < naxes; k++)
            d2 += sq(fmax(0.0, fabs(a[k] - centre[k]) - half));
        return fmax(0.0, sqrt(d2) - a[3]);
    default:
        return fmax(0.0, point_distance(g, centre, naxes) - half * sqrt((double)naxes));
    }
}

/* Smallest target spacing of body within half of centre (a box), m. */
static double target_min(const struct tlsph_body *body, const double centre[3], double half,
                         int naxes)
{
    double t = body->spacing;
    for (size_t r = 0; r < body->nrefine; r++) {
        const struct tlsph_refine *rf = &body->refine[r];
        const double d = box_distance(&rf->region, centre, half, naxes);
        t = fmin(t, rf->spacing + (rf->grading - 1.0) * d);
    }
    return t;
}

double tlsph_graded_finest(const struct tlsph_body *body)
{
    double c = body->spacing;
    for (size_t r = 0; r < body->nrefine; r++) {
        double cr = body->spacing;
        /* the cells split while larger than the target (walk_cell) */
        for (int k = 0; k < TLSPH_MAX_REFINE_LEVELS && cr > body->refine[r].spacing * (1.0 + 1e-9);
             k++)
            cr *= 0.5;
        c = fmin(c, cr);
    }
    return c;
}

struct graded_walk {
    const struct tlsph_body *body;
    int dimension, naxes;
    size_t budget; /* cells still allowed (leaves and splits) */
    int (*visit)(const double X[3], double size, void *ctx);
    void *ctx;
};

/* The cell of size c at centre X, at refinement level `level`. */
static int walk_cell(struct graded_walk *w, const double X[3], double c, int level)
{
    if (w->budget == 0)
        return TLSPH_GRADED_TOO_MANY;
    w->budget--;
    /* the cell grown by c on each side: half-width 3c/2 */
    const int split = level < TLSPH_MAX_REFINE_LEVELS &&
                      c > target_min(w->body, X, 1.5 * c, w->naxes) * (1.0 + 1e-9);
    if (!split) {
        if (!tlsph_geometry_contains(&w->body->geometry, X))
            return 0;
        return w->visit(X, c, w->ctx);
    }
    const double q = 0.25 * c, hc = 0.5 * c;
    const int nz = w->dimension == 2 ? 1 : 2;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++) {
                const double Y[3] = {X[0] + (i ? q : -q), X[1] + (j ? q : -q),
                                     w->dimension == 2 ? 0.0 : X[2] + (k ? q : -q)};
                const int r = walk_cell(w, Y, hc, level + 1);
                if (r)
                    return r;
            }
    return 0;
}

int tlsph_graded_visit(const struct tlsph_scene *s, size_t b, size_t budget,
                       int (*visit)(const double X[3], double size, void *ctx), void *ctx)
{
    const struct tlsph_body *body = &s->bodies[b];
    long lo[3], hi[3];
    const double total = tlsph_lattice_range(s, b, lo, hi);
    if (!isfinite(total))
        return TLSPH_GRADED_TOO_MANY;
    struct graded_walk w = {.body = body,
                            .dimension = s->dimension,
                            .naxes = s->dimension == 2 ? 2 : 3,
                            .budget = budget,
                            .visit = visit,
                            .ctx = ctx};
    const double h = body->spacing;
    /* grow the range by one cell (an empty axis range comes back as hi < lo) */
    for (int k = 0; k < w.naxes; k++) {
        if (hi[k] < lo[k]) {
            double glo[3], ghi[3];
            tlsph_geometry_bounds(&body->geometry, glo, ghi);
            lo[k] = (long)floor((glo[k] - body->origin[k]) / h - 0.5);
            hi[k] = lo[k];
        }
        lo[k]--;
        hi[k]++;
    }
    for (long k = lo[2]; k <= hi[2]; k++)
        for (long j = lo[1]; j <= hi[1]; j++)
            for (long i = lo[0]; i <= hi[0]; i++) {
                const double X[3] = {
                    body->origin[0] + ((double)i + 0.5) * h,
                    body->origin[1] + ((double)j + 0.5) * h,
                    s->dimension == 2 ? 0.0 : body->origin[2] + ((double)k + 0.5) * h};
                const int r = walk_cell(&w, X, h, 0);
                if (r)
                    return r;
            }
    return 0;
}
