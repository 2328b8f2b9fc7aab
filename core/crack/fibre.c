/* Fibres and the crack-tip search (fibre.h). */
#include "crack/fibre.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct item {
    long c[2];    /* in-plane cell */
    double along; /* coordinate along the axis, m */
    size_t index;
};

static int cmp_item(const void *a, const void *b)
{
    const struct item *x = a, *y = b;
    for (int k = 1; k >= 0; k--)
        if (x->c[k] != y->c[k])
            return x->c[k] < y->c[k] ? -1 : 1;
    if (x->along != y->along)
        return x->along < y->along ? -1 : 1;
    return x->index < y->index ? -1 : (x->index > y->index);
}

static enum tlsph_fibre_status stack(struct tlsph_fibres *f, struct item *it, size_t count,
                                     const double *X);

enum tlsph_fibre_status tlsph_fibres_build(struct tlsph_fibres *f, const double *X,
                                           const size_t *index, size_t count, double spacing,
                                           int axis, size_t *bad)
{
    memset(f, 0, sizeof *f);
    f->axis = axis;
    if (axis < 0 || axis > 2 || !(spacing > 0.0) || !isfinite(spacing) || count == 0)
        return TLSPH_FIBRE_BAD_INPUT;
    int pa[2];
    tlsph_fibre_plane_axes(axis, pa);
    double lo[2] = {INFINITY, INFINITY};
    for (size_t k = 0; k < count; k++)
        for (int a = 0; a < 2; a++)
            lo[a] = fmin(lo[a], X[3 * index[k] + pa[a]]);
    struct item *it = malloc(count * sizeof *it);
    if (!it)
        return TLSPH_FIBRE_NO_MEMORY;
    for (size_t k = 0; k < count; k++) {
        const double *x = X + 3 * index[k];
        for (int a = 0; a < 2; a++) {
            const double u = (x[pa[a]] - lo[a]) / spacing;
            const double c = nearbyint(u);
            if (!(fabs(u - c) <= TLSPH_FIBRE_OFFSET_TOL) || !(c < 1e15)) {
                if (bad)
                    *bad = index[k];
                free(it);
                return TLSPH_FIBRE_NOT_LATTICE;
            }
            it[k].c[a] = (long)c;
        }
        it[k].along = x[axis];
        it[k].index = index[k];
    }
    return stack(f, it, count, X);
}

/* Appends the fibres of g (particles and centres) to f as region r. */
static void append_fibres(struct tlsph_fibres *f, const struct tlsph_fibres *g, int r)
{
    const size_t used = f->n ? f->start[f->n] : 0;
    for (size_t j = 0; j < g->n; j++) {
        f->start[f->n + j] = used + g->start[j];
        memcpy(f->centre[f->n + j], g->centre[j], sizeof f->centre[0]);
        f->region[f->n + j] = r;
    }
    memcpy(f->particle + used, g->particle, g->start[g->n] * sizeof *f->particle);
    f->n += g->n;
    f->start[f->n] = used + g->start[g->n];
}

enum tlsph_fibre_status tlsph_fibres_build_regions(struct tlsph_fibres *f, const double *X,
                                                   const size_t *index, const int *region_of,
                                                   size_t count, double spacing,
                                                   const int *axes, int nregions, size_t *bad)
{
    memset(f, 0, sizeof *f);
    if (nregions < 1 || nregions > TLSPH_FIBRE_MAX_REGIONS)
        return TLSPH_FIBRE_BAD_INPUT;
    for (int r = 0; r < nregions; r++) {
        if (axes[r] < 0 || axes[r] > 2)
            return TLSPH_FIBRE_BAD_INPUT;
        f->region_axis[r] = axes[r];
    }
    f->axis = axes[0];
    f->nregions = nregions;
    /* at most one fibre per particle: the arrays sized by the particles in a region */
    size_t inside = 0;
    for (size_t k = 0; k < count; k++)
        inside += region_of[k] >= 0 && region_of[k] < nregions;
    size_t *sub = malloc((inside ? inside : 1) * sizeof *sub);
    f->start = malloc((inside + 1) * sizeof *f->start);
    f->particle = malloc((inside ? inside : 1) * sizeof *f->particle);
    f->centre = malloc((inside ? inside : 1) * sizeof *f->centre);
    f->region = malloc((inside ? inside : 1) * sizeof *f->region);
    enum tlsph_fibre_status st = TLSPH_FIBRE_OK;
    if (!sub || !f->start || !f->particle || !f->centre || !f->region)
        st = TLSPH_FIBRE_NO_MEMORY;
    else
        f->start[0] = 0;
    for (int r = 0; r < nregions && st == TLSPH_FIBRE_OK; r++) {
        size_t m = 0;
        for (size_t k = 0; k < count; k++)
            if (region_of[k] == r)
                sub[m++] = index[k];
        if (m == 0) {
            if (bad)
                *bad = (size_t)-1 - (size_t)r;
            st = TLSPH_FIBRE_BAD_INPUT;
            break;
        }
        struct tlsph_fibres g;
        st = tlsph_fibres_build(&g, X, sub, m, spacing, axes[r], bad);
        if (st == TLSPH_FIBRE_OK)
            append_fibres(f, &g, r);
        tlsph_fibres_release(&g);
    }
    free(sub);
    if (st != TLSPH_FIBRE_OK) {
        tlsph_fibres_release(f);
        return st;
    }
    return TLSPH_FIBRE_OK;
}

