/* The simple cubic lattice that turns a body's geometry into particle
 * positions: origin + (i + 1/2) h per axis, index ranges from floor/ceil of the
 * geometry's bounds so that positions never accumulate rounding, points visited
 * x fastest (the particles' initial order).  A body with "placement":
 * "conforming" takes its shells from conforming.c instead, through the same
 * entry points (count, visit, positions and volumes).
 *
 * Membership is that of tlsph_geometry_contains (geometry.c), made cheap for
 * geometries of many objects: the walk flattens the geometry tree and, for
 * each lattice row (fixed y and z), lists the children of each union or
 * difference whose bounding box meets the row; a point then only tests those
 * (and their x range).  Boxes are padded by a relative 1e-9, far above the
 * rounding of the membership tests, so a point is inside exactly when
 * tlsph_geometry_contains says so.  A union of 1000 small spheres, which tested
 * 1000 spheres per lattice point, tests the few a row meets. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene/parse_internal.h"

/* A geometry object in the walk's flat copy of the tree (breadth first, so
 * each composite's children are contiguous from .child). */
struct walk_node {
    const struct tlsph_geometry *g;
    double lo[3], hi[3]; /* padded bounding box, m */
    size_t child;        /* first child (composites) */
    size_t nactive;      /* children whose box meets the current row ... */
    size_t *active;      /* ... listed here (a slice of the shared buffer) */
};

struct walker {
    struct walk_node *node;
    size_t n;
    size_t *buf; /* n slots: node k's active list uses slots child.. of node k */
    int dimension;
};

static size_t count_objects(const struct tlsph_geometry *g)
{
    size_t n = 1;
    for (size_t i = 0; i < g->nchildren; i++)
        n += count_objects(&g->children[i]);
    return n;
}

size_t tlsph_geometry_count(const struct tlsph_geometry *g)
{
    return count_objects(g);
}

static void walker_free(struct walker *w)
{
    free(w->node);
    free(w->buf);
}

static int walker_init(struct walker *w, const struct tlsph_geometry *root, int dimension)
{
    w->n = count_objects(root);
    w->dimension = dimension;
    w->node = calloc(w->n, sizeof *w->node);
    w->buf = calloc(w->n, sizeof *w->buf);
    if (!w->node || !w->buf) {
        walker_free(w);
        return -1;
    }
    w->node[0].g = root;
    size_t next = 1;
    for (size_t k = 0; k < w->n; k++) {
        struct walk_node *nd = &w->node[k];
        nd->child = next;
        nd->active = w->buf + next;
        for (size_t i = 0; i < nd->g->nchildren; i++)
            w->node[next++].g = &nd->g->children[i];
        tlsph_geometry_bounds(nd->g, nd->lo, nd->hi);
        for (int c = 0; c < 3; c++) {
            const double pad =
                1e-9 * (fabs(nd->lo[c]) + fabs(nd->hi[c]) + (nd->hi[c] - nd->lo[c])) + 1e-300;
            nd->lo[c] -= pad;
            nd->hi[c] += pad;
        }
    }
    return 0;
}

/* For the row at (y, z): each composite's children whose box meets it. */
static void walker_row(struct walker *w, double y, double z)
{
    for (size_t k = 0; k < w->n; k++) {
        struct walk_node *nd = &w->node[k];
        nd->nactive = 0;
        for (size_t i = 0; i < nd->g->nchildren; i++) {
            const struct walk_node *c = &w->node[nd->child + i];
            if (y >= c->lo[1] && y <= c->hi[1] &&
                (w->dimension == 2 || (z >= c->lo[2] && z <= c->hi[2])))
                nd->active[nd->nactive++] = nd->child + i;
        }
    }
}

