/* Velocity constraints and the support's impulse, shared by the kinds that
 * prescribe velocity components (fixed, velocity). */
#ifndef TLSPH_BC_IMPULSE_H
#define TLSPH_BC_IMPULSE_H

#include <stddef.h>

#include "run/model.h"

/* Sets component c of particle i's velocity to value (m/s) and books the
 * momentum change in g->impulse (N s).  The support's impulse does work at the
 * mid-step velocity v_mid (m/s) of the prescribed motion: *work += impulse *
 * v_mid (J); see the constrain hook in core/bc/kind.h for why. */
static inline void tlsph_bc_impose(struct tlsph_model *m, struct tlsph_group *g, size_t i,
                                   int c, double value, double v_mid, double *work)
{
    double *v = m->p.v + 3 * i;
    const double dp = m->p.mass[i] * (value - v[c]);
    g->impulse[c] += dp;
    *work += dp * v_mid;
    v[c] = value;
}

#endif
