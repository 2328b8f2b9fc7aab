/* The convergence process's input: validation, the study it becomes, and
 * the reduction of one output from a result file (convergence.h). */
#include "convergence.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "results.h"

#define MAX_OUTPUTS 32
#define MAX_NAME 63
#define MAX_POINTERS 16

static const char *const reduces[] = {"final", "max", "min", "time_of_threshold", NULL};
static const char *const directions[] = {"rising", "falling", "either", NULL};

static int one_of(const char *s, const char *const *list)
{
    for (; s && *list; list++)
        if (!strcmp(s, *list))
            return 1;
    return 0;
}

static void unknown_keys(const json_t *obj, const char *at, const char *const *allowed,
                         struct tlsph_errors *err)
{
    const char *key;
    json_t *v;
    json_object_foreach((json_t *)obj, key, v) {
        if (!one_of(key, allowed)) {
            char p[128];
            tlsph_pointer_join(p, sizeof p, at, key);
            tlsph_errors_add(err, p, "unknown key \"%s\"", key);
        }
    }
}

static int name_ok(const char *s)
{
    size_t n = s ? strlen(s) : 0;
    if (n == 0 || n > MAX_NAME)
        return 0;
    for (; *s; s++)
        if (!((*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') ||
              *s == '_'))
            return 0;
    return 1;
}

static int positive(const json_t *v)
{
    return json_is_number(v) && json_number_value(v) > 0 && isfinite(json_number_value(v));
}

/* ------------------------------------------------------------ outputs */

static void check_output(const json_t *o, size_t i, const json_t *outputs, struct tlsph_errors *err)
{
    char at[64], p[128];
    tlsph_pointer_index(at, sizeof at, "/outputs", i);
    if (!json_is_object(o)) {
        tlsph_errors_add(err, at, "an output must be an object {name, series, reduce}");
        return;
    }
    static const char *const keys[] = {"name", "series", "component", "reduce", "threshold",
                                       "direction", NULL};
    unknown_keys(o, at, keys, err);
    const char *name = json_string_value(json_object_get(o, "name"));
    tlsph_pointer_join(p, sizeof p, at, "name");
    if (!json_object_get(o, "name"))
        tlsph_errors_add(err, at, "missing \"name\"");
    else if (!name_ok(name))
        tlsph_errors_add(err, p, "name must be 1..%d characters of [A-Za-z0-9_]", MAX_NAME);
    else
        for (size_t j = 0; j < i; j++) {
            const char *nj = json_string_value(json_object_get(json_array_get(outputs, j), "name"));
            if (nj && !strcmp(nj, name)) {
                tlsph_errors_add(err, p, "duplicate output name \"%s\" (also /outputs/%zu)", name, j);
                break;
            }
        }
    const char *series = json_string_value(json_object_get(o, "series"));
    tlsph_pointer_join(p, sizeof p, at, "series");
    if (!json_object_get(o, "series"))
        tlsph_errors_add(err, at, "missing \"series\"");
    else if (!series || !tres_series_name_ok(series))
        tlsph_errors_add(err, p, "series must be a series name such as \"kinetic_energy\" or "
                                 "\"groups/<bc>/reaction_force\"");
    const json_t *comp = json_object_get(o, "component");
    tlsph_pointer_join(p, sizeof p, at, "component");
    if (comp && (!json_is_integer(comp) || json_integer_value(comp) < -1 ||
                 json_integer_value(comp) > 2))
        tlsph_errors_add(err, p, "component must be an integer -1..2 (-1 = magnitude)");
    const char *reduce = json_string_value(json_object_get(o, "reduce"));
    tlsph_pointer_join(p, sizeof p, at, "reduce");
    if (!json_object_get(o, "reduce"))
        tlsph_errors_add(err, at, "missing \"reduce\"");
    else if (!one_of(reduce, reduces))
        tlsph_errors_add(err, p, "reduce must be \"final\", \"max\", \"min\" or \"time_of_threshold\"");
    const json_t *thr = json_object_get(o, "threshold"), *dir = json_object_get(o, "direction");
    const int timed = reduce && !strcmp(reduce, "time_of_threshold");
    tlsph_pointer_join(p, sizeof p, at, "threshold");
    if (timed && !thr)
        tlsph_errors_add(err, at, "time_of_threshold needs \"threshold\"");
    else if (thr && !timed)
        tlsph_errors_add(err, p, "threshold is used only with reduce \"time_of_threshold\"");
    else if (thr && (!json_is_number(thr) || !isfinite(json_number_value(thr))))
        tlsph_errors_add(err, p, "threshold must be a finite number (the series' unit)");
    tlsph_pointer_join(p, sizeof p, at, "direction");
    if (dir && !timed)
        tlsph_errors_add(err, p, "direction is used only with reduce \"time_of_threshold\"");
    else if (dir && !one_of(json_string_value(dir), directions))
        tlsph_errors_add(err, p, "direction must be \"rising\", \"falling\" or \"either\"");
}

/* ------------------------------------------------------------ ladder */

static int cmp_desc(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? 1 : x > y ? -1 : 0;
}

/* The spacings, coarsest first, into h (count in *n); 0 or -1 (errors added). */
static int ladder_spacings(const json_t *ladder, double *h, size_t *n, double *ratio,
                           struct tlsph_errors *err)
{
    const size_t before = err->count;
    const json_t *sp = json_object_get(ladder, "spacings");
    const json_t *s0 = json_object_get(ladder, "spacing"), *r = json_object_get(ladder, "ratio"),
                 *cnt = json_object_get(ladder, "count");
    *n = 0;
    if (sp && (s0 || r || cnt)) {
        tlsph_errors_add(err, "/ladder", "give either \"spacings\" or \"spacing\", \"ratio\" and "
                                         "\"count\", not both");
        return -1;
    }
    if (sp) {
        if (!json_is_array(sp) || json_array_size(sp) < TCONV_MIN_RUNS ||
            json_array_size(sp) > TCONV_MAX_RUNS) {
            tlsph_errors_add(err, "/ladder/spacings",
                             "spacings must be an array of %d to %d spacings (m), got %zu",
                             TCONV_MIN_RUNS, TCONV_MAX_RUNS,
                             json_is_array(sp) ? json_array_size(sp) : (size_t)0);
            return -1;
        }
        size_t i;
        json_t *v;
        json_array_foreach(sp, i, v) {
            char p[64];
            tlsph_pointer_index(p, sizeof p, "/ladder/spacings", i);
            if (!positive(v))
                tlsph_errors_add(err, p, "a spacing must be a number > 0 (m)");
            else
                h[(*n)++] = json_number_value(v);
        }
        if (err->count != before)
            return -1;
        qsort(h, *n, sizeof *h, cmp_desc);
        *ratio = pow(h[0] / h[*n - 1], 1.0 / (double)(*n - 1));
        for (size_t k = 0; k + 1 < *n; k++) {
            const double rk = h[k] / h[k + 1];
            if (fabs(rk / *ratio - 1.0) > TCONV_RATIO_TOL) {
                tlsph_errors_add(err, "/ladder/spacings",
                                 "the ratio of successive spacings must be constant (within "
                                 "%g %%): %g / %g = %g, the ladder's ratio is %g",
                                 100 * TCONV_RATIO_TOL, h[k], h[k + 1], rk, *ratio);
                return -1;
            }
        }
    } else {
        if (!s0)
            tlsph_errors_add(err, "/ladder", "missing \"spacings\" (or \"spacing\", \"ratio\", "
                                             "\"count\")");
        else if (!positive(s0))
            tlsph_errors_add(err, "/ladder/spacing", "spacing must be a number > 0 (m): the "
                                                     "coarsest spacing");
        if (s0 && !r)
            tlsph_errors_add(err, "/ladder", "missing \"ratio\"");
        else if (r && (!json_is_number(r) || !isfinite(json_number_value(r))))
            tlsph_errors_add(err, "/ladder/ratio", "ratio must be a number >= %g", TCONV_MIN_RATIO);
        if (s0 && !cnt)
            tlsph_errors_add(err, "/ladder", "missing \"count\"");
        else if (cnt && (!json_is_integer(cnt) || json_integer_value(cnt) < TCONV_MIN_RUNS ||
                         json_integer_value(cnt) > TCONV_MAX_RUNS))
            tlsph_errors_add(err, "/ladder/count", "count must be an integer %d..%d",
                             TCONV_MIN_RUNS, TCONV_MAX_RUNS);
        if (err->count != before)
            return -1;
        *ratio = json_number_value(r);
        *n = (size_t)json_integer_value(cnt);
        h[0] = json_number_value(s0);
        for (size_t k = 1; k < *n; k++)
            h[k] = h[0] / pow(*ratio, (double)k);
    }
    if (*ratio < TCONV_MIN_RATIO) {
        tlsph_errors_add(err, sp ? "/ladder/spacings" : "/ladder/ratio",
                         "the ratio of successive spacings is %g; it must be >= %g (closer "
                         "spacings leave the discretization error in the noise)",
                         *ratio, TCONV_MIN_RATIO);
        return -1;
    }
    return 0;
}

/* The pointers (new array): given, or every body's "spacing". */
static json_t *ladder_pointers(const json_t *ladder, const json_t *base, struct tlsph_errors *err)
{
    const json_t *given = json_object_get(ladder, "pointers");
    json_t *out = json_array();
    if (!out)
        return NULL;
    if (given) {
        if (!json_is_array(given) || json_array_size(given) == 0 ||
            json_array_size(given) > MAX_POINTERS) {
            tlsph_errors_add(err, "/ladder/pointers", "pointers must be an array of 1..%d JSON "
                                                      "pointers to spacings of base", MAX_POINTERS);
            json_decref(out);
            return NULL;
        }
        size_t i;
        json_t *v;
        json_array_foreach(given, i, v) json_array_append(out, v);
    } else {
        size_t i;
        json_t *b;
        json_array_foreach(json_object_get(base, "bodies"), i, b) {
            char p[64];
            snprintf(p, sizeof p, "/bodies/%zu/spacing", i);
            json_array_append_new(out, json_string(p));
        }
        if (json_array_size(out) == 0) {
            tlsph_errors_add(err, "/base/bodies", "base has no bodies to refine");
            json_decref(out);
            return NULL;
        }
    }
    size_t i;
    json_t *v;
    json_array_foreach(out, i, v) {
        char at[64];
        tlsph_pointer_index(at, sizeof at, "/ladder/pointers", i);
        const char *ptr = json_string_value(v);
        const json_t *val = ptr && ptr[0] == '/' ? tstudy_pointer_get((json_t *)base, ptr) : NULL;
        if (!positive(val))
            tlsph_errors_add(err, given ? at : "/base/bodies",
                             "%s must name a spacing of base (a number > 0)",
                             ptr ? ptr : "a pointer");
        for (size_t j = 0; j < i && ptr; j++) {
            const char *pj = json_string_value(json_array_get(out, j));
            if (pj && !strcmp(ptr, pj))
                tlsph_errors_add(err, at, "pointer \"%s\" is given twice", ptr);
        }
    }
    return out;
}

/* ------------------------------------------------------------ the study */

static json_t *sweep_of(const json_t *base, const json_t *pointers, const double *h, size_t n)
{
    json_t *params = json_array();
    const double h0 = json_number_value(
        tstudy_pointer_get((json_t *)base, json_string_value(json_array_get(pointers, 0))));
    size_t i;
    json_t *p;
    json_array_foreach(pointers, i, p) {
        const double bi = json_number_value(tstudy_pointer_get((json_t *)base, json_string_value(p)));
        json_t *values = json_array();
        for (size_t k = 0; k < n; k++)
            json_array_append_new(values, json_real(i == 0 ? h[k] : bi * h[k] / h0));
        json_array_append_new(params, json_pack("{s:O,s:o}", "pointer", p, "values", values));
    }
    return json_pack("{s:s,s:o}", "mode", "zip", "parameters", params);
}

/* The outputs a study summary can tabulate (final/max/min). */
static json_t *study_outputs(const json_t *outputs)
{
    json_t *out = json_array();
    size_t i;
    json_t *o;
    json_array_foreach(outputs, i, o) {
        const char *reduce = json_string_value(json_object_get(o, "reduce"));
        if (reduce && strcmp(reduce, "time_of_threshold")) {
            json_t *c = json_deep_copy(o);
            json_array_append_new(out, c);
        }
    }
    return out;
}

json_t *tconv_study(const json_t *inputs, struct tlsph_errors *err)
{
    const size_t before = err->count;
    if (!json_is_object(inputs)) {
        tlsph_errors_add(err, "", "the inputs must be an object {base, ladder, outputs, target}");
        return NULL;
    }
    static const char *const keys[] = {"base", "ladder", "outputs", "target", NULL};
    unknown_keys(inputs, "", keys, err);
    const json_t *base = json_object_get(inputs, "base");
    if (!json_is_object(base))
        tlsph_errors_add(err, base ? "/base" : "", base ? "base must be a scene object"
                                                        : "missing \"base\" (the scene)");
    const json_t *ladder = json_object_get(inputs, "ladder");
    double h[TCONV_MAX_RUNS], ratio = 0;
    size_t n = 0;
    json_t *pointers = NULL;
    if (!json_is_object(ladder)) {
        tlsph_errors_add(err, ladder ? "/ladder" : "",
                         ladder ? "ladder must be an object {spacings} or {spacing, ratio, count}"
                                : "missing \"ladder\" (the spacings)");
    } else {
        static const char *const lkeys[] = {"spacings", "spacing", "ratio", "count", "pointers",
                                            NULL};
        unknown_keys(ladder, "/ladder", lkeys, err);
        ladder_spacings(ladder, h, &n, &ratio, err);
        if (json_is_object(base))
            pointers = ladder_pointers(ladder, base, err);
    }
    const json_t *outputs = json_object_get(inputs, "outputs");
    if (!outputs) {
        tlsph_errors_add(err, "", "missing \"outputs\" (what to converge)");
    } else if (!json_is_array(outputs) || json_array_size(outputs) == 0 ||
               json_array_size(outputs) > MAX_OUTPUTS) {
        tlsph_errors_add(err, "/outputs", "outputs must be an array of 1..%d outputs", MAX_OUTPUTS);
    } else {
        size_t i;
        json_t *o;
        json_array_foreach(outputs, i, o) check_output(o, i, outputs, err);
    }
    const json_t *target = json_object_get(inputs, "target");
    if (target) {
        const json_t *rel = json_object_get(target, "relative_error");
        if (!json_is_object(target)) {
            tlsph_errors_add(err, "/target", "target must be an object {relative_error}");
        } else {
            static const char *const tkeys[] = {"relative_error", NULL};
            unknown_keys(target, "/target", tkeys, err);
            if (!rel)
                tlsph_errors_add(err, "/target", "missing \"relative_error\"");
            else if (!positive(rel) || json_number_value(rel) >= 1)
                tlsph_errors_add(err, "/target/relative_error",
                                 "relative_error must be a number in (0, 1): the GCI to reach");
        }
    }
    if (err->count != before || err->out_of_memory) {
        json_decref(pointers);
        return NULL;
    }
    json_t *spacings = json_array();
    for (size_t k = 0; k < n; k++)
        json_array_append_new(spacings, json_real(h[k]));
    json_t *conv = json_pack("{s:{s:O,s:o,s:f},s:O}", "ladder", "pointers", pointers, "spacings",
                             spacings, "ratio", ratio, "outputs", outputs);
    if (conv && target)
        json_object_set(conv, "target", (json_t *)target);
    json_t *study = conv ? json_pack("{s:O,s:o,s:o,s:o}", "base", base, "sweep",
                                     sweep_of(base, pointers, h, n), "outputs",
                                     study_outputs(outputs), "convergence", conv)
                         : NULL;
    json_decref(pointers);
    if (!study)
        tlsph_errors_add(err, "", "out of memory");
    return study;
}

int tconv_is_convergence(const json_t *stored)
{
    return json_is_object(json_object_get(stored, "convergence"));
}

/* ------------------------------------------------------------ values */

double tconv_crossing_time(const double *t, const double *v, size_t n, double threshold,
                           const char *direction)
{
    const int up = !direction || strcmp(direction, "falling");
    const int down = !direction || strcmp(direction, "rising");
    for (size_t i = 1; i < n; i++) {
        const double a = v[i - 1], b = v[i];
        if (!isfinite(a) || !isfinite(b))
            continue;
        if ((up && a < threshold && b >= threshold) || (down && a > threshold && b <= threshold))
            return t[i - 1] + (t[i] - t[i - 1]) * (threshold - a) / (b - a);
    }
    return NAN;
}

double tconv_output_value(const json_t *output, const char *h5path, char *err, size_t errsize)
{
    const char *series = json_string_value(json_object_get(output, "series"));
    const char *reduce = json_string_value(json_object_get(output, "reduce"));
    const json_t *jc = json_object_get(output, "component");
    const int comp = json_is_integer(jc) ? (int)json_integer_value(jc) : 0;
    double *t = NULL, *v = NULL;
    size_t n = 0;
    if (!series || !reduce) {
        snprintf(err, errsize, "output without series or reduce");
        return NAN;
    }
    if (tres_series_column(h5path, series, comp, &t, &v, &n, err, errsize) != TRES_OK)
        return NAN;
    double out = NAN;
    if (!strcmp(reduce, "time_of_threshold")) {
        out = tconv_crossing_time(t, v, n, json_number_value(json_object_get(output, "threshold")),
                                  json_string_value(json_object_get(output, "direction")));
        if (isnan(out))
            snprintf(err, errsize, "%s never crosses %g", series,
                     json_number_value(json_object_get(output, "threshold")));
    } else {
        for (size_t i = 0; i < n; i++) {
            if (!isfinite(v[i]))
                continue;
            if (!strcmp(reduce, "final") || isnan(out) ||
                (!strcmp(reduce, "max") && v[i] > out) || (!strcmp(reduce, "min") && v[i] < out))
                out = v[i];
        }
        if (isnan(out))
            snprintf(err, errsize, "%s has no finite value", series);
    }
    free(t);
    free(v);
    return out;
}