/* tlsph_geometry_contains for node k, at a point X of the current row. */
static int walker_contains(const struct walker *w, size_t k, const double X[3])
{
    const struct walk_node *nd = &w->node[k];
    if (X[0] < nd->lo[0] || X[0] > nd->hi[0])
        return 0;
    switch (nd->g->type) {
    case TLSPH_GEOM_UNION:
        for (size_t a = 0; a < nd->nactive; a++)
            if (walker_contains(w, nd->active[a], X))
                return 1;
        return 0;
    case TLSPH_GEOM_DIFFERENCE:
        /* the minuend is the first child, listed first when it meets the row */
        if (nd->nactive == 0 || nd->active[0] != nd->child || !walker_contains(w, nd->child, X))
            return 0;
        for (size_t a = 1; a < nd->nactive; a++)
            if (walker_contains(w, nd->active[a], X))
                return 0;
        return 1;
    default: return tlsph_geometry_contains(nd->g, X);
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

/* tlsph_lattice_visit for a conforming body: its shell points. */
static int conforming_visit(const struct tlsph_scene *s, size_t b,
                            int (*visit)(const double X[3], void *ctx), void *ctx)
{
    const size_t n = tlsph_conforming_count(s, b);
    double *X = malloc((n ? n : 1) * 3 * sizeof *X);
    if (!X)
        return -1;
    tlsph_conforming_fill(s, b, X, NULL);
    int r = 0;
    for (size_t i = 0; i < n && !r; i++)
        r = visit(X + 3 * i, ctx);
    free(X);
    return r;
}

/* A graded body's walk visits at most this many cells: bounded like the
 * uniform lattice's candidates (10 x the particle limit). */
static size_t graded_budget(const struct tlsph_scene *s)
{
    return 10 * (size_t)(s->max_particles > 0 ? s->max_particles : 1);
}

struct drop_size {
    int (*visit)(const double X[3], void *ctx);
    void *ctx;
};

static int drop_size_visit(const double X[3], double size, void *ctx)
{
    (void)size;
    const struct drop_size *d = ctx;
    return d->visit(X, d->ctx);
}

int tlsph_lattice_visit(const struct tlsph_scene *s, size_t b, const long lo[3], const long hi[3],
                        int (*visit)(const double X[3], void *ctx), void *ctx)
{
    const struct tlsph_body *body = &s->bodies[b];
    if (body->placement == TLSPH_PLACEMENT_CONFORMING)
        return conforming_visit(s, b, visit, ctx);
    if (body->nrefine) { /* too many cells: as out of memory (counted first, graded_count) */
        const int r = tlsph_graded_visit(s, b, graded_budget(s), drop_size_visit,
                                         &(struct drop_size){visit, ctx});
        return r == TLSPH_GRADED_TOO_MANY ? -1 : r;
    }
    const double h = body->spacing;
    struct walker w;
    if (walker_init(&w, &body->geometry, s->dimension) != 0)
        return -1;
    int r = 0;
    for (long k = lo[2]; k <= hi[2] && !r; k++) {
        const double z = s->dimension == 2 ? 0.0 : body->origin[2] + ((double)k + 0.5) * h;
        for (long j = lo[1]; j <= hi[1] && !r; j++) {
            const double y = body->origin[1] + ((double)j + 0.5) * h;
            walker_row(&w, y, z);
            for (long i = lo[0]; i <= hi[0]; i++) {
                const double X[3] = {body->origin[0] + ((double)i + 0.5) * h, y, z};
                if (!walker_contains(&w, 0, X))
                    continue;
                r = visit(X, ctx);
                if (r)
                    break;
            }
        }
    }
    walker_free(&w);
    return r;
}

struct store {
    double *out; /* NULL: count only */
    size_t cap, n;
};

static int store_point(const double X[3], void *ctx)
{
    struct store *st = ctx;
    if (st->out && st->n < st->cap)
        memcpy(st->out + 3 * st->n, X, 3 * sizeof *X);
    st->n++;
    return 0;
}

/* Stores up to cap points in out (when non-NULL) and sets *count to the number
 * of points inside.  0, or -1 when out of memory. */
static int lattice_walk(const struct tlsph_scene *s, size_t b, const long lo[3], const long hi[3],
                        double *out, size_t cap, size_t *count)
{
    struct store st = {.out = out, .cap = cap};
    if (tlsph_lattice_visit(s, b, lo, hi, store_point, &st) != 0)
        return -1;
    *count = st.n;
    return 0;
}

/* The graded leaves of body b: counted (out NULL) or stored with their volumes
 * and spacings (up to cap). */
struct graded_store {
    double *X, *vol, *spacing; /* NULL: count only */
    size_t cap, n;
    int dimension;
};

static int graded_point(const double X[3], double size, void *ctx)
{
    struct graded_store *st = ctx;
    if (st->X && st->n < st->cap) {
        memcpy(st->X + 3 * st->n, X, 3 * sizeof *X);
        st->vol[st->n] = st->dimension == 2 ? size * size : size * size * size;
        st->spacing[st->n] = size;
    }
    st->n++;
    return 0;
}

/* *count = the graded body's particles, SIZE_MAX when its walk visits more
 * cells than graded_budget allows. */
static void graded_count(const struct tlsph_scene *s, size_t b, size_t *count)
{
    struct graded_store st = {.dimension = s->dimension};
    const int r = tlsph_graded_visit(s, b, graded_budget(s), graded_point, &st);
    *count = r == TLSPH_GRADED_TOO_MANY ? SIZE_MAX : st.n;
}

int tlsph_lattice_count(const struct tlsph_scene *s, size_t b, size_t *count)
{
    if (s->bodies[b].placement == TLSPH_PLACEMENT_CONFORMING) {
        *count = tlsph_conforming_count(s, b);
        return 0;
    }
    if (s->bodies[b].nrefine) {
        graded_count(s, b, count);
        return 0;
    }
    long lo[3], hi[3];
    const double total = tlsph_lattice_range(s, b, lo, hi);
    *count = 0;
    if (!(total > 0.0) || !isfinite(total))
        return 0;
    return lattice_walk(s, b, lo, hi, NULL, 0, count);
}

/* A body of more than max_points particles: reported at pointer p. */
static int over_limit(const struct tlsph_scene *s, size_t b, size_t count, long max_points,
                      const char *p, struct tlsph_errors *err)
{
    if (count <= (size_t)max_points)
        return 0;
    tlsph_errors_add(err, p, "body '%s' has %zu particles, more than the limit of %ld",
                     s->bodies[b].name, count, max_points);
    return 1;
}

/* The lattice points of body b (tlsph_body_particles without volumes). */
static int lattice_points(const struct tlsph_scene *s, size_t b, long max_points, double **out,
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
    size_t count = 0;
    if (total > 0.0 && lattice_walk(s, b, lo, hi, NULL, 0, &count) != 0) {
        tlsph_errors_add(err, p, "out of memory for the geometry of body '%s'", s->bodies[b].name);
        return -1;
    }
    if (over_limit(s, b, count, max_points, p, err))
        return -1;
    if (count == 0)
        return 0;
    double *x = malloc(3 * count * sizeof *x);
    size_t again = 0;
    if (!x || lattice_walk(s, b, lo, hi, x, count, &again) != 0) {
        free(x);
        tlsph_errors_add(err, p, "out of memory for %zu particles of body '%s'", count,
                         s->bodies[b].name);
        return -1;
    }
    if (again != count) { /* cannot happen: the walk is deterministic */
        free(x);
        tlsph_errors_add(err, p, "internal error: lattice count changed");
        return -1;
    }
    *out = x;
    *n = count;
    return 0;
}

/* A conforming body's shells: counted first against max_points like the lattice. */
static int conforming_points(const struct tlsph_scene *s, size_t b, long max_points, double **out,
                             double **vol, size_t *n, struct tlsph_errors *err)
{
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_index(p, sizeof p, "/bodies", b);
    const size_t count = tlsph_conforming_count(s, b);
    if (over_limit(s, b, count, max_points, p, err))
        return -1;
    double *x = count ? malloc(3 * count * sizeof *x) : NULL;
    double *v = count && vol ? malloc(count * sizeof *v) : NULL;
    if (count && (!x || (vol && !v))) {
        free(x);
        free(v);
        tlsph_errors_add(err, p, "out of memory for %zu particles of body '%s'", count,
                         s->bodies[b].name);
        return -1;
    }
    tlsph_conforming_fill(s, b, x, v);
    *out = x;
    if (vol)
        *vol = v;
    *n = count;
    return 0;
}

/* A graded body's leaves with volumes and spacings, counted first against
 * max_points (reported at its "refine"). */
static int graded_points(const struct tlsph_scene *s, size_t b, long max_points, double **out,
                         double **vol, double **spacing, size_t *n, struct tlsph_errors *err)
{
    char P[TLSPH_POINTER_MAX], p[TLSPH_POINTER_MAX];
    tlsph_pointer_index(P, sizeof P, "/bodies", b);
    tlsph_pointer_join(p, sizeof p, P, "refine");
    size_t count;
    graded_count(s, b, &count);
    if (count == SIZE_MAX) {
        tlsph_errors_add(err, p,
                         "body '%s': its refinement visits more than 10 x the limit of %ld "
                         "particles in cells",
                         s->bodies[b].name, s->max_particles);
        return -1;
    }
    if (over_limit(s, b, count, max_points, p, err))
        return -1;
    if (count == 0)
        return 0;
    struct graded_store st = {.cap = count, .dimension = s->dimension};
    st.X = malloc(3 * count * sizeof *st.X);
    st.vol = malloc(count * sizeof *st.vol);
    st.spacing = malloc(count * sizeof *st.spacing);
    if (!st.X || !st.vol || !st.spacing ||
        tlsph_graded_visit(s, b, graded_budget(s), graded_point, &st) != 0 || st.n != count) {
        free(st.X);
        free(st.vol);
        free(st.spacing);
        tlsph_errors_add(err, P, "out of memory for %zu particles of body '%s'", count,
                         s->bodies[b].name);
        return -1;
    }
    *out = st.X;
    *n = count;
    if (vol)
        *vol = st.vol;
    else
        free(st.vol);
    if (spacing)
        *spacing = st.spacing;
    else
        free(st.spacing);
    return 0;
}

/* n copies of value in a new array (*a; NULL when n = 0), or -1. */
static int fill_array(double **a, size_t n, double value)
{
    *a = NULL;
    if (n == 0)
        return 0;
    double *v = malloc(n * sizeof *v);
    if (!v)
        return -1;
    for (size_t i = 0; i < n; i++)
        v[i] = value;
    *a = v;
    return 0;
}

int tlsph_body_fill(const struct tlsph_scene *s, size_t b, long max_points, double **out,
                    double **vol, double **spacing, size_t *n, struct tlsph_errors *err)
{
    *out = NULL;
    *n = 0;
    if (vol)
        *vol = NULL;
    if (spacing)
        *spacing = NULL;
    const struct tlsph_body *body = &s->bodies[b];
    if (body->placement == TLSPH_PLACEMENT_LATTICE && body->nrefine)
        return graded_points(s, b, max_points, out, vol, spacing, n, err);
    int r;
    if (body->placement == TLSPH_PLACEMENT_CONFORMING)
        r = conforming_points(s, b, max_points, out, vol, n, err);
    else
        r = lattice_points(s, b, max_points, out, n, err);
    if (r != 0)
        return -1;
    const double h = body->spacing;
    const int bad = (body->placement != TLSPH_PLACEMENT_CONFORMING && vol &&
                     fill_array(vol, *n, s->dimension == 2 ? h * h : h * h * h) != 0) ||
                    (spacing && fill_array(spacing, *n, h) != 0);
    if (bad) {
        free(*out);
        *out = NULL;
        if (vol) {
            free(*vol);
            *vol = NULL;
        }
        *n = 0;
        tlsph_errors_add(err, "", "out of memory for the volumes of body '%s'", body->name);
        return -1;
    }
    return 0;
}

int tlsph_body_particles(const struct tlsph_scene *s, size_t b, long max_points, double **out,
                         double **vol, size_t *n, struct tlsph_errors *err)
{
    return tlsph_body_fill(s, b, max_points, out, vol, NULL, n, err);
}

int tlsph_body_lattice(const struct tlsph_scene *s, size_t b, long max_points, double **out,
                       size_t *n, struct tlsph_errors *err)
{
    return tlsph_body_particles(s, b, max_points, out, NULL, n, err);
}
