/* The convergence result from a study's children (convergence.h): values per
 * output and resolution, the Richardson/GCI estimate (richardson.h), the
 * measured cost of each run, the fitted cost model and the prediction. */
#include "convergence.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "richardson.h"

/* One run, finest first after sorting. */
struct run {
    const struct tstudy_row *row;
    double h;                    /* the first pointer's spacing, m */
    double particles, steps, wall, memory, bpp;
    int ok;                      /* successful: its values count */
};

static json_t *num(double v)
{
    return isfinite(v) ? json_real(v) : json_null();
}

static double cost_of(const json_t *cost, const char *key)
{
    const json_t *v = json_is_object(cost) ? json_object_get(cost, key) : NULL;
    return json_is_number(v) ? json_number_value(v) : NAN;
}

static int by_spacing(const void *a, const void *b)
{
    const struct run *x = a, *y = b;
    return x->h < y->h ? -1 : x->h > y->h ? 1 : 0;
}

static json_t *fit_json(const double *h, const double *y, size_t n)
{
    struct trich_power_fit f;
    if (trich_fit_power(h, y, n, &f) != 0)
        return json_null();
    return json_pack("{s:o,s:o,s:o,s:I}", "q", num(f.q), "coefficient", num(f.c),
                     "rms_log_residual", num(f.rms_log_residual), "points", (json_int_t)f.n);
}

/* Least squares mem = a + b N over the runs with both known (peak RSS holds a
 * fixed part: the program, HDF5, the allocator).  0 or -1. */
static int linear_fit(const double *x, const double *y, size_t n, double *a, double *b)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(x[i]) && isfinite(y[i]) && x[i] > 0 && y[i] > 0) {
            sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
            k++;
        }
    const double den = (double)k * sxx - sx * sx;
    if (k < 2 || !(den > 0))
        return -1;
    *b = ((double)k * sxy - sx * sy) / den;
    *a = (sy - *b * sx) / (double)k;
    return 0;
}

struct costs {
    double h[TCONV_MAX_RUNS], particles[TCONV_MAX_RUNS], steps[TCONV_MAX_RUNS];
    double psteps[TCONV_MAX_RUNS], wall[TCONV_MAX_RUNS], memory[TCONV_MAX_RUNS];
    size_t n;
    double bpp_finest;  /* engine bytes per particle of the finest successful run */
};

/* Spacing h for every pointer (each keeps its ratio to the first, as the
 * ladder does) and the fitted cost there, into o. */
static void cost_at(json_t *o, double h, const struct costs *c, const json_t *params)
{
    json_t *sp = json_object();
    const double s0 = json_number_value(
        json_array_get(json_object_get(json_array_get(params, 0), "values"), 0));
    size_t i;
    json_t *p;
    json_array_foreach(params, i, p) {
        const double si = json_number_value(json_array_get(json_object_get(p, "values"), 0));
        const char *ptr = json_string_value(json_object_get(p, "pointer"));
        if (ptr)
            json_object_set_new(sp, ptr, num(h * si / s0));
    }
    json_object_set_new(o, "spacing", num(h));
    json_object_set_new(o, "spacings", sp);
    struct trich_power_fit fp, fw, fs;
    const double N = trich_fit_power(c->h, c->particles, c->n, &fp) == 0 ? trich_power_eval(&fp, h) : NAN;
    const double W = trich_fit_power(c->h, c->wall, c->n, &fw) == 0 ? trich_power_eval(&fw, h) : NAN;
    const double S = trich_fit_power(c->h, c->psteps, c->n, &fs) == 0 ? trich_power_eval(&fs, h) : NAN;
    double a, b;
    const double M = linear_fit(c->particles, c->memory, c->n, &a, &b) == 0 ? a + b * N : NAN;
    json_object_set_new(o, "particles", num(round(N)));
    json_object_set_new(o, "particle_steps", num(S));
    json_object_set_new(o, "wall_seconds", num(W));
    json_object_set_new(o, "peak_memory_bytes", num(M));
    json_object_set_new(o, "engine_bytes", num(c->bpp_finest * N));
}

/* The prediction for target: the spacing where the modelled GCI reaches it
 * and, because a spacing that does not divide the scene's dimensions changes
 * the discretised geometry (a 20 mm plate at 0.91 mm holds 22 rows, 19.97 mm),
 * also the next ladder spacing below it (h1 r^k, commensurate with the
 * ladder) with its modelled GCI. */
