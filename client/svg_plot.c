/* SVG rendering of line plots.  Ticks at 1/2/5 x 10^k steps, text XML-escaped. */
#include "svg_plot.h"

#include <math.h>
#include <string.h>

#define W 800.0
#define H 500.0
#define ML 95.0 /* margins */
#define MR 25.0
#define MT 40.0
#define MB 60.0

static const char *const colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                     "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

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

static double nice_step(double range, int target)
{
    double raw = range / target, mag = pow(10, floor(log10(raw))), r = raw / mag;
    double m = r < 1.5 ? 1 : r < 3 ? 2 : r < 7 ? 5 : 10;
    return m * mag;
}

/* Expands [*lo, *hi] to tick multiples; degenerate ranges get a width. */
static double axis_range(double *lo, double *hi)
{
    if (!(*hi > *lo)) {
        double d = fabs(*lo) > 0 ? fabs(*lo) * 0.5 : 1.0;
        *lo -= d;
        *hi += d;
    }
    double step = nice_step(*hi - *lo, 5);
    *lo = floor(*lo / step + 1e-9) * step;
    *hi = ceil(*hi / step - 1e-9) * step;
    if (!(*hi > *lo) || !isfinite(step) || step <= 0) { /* range tiny against its magnitude */
        step = fabs(*lo) > 0 ? fabs(*lo) : 1;
        *hi = *lo + step;
    }
    return step;
}

/* number of tick intervals, bounded (a range tiny against its magnitude) */
static int nticks(double lo, double hi, double step)
{
    double k = floor((hi - lo) / step + 0.5);
    return k < 1 || !isfinite(k) ? 1 : k > 20 ? 20 : (int)k;
}

static void fmt_tick(char *buf, size_t n, double v, double step)
{
    if (fabs(v) < step * 1e-6)
        v = 0;
    snprintf(buf, n, "%.4g", v);
}

int svg_plot_write(FILE *f, const plot_axes *ax, const plot_line *lines, size_t nlines)
{
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (size_t l = 0; l < nlines; l++)
        for (size_t i = 0; i < lines[l].n; i++) {
            x0 = fmin(x0, lines[l].x[i]);
            x1 = fmax(x1, lines[l].x[i]);
            y0 = fmin(y0, lines[l].y[i]);
            y1 = fmax(y1, lines[l].y[i]);
        }
    if (!isfinite(x0)) {
        x0 = y0 = 0;
        x1 = y1 = 1;
    }
    double xs = axis_range(&x0, &x1), ys = axis_range(&y0, &y1);
    double pw = W - ML - MR, ph = H - MT - MB;
#define PX(v) (ML + ((v) - x0) / (x1 - x0) * pw)
#define PY(v) (MT + ph - ((v) - y0) / (y1 - y0) * ph)

    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
               "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
               "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" font-size=\"12\">\n",
            W, H, W, H);
    fprintf(f, "<rect x=\"0\" y=\"0\" width=\"%.0f\" height=\"%.0f\" fill=\"white\"/>\n", W, H);
    if (ax->title) {
        fprintf(f, "<text x=\"%.1f\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">", ML + pw / 2);
        xml_text(f, ax->title);
        fputs("</text>\n", f);
    }
    /* grid and ticks */
    fputs("<g stroke=\"#e0e0e0\" stroke-width=\"1\">\n", f);
    for (int k_ = 0, nk_ = nticks(x0, x1, xs); k_ <= nk_; k_++)
        fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n", PX(x0 + k_ * xs), MT, PX(x0 + k_ * xs), MT + ph);
    for (int k_ = 0, nk_ = nticks(y0, y1, ys); k_ <= nk_; k_++)
        fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\"/>\n", ML, PY(y0 + k_ * ys), ML + pw, PY(y0 + k_ * ys));
    fputs("</g>\n<g fill=\"black\">\n", f);
    char b[64];
    for (int k_ = 0, nk_ = nticks(x0, x1, xs); k_ <= nk_; k_++) {
        double v = x0 + k_ * xs;
        fmt_tick(b, sizeof b, v, xs);
        fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">%s</text>\n", PX(v), MT + ph + 18, b);
    }
    for (int k_ = 0, nk_ = nticks(y0, y1, ys); k_ <= nk_; k_++) {
        double v = y0 + k_ * ys;
        fmt_tick(b, sizeof b, v, ys);
        fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"end\">%s</text>\n", ML - 6, PY(v) + 4, b);
    }
    fputs("</g>\n", f);
    fprintf(f, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"none\" stroke=\"black\"/>\n",
            ML, MT, pw, ph);
    fprintf(f, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">", ML + pw / 2, H - 15);
    xml_text(f, ax->xlabel);
    fprintf(f, "</text>\n<text transform=\"translate(18 %.2f) rotate(-90)\" text-anchor=\"middle\">",
            MT + ph / 2);
    xml_text(f, ax->ylabel);
    fputs("</text>\n", f);

    /* data */
    for (size_t l = 0; l < nlines; l++) {
        fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" points=\"",
                colors[l % (sizeof colors / sizeof *colors)]);
        for (size_t i = 0; i < lines[l].n; i++)
            fprintf(f, "%s%.2f,%.2f", i ? " " : "", PX(lines[l].x[i]), PY(lines[l].y[i]));
        fputs("\"><title>", f);
        xml_text(f, lines[l].label);
        fputs("</title></polyline>\n", f);
    }
    /* legend, top right inside the frame */
    double lw = 0;
    for (size_t l = 0; l < nlines; l++)
        lw = fmax(lw, 7.0 * (double)strlen(lines[l].label ? lines[l].label : ""));
    double lx = ML + pw - lw - 45, ly = MT + 10;
    fprintf(f, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"white\" "
               "fill-opacity=\"0.85\" stroke=\"#999\"/>\n",
            lx - 5, ly - 4, lw + 45, 18.0 * (double)nlines + 6);
    for (size_t l = 0; l < nlines; l++) {
        double yy = ly + 18.0 * (double)l + 9;
        fprintf(f, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"%s\" stroke-width=\"2\"/>\n",
                lx, yy, lx + 25, yy, colors[l % (sizeof colors / sizeof *colors)]);
        fprintf(f, "<text x=\"%.2f\" y=\"%.2f\">", lx + 32, yy + 4);
        xml_text(f, lines[l].label);
        fputs("</text>\n", f);
    }
    fputs("</svg>\n", f);
#undef PX
#undef PY
    return ferror(f) ? -1 : 0;
}
