/* Helpers of the split tests and benches (split_plate.h). */
#include "support/split_plate.h"

#include <math.h>

double split_plate_lattice(const struct tlsph_model *m, int axis, double v)
{
    double best = INFINITY, at = 0.0;
    for (size_t i = m->body_begin[0]; i < m->body_end[0]; i++) {
        const double c = m->p.X[3 * i + axis];
        if (fabs(c - v) < best) {
            best = fabs(c - v);
            at = c;
        }
    }
    return at;
}

double split_plate_verlet_term(const struct tlsph_model *m, double dt)
{
    double s = 0.0;
    for (size_t i = 0; i < m->p.n; i++) {
        const double *f = m->p.f + 3 * i;
        s += (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]) / m->p.mass[i];
    }
    return dt * dt / 8.0 * s;
}
