/* Result commands: fetch (resumable download), series (JSON/CSV), plot (SVG). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "commands.h"
#include "exitcodes.h"
#include "http.h"
#include "svg_plot.h"
#include "urls.h"

/* mkdir -p */
static int make_dirs(const char *dir)
{
    char *p = strdup(dir);
    if (!p) {
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    int rc = RC_OK;
    for (char *q = p + 1;; q++) {
        if (*q == '/' || *q == '\0') {
            char c = *q;
            *q = '\0';
            if (mkdir(p, 0777) != 0 && errno != EEXIST) {
                fprintf(stderr, "tlsph: cannot create directory %s: %s\n", p, strerror(errno));
                rc = RC_IO;
                break;
            }
            *q = c;
            if (c == '\0')
                break;
        }
    }
    free(p);
    struct stat st;
    if (rc == RC_OK && (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))) {
        fprintf(stderr, "tlsph: %s is not a directory\n", dir);
        rc = RC_IO;
    }
    return rc;
}

int cmd_fetch(const settings *s, int argc, char **argv)
{
    const char *id = NULL, *dir = NULL;
    int rc;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            dir = argv[++i];
        else if ((rc = take_id("fetch", "job", argv[i], &id)) != RC_OK)
            return rc;
    }
    if ((rc = need_id("fetch", "job", id)) != RC_OK)
        return rc;
    if (!dir || !*dir)
        dir = id;
    if ((rc = make_dirs(dir)) != RC_OK)
        return rc;
    const char *files[] = {"result.h5", "result.xmf"};
    for (int k = 0; k < 2 && rc == RC_OK; k++) {
        char path[128], dest[4096];
        snprintf(path, sizeof path, "/jobs/%s/results/%s", id, files[k]);
        if ((size_t)snprintf(dest, sizeof dest, "%s/%s", dir, files[k]) >= sizeof dest)
            return usage_error("fetch", "directory name too long", dir);
        rc = http_download(s, path, dest);
        if (rc == RC_OK)
            printf("%s\n", dest);
    }
    if (fflush(stdout) != 0)
        rc = RC_IO;
    return rc;
}

/* "/jobs/ID/results/series/NAME[?format=csv]", name percent-encoded keeping '/'. */
static char *series_path(const char *id, const char *name, int csv)
{
    char *esc = url_escape(name, 1);
    if (!esc)
        return NULL;
    size_t n = strlen(esc) + 96;
    char *p = malloc(n);
    if (p)
        snprintf(p, n, "/jobs/%s/results/series/%s%s", id, esc, csv ? "?format=csv" : "");
    free(esc);
    return p;
}

/* ID NAME...: the first argument that is no option is the job ID, the others
 * are series names (counted in *nnames); an unknown option is a usage error (msg). */
static int id_or_name(const char *cmd, const char *msg, const char *arg, const char **id, int *nnames)
{
    if (arg[0] == '-')
        return usage_error(cmd, msg, arg);
    if (!*id)
        *id = arg;
    else
        (*nnames)++;
    return RC_OK;
}

static int write_out(const char *d, size_t n)
{
    if (fwrite(d, 1, n, stdout) != n) {
        fprintf(stderr, "tlsph: cannot write the output: %s\n", strerror(errno));
        return RC_IO;
    }
    return RC_OK;
}

static int list_series(const settings *s, const char *id)
{
    char path[96];
    snprintf(path, sizeof path, "/jobs/%s/results/series", id);
    json_t *doc;
    int rc = http_json(s, "GET", path, NULL, HTTP_TIMEOUT, &doc);
    if (rc != RC_OK)
        return rc;
    size_t i;
    json_t *e;
    int w = 4;
    json_array_foreach(json_object_get(doc, "series"), i, e)
    {
        const char *nm = json_string_value(json_object_get(e, "name"));
        if (nm && (int)strlen(nm) > w && strlen(nm) < 80)
            w = (int)strlen(nm);
    }
    printf("%-*s  %-8s  %s\n", w, "NAME", "UNITS", "COMPONENTS");
    json_array_foreach(json_object_get(doc, "series"), i, e)
    {
        const char *nm = json_string_value(json_object_get(e, "name"));
        const char *un = json_string_value(json_object_get(e, "units"));
        json_t *comps = json_object_get(e, "components");
        printf("%-*s  %-8s  ", w, nm ? nm : "?", un && *un ? un : "-");
        if (json_is_array(comps)) {
            size_t k;
            json_t *c;
            json_array_foreach(comps, k, c) printf("%s%s", k ? "," : "", json_string_value(c) ? json_string_value(c) : "?");
        } else {
            fputs("-", stdout);
        }
        putchar('\n');
    }
    json_decref(doc);
    return RC_OK;
}

