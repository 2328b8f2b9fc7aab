/* Convergence commands: convergence submit | table | plot.  The daemon
 * computes the result (GET /jobs/ID/results/convergence); the client prints
 * it and draws the estimated error of each output against the wall time of
 * each run (log-log), with the prediction for the target and, given a
 * reference value, the true error beside the estimate. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "exitcodes.h"
#include "http.h"
#include "svg_plot.h"

#define MAX_LINES 48
#define MAX_REFS 16

static void print_number(FILE *f, const json_t *v, const char *fmt)
{
    if (json_is_number(v))
        fprintf(f, fmt, json_number_value(v));
    else
        fprintf(f, "%12s", "-");
}

/* "spacing S m, particles N, wall W s, peak memory M MiB" of a prediction. */
static void print_spacing_cost(FILE *f, const json_t *p)
{
    fprintf(f, "spacing ");
    print_number(f, json_object_get(p, "spacing"), "%.5g m");
    fprintf(f, ", particles ");
    print_number(f, json_object_get(p, "particles"), "%.0f");
    fprintf(f, ", wall ");
    print_number(f, json_object_get(p, "wall_seconds"), "%.4g s");
    fprintf(f, ", peak memory ");
    const json_t *m = json_object_get(p, "peak_memory_bytes");
    if (json_is_number(m))
        fprintf(f, "%.1f MiB", json_number_value(m) / 1048576.0);
    else
        fprintf(f, "-");
}

/* Text: the runs, then per output its values, errors and verdict. */
static void print_result(FILE *f, const json_t *d)
{
    const json_t *runs = json_object_get(d, "runs");
    fprintf(f, "ladder ratio %.4g, %zu runs%s (finest first)\n",
            json_number_value(json_object_get(d, "ratio")), json_array_size(runs),
            json_is_true(json_object_get(d, "complete")) ? "" : ", not all finished");
    fprintf(f, "%12s %12s %12s %12s %12s  %s\n", "spacing[m]", "particles", "steps", "wall[s]",
            "memory[MiB]", "status");
    size_t i, k;
    json_t *r, *o;
    json_array_foreach(runs, i, r) {
        print_number(f, json_object_get(r, "spacing"), "%12.5g");
        print_number(f, json_object_get(r, "particles"), " %12.0f");
        print_number(f, json_object_get(r, "steps"), " %12.0f");
        print_number(f, json_object_get(r, "wall_seconds"), " %12.4g");
        const json_t *m = json_object_get(r, "peak_memory_bytes");
        if (json_is_number(m))
            fprintf(f, " %12.1f", json_number_value(m) / 1048576.0);
        else
            fprintf(f, " %12s", "-");
        fprintf(f, "  %s\n", json_string_value(json_object_get(r, "status")));
    }
    const json_t *cw = json_object_get(json_object_get(d, "cost_model"), "wall_seconds");
    if (json_is_object(cw))
        fprintf(f, "cost model: wall = %.4g s x h^-%.3g (h in m; rms log residual %.3g, %lld runs)\n",
                json_number_value(json_object_get(cw, "coefficient")),
                json_number_value(json_object_get(cw, "q")),
                json_number_value(json_object_get(cw, "rms_log_residual")),
                (long long)json_integer_value(json_object_get(cw, "points")));
    json_array_foreach(json_object_get(d, "outputs"), i, o) {
        fprintf(f, "\n%s (%s of %s): %s\n", json_string_value(json_object_get(o, "name")),
                json_string_value(json_object_get(o, "reduce")),
                json_string_value(json_object_get(o, "series")),
                json_string_value(json_object_get(o, "status")));
        fprintf(f, "  %s\n", json_string_value(json_object_get(o, "reason")));
        fprintf(f, "  observed order ");
        print_number(f, json_object_get(o, "observed_order"), "%.4g");
        fprintf(f, ", extrapolated ");
        print_number(f, json_object_get(o, "extrapolated"), "%.10g");
        fprintf(f, ", Fs %.3g\n", json_number_value(json_object_get(o, "safety_factor")));
        const json_t *osc = json_object_get(o, "oscillation");
        if (json_is_number(osc))
            fprintf(f, "  oscillation: half range %.4g of the three finest values (%.3g of the "
                    "finest)\n", json_number_value(osc),
                    json_number_value(json_object_get(o, "oscillation_relative")));
        fprintf(f, "  %12s %16s %12s %12s %12s\n", "spacing[m]", "value", "error", "rel.error",
                "GCI");
        json_array_foreach(runs, k, r) {
            fprintf(f, "  ");
            print_number(f, json_object_get(r, "spacing"), "%12.5g");
            print_number(f, json_array_get(json_object_get(o, "values"), k), " %16.10g");
            print_number(f, json_array_get(json_object_get(o, "error_estimate"), k), " %12.4g");
            print_number(f, json_array_get(json_object_get(o, "relative_error"), k), " %12.4g");
            print_number(f, json_array_get(json_object_get(o, "gci"), k), " %12.4g");
            fputc('\n', f);
        }
        const json_t *p = json_object_get(o, "prediction");
        if (json_is_object(p)) {
            fprintf(f, "  target GCI %.3g: ", json_number_value(json_object_get(p, "relative_error")));
            print_spacing_cost(f, p);
            fprintf(f, "%s\n", json_is_true(json_object_get(p, "already_met")) ? " (already met)" : "");
            const json_t *ls = json_object_get(p, "ladder_step");
            if (json_is_object(ls)) {
                fprintf(f, "  next ladder step (GCI ");
                print_number(f, json_object_get(ls, "relative_error"), "%.3g");
                fprintf(f, "): ");
                print_spacing_cost(f, ls);
                fputc('\n', f);
            }
        }
    }
}

