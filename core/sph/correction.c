#include "sph/correction.h"

#include <math.h>

#include "sph/kernel.h"
#include "util/mat3.h"
#include "util/parallel.h"

int tlsph_correction_invert(double L[9], int dim, double Linv[9], double *condition)
{
    return tlsph_correction_invert_rcond(L, dim, Linv, condition, TLSPH_L_RCOND);
}

int tlsph_correction_invert_rcond(double L[9], int dim, double Linv[9], double *condition,
                                  double rcond)
{
    /* L is symmetric for a radial kernel; in 2-D it has no z row, and plane
     * strain means no gradient along z, so the z direction is the identity. */
    if (dim == 2) {
        L[2] = L[5] = L[6] = L[7] = 0.0;
        L[8] = 1.0;
    }
    /* With grad W = dw (X_j - X_i) and dw < 0, L as summed is -sum V |dw| d d^T;
     * it is negative definite, and its inverse is what eq. 16 needs. */
    double lam[3], Q[9];
    sym3_eigen(L, lam, Q);
    double amax = 0.0;
    for (int a = 0; a < 3; a++)
        amax = fmax(amax, fabs(lam[a]));
    double inv[3];
    int bad = 0;
    double amin = amax;
    for (int a = 0; a < 3; a++) {
        amin = fmin(amin, fabs(lam[a]));
        if (amax > 0.0 && fabs(lam[a]) > rcond * amax) {
            inv[a] = 1.0 / lam[a];
        } else {
            inv[a] = 0.0;
            bad = 1;
        }
    }
    *condition = !bad && amin > 0.0 ? amax / amin : 1.0;
    double s6[6];
    sym3_compose(Q, inv, s6);
    sym6_to_mat3(s6, Linv);
    return bad;
}

/* L_i of row i from its pairs; the pair constants from the kernel into
 * pairs.dw (and w) when fill, else read from them (the same values). */
static inline void row_matrix(const struct tlsph_model *m, size_t i, int fill, double L[9])
{
    const struct tlsph_particles *p = &m->p;
    const struct tlsph_pairs *pr = &m->pairs;
    const int dim = m->dim;
    const enum tlsph_kernel_type kt = m->scene.kernel;
    for (int c = 0; c < 9; c++)
        L[c] = 0.0;
    const double *Xi = p->X + 3 * i;
    for (int64_t k = pr->start[i]; k < pr->start[i + 1]; k++) {
        const size_t j = (size_t)pr->j[k];
        const double d[3] = {p->X[3 * j] - Xi[0], p->X[3 * j + 1] - Xi[1],
                             p->X[3 * j + 2] - Xi[2]};
        if (fill) {
            const double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            double w, dwdr;
            tlsph_kernel(kt, dim, r, 0.5 * (p->h[i] + p->h[j]), &w, &dwdr);
            pr->dw[k] = dwdr / r;
            if (pr->w)
                pr->w[k] = w;
        }
        const double s = p->vol0[j] * pr->dw[k];
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                L[3 * a + b] += s * d[a] * d[b];
    }
}

int tlsph_correction_row(struct tlsph_model *m, size_t i, double *condition)
{
    double L[9];
    row_matrix(m, i, 1, L);
    return tlsph_correction_invert(L, m->dim, m->p.Linv + 9 * i, condition);
}

int tlsph_correction_row_rcond(struct tlsph_model *m, size_t i, double *condition, double rcond)
{
    double L[9];
    row_matrix(m, i, 1, L);
    return tlsph_correction_invert_rcond(L, m->dim, m->p.Linv + 9 * i, condition, rcond);
}

int tlsph_correction_row_status(const struct tlsph_model *m, size_t i, double *condition)
{
    double L[9], Linv[9];
    row_matrix(m, i, 0, L);
    return tlsph_correction_invert(L, m->dim, Linv, condition);
}

void tlsph_correction_build(struct tlsph_model *m)
{
    const size_t n = m->p.n;
    const int64_t *start = m->pairs.start;
    size_t deficient = 0, isolated = 0;
    double worst = 1.0;

#pragma omp parallel for schedule(static) reduction(+ : deficient, isolated) reduction(max : worst) \
    if (n >= TLSPH_PARALLEL_MIN_ITEMS)
    for (size_t i = 0; i < n; i++) {
        if (start[i + 1] == start[i])
            isolated++;
        double cond;
        if (tlsph_correction_row(m, i, &cond))
            deficient++;
        else
            worst = fmax(worst, cond);
    }
    m->deficient_supports = deficient;
    m->isolated = isolated;
    m->max_L_condition = worst;
}