int cmd_series(const settings *s, int argc, char **argv)
{
    const char *id = NULL;
    int csv = 0, nnames = 0, rc;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--csv") == 0)
            csv = 1;
        else if ((rc = id_or_name("series", "unknown option", argv[i], &id, &nnames)) != RC_OK)
            return rc;
    }
    if ((rc = need_id("series", "job", id)) != RC_OK)
        return rc;
    if (nnames == 0)
        return list_series(s, id);
    int k = 0;
    if (!csv && nnames > 1)
        rc = write_out("[", 1);
    for (int i = 1; i < argc && rc == RC_OK; i++) {
        if (argv[i][0] == '-' || argv[i] == id)
            continue;
        char *path = series_path(id, argv[i], csv);
        if (!path) {
            fprintf(stderr, "tlsph: out of memory\n");
            return RC_IO;
        }
        http_response r;
        rc = http_text(s, path, &r);
        free(path);
        if (rc != RC_OK)
            break;
        if (k > 0)
            rc = write_out(csv ? "\n" : ",", 1);
        size_t len = r.len;
        if (!csv && nnames > 1)
            while (len > 0 && (r.body[len - 1] == '\n' || r.body[len - 1] == '\r'))
                len--;
        if (rc == RC_OK)
            rc = write_out(r.body, len);
        http_response_free(&r);
        k++;
    }
    if (rc == RC_OK && !csv && nnames > 1)
        rc = write_out("]\n", 2);
    if (fflush(stdout) != 0 && rc == RC_OK)
        rc = RC_IO;
    return rc;
}

/* ------------------------------------------------------------ plot */
typedef struct {
    char *name;    /* series name without ":comp" */
    int comp;      /* -1: all (vector) / scalar */
    json_t *doc;   /* series document */
    size_t ncomp;  /* components per value, 0 = scalar */
} series_ref;

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
    char *path = series_path(id, out->name, 0);
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

static const char *series_units(const series_ref *r)
{
    const char *u = json_string_value(json_object_get(r->doc, "units"));
    return u ? u : "";
}

/* Component label "name[x]" / "name:1" / "name". */
static char *comp_label(const series_ref *r, int c)
{
    char buf[600];
    if (c < 0) {
        snprintf(buf, sizeof buf, "%s", r->name);
    } else {
        const char *cn = json_string_value(json_array_get(json_object_get(r->doc, "components"), (size_t)c));
        if (cn)
            snprintf(buf, sizeof buf, "%s[%s]", r->name, cn);
        else
            snprintf(buf, sizeof buf, "%s[%d]", r->name, c);
    }
    return strdup(buf);
}

/* Builds one plot line: y = component c of ys versus time or versus xs (component xc),
 * pairing points by step; non-finite points are left out. */
static int make_line(const series_ref *ys, int c, const series_ref *xs, int xc, plot_line *pl, char **label)
{
    json_t *ysteps = json_object_get(ys->doc, "step"), *ytime = json_object_get(ys->doc, "time");
    size_t n = json_array_size(ytime);
    double *x = malloc((n ? n : 1) * sizeof *x), *y = malloc((n ? n : 1) * sizeof *y);
    *label = comp_label(ys, c);
    if (!x || !y || !*label) {
        free(x);
        free(y);
        free(*label);
        *label = NULL;
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    size_t m = 0, j = 0;
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
        x[m] = xv;
        y[m] = yv;
        m++;
    }
    pl->x = x;
    pl->y = y;
    pl->n = m;
    pl->label = *label;
    return RC_OK;
}