static int fetch(const settings *s, const char *id, int csv, json_t **doc)
{
    char path[128];
    snprintf(path, sizeof path, "/jobs/%s/results/convergence%s", id, csv ? "?format=csv" : "");
    if (!csv)
        return http_json(s, "GET", path, NULL, HTTP_TIMEOUT, doc);
    http_response r;
    int rc = http_text(s, path, &r);
    if (rc != RC_OK)
        return rc;
    if (fwrite(r.body, 1, r.len, stdout) != r.len || fflush(stdout) != 0)
        rc = RC_IO;
    http_response_free(&r);
    return rc;
}

static int conv_table(const settings *s, int argc, char **argv)
{
    const char *id = NULL;
    int csv = 0, json = 0, rc = RC_OK;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--csv") == 0)
            csv = 1;
        else if (strcmp(argv[i], "--json") == 0)
            json = 1;
        else if ((rc = take_id("convergence table", "job", argv[i], &id)) != RC_OK)
            return rc;
    }
    if ((rc = need_id("convergence table", "job", id)) != RC_OK)
        return rc;
    json_t *doc = NULL;
    if ((rc = fetch(s, id, csv, &doc)) != RC_OK || csv)
        return rc;
    if (json) {
        if (json_dumpf(doc, stdout, JSON_INDENT(2)) != 0)
            rc = RC_IO;
        putchar('\n');
    } else {
        print_result(stdout, doc);
    }
    json_decref(doc);
    return fflush(stdout) != 0 ? RC_IO : rc;
}

/* The strings and points of one plotted line. */
typedef struct {
    char label[160], quantity[160];
    double x[16], y[16];
} line_store;

static size_t add_points(line_store *st, const json_t *runs, const json_t *err, double ref_scale)
{
    size_t n = 0, k;
    json_t *r;
    json_array_foreach(runs, k, r) {
        const json_t *w = json_object_get(r, "wall_seconds"), *e = json_array_get(err, k);
        if (n < 16 && json_is_number(w) && json_is_number(e) && json_number_value(w) > 0 &&
            json_number_value(e) * ref_scale > 0) {
            st->x[n] = json_number_value(w);
            st->y[n] = json_number_value(e) * ref_scale;
            n++;
        }
    }
    return n;
}

/* REF of --reference NAME=VALUE for output name, or NAN. */
static double reference_of(const char *const *refs, size_t nrefs, const char *name)
{
    size_t len = strlen(name);
    for (size_t i = 0; i < nrefs; i++)
        if (strncmp(refs[i], name, len) == 0 && refs[i][len] == '=')
            return strtod(refs[i] + len + 1, NULL);
    return NAN;
}