/* The fibres of items it[0..count-1] (their cells set, along the coordinate
 * through the thickness): sorted, grouped by cell, centres; frees it. */
static enum tlsph_fibre_status stack(struct tlsph_fibres *f, struct item *it, size_t count,
                                     const double *X)
{
    qsort(it, count, sizeof *it, cmp_item);
    size_t nf = 0;
    for (size_t k = 0; k < count; k++)
        nf += k == 0 || it[k].c[0] != it[k - 1].c[0] || it[k].c[1] != it[k - 1].c[1];
    f->start = malloc((nf + 1) * sizeof *f->start);
    f->particle = malloc(count * sizeof *f->particle);
    f->centre = calloc(nf, sizeof *f->centre);
    if (!f->start || !f->particle || !f->centre) {
        free(it);
        tlsph_fibres_release(f);
        return TLSPH_FIBRE_NO_MEMORY;
    }
    size_t fk = 0;
    for (size_t k = 0; k < count; k++) {
        if (k == 0 || it[k].c[0] != it[k - 1].c[0] || it[k].c[1] != it[k - 1].c[1])
            f->start[fk++] = k;
        f->particle[k] = it[k].index;
    }
    f->start[nf] = count;
    f->n = nf;
    for (size_t j = 0; j < nf; j++) {
        const double m = (double)(f->start[j + 1] - f->start[j]);
        for (size_t k = f->start[j]; k < f->start[j + 1]; k++)
            for (int a = 0; a < 3; a++)
                f->centre[j][a] += X[3 * f->particle[k] + a] / m;
    }
    free(it);
    return TLSPH_FIBRE_OK;
}

/* ---------------------------------------------------------------- shells */

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* c = a x b, component k from the two others cyclically. */
static void cross3(const double a[3], const double b[3], double c[3])
{
    for (int k = 0; k < 3; k++)
        c[k] = a[(k + 1) % 3] * b[(k + 2) % 3] - a[(k + 2) % 3] * b[(k + 1) % 3];
}

/* P's offset from the shell's axis, normal to it (m), and its axial
 * coordinate (m). */
static double radial_offset(const struct tlsph_fibres *f, const double P[3], double rho[3])
{
    const double d[3] = {P[0] - f->base[0], P[1] - f->base[1], P[2] - f->base[2]};
    const double z = dot3(d, f->dir);
    for (int a = 0; a < 3; a++)
        rho[a] = d[a] - z * f->dir[a];
    return z;
}

int tlsph_fibres_normal(const struct tlsph_fibres *f, const double P[3], double n[3])
{
    if (f->axis != TLSPH_FIBRE_RADIAL) {
        for (int a = 0; a < 3; a++)
            n[a] = a == f->axis;
        return 0;
    }
    radial_offset(f, P, n);
    const double r = sqrt(dot3(n, n));
    if (!(r > 0.0))
        return -1;
    for (int a = 0; a < 3; a++)
        n[a] /= r;
    return 0;
}

