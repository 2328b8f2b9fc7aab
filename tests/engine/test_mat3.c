/* 3x3 algebra: Jacobi eigen-decomposition reconstructs A = Q diag(lam) Q^T with
 * orthonormal Q (1e-13), including repeated eigenvalues; inverse gives A A^-1 = I. */
#include <check.h>
#include <math.h>
#include <stdlib.h>

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

TLSPH_CHECK_MAIN("mat3", 0, eigen, inverse)
