/* plot: an SVG of time series versus time or versus another series (paired by
 * step).  The series documents carry the units; their names the quantities. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "exitcodes.h"
#include "http.h"
#include "svg_plot.h"
#include "urls.h"

typedef struct {
    char *name;   /* series name without ":comp" */
    int comp;     /* -1: all (vector) / scalar */
    json_t *doc;  /* series document */
    size_t ncomp; /* components per value, 0 = scalar */
} series_ref;

/* The strings one plotted line's plot_line points to. */
typedef struct {
    char label[600];
    char owner[256], quantity[256], component[64];
} line_names;

/* Parses NAME[:COMP] (COMP an index or a component name resolved after loading). */
static int load_series(const settings *s, const char *id, const char *spec, series_ref *out)
{
    memset(out, 0, sizeof *out);
    out->comp = -1;
    out->name = strdup(spec);
    if (!out->name) {
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    char *colon = strrchr(out->name, ':'), *compname = NULL;
    if (colon) {
        *colon = '\0';
        compname = colon + 1;
    }
    char *path = url_series_path(id, out->name, 0);
    if (!path) {
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    int rc = http_json(s, "GET", path, NULL, HTTP_TIMEOUT, &out->doc);
    free(path);
    if (rc != RC_OK)
        return rc;
    json_t *t = json_object_get(out->doc, "time"), *v = json_object_get(out->doc, "value");
    if (!json_is_array(t) || !json_is_array(v) || json_array_size(t) != json_array_size(v)) {
        fprintf(stderr, "tlsph: series %s: 'time' and 'value' are not arrays of the same length\n", out->name);
        return RC_NETWORK;
    }
    json_t *first = json_array_get(v, 0);
    json_t *comps = json_object_get(out->doc, "components");
    if (json_is_array(first))
        out->ncomp = json_array_size(first);
    else if (json_is_array(comps))
        out->ncomp = json_array_size(comps);
    if (compname) {
        if (out->ncomp == 0) {
            fprintf(stderr, "tlsph: series %s is scalar; no component '%s'\n", out->name, compname);
            return RC_USAGE;
        }
        char *end;
        long c = strtol(compname, &end, 10);
        if (*compname && !*end) {
            out->comp = (int)c;
        } else {
            size_t k;
            json_t *cn;
            json_array_foreach(comps, k, cn) if (json_string_value(cn) && strcmp(json_string_value(cn), compname) == 0)
                out->comp = (int)k;
        }
        if (out->comp < 0 || (size_t)out->comp >= out->ncomp) {
            fprintf(stderr, "tlsph: series %s has no component '%s' (0..%zu)\n", out->name, compname,
                    out->ncomp - 1);
            return RC_USAGE;
        }
    }
    return RC_OK;
}

static void series_free(series_ref *r)
{
    free(r->name);
    json_decref(r->doc);
    memset(r, 0, sizeof *r);
}

/* Value i of component c (-1 for scalar series); NAN when missing. */
static double series_value(const series_ref *r, size_t i, int c)
{
    json_t *v = json_array_get(json_object_get(r->doc, "value"), i);
    if (c >= 0)
        v = json_array_get(v, (size_t)c);
    return json_is_number(v) ? json_number_value(v) : NAN;
}

/* The legend label ("name[x]", "name[1]", "name") and what the line shows. */
static void name_line(const series_ref *r, int c, line_names *nm, plot_quantity *q)
{
    const char *units = json_string_value(json_object_get(r->doc, "units"));
    nm->component[0] = '\0';
    if (c >= 0) {
        const char *cn = json_string_value(json_array_get(json_object_get(r->doc, "components"), (size_t)c));
        if (cn)
            snprintf(nm->component, sizeof nm->component, "%s", cn);
        else
            snprintf(nm->component, sizeof nm->component, "%d", c);
        snprintf(nm->label, sizeof nm->label, "%s[%s]", r->name, nm->component);
    } else {
        snprintf(nm->label, sizeof nm->label, "%s", r->name);
    }
    plot_name_split(r->name, nm->owner, sizeof nm->owner, nm->quantity, sizeof nm->quantity);
    q->quantity = nm->quantity;
    q->component = c >= 0 ? nm->component : NULL;
    q->owner = nm->owner[0] ? nm->owner : NULL;
    q->units = units ? units : "";
}

/* Builds one plot line: y = component c of ys versus time or versus xs
 * (component xc), pairing points by step.  Non-finite points are left out, and
 * on a log axis points with y <= 0 (counted in *nonpositive). */
static int make_line(const series_ref *ys, int c, const series_ref *xs, int xc, int log_y, plot_line *pl,
                     line_names *nm, size_t *nonpositive)
{
    json_t *ysteps = json_object_get(ys->doc, "step"), *ytime = json_object_get(ys->doc, "time");
    size_t n = json_array_size(ytime);
    double *x = malloc((n ? n : 1) * sizeof *x), *y = malloc((n ? n : 1) * sizeof *y);
    if (!x || !y) {
        free(x);
        free(y);
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    name_line(ys, c, nm, &pl->what);
    size_t m = 0, j = 0;
    *nonpositive = 0;
    json_t *xsteps = xs ? json_object_get(xs->doc, "step") : NULL;
    size_t nx = json_array_size(xsteps);
    for (size_t i = 0; i < n; i++) {
        double xv;
        if (!xs) {
            xv = json_number_value(json_array_get(ytime, i));
        } else {
            /* steps ascend in both series: advance j to the same step */
            json_int_t st = json_integer_value(json_array_get(ysteps, i));
            while (j < nx && json_integer_value(json_array_get(xsteps, j)) < st)
                j++;
            if (j >= nx || json_integer_value(json_array_get(xsteps, j)) != st)
                continue;
            xv = series_value(xs, j, xc);
        }
        double yv = series_value(ys, i, c);
        if (!isfinite(xv) || !isfinite(yv))
            continue;
        if (log_y && yv <= 0) {
            (*nonpositive)++;
            continue;
        }
        x[m] = xv;
        y[m] = yv;
        m++;
    }
    pl->x = x;
    pl->y = y;
    pl->n = m;
    pl->label = nm->label;
    return RC_OK;
}

static int write_svg(const char *out, const plot_axes *ax, const plot_line *lines, size_t nl)
{
    FILE *f = fopen(out, "w");
    if (!f) {
        fprintf(stderr, "tlsph: cannot write %s: %s\n", out, strerror(errno));
        return RC_IO;
    }
    int werr = svg_plot_write(f, ax, lines, nl);
    if (fclose(f) != 0 && werr == 0)
        werr = -1;
    if (werr == -2) {
        fprintf(stderr,
                "tlsph plot: the series need more than %d panels (one per unit and magnitude); "
                "plot fewer at a time, or use --log\n",
                PLOT_MAX_PANELS);
        remove(out);
        return RC_USAGE;
    }
    if (werr != 0) {
        fprintf(stderr, "tlsph: cannot write %s: %s\n", out, errno ? strerror(errno) : "out of memory");
        return RC_IO;
    }
    return RC_OK;
}

int cmd_plot(const settings *s, int argc, char **argv)
{
    const char *id = NULL, *out = NULL, *xspec = NULL, *title = NULL;
    int nnames = 0, log_y = 0, rc = RC_OK;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (strcmp(argv[i], "--x") == 0 && i + 1 < argc)
            xspec = argv[++i];
        else if (strcmp(argv[i], "--title") == 0 && i + 1 < argc)
            title = argv[++i];
        else if (strcmp(argv[i], "--log") == 0)
            log_y = 1;
        else if ((rc = take_id_or_name("plot", "unknown option or missing value", argv[i], &id, &nnames)) !=
                 RC_OK)
            return rc;
    }
    if (!id || nnames == 0)
        return usage_error("plot", "usage: tlsph plot ID NAME[:COMP]... -o FILE.svg [--x NAME[:COMP]] [--log]",
                           NULL);
    if (!out)
        return usage_error("plot", "missing -o FILE.svg", NULL);
    if ((rc = id_check(id)) != RC_OK)
        return rc;

    series_ref *refs = calloc((size_t)nnames, sizeof *refs);
    series_ref xref;
    memset(&xref, 0, sizeof xref);
    size_t maxlines = 0, nl = 0;
    plot_line *lines = NULL;
    line_names *names = NULL, xnames;
    size_t *dropped = NULL;
    char xlabel[700] = "time [s]";
    if (!refs) {
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    int k = 0;
    for (int i = 1; i < argc && rc == RC_OK; i++) {
        if (strcmp(argv[i], "-o") == 0 || strcmp(argv[i], "--x") == 0 || strcmp(argv[i], "--title") == 0) {
            i++;
            continue;
        }
        if (argv[i][0] == '-' || argv[i] == id)
            continue;
        rc = load_series(s, id, argv[i], &refs[k]);
        maxlines += refs[k].comp < 0 && refs[k].ncomp > 0 ? refs[k].ncomp : 1;
        k++;
    }
    if (rc == RC_OK && xspec) {
        rc = load_series(s, id, xspec, &xref);
        if (rc == RC_OK && xref.ncomp > 0 && xref.comp < 0) {
            fprintf(stderr, "tlsph: --x %s is a vector series: choose a component, e.g. %s:0\n", xspec, xspec);
            rc = RC_USAGE;
        }
        if (rc == RC_OK) {
            plot_quantity q;
            name_line(&xref, xref.comp, &xnames, &q);
            plot_axis_label(xlabel, sizeof xlabel, sizeof xlabel - 1, &q, 1);
        }
    }
    if (rc == RC_OK) {
        lines = calloc(maxlines, sizeof *lines);
        names = calloc(maxlines, sizeof *names);
        dropped = calloc(maxlines, sizeof *dropped);
        if (!lines || !names || !dropped) {
            fprintf(stderr, "tlsph: out of memory\n");
            rc = RC_IO;
        }
    }
    for (int i = 0; i < nnames && rc == RC_OK; i++) {
        int c0 = refs[i].comp, c1 = refs[i].comp;
        if (refs[i].comp < 0 && refs[i].ncomp > 0) {
            c0 = 0;
            c1 = (int)refs[i].ncomp - 1;
        }
        for (int c = c0; c <= c1 && rc == RC_OK; c++) {
            rc = make_line(&refs[i], c, xspec ? &xref : NULL, xref.comp, log_y, &lines[nl], &names[nl],
                           &dropped[nl]);
            if (rc == RC_OK)
                nl++;
        }
    }
    if (rc == RC_OK) {
        plot_axes ax = {title, xlabel, log_y, 0, 0};
        rc = write_svg(out, &ax, lines, nl);
        for (size_t l = 0; rc == RC_OK && l < nl; l++) {
            fprintf(stderr, "%s: %zu points", lines[l].label, lines[l].n);
            if (dropped[l])
                fprintf(stderr, " (%zu points <= 0 left out of the log axis)", dropped[l]);
            fputc('\n', stderr);
        }
    }
    for (size_t l = 0; l < nl; l++) {
        free((void *)lines[l].x);
        free((void *)lines[l].y);
    }
    free(lines);
    free(names);
    free(dropped);
    for (int i = 0; i < nnames; i++)
        series_free(&refs[i]);
    free(refs);
    series_free(&xref);
    return rc;
}