void tlsph_fibres_local(const struct tlsph_fibres *f, const double P[3], const double v[3],
                        double out[2])
{
    if (f->axis != TLSPH_FIBRE_RADIAL) {
        int pa[2];
        tlsph_fibre_plane_axes(f->axis, pa);
        out[0] = v[pa[0]];
        out[1] = v[pa[1]];
        return;
    }
    double n[3], t[3];
    if (tlsph_fibres_normal(f, P, n) != 0) {
        out[0] = out[1] = 0.0;
        return;
    }
    cross3(f->dir, n, t);
    out[0] = dot3(v, t);
    out[1] = dot3(v, f->dir);
}

double tlsph_fibres_depth(const struct tlsph_fibres *f, const double X[3])
{
    if (f->axis != TLSPH_FIBRE_RADIAL)
        return X[f->axis];
    double rho[3];
    radial_offset(f, X, rho);
    return sqrt(dot3(rho, rho));
}

/* d (a fibre centre's offset from P) in the plane at P, into v, and its
 * length there: a plate's in-plane length; a shell's chord |d| (the arc
 * along the surface to second order in |d| / r), not the tangent
 * projection's, which would bring the far side of the tube to the tip. */
static double plane_vector(const struct tlsph_fibres *f, const double P[3], const double d[3],
                           double v[2])
{
    tlsph_fibres_local(f, P, d, v);
    return f->axis == TLSPH_FIBRE_RADIAL ? sqrt(dot3(d, d)) : hypot(v[0], v[1]);
}

struct ray {
    double z, theta, r;
    size_t index;
};

static int cmp_double(double a, double b)
{
    return a < b ? -1 : a > b;
}

static int cmp_ray_z(const void *a, const void *b)
{
    const struct ray *x = a, *y = b;
    const int c = cmp_double(x->z, y->z);
    return c ? c : (x->index > y->index) - (x->index < y->index);
}

enum tlsph_fibre_status tlsph_fibres_build_radial(struct tlsph_fibres *f, const double *X,
                                                  const size_t *index, size_t count,
                                                  double spacing, const double base[3],
                                                  const double dir[3], size_t *bad)
{
    memset(f, 0, sizeof *f);
    f->axis = TLSPH_FIBRE_RADIAL;
    const double ld = sqrt(dot3(dir, dir));
    if (!(spacing > 0.0) || !isfinite(spacing) || count == 0 || !(ld > 0.0) || !isfinite(ld))
        return TLSPH_FIBRE_BAD_INPUT;
    for (int a = 0; a < 3; a++) {
        f->base[a] = base[a];
        f->dir[a] = dir[a] / ld;
    }
    /* u: the coordinate axis least along dir, made normal to it; w = dir x u */
    int e = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(f->dir[k]) < fabs(f->dir[e]))
            e = k;
    double u[3] = {0, 0, 0}, w[3];
    u[e] = 1.0;
    const double ue = f->dir[e];
    for (int a = 0; a < 3; a++)
        u[a] -= ue * f->dir[a];
    const double un = sqrt(dot3(u, u));
    for (int a = 0; a < 3; a++)
        u[a] /= un;
    cross3(f->dir, u, w);
    const double tol = TLSPH_FIBRE_OFFSET_TOL * spacing;
    struct ray *ry = malloc(count * sizeof *ry);
    struct item *it = malloc(count * sizeof *it);
    if (!ry || !it) {
        free(ry);
        free(it);
        return TLSPH_FIBRE_NO_MEMORY;
    }
    for (size_t k = 0; k < count; k++) {
        double rho[3];
        ry[k].z = radial_offset(f, X + 3 * index[k], rho);
        ry[k].r = sqrt(dot3(rho, rho));
        ry[k].index = index[k];
        if (!(ry[k].r > tol) || !isfinite(ry[k].r) || !isfinite(ry[k].z)) {
            if (bad)
                *bad = index[k];
            free(ry);
            free(it);
            return TLSPH_FIBRE_BAD_INPUT;
        }
        double th = atan2(dot3(rho, w), dot3(rho, u));
        if (th > M_PI - tol / ry[k].r) /* a ray at -pi to round-off: one side only */
            th -= 2.0 * M_PI;
        ry[k].theta = th;
    }
    /* layers: runs of z within tol; then rays: runs of theta within tol / r */
    qsort(ry, count, sizeof *ry, cmp_ray_z);
    long layer = 0;
    for (size_t k = 0; k < count; k++) {
        layer += k > 0 && ry[k].z - ry[k - 1].z > tol;
        it[k] = (struct item){.c = {0, layer}, .along = ry[k].theta, .index = k};
    }
    qsort(it, count, sizeof *it, cmp_item); /* by layer, then theta */
    long cell = 0;
    for (size_t k = 0; k < count; k++) { /* it[k].index: a ray until the second pass */
        const struct ray *a = &ry[it[k].index], *b = k ? &ry[it[k - 1].index] : a;
        cell += k > 0 && (it[k].c[1] != it[k - 1].c[1] ||
                          (a->theta - b->theta) * fmax(a->r, b->r) > tol);
        it[k].c[0] = cell;
    }
    for (size_t k = 0; k < count; k++) {
        const struct ray *a = &ry[it[k].index];
        it[k].along = a->r;
        it[k].index = a->index;
    }
    free(ry);
    const enum tlsph_fibre_status st = stack(f, it, count, X);
    if (st != TLSPH_FIBRE_OK)
        return st;
    for (size_t j = 1; j < f->n; j++) /* every fibre the same size: the particles stack */
        if (f->start[j + 1] - f->start[j] != f->start[1] - f->start[0]) {
            if (bad)
                *bad = f->particle[f->start[j]];
            const double b0[3] = {f->base[0], f->base[1], f->base[2]};
            const double d0[3] = {f->dir[0], f->dir[1], f->dir[2]};
            tlsph_fibres_release(f);
            f->axis = TLSPH_FIBRE_RADIAL;
            memcpy(f->base, b0, sizeof b0);
            memcpy(f->dir, d0, sizeof d0);
            return TLSPH_FIBRE_NOT_STACKED;
        }
    return TLSPH_FIBRE_OK;
}