static json_t *prediction(const struct trich_estimate *e, const double *hs, double target,
                          const struct costs *c, const json_t *params)
{
    const double ht = trich_spacing_for(e, hs, target);
    const double h1 = hs[e->first];
    if (isnan(ht))
        return json_null();
    json_t *o = json_object();
    json_object_set_new(o, "relative_error", json_real(target));
    if (isinf(ht)) {
        json_object_set_new(o, "already_met", json_true());
        json_object_set_new(o, "spacing", json_null());
        return o;
    }
    json_object_set_new(o, "already_met", json_boolean(ht >= h1));
    cost_at(o, ht, c, params);
    const double k = floor(log(ht / h1) / log(e->ratio) + 1e-9);
    const double hl = h1 * pow(e->ratio, k);
    json_t *step = json_object();
    cost_at(step, hl, c, params);
    json_object_set_new(step, "relative_error",
                        num(e->safety_factor * e->error[e->first] / fabs(e->extrapolated) *
                            pow(hl / h1, e->order)));
    json_object_set_new(o, "ladder_step", step);
    return o;
}

static double row_value(const json_t *output, const struct run *r, char *why, size_t size)
{
    why[0] = '\0';
    if (!r->ok) {
        snprintf(why, size, "run %ld is %s", r->row->seq, r->row->status ? r->row->status : "?");
        return NAN;
    }
    return tconv_output_value(output, r->row->h5path, why, size);
}

static json_t *output_result(const json_t *output, const struct run *runs, size_t n,
                             const struct costs *c, const json_t *target,
                             const json_t *params)
{
    double h[TCONV_MAX_RUNS], f[TCONV_MAX_RUNS];
    json_t *values = json_array(), *missing = json_array();
    for (size_t i = 0; i < n; i++) {
        char why[256];
        h[i] = runs[i].h;
        f[i] = row_value(output, &runs[i], why, sizeof why);
        json_array_append_new(values, num(f[i]));
        if (isnan(f[i]) && why[0])
            json_array_append_new(missing, json_string(why));
    }
    struct trich_estimate e;
    trich_estimate(h, f, n, &e);
    json_t *o = json_pack("{s:O,s:O,s:O,s:o}", "name", json_object_get(output, "name"), "series",
                          json_object_get(output, "series"), "reduce",
                          json_object_get(output, "reduce"), "values", values);
    json_object_set_new(o, "status", json_string(trich_kind_name(e.kind)));
    json_object_set_new(o, "reason", json_string(trich_kind_reason(e.kind)));
    if (json_array_size(missing))
        json_object_set_new(o, "missing", missing);
    else
        json_decref(missing);
    json_object_set_new(o, "observed_order", num(e.order));
    json_object_set_new(o, "order_coarse", num(e.order_coarse));
    json_object_set_new(o, "asymptotic_ratio", num(e.asymptotic_ratio));
    json_object_set_new(o, "extrapolated", num(e.extrapolated));
    json_object_set_new(o, "safety_factor", json_real(e.safety_factor));
    json_object_set_new(o, "oscillation", num(e.oscillation));
    json_object_set_new(o, "oscillation_relative", num(e.oscillation_relative));
    json_t *err = json_array(), *rel = json_array(), *gci = json_array();
    for (size_t i = 0; i < n; i++) {
        json_array_append_new(err, num(i < TRICH_MAX ? e.error[i] : NAN));
        json_array_append_new(rel, num(i < TRICH_MAX ? e.relative[i] : NAN));
        json_array_append_new(gci, num(i < TRICH_MAX ? e.gci[i] : NAN));
    }
    json_object_set_new(o, "error_estimate", err);
    json_object_set_new(o, "relative_error", rel);
    json_object_set_new(o, "gci", gci);
    const json_t *rt = json_object_get(target, "relative_error");
    if (json_is_number(rt))
        json_object_set_new(o, "prediction", prediction(&e, h, json_number_value(rt), c,
                                                        params));
    return o;
}

