/* A dependency-free SVG line plot: axes with ticks, labels, legend. */
#ifndef TLSPH_CLIENT_SVG_PLOT_H
#define TLSPH_CLIENT_SVG_PLOT_H

#include <stddef.h>
#include <stdio.h>

typedef struct {
    const char *label; /* legend text */
    size_t n;          /* points */
    const double *x, *y;
} plot_line;

typedef struct {
    const char *title;  /* may be NULL */
    const char *xlabel; /* e.g. "time [s]" */
    const char *ylabel;
} plot_axes;

/* Writes a complete SVG document with one <polyline> per line (exactly n points
 * each; all values must be finite).  Returns 0, or -1 on a write error. */
int svg_plot_write(FILE *f, const plot_axes *ax, const plot_line *lines, size_t nlines);

#endif
