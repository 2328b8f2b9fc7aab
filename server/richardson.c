/* Richardson extrapolation and the GCI, see richardson.h. */
#include "richardson.h"

#include <math.h>

const char *trich_kind_name(enum trich_kind k)
{
    switch (k) {
    case TRICH_CONVERGING: return "converging";
    case TRICH_UNCHANGED: return "unchanged";
    case TRICH_OSCILLATORY: return "oscillatory";
    case TRICH_DIVERGENT: return "divergent";
    case TRICH_NON_ASYMPTOTIC: return "non_asymptotic";
    default: return "too_few";
    }
}

const char *trich_kind_reason(enum trich_kind k)
{
    switch (k) {
    case TRICH_CONVERGING:
        return "monotone convergence at the three finest spacings: Richardson extrapolation "
               "and GCI with Fs = 1.25";
    case TRICH_UNCHANGED:
        return "the three finest values are equal: no discretization error is visible";
    case TRICH_OSCILLATORY:
        return "the differences between successive spacings change sign (oscillatory "
               "convergence): no order and no Richardson estimate can be supported; half the "
               "range of the three finest values bounds the error instead (Stern et al. 2001)";
    case TRICH_DIVERGENT:
        return "the differences do not shrink as the spacing does: the ladder is not "
               "converging, no error estimate can be supported";
    case TRICH_NON_ASYMPTOTIC:
        return "the ladder is not in the asymptotic range (observed order outside [0.5, 6], "
               "or the coarser triplet's GCI ratio is not within 1 +- 0.15): no error "
               "estimate is given; refine, or drop the coarsest spacing";
    default:
        return "fewer than three finite values at the finest spacings: the order cannot be "
               "observed (with two, Roache's Fs = 3 needs an assumed order, which this "
               "process does not assume)";
    }
}

/* Observed order of the triplet f0, f1, f2 (finest first) at ratio r, or the
 * kind that stops it. */
static enum trich_kind triplet(double f0, double f1, double f2, double r, double *p)
{
    const double e21 = f1 - f0, e32 = f2 - f1;
    *p = NAN;
    if (e21 == 0.0 && e32 == 0.0)
        return TRICH_UNCHANGED;
    if (e21 == 0.0)
        return TRICH_NON_ASYMPTOTIC; /* an infinite order: the finest pair agrees by chance */
    const double s = e32 / e21;
    if (s < 0.0)
        return TRICH_OSCILLATORY;
    if (s <= 1.0)
        return TRICH_DIVERGENT;
    *p = log(s) / log(r);
    return *p < TRICH_ORDER_MIN || *p > TRICH_ORDER_MAX ? TRICH_NON_ASYMPTOTIC : TRICH_CONVERGING;
}

static void clear(struct trich_estimate *e, size_t n)
{
    e->n = n;
    e->first = 0;
    e->ratio = e->order = e->order_coarse = e->asymptotic_ratio = e->extrapolated = NAN;
    e->oscillation = e->oscillation_relative = NAN;
    e->safety_factor = TRICH_FS;
    for (size_t i = 0; i < TRICH_MAX; i++)
        e->error[i] = e->relative[i] = e->gci[i] = NAN;
}

