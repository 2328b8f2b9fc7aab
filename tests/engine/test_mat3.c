/* 3x3 algebra: Jacobi eigen-decomposition reconstructs A = Q diag(lam) Q^T with
 * orthonormal Q (1e-13), including repeated eigenvalues; the batched one gives
 * every matrix exactly (bit for bit) what it gets alone, whatever its
 * neighbours in the batch; inverse gives A A^-1 = I. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/mat3.h"
#include "support/check_main.h"

static void check_eigen(const double *A)
{
    double lam[3], Q[9], s[6], R[9], QtQ[9];
    sym3_eigen(A, lam, Q);
    sym3_compose(Q, lam, s);
    sym6_to_mat3(s, R);
    double scale = 0;
    for (int k = 0; k < 9; k++)
        scale = fmax(scale, fabs(A[k]));
    for (int k = 0; k < 9; k++)
        ck_assert_msg(fabs(R[k] - A[k]) <= 1e-13 * scale, "entry %d: %.17g vs %.17g", k, R[k], A[k]);
    mat3_mul_at(Q, Q, QtQ);
    for (int k = 0; k < 9; k++)
        ck_assert(fabs(QtQ[k] - (k % 4 == 0)) < 1e-13);
}

START_TEST(eigen)
{
    const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double D[9] = {2, 0, 0, 0, 2, 0, 0, 0, 5};
    const double A[9] = {4, 1, -2, 1, 2, 0.5, -2, 0.5, 3};
    const double B[9] = {1, 1e-9, 0, 1e-9, 1, 1e-9, 0, 1e-9, 1};
    check_eigen(I);
    check_eigen(D);
    check_eigen(A);
    check_eigen(B);
    srand(7);
    for (int t = 0; t < 200; t++) {
        double M[9];
        for (int r = 0; r < 3; r++)
            for (int c = r; c < 3; c++)
                M[3 * r + c] = M[3 * c + r] = rand() / (double)RAND_MAX - 0.5;
        check_eigen(M);
    }
}
END_TEST

/* Lanes that converge after different numbers of sweeps (C = I needs none, a
 * diagonal one none, a general one several, one with a zero off-diagonal skips
 * rotations) must not disturb each other: compare with one matrix at a time. */
START_TEST(eigen_batch)
{
    enum { N = 11 };
    /* clang-format off: one matrix a group */
    double M[9 * N] = {1, 0, 0, 0, 1, 0, 0, 0, 1,  4, 1, -2, 1, 2, 0.5, -2, 0.5, 3,
                       2, 0, 0, 0, 2, 0, 0, 0, 5,  1, 1e-9, 0, 1e-9, 1, 1e-9, 0, 1e-9, 1,
                       3, 0, 1, 0, 2, 0, 1, 0, 1};
    /* clang-format on */
    srand(11);
    for (int t = 5; t < N; t++)
        for (int r = 0; r < 3; r++)
            for (int c = r; c < 3; c++)
                M[9 * t + 3 * r + c] = M[9 * t + 3 * c + r] =
                    (r == c) + 0.1 * (rand() / (double)RAND_MAX - 0.5);
    double lam1[3 * N], Q1[9 * N];
    for (int t = 0; t < N; t++)
        sym3_eigen(M + 9 * t, lam1 + 3 * t, Q1 + 9 * t);
    for (int n = 1; n <= SYM3_EIGEN_LANES; n++)
        for (int first = 0; first + n <= N; first++) {
            double lam[3 * SYM3_EIGEN_LANES], Q[9 * SYM3_EIGEN_LANES];
            sym3_eigen_batch(n, M + 9 * first, lam, Q);
            ck_assert_msg(memcmp(lam, lam1 + 3 * first, 3 * n * sizeof *lam) == 0 &&
                              memcmp(Q, Q1 + 9 * first, 9 * n * sizeof *Q) == 0,
                          "batch of %d from %d differs", n, first);
        }
}
END_TEST

START_TEST(inverse)
{
    const double A[9] = {2, 1, 0.3, -1, 3, 0.2, 0.5, 0.1, 1.5};
    double Ai[9], P[9];
    ck_assert(fabs(mat3_inverse(A, Ai) - mat3_det(A)) < 1e-14);
    mat3_mul(A, Ai, P);
    for (int k = 0; k < 9; k++)
        ck_assert(fabs(P[k] - (k % 4 == 0)) < 1e-14);
}
END_TEST

TLSPH_CHECK_MAIN("mat3", 0, eigen, eigen_batch, inverse)
