/* Panels, axes and boxes of a line plot. */
#include "plot_layout.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FRAME_W 600.0      /* width of every panel's frame */
#define PANEL_H1 380.0     /* frame height of a lone panel */
#define PANEL_HN 230.0     /* frame height of each of several panels */
#define PANEL_GAP 40.0     /* between panels: room for the next y axis' power of ten */
#define TOP_TITLE 52.0     /* first frame's top, with a title */
#define TOP_PLAIN 34.0     /* ... and without */
#define BOTTOM 62.0        /* below the last frame: x tick labels, x label */
#define YLABEL_W 34.0      /* left of the tick labels: the rotated y label */
#define TICK_GAP 8.0       /* tick label to frame */
#define LEGEND_GAP 20.0    /* frame to legend */
#define LEGEND_ROW 18.0    /* one legend entry */
#define LEGEND_KEY 45.0    /* the line sample and padding of a legend entry */
#define RIGHT 16.0         /* right of the legend */

static double line_scale(const plot_line *l)
{
    double s = 0;
    for (size_t i = 0; i < l->n; i++)
        s = fmax(s, fabs(l->y[i]));
    return s;
}

static int same_units(const plot_line *a, const plot_line *b)
{
    const char *ua = a->what.units ? a->what.units : "", *ub = b->what.units ? b->what.units : "";
    return strcmp(ua, ub) == 0;
}

/* group[i] = the group of line i; returns the number of groups, or 0 when a
 * line of a new unit finds every one of the PLOT_MAX_PANELS panels taken (a
 * line of a known unit then joins the panel of the nearest magnitude).  Lines are taken largest first,
 * so that a group's first line is its largest. */
static size_t group_lines(const plot_line *lines, size_t n, int log_y, const double *scale,
                          size_t *order, size_t *group)
{
    for (size_t i = 0; i < n; i++) {
        size_t j = i;
        while (j > 0 && scale[order[j - 1]] < scale[i]) {
            order[j] = order[j - 1];
            j--;
        }
        order[j] = i;
    }
    size_t ng = 0, first[PLOT_MAX_PANELS]; /* first (largest) line of each group */
    for (size_t k = 0; k < n; k++) {
        size_t i = order[k], g, near = ng;
        double best = INFINITY;
        for (g = 0; g < ng; g++) {
            const plot_line *f = &lines[first[g]];
            if (!same_units(f, &lines[i]))
                continue;
            if (log_y || scale[i] == 0 || scale[i] * PLOT_SCALE_RATIO >= scale[first[g]])
                break;
            double d = fabs(log(scale[first[g]] / scale[i]));
            if (d < best) {
                best = d;
                near = g;
            }
        }
        if (g == ng && ng < PLOT_MAX_PANELS)
            first[ng++] = i;
        else if (g == ng && near < ng)
            g = near; /* out of panels: the nearest magnitude of the same unit */
        else if (g == ng)
            return 0;
        group[i] = g;
    }
    return ng;
}

static void data_range(const plot_line *lines, const size_t *idx, size_t n, int use_y, double *lo,
                       double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t k = 0; k < n; k++) {
        const plot_line *l = &lines[idx ? idx[k] : k];
        const double *v = use_y ? l->y : l->x;
        for (size_t i = 0; i < l->n; i++) {
            *lo = fmin(*lo, v[i]);
            *hi = fmax(*hi, v[i]);
        }
    }
}

/* Fits an axis over a data range that may be empty (no points). */
static void fit(plot_axis *a, double lo, double hi, int log)
{
    if (!(lo <= hi)) {
        lo = log ? 1 : 0;
        hi = log ? 10 : 1;
    }
    plot_axis_fit(a, lo, hi, log);
}

static size_t max_tick_chars(const plot_axis *a)
{
    size_t m = 0;
    for (size_t k = 0; k < a->nticks; k++)
        if (strlen(a->label[k]) > m)
            m = strlen(a->label[k]);
    return m;
}

static size_t legend_chars(const char *s)
{
    size_t n = strlen(s ? s : "");
    return n > PLOT_LEGEND_MAX_CHARS ? PLOT_LEGEND_MAX_CHARS : n;
}

