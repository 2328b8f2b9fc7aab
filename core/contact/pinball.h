/* The pin-ball contact law of paper 001 §4 (eqs. 31-35), after Campbell,
 * Vignjevic & Libersky (2000) and Belytschko & Yeh's pin-ball (1993).
 *
 * Every particle is a ball of radius R = k h (h its smoothing length, k the
 * scene's radius_factor).  Two balls of different bodies overlap by
 *   p_d = R_i + R_j - |x_i - x_j|                                    (eq. 31)
 * and, while p_d > 0, push each other apart along the line of centres with
 *   F = K_p min(F1, F2)                                              (eq. 32)
 *   F1 = rho_i rho_j R_i^3 R_j^3 / (rho_i R_i^3 + rho_j R_j^3) pdot / dt
 *        when approaching, 0 when separating                         (eq. 33)
 *   F2 = mu_i mu_j / (mu_i + mu_j) sqrt(R_i R_j / (R_i + R_j)) p_d^(3/2)   (eq. 34)
 * added to both particles' momentum equations (eq. 35).  F1 is the force that
 * stops the pair's relative motion within the step (up to the ball-volume
 * factor 4 pi / 3, which the paper leaves out), F2 a Hertz-type elastic
 * estimate; K_p is the paper's scale factor.
 *
 * Where the text leaves a choice, this implementation takes:
 *  - pdot = |v_i - v_j| (the paper's definition), and "approaching" means
 *    (v_j - v_i).(x_j - x_i) < 0; while separating F1 = 0, so F = 0: the law
 *    only resists approach (a pair at rest in overlap feels no force);
 *  - mu = the material's shear modulus G = E / (2 (1 + nu)) (the paper does
 *    not define mu; Lame's second constant is the usual meaning);
 *  - dt = the step that led to the current positions; at setup (dt = 0) F1
 *    has no bound and F = K_p F2;
 *  - in 2-D the same formulas give the force per metre of thickness (the
 *    paper's plane models use them unchanged with unit thickness).
 * Stable time step: the tangent stiffness of the elastic part,
 * k = K_p 3/2 mu* sqrt(R*) p_d^(1/2); F1 is a damper of coefficient
 * K_p rho* R*^3 / dt, explicit-stable while K_p rho* R*^3 / m* < 2 (docs). */
#ifndef TLSPH_CONTACT_PINBALL_H
#define TLSPH_CONTACT_PINBALL_H

#include <math.h>

#include "contact/contact.h"
#include "contact/penalty.h" /* struct tlsph_contact_pair */

enum { TLSPH_PINBALL_RADIUS_FACTOR, TLSPH_PINBALL_SCALE_FACTOR }; /* params[] */

/* Body constants: radius = k h, a = rho R^3, b = mu.  pdot = |v_j - v_i|;
 * inv_dt = 1/dt (infinite at setup).  Commutative in i, j. */
static inline __attribute__((always_inline)) struct tlsph_contact_pair
tlsph_pinball_pair(const struct tlsph_contact_body *bi, const struct tlsph_contact_body *bj,
                   double pd, int approaching, double pdot, double inv_dt, double kp)
{
    const double rstar = bi->radius * bj->radius / (bi->radius + bj->radius);
    const double mustar = bi->b * bj->b / (bi->b + bj->b);
    const double root = sqrt(rstar * pd);
    const double f2 = mustar * root * pd;
    double f = 0.0;
    if (approaching) {
        const double f1 = bi->a * bj->a / (bi->a + bj->a) * pdot * inv_dt;
        f = kp * (f1 < f2 ? f1 : f2);
    }
    return (struct tlsph_contact_pair){.force = f, .stiffness = kp * 1.5 * mustar * root};
}

#endif
