/* SPH kernels with compact support 2h (q = r/h in [0, 2]).
 *
 *   cubic B-spline (M4): W = s_d/h^d * { 1 - 3/2 q^2 + 3/4 q^3   (q < 1)
 *                                      { 1/4 (2 - q)^3           (1 <= q < 2)
 *                        s_2 = 10/(7 pi), s_3 = 1/pi
 *   Wendland C2:         W = s_d/h^d * (1 - q/2)^4 (2q + 1)
 *                        s_2 = 7/(4 pi),  s_3 = 21/(16 pi)
 *
 * Both integrate to 1 over the plane (2-D) or space (3-D).  Used only while the
 * reference pairs are built, so plain functions are enough. */
#ifndef TLSPH_KERNEL_H
#define TLSPH_KERNEL_H

#include "scene/scene.h"

/* W(r) in 1/m^d and dW/dr in 1/m^(d+1) for smoothing length h (m). */
void tlsph_kernel(enum tlsph_kernel_type type, int dim, double r, double h, double *w,
                  double *dwdr);
const char *tlsph_kernel_name(enum tlsph_kernel_type type);

#endif