double tlsph_fibre_damage(const struct tlsph_fibres *f, size_t k, const double *D)
{
    double sum = 0.0;
    for (size_t p = f->start[k]; p < f->start[k + 1]; p++)
        sum += D[f->particle[p]];
    return sum;
}

/* Eq. 20 over the fibres cand[0..ncand-1] (all when cand is NULL). */
static long next_tip(const struct tlsph_fibres *f, const double *D, const struct tlsph_tip_search *q,
                     const size_t *cand, size_t ncand)
{
    double v1[2];
    tlsph_fibres_local(f, q->tip, q->direction, v1);
    const double n1 = hypot(v1[0], v1[1]);
    if (!(n1 > 0.0) || !(q->radius > 0.0))
        return -1;
    /* |theta| <= theta_c / 2  <=>  cos theta >= cos(theta_c / 2) (theta in [0, pi]) */
    const double cos_half = cos(0.5 * fmin(q->theta_c, 2.0 * M_PI));
    /* the tip's own fibre (distance 0 up to round-off) is not a candidate */
    const double r_min = 1e-9 * q->radius;
    long best = -1;
    double best_D = 0.0, best_r = 0.0;
    const size_t n = cand ? ncand : f->n;
    for (size_t c = 0; c < n; c++) {
        const size_t j = cand ? cand[c] : c;
        if (!tlsph_fibres_sees(f, j))
            continue;
        const double d[3] = {f->centre[j][0] - q->tip[0], f->centre[j][1] - q->tip[1],
                             f->centre[j][2] - q->tip[2]};
        double v2[2];
        const double r = plane_vector(f, q->tip, d, v2);
        if (!(r > r_min) || r > q->radius)
            continue;
        const double c2 = (v1[0] * v2[0] + v1[1] * v2[1]) / (n1 * r);
        /* round-off may put a fibre exactly on the fan's edge a hair outside */
        if (c2 < cos_half - 1e-12)
            continue;
        const double Dj = tlsph_fibre_damage(f, j, D);
        if (!(Dj >= q->D_c))
            continue;
        if (best < 0 || Dj > best_D || (Dj == best_D && r < best_r) ||
            (Dj == best_D && r == best_r && (long)j < best)) {
            best = (long)j;
            best_D = Dj;
            best_r = r;
        }
    }
    return best;
}

long tlsph_fibre_next_tip(const struct tlsph_fibres *f, const double *D,
                          const struct tlsph_tip_search *q)
{
    return next_tip(f, D, q, NULL, 0);
}