static int name_y_axis(plot_panel *P, const plot_line *lines, size_t max_chars)
{
    P->ylabel[0] = '\0';
    if (P->nlines == 0)
        return 0;
    plot_quantity *q = malloc(P->nlines * sizeof *q);
    if (!q)
        return -1;
    for (size_t k = 0; k < P->nlines; k++)
        q[k] = lines[P->line[k]].what;
    plot_axis_label(P->ylabel, sizeof P->ylabel, max_chars, q, P->nlines);
    free(q);
    return 0;
}

int plot_layout_make(plot_layout *L, const plot_line *lines, size_t n, int log_y, int title)
{
    memset(L, 0, sizeof *L);
    size_t *order = malloc((n ? n : 1) * sizeof *order), *group = malloc((n ? n : 1) * sizeof *group);
    double *scale = malloc((n ? n : 1) * sizeof *scale);
    L->storage = malloc((n ? n : 1) * sizeof *L->storage);
    if (!order || !group || !scale || !L->storage) {
        free(order);
        free(group);
        free(scale);
        plot_layout_free(L);
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        scale[i] = line_scale(&lines[i]);
    size_t ng = n ? group_lines(lines, n, log_y, scale, order, group) : 0;
    free(order);
    free(scale);
    if (n && ng == 0) {
        free(group);
        plot_layout_free(L);
        return -2;
    }
    /* panels in the order of their first line; lines in the caller's order */
    size_t rank[PLOT_MAX_PANELS], np = 0, used = 0;
    for (size_t i = 0; i < n; i++) {
        size_t p = 0;
        while (p < np && rank[p] != group[i])
            p++;
        if (p == np)
            rank[np++] = group[i];
    }
    if (n == 0)
        np = 1; /* an empty frame */
    L->npanels = np;
    for (size_t p = 0; p < np; p++) {
        plot_panel *P = &L->panel[p];
        P->line = L->storage + used;
        for (size_t i = 0; i < n; i++)
            if (group[i] == rank[p])
                P->line[P->nlines++] = i;
        used += P->nlines;
    }
    free(group);

    double lo, hi;
    data_range(lines, NULL, n, 0, &lo, &hi);
    fit(&L->x, lo, hi, 0);
    size_t tick_chars = 0, lchars = 0;
    for (size_t p = 0; p < np; p++) {
        plot_panel *P = &L->panel[p];
        data_range(lines, P->line, P->nlines, 1, &lo, &hi);
        fit(&P->y, lo, hi, log_y);
        if (max_tick_chars(&P->y) > tick_chars)
            tick_chars = max_tick_chars(&P->y);
        for (size_t k = 0; k < P->nlines; k++)
            if (legend_chars(lines[P->line[k]].label) > lchars)
                lchars = legend_chars(lines[P->line[k]].label);
    }
    double ml = YLABEL_W + PLOT_CHAR_W * (double)tick_chars + TICK_GAP;
    double lw = LEGEND_KEY + PLOT_CHAR_W * (double)lchars;
    double top = title ? TOP_TITLE : TOP_PLAIN;
    for (size_t p = 0; p < np; p++) {
        plot_panel *P = &L->panel[p];
        double lh = LEGEND_ROW * (double)P->nlines + 8;
        double h = fmax(np == 1 ? PANEL_H1 : PANEL_HN, lh);
        P->frame = (plot_box){ml, top, FRAME_W, h};
        P->legend = (plot_box){ml + FRAME_W + LEGEND_GAP, top, lw, P->nlines ? lh : 0};
        top += h + PANEL_GAP;
        if (name_y_axis(P, lines, (size_t)(h / PLOT_CHAR_W)) != 0) {
            plot_layout_free(L);
            return -1;
        }
    }
    L->width = ml + FRAME_W + LEGEND_GAP + lw + RIGHT;
    L->height = top - PANEL_GAP + BOTTOM;
    L->title_y = 24;
    return 0;
}

void plot_layout_free(plot_layout *L)
{
    free(L->storage);
    memset(L, 0, sizeof *L);
}

double plot_layout_px(const plot_layout *L, const plot_panel *p, double x)
{
    return p->frame.x + plot_axis_frac(&L->x, x) * p->frame.w;
}

double plot_layout_py(const plot_panel *p, double y)
{
    return p->frame.y + p->frame.h - plot_axis_frac(&p->y, y) * p->frame.h;
}
