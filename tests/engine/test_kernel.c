/* Kernels: normalisation (integral of W over the plane/space = 1, eq. 7),
 * compact support, and dW/dr against a central finite difference.
 * Reference: the analytic normalisation constants in core/sph/kernel.h.
 * Tolerance: 1e-6 for the integral (midpoint quadrature with 2000 radial
 * cells converges as O(dr^2) ~ 1e-7 here), 1e-6 relative for the derivative. */
#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "sph/kernel.h"
#include "support/check_main.h"

static double integral(enum tlsph_kernel_type t, int dim, double h)
{
    const int nr = 2000;
    const double dr = 2.0 * h / nr;
    double sum = 0.0;
    for (int k = 0; k < nr; k++) {
        const double r = (k + 0.5) * dr;
        double w, dw;
        tlsph_kernel(t, dim, r, h, &w, &dw);
        sum += w * (dim == 2 ? 2.0 * M_PI * r : 4.0 * M_PI * r * r) * dr;
    }
    return sum;
}

START_TEST(normalisation)
{
    const enum tlsph_kernel_type types[2] = {TLSPH_KERNEL_CUBIC_SPLINE, TLSPH_KERNEL_WENDLAND_C2};
    for (int t = 0; t < 2; t++)
        for (int dim = 2; dim <= 3; dim++) {
            const double I = integral(types[t], dim, 1.7e-3);
            ck_assert_msg(fabs(I - 1.0) < 1e-6, "kernel %d dim %d integrates to %.9f", t, dim, I);
        }
}
END_TEST

START_TEST(support_and_gradient)
{
    const enum tlsph_kernel_type types[2] = {TLSPH_KERNEL_CUBIC_SPLINE, TLSPH_KERNEL_WENDLAND_C2};
    const double h = 0.01;
    for (int t = 0; t < 2; t++)
        for (int dim = 2; dim <= 3; dim++) {
            double w, dw;
            tlsph_kernel(types[t], dim, 2.0 * h, h, &w, &dw);
            ck_assert(w == 0.0 && dw == 0.0);
            tlsph_kernel(types[t], dim, 2.5 * h, h, &w, &dw);
            ck_assert(w == 0.0 && dw == 0.0);
            for (double q = 0.05; q < 1.99; q += 0.1) {
                const double r = q * h, eps = 1e-6 * h;
                double wp, wm, d, dummy;
                tlsph_kernel(types[t], dim, r + eps, h, &wp, &dummy);
                tlsph_kernel(types[t], dim, r - eps, h, &wm, &dummy);
                tlsph_kernel(types[t], dim, r, h, &w, &d);
                const double fd = (wp - wm) / (2 * eps);
                ck_assert_msg(fabs(fd - d) <= 1e-6 * fabs(d) + 1e-9 * fabs(w) / h,
                              "kernel %d dim %d q %.2f: dW/dr %.12g vs finite difference %.12g", t,
                              dim, q, d, fd);
                ck_assert(d <= 0.0 && w > 0.0);
            }
        }
}
END_TEST

TLSPH_CHECK_MAIN("kernel", 0, normalisation, support_and_gradient)
