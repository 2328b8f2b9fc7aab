/* Surface-conforming particle placement ("placement": "conforming") for a
 * sphere (a disc in 2-D) or a cylinder: particles on concentric shells that
 * follow the curved surface, so that a sphere touches a flat at a point that
 * grows like the Hertz contact, not with the flat patch a lattice cuts out of it.
 *
 * The radius R is cut into N = round(R / h) shells of thickness t = R / N;
 * shell k (k = 0 at the centre) spans [k t, (k + 1) t] and its particles sit at
 * its middle radius r = (k + 1/2) t, so the outer shell is at R - t/2 (half a
 * spacing inside the surface, as on the lattice).  A ring of circumference C
 * holds 4 max(1, round(C / (4 h))) particles at the angles (i + 1/2) 2 pi / n.
 *  - 2-D disc: one ring per shell.
 *  - Sphere: M = max(1, round(pi r / h)) rings per shell at the polar angles
 *    theta_j = (j + 1/2) pi / M about the z axis (C = 2 pi r sin(theta_j)):
 *    arc spacing about h both ways.
 *  - Cylinder: round(L / h) layers of thickness dz = L / layers across the
 *    axis, at (l + 1/2) dz from the base, each holding the rings of a disc.
 * Every particle of a shell gets the shell's volume (area in 2-D; ring area x
 * dz in a cylinder layer) divided by its count, so the volumes sum to the
 * body's 4/3 pi R^3 (pi R^2, pi R^2 L) up to round-off.  Counts are multiples
 * of 4 and no angle lies on an axis, so the point set is mirror-symmetric
 * about the planes x = c_x and y = c_y through the centre c (the cylinder: the
 * two planes through its axis along u and w below) with no particle on them:
 * a quarter cut by those planes (a difference whose first object is the sphere)
 * keeps exactly a quarter of each shell, and its volumes a quarter of the body's.
 *
 * A cylinder whose body has "thickness_axis": "radial" (a shell wall, its
 * particles stacked into radial fibres) puts the outer shell's count on every
 * ring instead, at the same angles: the shells' particles lie on common rays.
 *
 * Points come layer by layer, shell by shell from the centre outwards, rings
 * by increasing theta, azimuths increasing: deterministic, no random numbers. */
#include <math.h>
#include <stdlib.h>

#include "scene/parse_internal.h"

static long ring_count(double circumference, double h)
{
    const long q = lround(circumference / (4.0 * h));
    return 4 * (q > 0 ? q : 1);
}

/* The primitive whose shells a conforming body uses: the geometry itself, or
 * the first object of a difference, when it is a sphere or a cylinder. */
const struct tlsph_geometry *tlsph_conforming_base(const struct tlsph_geometry *g)
{
    if (g->type == TLSPH_GEOM_DIFFERENCE && g->nchildren > 0)
        g = &g->children[0];
    return g->type == TLSPH_GEOM_SPHERE || g->type == TLSPH_GEOM_CYLINDER ? g : NULL;
}

/* Appends P (and its volume) when the body's geometry holds it; returns the
 * new count. */
static size_t keep(const struct tlsph_body *body, const double P[3], double each, double *X,
                   double *vol, size_t n)
{
    if (!tlsph_geometry_contains(&body->geometry, P))
        return n;
    if (X)
        for (int d = 0; d < 3; d++)
            X[3 * n + d] = P[d];
    if (vol)
        vol[n] = each;
    return n + 1;
}