enum trich_kind trich_estimate(const double *h, const double *f, size_t n,
                               struct trich_estimate *e)
{
    if (n > TRICH_MAX)
        n = TRICH_MAX;
    clear(e, n);
    /* the finest values may be missing (runs not finished): start at the
     * first finite one, and use the consecutive finite values from there */
    size_t s = 0;
    while (s < n && !(isfinite(f[s]) && isfinite(h[s]) && h[s] > 0))
        s++;
    e->first = s;
    h += s, f += s, n -= s;
    size_t m = 0;
    while (m < n && isfinite(f[m]) && isfinite(h[m]) && h[m] > 0)
        m++;
    if (m < 3)
        return e->kind = TRICH_TOO_FEW;
    const double r = h[1] / h[0];
    e->ratio = r;
    double p;
    e->kind = triplet(f[0], f[1], f[2], r, &p);
    e->order = p;
    if (e->kind == TRICH_OSCILLATORY) {
        const double hi = fmax(f[0], fmax(f[1], f[2])), lo = fmin(f[0], fmin(f[1], f[2]));
        e->oscillation = 0.5 * (hi - lo);
        e->oscillation_relative = f[0] != 0.0 ? e->oscillation / fabs(f[0]) : NAN;
    }
    if (e->kind == TRICH_UNCHANGED) {
        e->extrapolated = f[0];
    } else if (e->kind == TRICH_CONVERGING) {
        e->extrapolated = f[0] + (f[0] - f[1]) / (pow(r, p) - 1.0);
        if (m >= 4) {
            /* Roache's check with each triplet's own observed order:
             * GCI_23 / (r^p12 GCI_12) = (f1/f2) (r^p12 - 1) / (r^p23 - 1),
             * 1 when both triplets show the same order. */
            double p2;
            enum trich_kind k2 = triplet(f[1], f[2], f[3], r, &p2);
            e->order_coarse = p2;
            if (k2 == TRICH_CONVERGING && f[1] != 0.0) {
                e->asymptotic_ratio =
                    fabs(f[0] / f[1]) * (pow(r, p) - 1.0) / (pow(r, p2) - 1.0);
                if (fabs(e->asymptotic_ratio - 1.0) > TRICH_ASYMPTOTIC_TOL)
                    e->kind = TRICH_NON_ASYMPTOTIC;
            } else {
                e->kind = TRICH_NON_ASYMPTOTIC;
            }
        }
    }
    if (e->kind == TRICH_CONVERGING || e->kind == TRICH_UNCHANGED) {
        for (size_t i = 0; i < m; i++) {
            const double err = fabs(f[i] - e->extrapolated);
            e->error[s + i] = err;
            e->relative[s + i] = e->extrapolated != 0.0 ? err / fabs(e->extrapolated) : NAN;
            e->gci[s + i] = f[i] != 0.0 ? e->safety_factor * err / fabs(f[i]) : NAN;
        }
    } else {
        e->extrapolated = NAN;
    }
    return e->kind;
}

int trich_fit_power(const double *h, const double *y, size_t n, struct trich_power_fit *fit)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    size_t k = 0;
    fit->q = fit->c = fit->rms_log_residual = NAN;
    fit->n = 0;
    for (size_t i = 0; i < n; i++) {
        if (!(h[i] > 0) || !(y[i] > 0) || !isfinite(h[i]) || !isfinite(y[i]))
            continue;
        const double x = log(h[i]), v = log(y[i]);
        sx += x, sy += v, sxx += x * x, sxy += x * v;
        k++;
    }
    const double den = (double)k * sxx - sx * sx;
    if (k < 2 || !(fabs(den) > 1e-300))
        return -1;
    const double slope = ((double)k * sxy - sx * sy) / den;
    const double icept = (sy - slope * sx) / (double)k;
    fit->q = -slope;
    fit->c = exp(icept);
    fit->n = k;
    double ss = 0;
    for (size_t i = 0; i < n; i++) {
        if (!(h[i] > 0) || !(y[i] > 0) || !isfinite(h[i]) || !isfinite(y[i]))
            continue;
        const double d = log(y[i]) - (icept + slope * log(h[i]));
        ss += d * d;
    }
    fit->rms_log_residual = sqrt(ss / (double)k);
    return 0;
}

double trich_power_eval(const struct trich_power_fit *fit, double h)
{
    return fit->c * pow(h, -fit->q);
}

double trich_spacing_for(const struct trich_estimate *e, const double *h, double target)
{
    const double h1 = e->first < e->n ? h[e->first] : NAN;
    if (e->kind == TRICH_UNCHANGED)
        return INFINITY;
    if (e->kind != TRICH_CONVERGING || !(target > 0) || !(h1 > 0) || e->extrapolated == 0.0)
        return NAN;
    const double e1 = e->error[e->first];
    if (e1 == 0.0)
        return INFINITY;
    /* Fs E1 (h/h1)^p / |f_ext| = target */
    const double g1 = e->safety_factor * e1 / fabs(e->extrapolated);
    return h1 * pow(target / g1, 1.0 / e->order);
}