long tlsph_fibre_next_tip_among(const struct tlsph_fibres *f, const double *D,
                                const struct tlsph_tip_search *q, const size_t *cand,
                                size_t ncand)
{
    return next_tip(f, D, q, cand, ncand);
}

size_t tlsph_fibres_within(const struct tlsph_fibres *f, const double point[3], double radius,
                           size_t *out, size_t max)
{
    size_t n = 0;
    for (size_t j = 0; j < f->n; j++) {
        if (!tlsph_fibres_sees(f, j))
            continue;
        const double d[3] = {f->centre[j][0] - point[0], f->centre[j][1] - point[1],
                             f->centre[j][2] - point[2]};
        double v[2];
        if (plane_vector(f, point, d, v) <= radius) {
            if (out && n < max)
                out[n] = j;
            n++;
        }
    }
    return n;
}

void tlsph_fibres_release(struct tlsph_fibres *f)
{
    free(f->start);
    free(f->particle);
    free(f->centre);
    free(f->region);
    memset(f, 0, sizeof *f);
}

int tlsph_fibres_split_prepare(const struct tlsph_fibres *f, size_t k, struct tlsph_fibres *fresh)
{
    *fresh = *f; /* the header: axis, base, dir, regions */
    fresh->only = 0;
    const size_t count = f->n ? f->start[f->n] : 0;
    fresh->start = malloc((f->n + k + 1) * sizeof *fresh->start);
    fresh->particle = malloc((count + k) * sizeof *fresh->particle);
    fresh->centre = malloc((f->n + k) * sizeof *fresh->centre);
    fresh->region = f->region ? malloc((f->n + k) * sizeof *fresh->region) : NULL;
    if (!fresh->start || !fresh->particle || !fresh->centre || (f->region && !fresh->region)) {
        tlsph_fibres_release(fresh);
        return -1;
    }
    return 0;
}

static void fibre_centre(struct tlsph_fibres *f, size_t j, const double *X)
{
    const double m = (double)(f->start[j + 1] - f->start[j]);
    for (int a = 0; a < 3; a++)
        f->centre[j][a] = 0.0;
    for (size_t p = f->start[j]; p < f->start[j + 1]; p++)
        for (int a = 0; a < 3; a++)
            f->centre[j][a] += X[3 * f->particle[p] + a] / m;
}

/* The slot of i among the parents, or k. */
static size_t parent_slot(const size_t *parent, size_t k, size_t i)
{
    size_t s = 0;
    while (s < k && parent[s] != i)
        s++;
    return s;
}

size_t tlsph_fibres_split_commit(struct tlsph_fibres *f, struct tlsph_fibres *fresh,
                                 const size_t *parent, size_t k, size_t at, const double *X)
{
    const size_t count = f->n ? f->start[f->n] : 0;
    memcpy(fresh->start, f->start, (f->n + 1) * sizeof *f->start);
    memcpy(fresh->particle, f->particle, count * sizeof *f->particle);
    memcpy(fresh->centre, f->centre, f->n * sizeof *f->centre);
    if (f->region)
        memcpy(fresh->region, f->region, f->n * sizeof *f->region);
    size_t nf = f->n, used = count;
    for (size_t j = 0; j < f->n; j++) {
        const size_t first = used;
        for (size_t p = f->start[j]; p < f->start[j + 1]; p++) {
            const size_t s = parent_slot(parent, k, f->particle[p]);
            if (s < k)
                fresh->particle[used++] = at + s;
        }
        if (used == first)
            continue;
        fresh->start[++nf] = used;
        if (fresh->region) /* the new face's fibre stays in its parent's region */
            fresh->region[nf - 1] = f->region[j];
        fibre_centre(fresh, j, X);
        fibre_centre(fresh, nf - 1, X);
    }
    const size_t added = nf - f->n;
    fresh->n = nf;
    tlsph_fibres_release(f);
    *f = *fresh;
    memset(fresh, 0, sizeof *fresh);
    return added;
}

void tlsph_fibres_shift(struct tlsph_fibres *f, size_t at, size_t k)
{
    const size_t count = f->n ? f->start[f->n] : 0;
    for (size_t p = 0; p < count; p++)
        if (f->particle[p] >= at)
            f->particle[p] += k;
}
