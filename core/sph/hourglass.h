/* Hourglass control for TLSPH, Ganzenmueller (CMAME 286, 2015): the pair's
 * deformation predicted by the particles' own F disagrees with the actual
 * separation when zero-energy (hourglass) modes appear; a spring along the
 * current pair direction removes that disagreement.
 *
 *   err_ij   = 1/2 (F_i + F_j) X_ij - x_ij          (X_ij = X_j - X_i, x_ij = x_j - x_i)
 *   delta_ij = 2 err_ij . x_ij / r_ij               (= delta^i_ij + delta^j_ji)
 *   f_i     += -alpha/2 E V_i V_j W(X_ij) / |X_ij|^2 * delta_ij * x_ij / r_ij
 *
 * The force is central and antisymmetric (momentum and angular momentum are
 * conserved) and vanishes for any affine motion, rigid rotations included. */
#ifndef TLSPH_HOURGLASS_H
#define TLSPH_HOURGLASS_H

/* Returns the scalar c such that f_i += c * (x_j - x_i). coeff = alpha/2 E V_i. */
static inline double hourglass_pair(double coeff, double Vj, double w, const double *Fi,
                                    const double *Fj, double d0, double d1, double d2,
                                    double x0, double x1, double x2)
{
    const double p0 = (Fi[0] + Fj[0]) * d0 + (Fi[1] + Fj[1]) * d1 + (Fi[2] + Fj[2]) * d2;
    const double p1 = (Fi[3] + Fj[3]) * d0 + (Fi[4] + Fj[4]) * d1 + (Fi[5] + Fj[5]) * d2;
    const double p2 = (Fi[6] + Fj[6]) * d0 + (Fi[7] + Fj[7]) * d1 + (Fi[8] + Fj[8]) * d2;
    const double r2 = x0 * x0 + x1 * x1 + x2 * x2;
    const double R2 = d0 * d0 + d1 * d1 + d2 * d2;
    /* (p - 2x).x / r, then divided again by r for the unit direction */
    const double delta_over_r = ((p0 - 2.0 * x0) * x0 + (p1 - 2.0 * x1) * x1 + (p2 - 2.0 * x2) * x2) / r2;
    return -coeff * Vj * w / R2 * delta_over_r;
}

#endif
