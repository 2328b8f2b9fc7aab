/* The default contact law: a Hertz-type penalty with damping (docs/contact.md).
 *
 * Two particles of radii R_i, R_j touch when their distance r < R_i + R_j;
 * the overlap is delta = R_i + R_j - r.  The elastic force takes one of two
 * Hertz forms (scene key "form"):
 *   line (default): the line contact of two parallel cylinders, whose Hertz
 *     solution has no closed force-approach law (the approach depends
 *     logarithmically on the bodies' size), so its leading term is taken,
 *     over the contact's length w:
 *       F_e = pi/4 E* w delta,  k = dF_e/ddelta = pi/4 E* w,
 *     w = 1 m in 2-D (forces per metre of thickness), w = R_i + R_j (the
 *     particles' width) in 3-D;
 *   point (3-D only; in 2-D it is the line form): two spheres,
 *       F_e = 4/3 E* sqrt(R*) delta^(3/2),  k = 2 E* sqrt(R* delta),
 *     R* = R_i R_j / (R_i + R_j);
 * with 1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j.  Why line is the default:
 * the particles of two flat faces meet as a layer, and the point form is far
 * softer than the bulk at small overlaps (a steel bar at 1 m/s: 1/50 of a
 * particle column's stiffness, a contact 40 % too long in 3-D, docs), while
 * the line form is 0.39 of it in both dimensions.
 * Damping, a fraction zeta of the critical damping of the pair's oscillator:
 *   F_d = 2 zeta sqrt(m* k) w_n,  m* = m_i m_j / (m_i + m_j),
 * w_n the speed of approach along the line of centres.  F = max(F_e + F_d, 0):
 * contact pushes, never pulls.
 *
 * The radius is half the edge of the particle's cell, R = V0^(1/d) / 2 (d the
 * dimension, V0 its reference volume): on the lattice, two flat faces of
 * bodies touch when their outer particles are one spacing apart, so contact
 * starts when the surfaces meet.  (The sphere of equal volume, R = 0.62 V0^(1/3),
 * would start it 0.24 spacing early.) */
#ifndef TLSPH_CONTACT_PENALTY_H
#define TLSPH_CONTACT_PENALTY_H

#include <math.h>

#include "contact/contact.h"

enum { TLSPH_PENALTY_DAMPING };                                      /* params[] */
enum tlsph_penalty_form { TLSPH_PENALTY_LINE, TLSPH_PENALTY_POINT }; /* choice */

struct tlsph_contact_pair {
    double force;     /* F >= 0, N (N/m in 2-D) */
    double stiffness; /* dF/ddelta of the elastic part, N/m (N/m^2 in 2-D) */
};

/* Body constants: radius, a = (1 - nu^2)/E, b = the body's share of the line
 * contact's length w (3-D: its radius; 2-D: 0.5 m, so that w = 1 m).  point is
 * a compile-time constant (the sphere form).  Every operation is commutative
 * in i, j, so the pair gives the same F from either side. */
static inline __attribute__((always_inline)) struct tlsph_contact_pair
tlsph_penalty_pair(const int point, const struct tlsph_contact_body *bi,
                   const struct tlsph_contact_body *bj, double mi, double mj, double delta,
                   double approach, double zeta)
{
    const double estar = 1.0 / (bi->a + bj->a);
    double fe, k;
    if (point) {
        const double reff = bi->radius * bj->radius / (bi->radius + bj->radius);
        const double root = sqrt(reff * delta);
        fe = (4.0 / 3.0) * estar * root * delta;
        k = 2.0 * estar * root;
    } else {
        k = 0.25 * M_PI * estar * (bi->b + bj->b);
        fe = k * delta;
    }
    const double meff = mi * mj / (mi + mj);
    const double f = fe + 2.0 * zeta * sqrt(meff * k) * approach;
    return (struct tlsph_contact_pair){.force = f > 0.0 ? f : 0.0, .stiffness = k};
}

#endif
