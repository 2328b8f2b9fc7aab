/* Paper 003's 3-D visibility condition; the cases and the choices are in
 * visibility.h. */
#include "crack/visibility.h"

#include <math.h>

static void sub(const double *a, const double *b, double *r)
{
    r[0] = a[0] - b[0];
    r[1] = a[1] - b[1];
    r[2] = a[2] - b[2];
}

static void cross(const double *a, const double *b, double *r)
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double norm(const double *a)
{
    return sqrt(dot(a, a));
}

/* -1, 0 or +1: x against a tolerance already scaled to x's size */
static int sign_tol(double x, double tol)
{
    return x > tol ? 1 : (x < -tol ? -1 : 0);
}

/* Twice the signed area of the 2-D triangle p q r. */
static double orient2(const double *p, const double *q, const double *r)
{
    return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
}

/* Do the closed 2-D segments pq and rs meet (crossing, touching, or
 * overlapping when collinear)?  len2 is the squared length scale of the
 * picture: orientations below EPS len2 count as collinear. */
static bool segments_meet(const double *p, const double *q, const double *r, const double *s, double len2)
{
    const double tol = TLSPH_SIGHT_EPS * len2;
    const int o1 = sign_tol(orient2(p, q, r), tol), o2 = sign_tol(orient2(p, q, s), tol);
    const int o3 = sign_tol(orient2(r, s, p), tol), o4 = sign_tol(orient2(r, s, q), tol);
    if (o1 * o2 > 0 || o3 * o4 > 0)
        return false;
    if (o1 != 0 || o2 != 0 || o3 != 0 || o4 != 0)
        return true;
    /* all four collinear: they meet when their extents overlap on both axes */
    const double slack = TLSPH_SIGHT_EPS * sqrt(len2);
    for (int a = 0; a < 2; a++) {
        const double lo1 = fmin(p[a], q[a]), hi1 = fmax(p[a], q[a]);
        const double lo2 = fmin(r[a], s[a]), hi2 = fmax(r[a], s[a]);
        if (hi1 < lo2 - slack || hi2 < lo1 - slack)
            return false;
    }
    return true;
}

/* Case 2: A, B and the facet share a plane of normal N. */
static enum tlsph_sight coplanar(const double A[3], const double B[3], const double T[3][3], const double N[3],
                                 double len2)
{
    int drop = 0; /* the axis of N's largest component: the best-conditioned projection */
    for (int k = 1; k < 3; k++)
        if (fabs(N[k]) > fabs(N[drop]))
            drop = k;
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    const double a[2] = {A[u], A[v]}, b[2] = {B[u], B[v]};
    double t[3][2];
    for (int k = 0; k < 3; k++) {
        t[k][0] = T[k][u];
        t[k][1] = T[k][v];
    }
    for (int k = 0; k < 3; k++)
        if (segments_meet(a, b, t[k], t[(k + 1) % 3], len2))
            return TLSPH_SIGHT_COPLANAR_BLOCKED;
    return TLSPH_SIGHT_COPLANAR_CLEAR;
}

enum tlsph_sight tlsph_sight_through_facet(const double A[3], const double B[3], const double T[3][3])
{
    double e1[3], e2[3], e3[3], N[3], delta[3], TA[3];
    sub(T[1], T[0], e1);
    sub(T[2], T[0], e2);
    sub(T[2], T[1], e3);
    cross(e1, e2, N); /* eq. 33 */
    sub(B, A, delta); /* eq. 36 */
    sub(A, T[0], TA);
    double L = fmax(fmax(norm(e1), norm(e2)), norm(e3)); /* the facet's size */
    const double nN = norm(N);
    if (nN <= TLSPH_SIGHT_EPS * L * L || !(nN > 0))
        return TLSPH_SIGHT_NO_FACET;
    L = fmax(L, fmax(norm(delta), norm(TA)));

    const double n_delta = dot(N, delta);
    if (fabs(n_delta) <= TLSPH_SIGHT_EPS * nN * norm(delta)) {
        if (fabs(dot(N, TA)) > TLSPH_SIGHT_EPS * nN * L)
            return TLSPH_SIGHT_PARALLEL; /* eq. 34 */
        return coplanar(A, B, T, N, L * L); /* eq. 35 */
    }

    const double lambda = -dot(N, TA) / n_delta; /* eqs. 37-38 */
    if (lambda < -TLSPH_SIGHT_EPS || lambda > 1 + TLSPH_SIGHT_EPS)
        return TLSPH_SIGHT_SHORT;

    double P[3], PT[3][3], Nk[3];
    for (int c = 0; c < 3; c++)
        P[c] = A[c] + lambda * delta[c];
    for (int k = 0; k < 3; k++)
        sub(T[k], P, PT[k]);
    /* eqs. 39-42: N.N_k / |N|^2 is P's barycentric coordinate opposite vertex k + 2 */
    const double nN2 = nN * nN;
    bool on_side = false;
    for (int k = 0; k < 3; k++) {
        cross(PT[k], PT[(k + 1) % 3], Nk);
        const double b = dot(N, Nk) / nN2;
        if (b < -TLSPH_SIGHT_EPS)
            return TLSPH_SIGHT_OUTSIDE;
        if (b <= TLSPH_SIGHT_EPS)
            on_side = true;
    }
    return on_side ? TLSPH_SIGHT_ON_SIDE : TLSPH_SIGHT_INSIDE;
}
