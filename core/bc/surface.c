/* Reference area vectors of a particle layer: see core/bc/surface.h. */
#include "bc/surface.h"

#include <math.h>
#include <stdlib.h>

#include "scene/json_check.h"
#include "util/mat3.h"

/* Outward colour gradient of particle i: away from its neighbours, 1/m. */
static void colour_gradient(const struct tlsph_model *m, size_t i, double c[3])
{
    const double *Xi = m->p.X + 3 * i;
    c[0] = c[1] = c[2] = 0.0;
    for (int64_t k = m->pairs.start[i]; k < m->pairs.start[i + 1]; k++) {
        const size_t j = (size_t)m->pairs.j[k];
        const double *Xj = m->p.X + 3 * j;
        /* dw = W'/r < 0: -dw (Xi - Xj) points from j to i */
        const double w = -m->pairs.dw[k] * m->p.vol0[j];
        for (int d = 0; d < 3; d++)
            c[d] += w * (Xi[d] - Xj[d]);
    }
}

/* Refines n, the normal of the plane fitted at particle i (tangents t1, t2;
 * t2 unused in 2-D), to the surface's normal at i: the least-squares quadric
 * through i,  w = c1 u + c2 v + c3 u^2 + c4 u v + c5 v^2  (2-D: c1 u + c3 u^2),
 * over the group's particles in i's support, (u, v, w) their offsets from i
 * along t1, t2, n in spacings; then n ~ n - c1 t1 - c2 t2.  A plane through a
 * one-sided patch of a curved surface (near the edge of the loaded region)
 * tilts with the sag it cannot follow; the quadric follows it.  On a flat
 * face w = 0 and n stays.  Leaves n when the system is singular. */
static void quadric_normal(const struct tlsph_model *m, size_t i, const unsigned char *mark,
                           const double t1[3], const double t2[3], double n[3])
{
    const int nb = m->dim == 2 ? 2 : 5;
    double M[5][6] = {{0}}; /* normal equations, the right-hand side in column 5 */
    const double *X = m->p.X;
    const double s = m->scene.bodies[m->p.body[i]].spacing;
    for (int64_t k = m->pairs.start[i]; k < m->pairs.start[i + 1]; k++) {
        const size_t j = (size_t)m->pairs.j[k];
        if (!mark[j])
            continue;
        double d[3];
        for (int c = 0; c < 3; c++)
            d[c] = (X[3 * j + c] - X[3 * i + c]) / s;
        const double u = d[0] * t1[0] + d[1] * t1[1] + d[2] * t1[2];
        const double v = nb == 5 ? d[0] * t2[0] + d[1] * t2[1] + d[2] * t2[2] : 0.0;
        const double w = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
        const double phi2[2] = {u, u * u}, phi5[5] = {u, v, u * u, u * v, v * v};
        const double *phi = nb == 5 ? phi5 : phi2;
        for (int a = 0; a < nb; a++) {
            for (int b = 0; b < nb; b++)
                M[a][b] += phi[a] * phi[b];
            M[a][5] += phi[a] * w;
        }
    }
    double big = 0.0;
    for (int a = 0; a < nb; a++)
        big = fmax(big, M[a][a]);
    for (int col = 0; col < nb; col++) { /* Gauss-Jordan, partial pivoting */
        int piv = col;
        for (int r = col + 1; r < nb; r++)
            if (fabs(M[r][col]) > fabs(M[piv][col]))
                piv = r;
        if (!(fabs(M[piv][col]) > 1e-9 * big))
            return;
        for (int c = 0; c < 6; c++) {
            const double tmp = M[col][c];
            M[col][c] = M[piv][c];
            M[piv][c] = tmp;
        }
        for (int r = 0; r < nb; r++) {
            if (r == col)
                continue;
            const double f = M[r][col] / M[col][col];
            for (int c = col; c < 6; c++)
                M[r][c] -= f * M[col][c];
        }
    }
    const double c1 = M[0][5] / M[0][0], c2 = nb == 5 ? M[1][5] / M[1][1] : 0.0;
    double len = 0.0;
    for (int c = 0; c < 3; c++) {
        n[c] -= c1 * t1[c] + c2 * (nb == 5 ? t2[c] : 0.0);
        len += n[c] * n[c];
    }
    len = sqrt(len);
    for (int c = 0; c < 3; c++)
        n[c] /= len;
}

/* Unit normal of the surface through the group's particles in i's support
 * (mark[j]: j is in the group), i included, into n: the normal of their
 * plane (2-D: line), refined by quadric_normal; 0, or -1 when undetermined. */
