/* 3x3 tensor algebra used in per-particle loops.  Matrices are row-major
 * double[9]; symmetric tensors are double[6] in the order xx xy xz yy yz zz.
 * Everything is static inline so the per-particle loops stay free of calls. */
#ifndef TLSPH_MAT3_H
#define TLSPH_MAT3_H

#include <math.h>
#include <string.h>

static inline double mat3_det(const double *A)
{
    return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
           A[2] * (A[3] * A[7] - A[4] * A[6]);
}

/* adj(A) = det(A) A^-1 (the transposed cofactor matrix), defined for any A. */
static inline void mat3_adjugate(const double *A, double *adj)
{
    adj[0] = A[4] * A[8] - A[5] * A[7];
    adj[1] = A[2] * A[7] - A[1] * A[8];
    adj[2] = A[1] * A[5] - A[2] * A[4];
    adj[3] = A[5] * A[6] - A[3] * A[8];
    adj[4] = A[0] * A[8] - A[2] * A[6];
    adj[5] = A[2] * A[3] - A[0] * A[5];
    adj[6] = A[3] * A[7] - A[4] * A[6];
    adj[7] = A[1] * A[6] - A[0] * A[7];
    adj[8] = A[0] * A[4] - A[1] * A[3];
}

/* Adjugate-based inverse; returns the determinant (inverse not written when 0). */
static inline double mat3_inverse(const double *A, double *Ai)
{
    double adj[9];
    mat3_adjugate(A, adj);
    const double det = A[0] * adj[0] + A[1] * adj[3] + A[2] * adj[6];
    if (det == 0.0)
        return 0.0;
    const double r = 1.0 / det;
    for (int k = 0; k < 9; k++)
        Ai[k] = adj[k] * r;
    return det;
}

/* C = A B */
static inline void mat3_mul(const double *A, const double *B, double *C)
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            C[3 * r + c] = A[3 * r] * B[c] + A[3 * r + 1] * B[3 + c] + A[3 * r + 2] * B[6 + c];
}

/* C = A B^T */
static inline void mat3_mul_bt(const double *A, const double *B, double *C)
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            C[3 * r + c] =
                A[3 * r] * B[3 * c] + A[3 * r + 1] * B[3 * c + 1] + A[3 * r + 2] * B[3 * c + 2];
}

/* C = A^T B */
static inline void mat3_mul_at(const double *A, const double *B, double *C)
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            C[3 * r + c] = A[r] * B[c] + A[3 + r] * B[3 + c] + A[6 + r] * B[6 + c];
}

/* B = Q^T A Q: A expressed in the orthonormal basis of Q's columns. */
static inline void mat3_to_basis(const double *Q, const double *A, double *B)
{
    double T[9];
    mat3_mul_at(Q, A, T);
    mat3_mul(T, Q, B);
}

/* A = Q B Q^T: back from the basis of Q's columns. */
static inline void mat3_from_basis(const double *Q, const double *B, double *A)
{
    double T[9];
    mat3_mul(Q, B, T);
    mat3_mul_bt(T, Q, A);
}

static inline void sym6_to_mat3(const double *s, double *A)
{
    A[0] = s[0]; A[1] = s[1]; A[2] = s[2];
    A[3] = s[1]; A[4] = s[3]; A[5] = s[4];
    A[6] = s[2]; A[7] = s[4]; A[8] = s[5];
}

static inline void mat3_to_sym6(const double *A, double *s)
{
    s[0] = A[0];
    s[1] = 0.5 * (A[1] + A[3]);
    s[2] = 0.5 * (A[2] + A[6]);
    s[3] = A[4];
    s[4] = 0.5 * (A[5] + A[7]);
    s[5] = A[8];
}

/* The most matrices sym3_eigen_batch decomposes at once. */
#define SYM3_EIGEN_LANES 4