/* Sphere (disc in 2-D) of centre c, radius R. */
static size_t sphere_shells(const struct tlsph_scene *s, const struct tlsph_body *body,
                            const double *c, double R, double *X, double *vol)
{
    const double h = body->spacing, pi = acos(-1.0);
    const long N = lround(R / h); /* 0 below half a spacing: no particle, refused as empty */
    const double t = R / (double)N;
    size_t n = 0;
    for (long k = 0; k < N; k++) {
        const double r = ((double)k + 0.5) * t, ri = (double)k * t, ro = (double)(k + 1) * t;
        const long M0 = s->dimension == 2 ? 1 : lround(pi * r / h);
        const long M = M0 > 0 ? M0 : 1;
        /* the shell's count first: every particle gets volume / count */
        long count = 0;
        for (long j = 0; j < M; j++) {
            const double sin_t = s->dimension == 2 ? 1.0 : sin(((double)j + 0.5) * pi / (double)M);
            count += ring_count(2.0 * pi * r * sin_t, h);
        }
        const double shell = s->dimension == 2 ? pi * (ro * ro - ri * ri)
                                               : 4.0 / 3.0 * pi * (ro * ro * ro - ri * ri * ri);
        const double each = shell / (double)count;
        for (long j = 0; j < M; j++) {
            const double theta = s->dimension == 2 ? 0.5 * pi : ((double)j + 0.5) * pi / (double)M;
            const double sin_t = sin(theta), cos_t = s->dimension == 2 ? 0.0 : cos(theta);
            const long nj = ring_count(2.0 * pi * r * sin_t, h);
            for (long i = 0; i < nj; i++) {
                const double phi = ((double)i + 0.5) * 2.0 * pi / (double)nj;
                const double P[3] = {c[0] + r * sin_t * cos(phi), c[1] + r * sin_t * sin(phi),
                                     s->dimension == 2 ? 0.0 : c[2] - r * cos_t};
                n = keep(body, P, each, X, vol, n);
            }
        }
    }
    return n;
}

/* Cylinder (3-D): a[0..2] base centre, a[3..5] unit axis, a[6] radius, a[7]
 * length.  round(L / h) layers across the axis, each the rings of a disc. */
static size_t cylinder_shells(const struct tlsph_body *body, const double *a, double *X,
                              double *vol)
{
    const double h = body->spacing, pi = acos(-1.0), R = a[6], L = a[7];
    const long N = lround(R / h), layers = lround(L / h);
    const double t = R / (double)N, dz = L / (double)layers;
    /* u: the coordinate axis least along the cylinder's, made normal to it; w = axis x u */
    int e = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(a[3 + k]) < fabs(a[3 + e]))
            e = k;
    double u[3] = {0, 0, 0}, w[3];
    u[e] = 1.0;
    const double ua = a[3 + e];
    for (int k = 0; k < 3; k++)
        u[k] -= ua * a[3 + k];
    const double un = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int k = 0; k < 3; k++)
        u[k] /= un;
    w[0] = a[4] * u[2] - a[5] * u[1];
    w[1] = a[5] * u[0] - a[3] * u[2];
    w[2] = a[3] * u[1] - a[4] * u[0];
    /* a shell wall with radial fibres ("thickness_axis": "radial"): every ring
     * holds the outer shell's count, so the particles of all shells lie on
     * common rays from the axis and stack into fibres (crack/fibre.h); the
     * inner shells' arc spacing is then their radius over the outer's times h */
    const long n_outer = ring_count(2.0 * pi * (R - 0.5 * t), h);
    size_t n = 0;
    for (long l = 0; l < layers; l++) {
        const double z = ((double)l + 0.5) * dz;
        for (long k = 0; k < N; k++) {
            const double r = ((double)k + 0.5) * t, ri = (double)k * t, ro = (double)(k + 1) * t;
            const long nk = body->thickness_axis == 3 ? n_outer : ring_count(2.0 * pi * r, h);
            const double each = pi * (ro * ro - ri * ri) * dz / (double)nk;
            for (long i = 0; i < nk; i++) {
                const double phi = ((double)i + 0.5) * 2.0 * pi / (double)nk;
                const double cu = r * cos(phi), cw = r * sin(phi);
                double P[3];
                for (int d = 0; d < 3; d++)
                    P[d] = a[d] + z * a[3 + d] + cu * u[d] + cw * w[d];
                n = keep(body, P, each, X, vol, n);
            }
        }
    }
    return n;
}

/* Every shell point of body b inside its geometry, with its volume; returns
 * the number of points.  X and vol (when non-NULL) receive them. */
static size_t place(const struct tlsph_scene *s, size_t b, double *X, double *vol)
{
    const struct tlsph_body *body = &s->bodies[b];
    const struct tlsph_geometry *g = tlsph_conforming_base(&body->geometry);
    if (!g)
        return 0;
    if (g->type == TLSPH_GEOM_SPHERE)
        return sphere_shells(s, body, g->a, g->a[3], X, vol);
    return cylinder_shells(body, g->a, X, vol);
}

size_t tlsph_conforming_count(const struct tlsph_scene *s, size_t b)
{
    return place(s, b, NULL, NULL);
}

void tlsph_conforming_fill(const struct tlsph_scene *s, size_t b, double *X, double *vol)
{
    place(s, b, X, vol);
}
