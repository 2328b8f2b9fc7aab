/* Small frame algebra for rigid bodies: rotations as 3x3 row-major matrices.
 * Shared by the shapes' parsers (core/rigid/<shape>.c) and the motion
 * (core/rigid/motion.c). */
#ifndef TLSPH_RIGID_FRAME_H
#define TLSPH_RIGID_FRAME_H

#include <math.h>

/* The rotation by the rotation vector w (axis x angle, rad): Rodrigues'
 * formula R = I + sin(t) K + (1 - cos(t)) K^2, K the cross-product matrix of
 * the unit axis, t = |w|.  Exact for any angle (the identity for w = 0). */
static inline void rigid_rotation(const double w[3], double R[9])
{
    const double t = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int k = 0; k < 9; k++)
        R[k] = k % 4 == 0 ? 1.0 : 0.0;
    if (!(t > 0.0))
        return;
    const double k0 = w[0] / t, k1 = w[1] / t, k2 = w[2] / t;
    const double s = sin(t), c = 1.0 - cos(t);
    const double K[9] = {0.0, -k2, k1, k2, 0.0, -k0, -k1, k0, 0.0};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double kk = 0.0;
            for (int l = 0; l < 3; l++)
                kk += K[3 * i + l] * K[3 * l + j];
            R[3 * i + j] += s * K[3 * i + j] + c * kk;
        }
}

/* Axes (columns of A) of a frame whose z is the unit vector a: x = the unit
 * part of a x e_k (e_k the coordinate axis least aligned with a, first on
 * ties), y = a x x.  In 2-D (a in the x-y plane) that is x = e_z. */
static inline void rigid_axes_from_z(const double a[3], double A[9])
{
    int k = 0;
    for (int c = 1; c < 3; c++)
        if (fabs(a[c]) < fabs(a[k]))
            k = c;
    double e[3] = {0.0, 0.0, 0.0};
    e[k] = 1.0;
    double x[3] = {a[1] * e[2] - a[2] * e[1], a[2] * e[0] - a[0] * e[2], a[0] * e[1] - a[1] * e[0]};
    const double l = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (int c = 0; c < 3; c++)
        x[c] /= l;
    const double y[3] = {a[1] * x[2] - a[2] * x[1], a[2] * x[0] - a[0] * x[2],
                         a[0] * x[1] - a[1] * x[0]};
    for (int r = 0; r < 3; r++) {
        A[3 * r] = x[r];
        A[3 * r + 1] = y[r];
        A[3 * r + 2] = a[r];
    }
}

/* A shape along the unit axis a (cylinder, cone): its reference point at
 * origin + offset a (z = 0 in 2-D, dim), its frame's z along a. */
static inline void rigid_place_on_axis(const double origin[3], const double a[3], double offset,
                                       int dim, double centre[3], double axes[9])
{
    for (int k = 0; k < 3; k++)
        centre[k] = origin[k] + offset * a[k];
    if (dim == 2)
        centre[2] = 0.0;
    rigid_axes_from_z(a, axes);
}

#endif