json_t *tconv_result(const json_t *stored, const struct tstudy_row *rows, size_t n)
{
    const json_t *conv = json_object_get(stored, "convergence");
    const json_t *ladder = json_object_get(conv, "ladder");
    const json_t *pointers = json_object_get(ladder, "pointers");
    const char *p0 = json_string_value(json_array_get(pointers, 0));
    const json_t *params = json_object_get(json_object_get(stored, "sweep"), "parameters");
    if (n > TCONV_MAX_RUNS)
        n = TCONV_MAX_RUNS;
    struct run runs[TCONV_MAX_RUNS];
    struct costs c = {.n = 0, .bpp_finest = NAN};
    size_t complete = 0;
    for (size_t i = 0; i < n; i++) {
        const json_t *hv = p0 && json_is_object(rows[i].params) ? json_object_get(rows[i].params, p0)
                                                                : NULL;
        runs[i].row = &rows[i];
        runs[i].h = json_is_number(hv) ? json_number_value(hv) : NAN;
        runs[i].ok = rows[i].status && !strcmp(rows[i].status, "successful");
        runs[i].particles = cost_of(rows[i].cost, "particles");
        runs[i].steps = cost_of(rows[i].cost, "steps");
        runs[i].wall = cost_of(rows[i].cost, "wall_seconds");
        runs[i].memory = cost_of(rows[i].cost, "peak_memory_bytes");
        runs[i].bpp = cost_of(rows[i].cost, "bytes_per_particle");
        if (rows[i].status && (runs[i].ok || !strcmp(rows[i].status, "failed") ||
                               !strcmp(rows[i].status, "dismissed")))
            complete++;
    }
    qsort(runs, n, sizeof *runs, by_spacing);
    json_t *jruns = json_array();
    for (size_t i = 0; i < n; i++) {
        const struct run *r = &runs[i];
        const double ps = r->particles * r->steps;
        json_array_append_new(
            jruns, json_pack("{s:I,s:s?,s:s?,s:o,s:o,s:o,s:o,s:o,s:o,s:o}", "seq",
                             (json_int_t)r->row->seq, "job_id", r->row->job_id, "status",
                             r->row->status, "spacing", num(r->h), "particles", num(r->particles),
                             "steps", num(r->steps), "particle_steps", num(ps), "wall_seconds",
                             num(r->wall), "peak_memory_bytes", num(r->memory),
                             "bytes_per_particle", num(r->bpp)));
        if (r->ok) {
            c.h[c.n] = r->h;
            c.particles[c.n] = r->particles;
            c.steps[c.n] = r->steps;
            c.psteps[c.n] = ps;
            c.wall[c.n] = r->wall;
            c.memory[c.n] = r->memory;
            if (isnan(c.bpp_finest))
                c.bpp_finest = r->bpp;
            c.n++;
        }
    }
    json_t *cost = json_object();
    json_object_set_new(cost, "wall_seconds", fit_json(c.h, c.wall, c.n));
    json_object_set_new(cost, "particle_steps", fit_json(c.h, c.psteps, c.n));
    json_object_set_new(cost, "particles", fit_json(c.h, c.particles, c.n));
    double a, b;
    if (linear_fit(c.particles, c.memory, c.n, &a, &b) == 0)
        json_object_set_new(cost, "peak_memory_bytes",
                            json_pack("{s:o,s:o}", "fixed", num(a), "per_particle", num(b)));
    else
        json_object_set_new(cost, "peak_memory_bytes", json_null());
    const json_t *target = json_object_get(conv, "target");
    json_t *outs = json_array();
    size_t i;
    json_t *o;
    json_array_foreach(json_object_get(conv, "outputs"), i, o)
        json_array_append_new(outs, output_result(o, runs, n, &c, target, params));
    json_t *res = json_pack("{s:b,s:O,s:O,s:o,s:o,s:o}", "complete", complete == n && n > 0,
                            "pointers", pointers, "ratio", json_object_get(ladder, "ratio"),
                            "runs", jruns, "cost_model", cost, "outputs", outs);
    if (res)
        json_object_set(res, "target", target ? (json_t *)target : json_null());
    return res;
}

json_t *tconv_result_table(const json_t *result)
{
    static const char *const cols[] = {
        "output", "status", "spacing", "value", "error_estimate", "relative_error", "gci",
        "observed_order", "extrapolated", "particles", "steps", "particle_steps",
        "wall_seconds", "peak_memory_bytes", NULL};
    json_t *columns = json_array(), *rows = json_array();
    for (const char *const *c = cols; *c; c++)
        json_array_append_new(columns, json_string(*c));
    const json_t *runs = json_object_get(result, "runs");
    size_t i, k;
    json_t *o, *r;
    json_array_foreach(json_object_get(result, "outputs"), i, o) {
        json_array_foreach(runs, k, r) {
            json_t *row = json_pack(
                "[O,O,O,O,O,O,O,O,O,O,O,O,O,O]", json_object_get(o, "name"),
                json_object_get(o, "status"), json_object_get(r, "spacing"),
                json_array_get(json_object_get(o, "values"), k),
                json_array_get(json_object_get(o, "error_estimate"), k),
                json_array_get(json_object_get(o, "relative_error"), k),
                json_array_get(json_object_get(o, "gci"), k), json_object_get(o, "observed_order"),
                json_object_get(o, "extrapolated"), json_object_get(r, "particles"),
                json_object_get(r, "steps"), json_object_get(r, "particle_steps"),
                json_object_get(r, "wall_seconds"), json_object_get(r, "peak_memory_bytes"));
            if (row)
                json_array_append_new(rows, row);
        }
    }
    return json_pack("{s:o,s:o}", "columns", columns, "rows", rows);
}
