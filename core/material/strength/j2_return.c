#include "material/strength/j2_return.h"

#include <math.h>

#include "material/strength/strength.h"

struct eval {
    double r, dr;   /* residual and its slope d r / d dgamma */
    double sigma_y; /* flow stress */
    double T;       /* temperature at this dgamma */
};

static void residual(const struct tlsph_material *m, const struct tlsph_j2_input *in,
                     double dgamma, struct eval *e)
{
    const double G3 = 3.0 * in->G;
    const double rate = in->dt > 0.0 ? dgamma / in->dt : 0.0;
    const double tau_eq = in->q_trial - G3 * dgamma; /* end-of-step Kirchhoff von Mises */
    e->T = in->T + in->heating * tau_eq * dgamma;
    struct tlsph_flow f;
    m->strength->flow(m, in->eps_p + dgamma, rate, e->T, &f);
    e->sigma_y = f.stress;
    e->r = tau_eq - in->J * f.stress;
    double slope = f.d_strain;
    if (in->dt > 0.0 && f.d_rate != 0.0)
        slope += f.d_rate / in->dt;
    if (in->heating > 0.0 && f.d_temperature != 0.0)
        slope += f.d_temperature * in->heating * (in->q_trial - 2.0 * G3 * dgamma);
    e->dr = -G3 - in->J * slope;
}

int tlsph_j2_return(const struct tlsph_material *m, const struct tlsph_j2_input *in,
                    struct tlsph_j2_result *out)
{
    struct eval e;
    int have_zero = 0; /* e holds the residual at dgamma = 0 */
    double yield = in->yield;
    if (!(yield > 0.0)) {
        residual(m, in, 0.0, &e);
        have_zero = 1;
        yield = e.sigma_y;
    }
    out->dgamma = 0.0;
    out->sigma_y = yield;
    out->T = in->T;
    out->iterations = 0;
    out->converged = 1;
    out->yield = yield;
    if (!(in->q_trial - in->J * yield > 0.0))
        return 0; /* inside or on the yield surface: elastic step */
    out->yield = 0.0; /* the state moves: the cached value is stale */

    const double G3 = 3.0 * in->G;
    const double tol = 1e-12 * in->q_trial;
    double lo = 0.0, hi = in->q_trial / G3;
    /* First guess: the caller's; else the Newton step from dgamma = 0 when its
     * slope is usable, else the perfectly plastic estimate; always inside the
     * bracket. */
    double x = in->guess;
    if (!(x > lo && x < hi)) {
        if (!have_zero)
            residual(m, in, 0.0, &e);
        x = (isfinite(e.dr) && e.dr < 0.0) ? -e.r / e.dr : e.r / G3;
        if (!(x > lo && x < hi))
            x = 0.5 * (lo + hi);
    }
    out->converged = 0;
    for (int it = 1; it <= TLSPH_J2_MAX_ITERATIONS; it++) {
        residual(m, in, x, &e);
        out->iterations = it;
        if (fabs(e.r) <= tol) {
            out->converged = 1;
            break;
        }
        if (e.r > 0.0)
            lo = x;
        else
            hi = x;
        if (hi - lo <= 1e-14 * hi) {
            out->converged = 1;
            break;
        }
        const double step = -e.r / e.dr, newton = x + step;
        if (isfinite(newton) && e.dr < 0.0 && newton > lo && newton < hi) {
            x = newton;
            /* Quadratic convergence: after a step this small the residual at x
             * is ~(1e-7)^2 relative, below tol; finish without evaluating it
             * (the stress and heat follow from x in closed form). */
            if (fabs(step) <= 1e-7 * x) {
                out->converged = 1;
                out->dgamma = x;
                out->sigma_y = (in->q_trial - G3 * x) / in->J;
                out->T = in->T + in->heating * (in->q_trial - G3 * x) * x;
                return 1;
            }
        } else {
            x = 0.5 * (lo + hi);
        }
    }
    out->dgamma = x;
    out->sigma_y = e.sigma_y;
    out->T = e.T;
    return 1;
}