static int fitted_normal(const struct tlsph_model *m, size_t i, const unsigned char *mark,
                         double n[3])
{
    const int64_t k0 = m->pairs.start[i], k1 = m->pairs.start[i + 1];
    const double *X = m->p.X;
    double cen[3] = {X[3 * i], X[3 * i + 1], X[3 * i + 2]};
    size_t count = 1;
    for (int64_t k = k0; k < k1; k++)
        if (mark[m->pairs.j[k]]) {
            for (int d = 0; d < 3; d++)
                cen[d] += X[3 * (size_t)m->pairs.j[k] + d];
            count++;
        }
    for (int d = 0; d < 3; d++)
        cen[d] /= (double)count;
    /* the scatter about the centroid, i's own term first */
    double C[9];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            C[3 * a + b] = (X[3 * i + a] - cen[a]) * (X[3 * i + b] - cen[b]);
    for (int64_t k = k0; k < k1; k++) {
        const size_t j = (size_t)m->pairs.j[k];
        if (!mark[j])
            continue;
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                C[3 * a + b] += (X[3 * j + a] - cen[a]) * (X[3 * j + b] - cen[b]);
    }
    if (m->dim == 2) /* the normal lies in the x-y plane: z is never the smallest */
        C[8] = 2.0 * (C[0] + C[4]);
    double lam[3], Q[9];
    sym3_eigen(C, lam, Q);
    int lo = 0;
    for (int k = 1; k < 3; k++)
        if (lam[k] < lam[lo])
            lo = k;
    /* the next smallest, mi: the surface's spread along it (in 2-D the
     * in-plane tangent); hi the third */
    const int mi = lam[(lo + 1) % 3] <= lam[(lo + 2) % 3] ? (lo + 1) % 3 : (lo + 2) % 3;
    const int hi = 3 - lo - mi;
    /* a plane needs spread in d - 1 directions, well above the sag across it */
    if (!(lam[mi] > 0.0) || lam[lo] > 0.25 * lam[mi])
        return -1;
    double t1[3], t2[3];
    for (int d = 0; d < 3; d++) {
        n[d] = Q[3 * d + lo];
        t1[d] = Q[3 * d + mi];
        t2[d] = Q[3 * d + hi];
    }
    quadric_normal(m, i, mark, t1, t2, n);
    return 0;
}

int tlsph_surface_areas(const struct tlsph_model *m, const int32_t *index, size_t n,
                        const double *normal, double area, double *out, const char *name,
                        const char *pointer, struct tlsph_errors *err)
{
    unsigned char *mark = calloc(m->p.n, 1);
    if (!mark) {
        tlsph_errors_add(err, pointer, "out of memory");
        return -1;
    }
    for (size_t a = 0; a < n; a++)
        mark[index[a]] = 1;
    double outward = 0.0, sum = 0.0;
    int rc = 0;
    for (size_t a = 0; a < n; a++) {
        const size_t i = (size_t)index[a];
        double c[3], nn[3];
        colour_gradient(m, i, c);
        const double cn = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        const double s = m->scene.bodies[m->p.body[i]].spacing;
        /* interior particles: c is round-off of a sum of terms ~ 1/s */
        if (!(cn * s > 1e-6)) {
            tlsph_errors_add(err, pointer,
                             "boundary condition '%s' selects particle %lld at (%g, %g, %g) m, "
                             "which is not on the surface of its body (its neighbours surround "
                             "it): select only the loaded surface's outermost layer",
                             name, (long long)m->p.id[i], m->p.X[3 * i], m->p.X[3 * i + 1],
                             m->p.X[3 * i + 2]);
            rc = -1;
            break;
        }
        if (normal) {
            for (int d = 0; d < 3; d++)
                nn[d] = normal[d];
            outward += (nn[0] * c[0] + nn[1] * c[1] + nn[2] * c[2]) / cn;
        } else if (fitted_normal(m, i, mark, nn) == 0) {
            if (nn[0] * c[0] + nn[1] * c[1] + nn[2] * c[2] < 0.0)
                for (int d = 0; d < 3; d++)
                    nn[d] = -nn[d];
        } else {
            for (int d = 0; d < 3; d++)
                nn[d] = c[d] / cn;
        }
        const double dA = m->p.vol0[i] / s;
        for (int d = 0; d < 3; d++)
            out[3 * a + d] = dA * nn[d];
        sum += dA;
    }
    free(mark);
    if (rc != 0)
        return rc;
    if (normal && !(outward > 0.0)) {
        char q[TLSPH_POINTER_MAX];
        tlsph_pointer_join(q, sizeof q, pointer, "normal");
        tlsph_errors_add(err, q,
                         "boundary condition '%s': 'normal' (%g, %g, %g) points into the body "
                         "at the selected particles; give the loaded surface's outward normal "
                         "(a positive pressure pushes against it, into the body)",
                         name, normal[0], normal[1], normal[2]);
        return -1;
    }
    if (area > 0.0) {
        const double scale = area / sum;
        for (size_t k = 0; k < 3 * n; k++)
            out[k] *= scale;
    }
    return 0;
}