static int write_plot(const char *out, const char *title, const json_t *d, const char *const *refs,
                      size_t nrefs)
{
    line_store *st = calloc(MAX_LINES, sizeof *st);
    plot_line lines[MAX_LINES];
    size_t nl = 0, i;
    json_t *o;
    const json_t *runs = json_object_get(d, "runs");
    if (!st) {
        fprintf(stderr, "tlsph: out of memory\n");
        return RC_IO;
    }
    json_array_foreach(json_object_get(d, "outputs"), i, o) {
        const char *name = json_string_value(json_object_get(o, "name"));
        if (!name || nl + 3 > MAX_LINES)
            continue;
        /* the estimate: |f_i - f_ext| / |f_ext| */
        line_store *e = &st[nl];
        snprintf(e->label, sizeof e->label, "%s: estimated error", name);
        snprintf(e->quantity, sizeof e->quantity, "relative error");
        size_t n = add_points(e, runs, json_object_get(o, "relative_error"), 1.0);
        if (n > 0)
            lines[nl++] = (plot_line){e->label, {e->quantity, NULL, NULL, "1"}, n, e->x, e->y};
        /* the truth, when the user knows it: |f_i - ref| / |ref| */
        const double ref = reference_of(refs, nrefs, name);
        if (isfinite(ref) && ref != 0) {
            line_store *t = &st[nl];
            json_t *err = json_array();
            size_t k;
            json_t *v;
            json_array_foreach(json_object_get(o, "values"), k, v)
                json_array_append_new(err, json_is_number(v) ? json_real(fabs(json_number_value(v) - ref) / fabs(ref))
                                                             : json_null());
            snprintf(t->label, sizeof t->label, "%s: true error (reference %g)", name, ref);
            snprintf(t->quantity, sizeof t->quantity, "relative error");
            n = add_points(t, runs, err, 1.0);
            json_decref(err);
            if (n > 0)
                lines[nl++] = (plot_line){t->label, {t->quantity, NULL, NULL, "1"}, n, t->x, t->y};
        }
        /* the prediction: from the finest run to (predicted wall, target) */
        const json_t *p = json_object_get(o, "prediction");
        const json_t *pw = json_object_get(p, "wall_seconds"), *pt = json_object_get(p, "relative_error");
        if (n > 0 && e->x[0] > 0 && json_is_number(pw) && json_number_value(pw) > 0 &&
            json_is_number(pt)) {
            line_store *q = &st[nl];
            /* the error model's target is the GCI = Fs x relative error: draw
             * the relative error it implies */
            const double fs = json_number_value(json_object_get(o, "safety_factor"));
            q->x[0] = e->x[0];
            q->y[0] = e->y[0];
            q->x[1] = json_number_value(pw);
            q->y[1] = json_number_value(pt) / (fs > 0 ? fs : 1.0);
            snprintf(q->label, sizeof q->label, "%s: prediction for GCI %g", name, json_number_value(pt));
            snprintf(q->quantity, sizeof q->quantity, "relative error");
            lines[nl++] = (plot_line){q->label, {q->quantity, NULL, NULL, "1"}, 2, q->x, q->y};
        }
    }
    if (nl == 0) {
        fprintf(stderr, "tlsph: no output has an error estimate to plot (see `tlsph convergence "
                        "table`)\n");
        free(st);
        return RC_FAILED;
    }
    FILE *f = fopen(out, "w");
    if (!f) {
        perror(out);
        free(st);
        return RC_IO;
    }
    plot_axes ax = {title, "wall time [s]", 1, 1, 1};
    int werr = svg_plot_write(f, &ax, lines, nl);
    if (fclose(f) != 0 || werr != 0) {
        fprintf(stderr, "tlsph: cannot write %s\n", out);
        free(st);
        return RC_IO;
    }
    free(st);
    return RC_OK;
}

static int conv_plot(const settings *s, int argc, char **argv)
{
    const char *id = NULL, *out = NULL, *title = "estimated error vs wall time";
    const char *refs[MAX_REFS];
    size_t nrefs = 0;
    int rc;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (strcmp(argv[i], "--title") == 0 && i + 1 < argc)
            title = argv[++i];
        else if (strcmp(argv[i], "--reference") == 0 && i + 1 < argc) {
            if (nrefs == MAX_REFS || !strchr(argv[i + 1], '='))
                return usage_error("convergence plot", "--reference NAME=VALUE (at most 16)",
                                   argv[i + 1]);
            refs[nrefs++] = argv[++i];
        } else if ((rc = take_id("convergence plot", "job", argv[i], &id)) != RC_OK)
            return rc;
    }
    if ((rc = need_id("convergence plot", "job", id)) != RC_OK)
        return rc;
    if (!out)
        return usage_error("convergence plot", "missing -o FILE.svg", NULL);
    json_t *doc = NULL;
    if ((rc = fetch(s, id, 0, &doc)) != RC_OK)
        return rc;
    rc = write_plot(out, title, doc, refs, nrefs);
    json_decref(doc);
    return rc;
}

int cmd_convergence(const settings *s, int argc, char **argv)
{
    if (argc < 2)
        return usage_error("convergence", "expected submit, table or plot", NULL);
    const char *sub = argv[1];
    if (strcmp(sub, "submit") == 0)
        return submit_file(s, argc - 1, argv + 1, "convergence submit", "CONVERGENCE.json",
                           "convergence", NULL);
    if (strcmp(sub, "table") == 0)
        return conv_table(s, argc - 1, argv + 1);
    if (strcmp(sub, "plot") == 0)
        return conv_plot(s, argc - 1, argv + 1);
    return usage_error("convergence", "unknown subcommand", sub);
}
