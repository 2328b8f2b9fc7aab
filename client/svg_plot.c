/* SVG rendering of a laid-out line plot; text is XML-escaped. */
#include "svg_plot.h"

#include <math.h>
#include <string.h>

static const char *const colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                     "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
#define NCOLORS (sizeof colors / sizeof *colors)
/* past the tenth line the colours repeat with a dash pattern */
static const char *const dashes[] = {"", " stroke-dasharray=\"6 3\"", " stroke-dasharray=\"2 2\""};

static void xml_text(FILE *f, const char *s)
{
    for (; s && *s; s++) {
        unsigned char c = (unsigned char)*s;
        switch (c) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&apos;", f); break;
        default:
            if (c < 0x20 || c == 0x7f)
                fputc(' ', f); /* not allowed in XML 1.0 */
            else
                fputc(c, f);
        }
    }
}

/* Legend text: a long label keeps its end, which tells the series apart. */
static void legend_text(FILE *f, const char *s)
{
    size_t n = strlen(s ? s : "");
    if (n <= PLOT_LEGEND_MAX_CHARS) {
        xml_text(f, s);
        return;
    }
    const char *t = s + n - (PLOT_LEGEND_MAX_CHARS - 3);
    while (((unsigned char)*t & 0xC0) == 0x80) /* not inside a UTF-8 sequence */
        t++;
    fputs("...", f);
    xml_text(f, t);
}

/* "×10^p" at (x, y) */
static void power_text(FILE *f, double x, double y, const char *anchor, int power)
{
    if (power != 0)
        fprintf(f,
                "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"%s\">\xc3\x97"
                "10<tspan baseline-shift=\"super\" font-size=\"9\">%d</tspan></text>\n",
                x, y, anchor, power);
}

/* a log axis' "1e-8" as 10 with a superscript */
static void tick_text(FILE *f, const plot_axis *a, size_t k)
{
    if (a->log && strncmp(a->label[k], "1e", 2) == 0)
        fprintf(f, "10<tspan baseline-shift=\"super\" font-size=\"9\">%s</tspan>", a->label[k] + 2);
    else
        fputs(a->label[k], f);
}

static void line_style(FILE *f, size_t l)
{
    fprintf(f, "stroke=\"%s\"%s", colors[l % NCOLORS], dashes[(l / NCOLORS) % 3]);
}

static void draw_grid(FILE *f, const plot_layout *L, const plot_panel *P)
{
    const plot_box *b = &P->frame;
    fputs("<g stroke=\"#e0e0e0\" stroke-width=\"1\">\n", f);
    for (size_t k = 0; k < L->x.nticks; k++) {
        double x = plot_layout_px(L, P, L->x.tick[k]);
        fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n", x, b->y, x, b->y + b->h);
    }
    for (size_t k = 0; k < P->y.nticks; k++) {
        double y = plot_layout_py(P, P->y.tick[k]);
        fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n", b->x, y, b->x + b->w, y);
    }
    fputs("</g>\n", f);
}

static void draw_y_axis(FILE *f, const plot_panel *P)
{
    const plot_box *b = &P->frame;
    fputs("<g fill=\"black\">\n", f);
    for (size_t k = 0; k < P->y.nticks; k++) {
        fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"end\">", b->x - 6,
                plot_layout_py(P, P->y.tick[k]) + 4);
        tick_text(f, &P->y, k);
        fputs("</text>\n", f);
    }
    power_text(f, b->x, b->y - 7, "start", P->y.power);
    fprintf(f, "<text class=\"ylabel\" transform=\"translate(18 %.2f) rotate(-90)\" text-anchor=\"middle\">",
            b->y + b->h / 2);
    xml_text(f, P->ylabel);
    fputs("</text>\n</g>\n", f);
}

static void draw_x_axis(FILE *f, const plot_layout *L, const plot_panel *P, const char *xlabel)
{
    const plot_box *b = &P->frame;
    double base = b->y + b->h;
    fputs("<g fill=\"black\">\n", f);
    for (size_t k = 0; k < L->x.nticks; k++) {
        fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">", plot_layout_px(L, P, L->x.tick[k]),
                base + 18);
        tick_text(f, &L->x, k);
        fputs("</text>\n", f);
    }
    power_text(f, b->x + b->w, base + 34, "end", L->x.power);
    fprintf(f, "<text class=\"xlabel\" x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">", b->x + b->w / 2,
            base + 48);
    xml_text(f, xlabel);
    fputs("</text>\n</g>\n", f);
}