/* sym3_eigen (below) of n <= SYM3_EIGEN_LANES matrices at once: A holds n row-major
 * matrices [9n], lam [3n] and Q [9n] receive theirs.  Each matrix gets exactly
 * the rotations, operations and sweeps it gets alone (a converged one is left
 * alone while the others go on), so the results are the same bit for bit.
 * Why: a rotation is a chain of two divisions and two square roots, each
 * waiting for the last, and the processor's dividers idle for most of it; the
 * chains of independent matrices interleaved overlap (measured: 1.5-2x fewer
 * nanoseconds per matrix with 4 at once, docs/performance.md). */
static inline void sym3_eigen_batch(int n, const double *A, double *lam, double *Q)
{
    double a[SYM3_EIGEN_LANES][3][3], v[SYM3_EIGEN_LANES][3][3];
    int active[SYM3_EIGEN_LANES];
    for (int l = 0; l < n; l++) {
        const double *M = A + 9 * l;
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) {
                /* the upper triangle, mirrored */
                a[l][r][c] = r <= c ? M[3 * r + c] : M[3 * c + r];
                v[l][r][c] = r == c;
            }
        active[l] = 1;
    }
    for (int sweep = 0; sweep < 32; sweep++) {
        int any = 0;
        for (int l = 0; l < n; l++) {
            if (!active[l])
                continue;
            double(*m)[3] = a[l];
            const double off = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
            const double diag = m[0][0] * m[0][0] + m[1][1] * m[1][1] + m[2][2] * m[2][2];
            if (off <= 1e-32 * diag || off == 0.0)
                active[l] = 0;
            else
                any = 1;
        }
        if (!any)
            break;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++)
                for (int l = 0; l < n; l++) {
                    double(*m)[3] = a[l], (*w)[3] = v[l];
                    const double apq = m[p][q];
                    if (!active[l] || apq == 0.0)
                        continue;
                    const double theta = (m[q][q] - m[p][p]) / (2.0 * apq);
                    const double t =
                        (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                    const double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
                    for (int k = 0; k < 3; k++) {
                        const double akp = m[k][p], akq = m[k][q];
                        m[k][p] = c * akp - s * akq;
                        m[k][q] = s * akp + c * akq;
                    }
                    for (int k = 0; k < 3; k++) {
                        const double apk = m[p][k], aqk = m[q][k];
                        m[p][k] = c * apk - s * aqk;
                        m[q][k] = s * apk + c * aqk;
                    }
                    for (int k = 0; k < 3; k++) {
                        const double vkp = w[k][p], vkq = w[k][q];
                        w[k][p] = c * vkp - s * vkq;
                        w[k][q] = s * vkp + c * vkq;
                    }
                }
    }
    for (int l = 0; l < n; l++) {
        for (int k = 0; k < 3; k++)
            lam[3 * l + k] = a[l][k][k];
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                Q[9 * l + 3 * r + c] = v[l][r][c];
    }
}

/* Eigen-decomposition of a symmetric matrix by cyclic Jacobi rotations.
 * A (row-major, symmetric) -> eigenvalues lam[3], eigenvectors as the columns
 * of Q (row-major), A = Q diag(lam) Q^T.  Jacobi is used rather than the
 * closed-form cubic because it is exact for (near-)repeated eigenvalues,
 * which is the common case here (an undeformed particle has C = I). */
static inline void sym3_eigen(const double *A, double lam[3], double *Q)
{
    sym3_eigen_batch(1, A, lam, Q);
}

/* S = Q diag(d) Q^T as sym6. */
static inline void sym3_compose(const double *Q, const double d[3], double *s)
{
    double M[9];
    for (int r = 0; r < 3; r++)
        for (int c = r; c < 3; c++)
            M[3 * r + c] = Q[3 * r] * d[0] * Q[3 * c] + Q[3 * r + 1] * d[1] * Q[3 * c + 1] +
                           Q[3 * r + 2] * d[2] * Q[3 * c + 2];
    s[0] = M[0]; s[1] = M[1]; s[2] = M[2]; s[3] = M[4]; s[4] = M[5]; s[5] = M[8];
}

#endif
