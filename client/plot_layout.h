/* Where everything of a line plot goes.  Lines are grouped into panels stacked
 * over one shared x axis: lines of different units never share a panel, and
 * neither do lines whose magnitudes differ by more than PLOT_SCALE_RATIO (on a
 * log axis only the unit separates).  Each panel has its own y axis and, to the
 * right of its frame, its own legend: no legend ever lies over a curve.  A
 * panel is as tall as its legend needs.  All lengths are SVG user units (px). */
#ifndef TLSPH_CLIENT_PLOT_LAYOUT_H
#define TLSPH_CLIENT_PLOT_LAYOUT_H

#include <stddef.h>

#include "plot_axis.h"
#include "plot_label.h"

#define PLOT_MAX_PANELS 6    /* further groups share the last panel */
#define PLOT_SCALE_RATIO 10.0 /* largest |y| of a panel / largest |y| of each of its lines */
#define PLOT_CHAR_W 7.5       /* estimated advance of one character at font-size 12 */
#define PLOT_LEGEND_MAX_CHARS 48 /* longer legend texts keep their end */

typedef struct {
    const char *label;  /* legend text, e.g. "groups/right/reaction_force[x]" */
    plot_quantity what; /* for the y label and the grouping (units) */
    size_t n;           /* points */
    const double *x, *y; /* finite; y > 0 on a log axis */
} plot_line;

typedef struct {
    double x, y, w, h;
} plot_box;

typedef struct {
    size_t nlines;
    size_t *line;      /* indices into the caller's lines, in the caller's order */
    plot_box frame;    /* the curves' region: every point of the panel's lines lies inside */
    plot_box legend;   /* right of frame, never overlapping any frame */
    plot_axis y;
    char ylabel[256];  /* names the quantity and its unit (plot_label.h) */
} plot_panel;

typedef struct {
    double width, height; /* the whole picture */
    double title_y;       /* baseline of the title */
    plot_axis x;          /* shared by all panels */
    size_t npanels;
    plot_panel panel[PLOT_MAX_PANELS];
    size_t *storage;      /* the panels' line indices */
} plot_layout;

/* Lays out lines[0..n-1] (title: leave room for one).  Returns 0; -1 when out
 * of memory; -2 when a line finds no panel: its unit is new and PLOT_MAX_PANELS
 * panels are taken (by other units or magnitudes). */
int plot_layout_make(plot_layout *L, const plot_line *lines, size_t n, int log_y, int title);
void plot_layout_free(plot_layout *L);

/* Picture coordinates of data point (x, y) of a line of panel p. */
double plot_layout_px(const plot_layout *L, const plot_panel *p, double x);
double plot_layout_py(const plot_panel *p, double y);

#endif
