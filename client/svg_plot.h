/* A dependency-free SVG line plot: panels over one x axis (plot_layout.h), each
 * with its ticks, its y label naming the quantity and unit, and its legend
 * beside the curves. */
#ifndef TLSPH_CLIENT_SVG_PLOT_H
#define TLSPH_CLIENT_SVG_PLOT_H

#include <stddef.h>
#include <stdio.h>

#include "plot_layout.h"

typedef struct {
    const char *title;  /* may be NULL */
    const char *xlabel; /* e.g. "time [s]" */
    int log_y;          /* log10 y axes */
    int log_x;          /* log10 x axis (every x > 0) */
    int markers;        /* a dot at every point: the data are a few discrete runs */
} plot_axes;

/* Writes a complete SVG document.  For tests and tools it marks what it draws:
 * each panel's frame is <rect class="frame" id="frame-P">, its legend box
 * <rect class="legend" id="legend-P">, and each line one
 * <polyline class="curve" data-panel="P"> with exactly n points (with markers,
 * followed by n <circle class="marker">).  Returns 0;
 * -1 on a write error or when out of memory; -2 when the lines need more than
 * PLOT_MAX_PANELS panels (plot_layout_make). */
int svg_plot_write(FILE *f, const plot_axes *ax, const plot_line *lines, size_t nlines);

#endif
