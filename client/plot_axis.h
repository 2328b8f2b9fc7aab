/* One axis of a plot: its range widened to round ticks, the ticks, and their
 * labels printed alike (one number of decimals per axis; a power of ten shown
 * once at the axis end instead of in every label when the numbers are very
 * large or very small). */
#ifndef TLSPH_CLIENT_PLOT_AXIS_H
#define TLSPH_CLIENT_PLOT_AXIS_H

#include <stddef.h>

#define PLOT_MAX_TICKS 24

typedef struct {
    int log;                           /* log10 axis (then lo, hi are powers of ten) */
    double lo, hi;                     /* the axis range, data units, lo < hi */
    size_t nticks;                     /* 2 .. PLOT_MAX_TICKS */
    double tick[PLOT_MAX_TICKS];       /* tick values, ascending, lo .. hi */
    char label[PLOT_MAX_TICKS][24];    /* tick labels (ASCII) */
    int power;                         /* labels are values / 10^power; 0: none shown */
} plot_axis;

/* Fits an axis over the data range [lo, hi] (finite; lo == hi gets a width).
 * A log axis needs lo > 0. */
void plot_axis_fit(plot_axis *a, double lo, double hi, int log);

/* Where v sits along the axis: 0 at lo, 1 at hi. */
double plot_axis_frac(const plot_axis *a, double v);

#endif
