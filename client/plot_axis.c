/* Axis ranges and ticks.  Linear ticks step by 1, 2 or 5 x 10^k; log ticks sit on
 * whole decades. */
#include "plot_axis.h"

#include <math.h>
#include <stdio.h>

/* Outside [1e-3, 1e5) the labels would need exponents or many zeros: they are
 * printed as multiples of one power of ten instead. */
#define PLAIN_MIN 1e-3
#define PLAIN_MAX 1e5

static double nice_step(double range, int target)
{
    double raw = range / target, mag = pow(10, floor(log10(raw))), r = raw / mag;
    double m = r < 1.5 ? 1 : r < 3 ? 2 : r < 7 ? 5 : 10;
    return m * mag;
}

static void two_ticks(plot_axis *a, double lo, double hi)
{
    a->lo = lo;
    a->hi = hi;
    a->nticks = 2;
    a->tick[0] = lo;
    a->tick[1] = hi;
}

static void label_linear(plot_axis *a, double step)
{
    double m = fmax(fabs(a->lo), fabs(a->hi));
    a->power = 0;
    if (m > 0 && (m >= PLAIN_MAX || m < PLAIN_MIN))
        a->power = (int)floor(log10(m));
    double scale = pow(10, a->power), s = step / scale;
    int dec = (int)-floor(log10(s) + 1e-9);
    dec = dec < 0 ? 0 : dec > 12 ? 12 : dec;
    for (size_t k = 0; k < a->nticks; k++) {
        double v = a->tick[k] / scale;
        if (fabs(v) < s * 1e-9)
            v = 0; /* no "-0.0" */
        snprintf(a->label[k], sizeof a->label[k], "%.*f", dec, v);
    }
}

static void fit_linear(plot_axis *a, double lo, double hi)
{
    if (!(hi > lo)) {
        double d = fabs(lo) > 0 ? fabs(lo) * 0.5 : 1.0;
        lo -= d;
        hi += d;
    }
    double step = nice_step(hi - lo, 5);
    double l = floor(lo / step + 1e-9) * step, h = ceil(hi / step - 1e-9) * step;
    double k = (h - l) / step;
    if (!(h > l) || !isfinite(k) || k + 1.5 > PLOT_MAX_TICKS) {
        /* a range tiny against its magnitude: the data's own ends */
        two_ticks(a, lo, hi);
        label_linear(a, hi - lo);
        return;
    }
    a->lo = l;
    a->hi = h;
    a->nticks = (size_t)(k + 0.5) + 1;
    for (size_t i = 0; i < a->nticks; i++)
        a->tick[i] = l + (double)i * step;
    a->tick[a->nticks - 1] = h;
    label_linear(a, step);
}

static void fit_log(plot_axis *a, double lo, double hi)
{
    double el = floor(log10(lo) + 1e-9), eh = ceil(log10(hi) - 1e-9);
    if (eh <= el)
        eh = el + 1;
    double every = ceil((eh - el) / (PLOT_MAX_TICKS / 2));
    eh = el + every * ceil((eh - el) / every);
    a->lo = pow(10, el);
    a->hi = pow(10, eh);
    a->nticks = 0;
    a->power = 0;
    for (double e = el; e <= eh + 0.5 && a->nticks < PLOT_MAX_TICKS; e += every) {
        a->tick[a->nticks] = pow(10, e);
        snprintf(a->label[a->nticks], sizeof a->label[0], "1e%d", (int)e);
        a->nticks++;
    }
}

void plot_axis_fit(plot_axis *a, double lo, double hi, int log)
{
    a->log = log;
    if (log)
        fit_log(a, lo, hi);
    else
        fit_linear(a, lo, hi);
}

double plot_axis_frac(const plot_axis *a, double v)
{
    if (a->log)
        return (log10(v) - log10(a->lo)) / (log10(a->hi) - log10(a->lo));
    return (v - a->lo) / (a->hi - a->lo);
}