static void draw_markers(FILE *f, const plot_layout *L, const plot_panel *P, const plot_line *line, size_t l)
{
    for (size_t i = 0; i < line->n; i++)
        fprintf(f, "<circle class=\"marker\" cx=\"%.2f\" cy=\"%.2f\" r=\"3\" fill=\"%s\"/>\n",
                plot_layout_px(L, P, line->x[i]), plot_layout_py(P, line->y[i]), colors[l % NCOLORS]);
}

static void draw_curves(FILE *f, const plot_layout *L, size_t p, const plot_line *lines, int markers)
{
    const plot_panel *P = &L->panel[p];
    for (size_t k = 0; k < P->nlines; k++) {
        size_t l = P->line[k];
        fprintf(f, "<polyline class=\"curve\" data-panel=\"%zu\" fill=\"none\" stroke-width=\"1.5\" ", p);
        line_style(f, l);
        fputs(" points=\"", f);
        for (size_t i = 0; i < lines[l].n; i++)
            fprintf(f, "%s%.2f,%.2f", i ? " " : "", plot_layout_px(L, P, lines[l].x[i]),
                    plot_layout_py(P, lines[l].y[i]));
        fputs("\"><title>", f);
        xml_text(f, lines[l].label);
        fputs("</title></polyline>\n", f);
        if (markers)
            draw_markers(f, L, P, &lines[l], l);
        else if (lines[l].n == 1) { /* a polyline of one point draws nothing */
            fprintf(f, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"3\" fill=\"%s\"/>\n",
                    plot_layout_px(L, P, lines[l].x[0]), plot_layout_py(P, lines[l].y[0]), colors[l % NCOLORS]);
        }
    }
}

static void draw_legend(FILE *f, size_t p, const plot_panel *P, const plot_line *lines)
{
    const plot_box *b = &P->legend;
    if (P->nlines == 0)
        return;
    fprintf(f, "<rect class=\"legend\" id=\"legend-%zu\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" "
               "height=\"%.2f\" fill=\"white\" stroke=\"#999\"/>\n",
            p, b->x, b->y, b->w, b->h);
    for (size_t k = 0; k < P->nlines; k++) {
        size_t l = P->line[k];
        double yy = b->y + 13 + 18.0 * (double)k;
        fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke-width=\"2\" ", b->x + 6, yy,
                b->x + 31, yy);
        line_style(f, l);
        fprintf(f, "/>\n<text x=\"%.2f\" y=\"%.2f\">", b->x + 38, yy + 4);
        legend_text(f, lines[l].label);
        fputs("</text>\n", f);
    }
}

int svg_plot_write(FILE *f, const plot_axes *ax, const plot_line *lines, size_t nlines)
{
    plot_layout L;
    int rc = plot_layout_make(&L, lines, nlines, ax->log_y, ax->title != NULL);
    if (rc != 0)
        return rc;
    if (ax->log_x) { /* the layout fits a linear x axis; refit it over the positive x */
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = 0; i < nlines; i++)
            for (size_t k = 0; k < lines[i].n; k++)
                if (lines[i].x[k] > 0) {
                    lo = fmin(lo, lines[i].x[k]);
                    hi = fmax(hi, lines[i].x[k]);
                }
        if (lo <= hi)
            plot_axis_fit(&L.x, lo, hi, 1);
    }
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
               "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
               "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" font-size=\"12\">\n",
            L.width, L.height, L.width, L.height);
    fprintf(f, "<rect x=\"0\" y=\"0\" width=\"%.0f\" height=\"%.0f\" fill=\"white\"/>\n", L.width, L.height);
    if (ax->title) {
        const plot_box *b = &L.panel[0].frame;
        fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\" font-size=\"15\">", b->x + b->w / 2,
                L.title_y);
        xml_text(f, ax->title);
        fputs("</text>\n", f);
    }
    for (size_t p = 0; p < L.npanels; p++) {
        const plot_panel *P = &L.panel[p];
        draw_grid(f, &L, P);
        draw_y_axis(f, P);
        fprintf(f, "<rect class=\"frame\" id=\"frame-%zu\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" "
                   "height=\"%.2f\" fill=\"none\" stroke=\"black\"/>\n",
                p, P->frame.x, P->frame.y, P->frame.w, P->frame.h);
        draw_curves(f, &L, p, lines, ax->markers);
        draw_legend(f, p, P, lines);
    }
    draw_x_axis(f, &L, &L.panel[L.npanels - 1], ax->xlabel);
    fputs("</svg>\n", f);
    plot_layout_free(&L);
    return ferror(f) ? -1 : 0;
}
