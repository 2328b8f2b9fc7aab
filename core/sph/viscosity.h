/* Monaghan artificial viscosity as written in paper 001 eq. 18:
 *
 *   pi_ij = (-beta1 c mu_ij + beta2 mu_ij^2) / rho0   if v_ij . x_ij < 0 (approaching), else 0
 *   mu_ij = h v_ij . x_ij / (|x_ij|^2 + 0.01 h^2),     v_ij = v_i - v_j, x_ij = x_i - x_j
 *
 * applied as a central pair force with the reference kernel slope (TLSPH keeps
 * kernels in the reference configuration) along the current pair direction:
 *
 *   f_i += -m_i m_j pi_ij W'(|X_ij|) x_ij / |x_ij|
 *
 * W' < 0, so approaching pairs repel; separating pairs feel nothing. */
#ifndef TLSPH_VISCOSITY_H
#define TLSPH_VISCOSITY_H

#include <math.h>

/* Returns c such that f_i += c * (x_j - x_i).  dwr = W'(R)/R (pairs.dw), R = |X_ij|. */
static inline double viscosity_pair(double mi_mj, double h, double c, double rho0, double beta1,
                                    double beta2, double dwr, double R, double x0, double x1,
                                    double x2, double v0, double v1, double v2)
{
    /* x, v here are x_j - x_i and v_j - v_i: their dot product equals v_ij . x_ij */
    const double vx = x0 * v0 + x1 * v1 + x2 * v2;
    if (vx >= 0.0)
        return 0.0;
    const double r2 = x0 * x0 + x1 * x1 + x2 * x2;
    const double mu = h * vx / (r2 + 0.01 * h * h);
    const double pi = (-beta1 * c * mu + beta2 * mu * mu) / rho0;
    /* f_i = -m_i m_j pi W'(R) (x_i - x_j)/r = m_i m_j pi W'(R) (x_j - x_i)/r */
    return mi_mj * pi * dwr * R / sqrt(r2);
}

#endif
