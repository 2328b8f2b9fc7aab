/* Reference area vectors of a surface given as the particles of its outermost
 * layer (core/bc/surface.c): what a surface load (a pressure) multiplies.
 *
 * Each particle i of the layer gets N dA_i, pointing out of the body:
 *  - magnitude dA_i = V_i / s, V_i its reference volume and s its body's
 *    spacing: the particle's cell face.  On a lattice face every particle
 *    holds s^2 (s in 2-D) and a face of n x m cells sums to its area exactly;
 *    on conforming shells V_i / s is the arc (times dz) at the particle's
 *    middle radius, half a spacing off the surface (the relative error on a
 *    curved face is s / 2R), which a given total area corrects: the
 *    magnitudes are scaled so that they sum to it.
 *  - direction: a given normal (a flat face), or each particle's own: the
 *    normal of the plane (line in 2-D) fitted through the layer's particles
 *    within its support (the smallest principal direction of their scatter
 *    about their centroid), refined by a quadric through the particle (a
 *    one-sided patch of a curved surface, near the layer's edge, tilts the
 *    plane by its sag), oriented outwards by the colour gradient
 *    c_i = sum_j V_j |W'| (X_i - X_j) / |X_i - X_j|, which points away from
 *    the body's particles.  The fit is exact on a flat face up to its edges
 *    and corners (where the colour gradient alone tilts by 45 degrees, and a
 *    load would lose 1 - cos 45 of its share there) and radial on conforming
 *    shells; at the ends of a loaded cylinder wall the axial force it leaks is
 *    6e-5 of the caps' load (the plane alone: 1.2 %, tests/physics/
 *    test_pressure.c).  Where the fit is undetermined (a lone particle, a
 *    single row in 3-D) the colour gradient's direction is used.
 * A particle whose colour gradient vanishes (its neighbours surround it: not
 * on the surface) is refused, and so is a given normal that points into the
 * body (against the colour gradient summed over the layer). */
#ifndef TLSPH_BC_SURFACE_H
#define TLSPH_BC_SURFACE_H

#include <stddef.h>
#include <stdint.h>

#include "run/model.h"

/* The area vectors (m^2, m per metre of thickness in 2-D) of the n particles
 * index[0..n-1] of m (pairs built) into out [3n]: normal (unit, outward) for
 * all of them or NULL for each its own, and their magnitudes scaled to sum to
 * area when area > 0.  Reports at pointer (a given normal at pointer/normal)
 * naming the condition `name` and returns -1, or 0. */
int tlsph_surface_areas(const struct tlsph_model *m, const int32_t *index, size_t n,
                        const double *normal, double area, double *out, const char *name,
                        const char *pointer, struct tlsph_errors *err);

#endif
