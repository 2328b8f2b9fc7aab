/* Surface-conforming particle placement ("placement": "conforming") for a
 * sphere (a disc in 2-D): particles on concentric shells that follow the
 * surface, so that a curved body touches a flat one at a point that grows like
 * the Hertz contact, not with the flat patch a lattice cuts out of it.
 *
 * The radius R is cut into N = round(R / h) shells of thickness
 * t = R / N; shell k (k = 0 at the centre) spans [k t, (k + 1) t] and its
 * particles sit at its middle radius r = (k + 1/2) t, so the outer shell is at
 * R - t/2 (half a spacing inside the surface, as on the lattice).
 *  - 2-D: one ring per shell of n = 4 round(2 pi r / (4 h)) particles at the
 *    angles (i + 1/2) 2 pi / n.
 *  - 3-D: M = max(1, round(pi r / h)) rings per shell at the polar angles
 *    theta_j = (j + 1/2) pi / M about the z axis, ring j with
 *    n_j = 4 max(1, round(2 pi r sin(theta_j) / (4 h))) particles at the
 *    azimuths (i + 1/2) 2 pi / n_j: arc spacing about h both ways.
 * Every particle of a shell gets the shell's volume (area in 2-D) divided by
 * its count, so the volumes sum to the sphere's 4/3 pi R^3 (pi R^2) up to
 * round-off.  Counts are multiples of 4 and no angle lies on an axis, so the
 * point set is mirror-symmetric about the planes x = c_x and y = c_y through
 * the centre c (and z = c_z) with no particle on them: a quarter sphere cut by
 * those planes (a difference whose first object is the sphere) keeps exactly a
 * quarter of each shell, and its volumes sum to a quarter of the sphere's.
 *
 * Points come shell by shell from the centre outwards, rings by increasing
 * theta, azimuths increasing: deterministic, no random numbers. */
#include <math.h>
#include <stdlib.h>

#include "scene/parse_internal.h"

static long ring_count(double circumference, double h)
{
    const long q = lround(circumference / (4.0 * h));
    return 4 * (q > 0 ? q : 1);
}

/* The sphere whose shells a conforming body uses: the geometry itself, or the
 * first object of a difference.  NULL when the geometry has none. */
const struct tlsph_geometry *tlsph_conforming_sphere(const struct tlsph_geometry *g)
{
    if (g->type == TLSPH_GEOM_SPHERE)
        return g;
    if (g->type == TLSPH_GEOM_DIFFERENCE && g->nchildren > 0 &&
        g->children[0].type == TLSPH_GEOM_SPHERE)
        return &g->children[0];
    return NULL;
}

/* Visits every shell point of body b inside its geometry with its volume;
 * returns the number of points.  X and vol (when non-NULL) receive them. */
static size_t place(const struct tlsph_scene *s, size_t b, double *X, double *vol)
{
    const struct tlsph_body *body = &s->bodies[b];
    const struct tlsph_geometry *sp = tlsph_conforming_sphere(&body->geometry);
    if (!sp)
        return 0;
    const double *c = sp->a, R = sp->a[3], h = body->spacing;
    const long N = lround(R / h); /* 0 below half a spacing: no particle, refused as empty */
    const double t = R / (double)N;
    const double pi = acos(-1.0);
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
                if (!tlsph_geometry_contains(&body->geometry, P))
                    continue;
                if (X)
                    for (int d = 0; d < 3; d++)
                        X[3 * n + d] = P[d];
                if (vol)
                    vol[n] = each;
                n++;
            }
        }
    }
    return n;
}

size_t tlsph_conforming_count(const struct tlsph_scene *s, size_t b)
{
    return place(s, b, NULL, NULL);
}

void tlsph_conforming_fill(const struct tlsph_scene *s, size_t b, double *X, double *vol)
{
    place(s, b, X, vol);
}
