/* The deformation gradient carried through a split (split_carry.h). */
#include "crack/split_carry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/mat3.h"

int tlsph_split_carry_row(struct tlsph_model *m, size_t i)
{
    struct tlsph_particles *p = &m->p;
    if (!p->F_carry)
        return 0;
    /* S = sum_j V_j (u_j - u_i) (x) grad W_i(X_ij), as the gather sums it */
    double S[9] = {0};
    const double *Xi = p->X + 3 * i, *xi = p->x + 3 * i;
    for (int64_t k = m->pairs.start[i]; k < m->pairs.start[i + 1]; k++) {
        const size_t j = (size_t)m->pairs.j[k];
        const double s = p->vol0[j] * m->pairs.dw[k];
        double d[3], du[3];
        for (int a = 0; a < 3; a++) {
            d[a] = p->X[3 * j + a] - Xi[a];
            du[a] = (p->x[3 * j + a] - p->X[3 * j + a]) - (xi[a] - Xi[a]);
        }
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                S[3 * r + c] += du[r] * (s * d[c]);
    }
    /* the damage-aware treatment subtracts what damaged neighbours did not
     * transmit (sph/damage_aware.h; a gather with dt = 0 adds nothing to it) */
    if (p->crack_gradient)
        for (int a = 0; a < 9; a++)
            S[a] -= p->crack_gradient[9 * i + a];
    double *L = p->Linv + 9 * i, *G = p->F_carry + 9 * i;
    double SL[9], Fraw[9], Frawi[9], Gnew[9], Lc[9];
    mat3_mul(S, L, SL);
    for (int a = 0; a < 9; a++)
        Fraw[a] = (a % 4 == 0) + SL[a];
    const double det = mat3_det(Fraw);
    int carried = 0;
    /* a failed point carries no stress and its F is no longer updated */
    const int failed = p->damage && p->damage[i] >= 1.0;
    if (!failed && det != 0.0 && isfinite(det)) {
        mat3_inverse(Fraw, Frawi);
        mat3_mul(Frawi, p->F + 9 * i, Gnew);
        carried = 1;
        for (int a = 0; a < 9; a++)
            carried &= isfinite(Gnew[a]);
    }
    if (carried)
        memcpy(G, Gnew, sizeof Gnew);
    mat3_mul(L, G, Lc);
    memcpy(L, Lc, sizeof Lc);
    return carried;
}

int tlsph_split_carry_enable(struct tlsph_model *m)
{
    struct tlsph_particles *p = &m->p;
    if (p->F_carry)
        return 0;
    const size_t cap = p->cap > p->n ? p->cap : p->n;
    double *G = calloc(9 * (cap ? cap : 1), sizeof *G);
    if (!G)
        return -1;
    for (size_t i = 0; i < cap; i++)
        G[9 * i] = G[9 * i + 4] = G[9 * i + 8] = 1.0;
    p->F_carry = G;
    m->bytes_allocated += 9 * cap * sizeof *G;
    return 0;
}

void tlsph_split_hencky(const double F[9], double H[6])
{
    double C[9];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            C[3 * r + c] = F[r] * F[c] + F[3 + r] * F[3 + c] + F[6 + r] * F[6 + c];
    double lam[3], Q[9], d[3];
    sym3_eigen(C, lam, Q);
    for (int a = 0; a < 3; a++)
        d[a] = 0.5 * log(lam[a]);
    sym3_compose(Q, d, H);
}
