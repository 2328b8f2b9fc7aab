#include "sph/kernel.h"

#include <math.h>

static double norm_cubic(int dim)
{
    return dim == 2 ? 10.0 / (7.0 * M_PI) : 1.0 / M_PI;
}

static double norm_wendland(int dim)
{
    return dim == 2 ? 7.0 / (4.0 * M_PI) : 21.0 / (16.0 * M_PI);
}

void tlsph_kernel(enum tlsph_kernel_type type, int dim, double r, double h, double *w,
                  double *dwdr)
{
    const double q = r / h;
    const double hd = dim == 2 ? h * h : h * h * h;
    *w = 0.0;
    *dwdr = 0.0;
    if (q >= 2.0)
        return;
    if (type == TLSPH_KERNEL_CUBIC_SPLINE) {
        const double s = norm_cubic(dim) / hd;
        if (q < 1.0) {
            *w = s * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
            *dwdr = s * (-3.0 * q + 2.25 * q * q) / h;
        } else {
            const double t = 2.0 - q;
            *w = s * 0.25 * t * t * t;
            *dwdr = -s * 0.75 * t * t / h;
        }
    } else {
        const double s = norm_wendland(dim) / hd;
        const double t = 1.0 - 0.5 * q;
        const double t3 = t * t * t;
        *w = s * t3 * t * (2.0 * q + 1.0);
        /* d/dq [(1-q/2)^4 (2q+1)] = -5 q (1-q/2)^3 */
        *dwdr = -s * 5.0 * q * t3 / h;
    }
}

const char *tlsph_kernel_name(enum tlsph_kernel_type type)
{
    return type == TLSPH_KERNEL_CUBIC_SPLINE ? "cubic_spline" : "wendland_c2";
}