int cmd_plot(const settings *s, int argc, char **argv)
{
    const char *id = NULL, *out = NULL, *xspec = NULL, *title = NULL;
    int nnames = 0, rc;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (strcmp(argv[i], "--x") == 0 && i + 1 < argc)
            xspec = argv[++i];
        else if (strcmp(argv[i], "--title") == 0 && i + 1 < argc)
            title = argv[++i];
        else if ((rc = id_or_name("plot", "unknown option or missing value", argv[i], &id, &nnames)) !=
                 RC_OK)
            return rc;
    }
    if (!id || nnames == 0)
        return usage_error("plot", "usage: tlsph plot ID NAME[:COMP]... -o FILE.svg [--x NAME[:COMP]]", NULL);
    if (!out)
        return usage_error("plot", "missing -o FILE.svg", NULL);
    if ((rc = id_check(id)) != RC_OK)
        return rc;

    series_ref *refs = calloc((size_t)nnames, sizeof *refs);
    series_ref xref;
    memset(&xref, 0, sizeof xref);
    size_t maxlines = 0, nl = 0;
    plot_line *lines = NULL;
    char **labels = NULL;
    char ylabel[1024] = "", xlabel[700] = "time [s]";
    if (!refs) {
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    int k = 0;
    for (int i = 1; i < argc && rc == RC_OK; i++) {
        if (argv[i][0] == '-') {
            if (strcmp(argv[i], "-o") == 0 || strcmp(argv[i], "--x") == 0 || strcmp(argv[i], "--title") == 0)
                i++;
            continue;
        }
        if (argv[i] == id)
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
            char *xl = comp_label(&xref, xref.comp);
            if (!xl)
                rc = RC_IO;
            else
                snprintf(xlabel, sizeof xlabel, "%s [%s]", xl, *series_units(&xref) ? series_units(&xref) : "-");
            free(xl);
        }
    }
    if (rc == RC_OK) {
        lines = calloc(maxlines, sizeof *lines);
        labels = calloc(maxlines, sizeof *labels);
        if (!lines || !labels) {
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
            rc = make_line(&refs[i], c, xspec ? &xref : NULL, xref.comp, &lines[nl], &labels[nl]);
            if (rc == RC_OK)
                nl++;
        }
        /* y label: the units (distinct ones joined); with one series its name too */
        const char *u = *series_units(&refs[i]) ? series_units(&refs[i]) : "-";
        size_t ul = strlen(ylabel);
        if (!strstr(ylabel, u) && ul + strlen(u) + 3 < sizeof ylabel)
            snprintf(ylabel + ul, sizeof ylabel - ul, "%s%s", ul ? ", " : "", u);
    }
    if (rc == RC_OK) {
        char yl[1200];
        if (nl == 1)
            snprintf(yl, sizeof yl, "%s [%s]", labels[0], ylabel);
        else
            snprintf(yl, sizeof yl, "[%s]", ylabel);
        plot_axes ax = {title, xlabel, yl};
        FILE *f = fopen(out, "w");
        if (!f) {
            fprintf(stderr, "tlsph: cannot write %s: %s\n", out, strerror(errno));
            rc = RC_IO;
        } else {
            int werr = svg_plot_write(f, &ax, lines, nl);
            if (fclose(f) != 0 || werr != 0) {
                fprintf(stderr, "tlsph: cannot write %s: %s\n", out, strerror(errno));
                rc = RC_IO;
            }
        }
        if (rc == RC_OK)
            for (size_t l = 0; l < nl; l++)
                fprintf(stderr, "%s: %zu points\n", labels[l], lines[l].n);
    }
    for (size_t l = 0; l < nl; l++) {
        free((void *)lines[l].x);
        free((void *)lines[l].y);
        free(labels[l]);
    }
    free(lines);
    free(labels);
    for (int i = 0; i < nnames; i++)
        series_free(&refs[i]);
    free(refs);
    series_free(&xref);
    return rc;
}
