/* Parametric studies, see study.h.
 *
 * Validation collects every problem (pointer relative to the study input)
 * before anything is expanded; the sweep size is computed and checked against
 * max_children before any child is built. */
#include "study.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "numtext.h"
#include "results.h"
#include "strbuf.h"

#define MAX_PARAMETERS 16
#define MAX_VALUES 1000
#define MAX_OUTPUTS 64
#define MAX_OUTPUT_NAME 63
#define MAX_POINTER 1024

/* ------------------------------------------------------------ RFC 6901 */

/* Next reference token of p (which points at a '/'): unescaped into tok.
 * Returns a pointer past the token, or NULL when the escape is invalid or
 * the token is too long. */
static const char *next_token(const char *p, char *tok, size_t size)
{
    size_t n = 0;
    p++; /* the '/' */
    for (; *p && *p != '/'; p++) {
        char c = *p;
        if (c == '~') {
            if (p[1] == '0')
                c = '~';
            else if (p[1] == '1')
                c = '/';
            else
                return NULL;
            p++;
        }
        if (n + 1 >= size)
            return NULL;
        tok[n++] = c;
    }
    tok[n] = '\0';
    return p;
}

/* Decimal array index without leading zeros ("-" and signs refused). */
static int parse_index(const char *tok, size_t *out)
{
    if (!*tok || (tok[0] == '0' && tok[1]))
        return -1;
    size_t v = 0;
    for (const char *s = tok; *s; s++) {
        if (*s < '0' || *s > '9')
            return -1;
        if (v > (SIZE_MAX - 9) / 10)
            return -1;
        v = v * 10 + (size_t)(*s - '0');
    }
    *out = v;
    return 0;
}

/* Syntax check: "" or a sequence of "/token" with valid escapes. */
static int pointer_syntax_ok(const char *pointer)
{
    char tok[MAX_POINTER];
    if (!pointer || strlen(pointer) >= MAX_POINTER)
        return 0;
    const char *p = pointer;
    while (*p) {
        if (*p != '/')
            return 0;
        p = next_token(p, tok, sizeof tok);
        if (!p)
            return 0;
    }
    return 1;
}

static json_t *child_of(json_t *v, const char *tok)
{
    if (json_is_object(v))
        return json_object_get(v, tok);
    if (json_is_array(v)) {
        size_t i;
        if (parse_index(tok, &i) < 0 || i >= json_array_size(v))
            return NULL;
        return json_array_get(v, i);
    }
    return NULL;
}

json_t *tstudy_pointer_get(json_t *root, const char *pointer)
{
    if (!root || !pointer_syntax_ok(pointer))
        return NULL;
    char tok[MAX_POINTER];
    json_t *v = root;
    const char *p = pointer;
    while (*p && v) {
        p = next_token(p, tok, sizeof tok);
        v = child_of(v, tok);
    }
    return v;
}

/* Parent container of the value at pointer, and the last token (unescaped). */
static json_t *pointer_parent(json_t *root, const char *pointer, char *last, size_t size)
{
    if (!root || !pointer || !*pointer || !pointer_syntax_ok(pointer))
        return NULL;
    const char *slash = strrchr(pointer, '/'); /* escapes never contain '/' */
    size_t plen = (size_t)(slash - pointer);
    char parent[MAX_POINTER];
    memcpy(parent, pointer, plen);
    parent[plen] = '\0';
    if (!next_token(slash, last, size))
        return NULL;
    return tstudy_pointer_get(root, parent);
}

int tstudy_pointer_set(json_t *root, const char *pointer, json_t *value)
{
    char last[MAX_POINTER];
    int rc = -1;
    if (!value)
        return -1;
    json_t *parent = pointer_parent(root, pointer, last, sizeof last);
    if (json_is_object(parent)) {
        rc = json_object_set(parent, last, value);
    } else if (json_is_array(parent)) {
        size_t i;
        if (parse_index(last, &i) == 0 && i < json_array_size(parent))
            rc = json_array_set(parent, i, value);
    }
    json_decref(value); /* steals value in every case */
    return rc;
}

/* ------------------------------------------------------------ validation */

struct param {
    const char *pointer; /* borrowed from the study */
    json_t *values;      /* owned array */
};

struct plan {
    struct param p[MAX_PARAMETERS];
    size_t np;
    int zip;
    const char *seen[MAX_PARAMETERS]; /* every valid pointer so far (for overlaps) */
    size_t nseen;
};

static void plan_free(struct plan *pl)
{
    for (size_t i = 0; i < pl->np; i++)
        json_decref(pl->p[i].values);
    memset(pl, 0, sizeof *pl);
}

static const char *type_name(const json_t *v)
{
    switch (json_typeof(v)) {
    case JSON_OBJECT: return "an object";
    case JSON_ARRAY: return "an array";
    case JSON_STRING: return "a string";
    case JSON_INTEGER: return "an integer";
    case JSON_REAL: return "a number";
    case JSON_TRUE:
    case JSON_FALSE: return "a boolean";
    default: return "null";
    }
}

/* Rejects keys outside allowed (NULL-terminated). */
static void check_keys(const json_t *obj, const char *at, const char *const *allowed,
                       struct tlsph_errors *err)
{
    const char *key;
    json_t *v;
    json_object_foreach((json_t *)obj, key, v) {
        int ok = 0;
        for (const char *const *a = allowed; *a; a++)
            ok |= strcmp(key, *a) == 0;
        if (!ok) {
            char ptr[MAX_POINTER + 64];
            tlsph_pointer_join(ptr, sizeof ptr, at, key);
            tlsph_errors_add(err, ptr, "unknown key \"%s\"", key);
        }
    }
}

static void sub(char *out, size_t size, const char *base, const char *seg)
{
    tlsph_pointer_join(out, size, base, seg);
}

/* "/a/b" is "/a" or below it (segment-wise). */
static int pointer_within(const char *p, const char *prefix)
{
    size_t n = strlen(prefix);
    return strncmp(p, prefix, n) == 0 && (p[n] == '\0' || p[n] == '/');
}

/* linspace(start, stop, num) inclusive, numpy's formula start + i * step with
 * step = (stop - start) / (num - 1); integers when both ends are JSON integers
 * and every value is integral.  A step that is not a finite number (stop -
 * start overflows a double) and neighbouring values that round to the same
 * double are refused with an error at `at`: either would otherwise give fewer
 * distinct children than num, or a value that JSON cannot hold.  NULL then. */
static json_t *linspace(const json_t *jstart, const json_t *jstop, size_t num, const char *at,
                        struct tlsph_errors *err)
{
    double start = json_number_value(jstart), stop = json_number_value(jstop);
    double step = num > 1 ? (stop - start) / (double)(num - 1) : 0.0;
    if (!isfinite(step)) {
        tlsph_errors_add(err, at,
                         "the step (stop - start) / (num - 1) is not a finite number "
                         "(start %g, stop %g, num %zu): stop - start overflows a double",
                         start, stop, num);
        return NULL;
    }
    int ints = json_is_integer(jstart) && json_is_integer(jstop);
    double *v = malloc(num * sizeof *v);
    json_t *a = json_array();
    if (!v || !a) {
        tlsph_errors_add(err, at, "out of memory");
        goto fail;
    }
    for (size_t i = 0; i < num; i++) {
        v[i] = i + 1 == num && num > 1 ? stop : start + (double)i * step;
        if (i > 0 && step != 0.0 && v[i] == v[i - 1]) {
            tlsph_errors_add(err, at,
                             "values %zu and %zu of the range are both %.17g: a step of %g is "
                             "below double precision here; use a smaller num or a wider range",
                             i - 1, i, v[i], step);
            goto fail;
        }
        if (ints && (v[i] != floor(v[i]) || fabs(v[i]) > 9007199254740992.0))
            ints = 0;
    }
    for (size_t i = 0; i < num; i++)
        if (json_array_append_new(a, ints ? json_integer((json_int_t)v[i]) : json_real(v[i])) != 0) {
            tlsph_errors_add(err, at, "out of memory");
            goto fail;
        }
    free(v);
    return a;
fail:
    free(v);
    json_decref(a);
    return NULL;
}

static int name_ok(const char *s)
{
    if (!*s || strlen(s) > MAX_OUTPUT_NAME)
        return 0;
    for (; *s; s++)
        if (!((*s >= 'A' && *s <= 'Z') || (*s >= 'a' && *s <= 'z') || (*s >= '0' && *s <= '9') ||
              *s == '_'))
            return 0;
    return 1;
}

static const char *const fixed_columns[] = {"seq", "job_id", "status", "particles", "steps",
                                            "wall_seconds", "particle_steps_per_second", NULL};

static void validate_outputs(const json_t *outputs, struct tlsph_errors *err)
{
    if (!json_is_array(outputs)) {
        tlsph_errors_add(err, "/outputs", "outputs must be an array, not %s", type_name(outputs));
        return;
    }
    if (json_array_size(outputs) > MAX_OUTPUTS)
        tlsph_errors_add(err, "/outputs", "at most %d outputs, got %zu", MAX_OUTPUTS,
                         json_array_size(outputs));
    static const char *const keys[] = {"name", "series", "component", "reduce", NULL};
    size_t i;
    json_t *o;
    json_array_foreach(outputs, i, o) {
        char at[64], p[128];
        tlsph_pointer_index(at, sizeof at, "/outputs", i);
        if (!json_is_object(o)) {
            tlsph_errors_add(err, at, "an output must be an object, not %s", type_name(o));
            continue;
        }
        check_keys(o, at, keys, err);
        json_t *name = json_object_get(o, "name");
        sub(p, sizeof p, at, "name");
        if (!name) {
            tlsph_errors_add(err, at, "missing \"name\"");
        } else if (!json_is_string(name) || !name_ok(json_string_value(name))) {
            tlsph_errors_add(err, p, "name must be 1..%d characters of [A-Za-z0-9_]", MAX_OUTPUT_NAME);
        } else {
            const char *n = json_string_value(name);
            for (const char *const *c = fixed_columns; *c; c++)
                if (strcmp(n, *c) == 0)
                    tlsph_errors_add(err, p, "name \"%s\" is a reserved column name", n);
            for (size_t j = 0; j < i; j++) {
                json_t *nj = json_object_get(json_array_get(outputs, j), "name");
                if (json_is_string(nj) && strcmp(json_string_value(nj), n) == 0) {
                    tlsph_errors_add(err, p, "duplicate output name \"%s\" (also /outputs/%zu)", n, j);
                    break;
                }
            }
        }
        json_t *series = json_object_get(o, "series");
        sub(p, sizeof p, at, "series");
        if (!series)
            tlsph_errors_add(err, at, "missing \"series\"");
        else if (!json_is_string(series) || !tres_series_name_ok(json_string_value(series)))
            tlsph_errors_add(err, p, "series must be a series name such as \"kinetic_energy\" or "
                                     "\"groups/<bc>/reaction_force\"");
        json_t *comp = json_object_get(o, "component");
        sub(p, sizeof p, at, "component");
        if (comp && (!json_is_integer(comp) || json_integer_value(comp) < -1 ||
                     json_integer_value(comp) > 2))
            tlsph_errors_add(err, p, "component must be an integer -1..2 (-1 = magnitude)");
        json_t *reduce = json_object_get(o, "reduce");
        sub(p, sizeof p, at, "reduce");
        if (reduce) {
            const char *r = json_string_value(reduce);
            if (!r || (strcmp(r, "final") && strcmp(r, "max") && strcmp(r, "min")))
                tlsph_errors_add(err, p, "reduce must be \"final\", \"max\" or \"min\"");
        }
    }
}

/* Validates one parameter; on success stores it in the plan. */
static void validate_parameter(const json_t *base, const json_t *prm, size_t i, struct plan *pl,
                               struct tlsph_errors *err)
{
    char at[64], p[128];
    tlsph_pointer_index(at, sizeof at, "/sweep/parameters", i);
    if (!json_is_object(prm)) {
        tlsph_errors_add(err, at, "a parameter must be an object, not %s", type_name(prm));
        return;
    }
    static const char *const keys[] = {"pointer", "values", "range", NULL};
    check_keys(prm, at, keys, err);
    size_t before = err->count;

    /* pointer */
    json_t *jp = json_object_get(prm, "pointer");
    const char *pointer = json_string_value(jp);
    sub(p, sizeof p, at, "pointer");
    if (!jp) {
        tlsph_errors_add(err, at, "missing \"pointer\"");
    } else if (!pointer || !*pointer || pointer[0] != '/' || !pointer_syntax_ok(pointer)) {
        tlsph_errors_add(err, p, "pointer must be an RFC 6901 JSON pointer into base such as "
                                 "\"/bodies/0/spacing\" (~0 for ~, ~1 for /)");
        pointer = NULL;
    } else if (!tstudy_pointer_get((json_t *)base, pointer)) {
        char last[MAX_POINTER];
        json_t *parent = json_is_object(base) ? pointer_parent((json_t *)base, pointer, last, sizeof last)
                                              : NULL;
        if (!json_is_object(parent)) {
            if (json_is_object(base))
                tlsph_errors_add(err, p, "pointer \"%s\" does not resolve in base (neither the "
                                         "value nor its parent object exists)", pointer);
            pointer = NULL;
        }
    }
    if (pointer) {
        for (size_t j = 0; j < pl->nseen; j++) {
            if (pointer_within(pointer, pl->seen[j]) || pointer_within(pl->seen[j], pointer)) {
                tlsph_errors_add(err, p, "pointer \"%s\" overlaps \"%s\" of another parameter",
                                 pointer, pl->seen[j]);
                pointer = NULL;
                break;
            }
        }
        if (pointer && pl->nseen < MAX_PARAMETERS)
            pl->seen[pl->nseen++] = pointer;
    }

    /* values | range */
    json_t *values = json_object_get(prm, "values"), *range = json_object_get(prm, "range");
    json_t *list = NULL;
    if (values && range) {
        tlsph_errors_add(err, at, "give either \"values\" or \"range\", not both");
    } else if (!values && !range) {
        tlsph_errors_add(err, at, "missing \"values\" or \"range\"");
    } else if (values) {
        sub(p, sizeof p, at, "values");
        if (!json_is_array(values) || json_array_size(values) == 0 ||
            json_array_size(values) > MAX_VALUES)
            tlsph_errors_add(err, p, "values must be a non-empty array of at most %d values",
                             MAX_VALUES);
        else
            list = json_incref(values);
    } else {
        sub(p, sizeof p, at, "range");
        if (!json_is_object(range)) {
            tlsph_errors_add(err, p, "range must be an object {start, stop, num}");
        } else {
            static const char *const rkeys[] = {"start", "stop", "num", NULL};
            size_t rbefore = err->count;
            check_keys(range, p, rkeys, err);
            json_t *start = json_object_get(range, "start"), *stop = json_object_get(range, "stop"),
                   *num = json_object_get(range, "num");
            char q[160];
            const char *names[2] = {"start", "stop"};
            json_t *ends[2] = {start, stop};
            for (int k = 0; k < 2; k++) {
                sub(q, sizeof q, p, names[k]);
                if (!ends[k])
                    tlsph_errors_add(err, p, "missing \"%s\"", names[k]);
                else if (!json_is_number(ends[k]))
                    tlsph_errors_add(err, q, "%s must be a number", names[k]);
            }
            sub(q, sizeof q, p, "num");
            if (!num)
                tlsph_errors_add(err, p, "missing \"num\"");
            else if (!json_is_integer(num) || json_integer_value(num) < 1 ||
                     json_integer_value(num) > MAX_VALUES)
                tlsph_errors_add(err, q, "num must be an integer 1..%d", MAX_VALUES);
            if (err->count == rbefore)
                list = linspace(start, stop, (size_t)json_integer_value(num), p, err);
        }
    }
    if (err->count == before && pointer && list && pl->np < MAX_PARAMETERS) {
        pl->p[pl->np].pointer = pointer;
        pl->p[pl->np].values = list;
        pl->np++;
    } else {
        json_decref(list);
    }
}

/* Validates the whole study; fills plan when there is no error.  Returns the
 * number of children (0 on error). */
static size_t validate(const json_t *study, size_t max_children, struct plan *pl,
                       struct tlsph_errors *err)
{
    memset(pl, 0, sizeof *pl);
    size_t before = err->count;
    if (!json_is_object(study)) {
        tlsph_errors_add(err, "", "the study must be an object {base, sweep, outputs}, not %s",
                         study ? type_name(study) : "empty");
        return 0;
    }
    static const char *const keys[] = {"base", "sweep", "outputs", "max_parallel", NULL};
    check_keys(study, "", keys, err);
    /* how many children Slurm runs at once (the job array's %limit,
     * executor_slurm.h); the local executor runs max_jobs at most anyway */
    const json_t *mp = json_object_get(study, "max_parallel");
    if (mp && !(json_is_integer(mp) && json_integer_value(mp) >= 1 &&
                json_integer_value(mp) <= 1000000))
        tlsph_errors_add(err, "/max_parallel", "max_parallel must be an integer in 1..1000000");

    const json_t *base = json_object_get(study, "base");
    if (!base)
        tlsph_errors_add(err, "", "missing \"base\" (the scene to vary)");
    else if (!json_is_object(base))
        tlsph_errors_add(err, "/base", "base must be a scene object, not %s", type_name(base));

    const json_t *sweep = json_object_get(study, "sweep");
    const json_t *params = NULL;
    if (!sweep) {
        tlsph_errors_add(err, "", "missing \"sweep\"");
    } else if (!json_is_object(sweep)) {
        tlsph_errors_add(err, "/sweep", "sweep must be an object {mode, parameters}, not %s",
                         type_name(sweep));
    } else {
        static const char *const skeys[] = {"mode", "parameters", NULL};
        check_keys(sweep, "/sweep", skeys, err);
        json_t *mode = json_object_get(sweep, "mode");
        if (mode) {
            const char *m = json_string_value(mode);
            if (m && strcmp(m, "zip") == 0)
                pl->zip = 1;
            else if (!m || strcmp(m, "product") != 0)
                tlsph_errors_add(err, "/sweep/mode", "mode must be \"product\" or \"zip\"");
        }
        params = json_object_get(sweep, "parameters");
        if (!params) {
            tlsph_errors_add(err, "/sweep", "missing \"parameters\"");
            params = NULL;
        } else if (!json_is_array(params) || json_array_size(params) == 0 ||
                   json_array_size(params) > MAX_PARAMETERS) {
            tlsph_errors_add(err, "/sweep/parameters",
                             "parameters must be a non-empty array of at most %d parameters",
                             MAX_PARAMETERS);
            params = NULL;
        }
    }
    if (params) {
        size_t i;
        json_t *prm;
        json_array_foreach(params, i, prm) validate_parameter(json_is_object(base) ? base : NULL,
                                                               prm, i, pl, err);
    }
    const json_t *outputs = json_object_get(study, "outputs");
    if (outputs)
        validate_outputs(outputs, err);

    /* sizes: only when every parameter is usable */
    size_t total = 0;
    if (params && pl->np == json_array_size(params)) {
        if (pl->zip) {
            total = json_array_size(pl->p[0].values);
            for (size_t i = 1; i < pl->np; i++) {
                size_t len = json_array_size(pl->p[i].values);
                if (len != total) {
                    char at[96];
                    tlsph_pointer_index(at, sizeof at, "/sweep/parameters", i);
                    tlsph_errors_add(err, at,
                                     "zip needs equal lengths: this parameter has %zu values, "
                                     "/sweep/parameters/0 has %zu",
                                     len, total);
                }
            }
        } else {
            total = 1;
            int overflow = 0;
            for (size_t i = 0; i < pl->np; i++) {
                size_t len = json_array_size(pl->p[i].values);
                if (total > SIZE_MAX / len)
                    overflow = 1;
                else
                    total *= len;
            }
            if (overflow)
                total = SIZE_MAX;
        }
        if (total > max_children) {
            if (total == SIZE_MAX)
                tlsph_errors_add(err, "/sweep/parameters",
                                 "the sweep has too many children (at most %zu)", max_children);
            else
                tlsph_errors_add(err, "/sweep/parameters",
                                 "the sweep has %zu children, at most %zu are allowed", total,
                                 max_children);
        }
    }
    if (err->count != before || err->out_of_memory) {
        plan_free(pl);
        return 0;
    }
    return total;
}

int tstudy_expand(const json_t *study, size_t max_children, struct tstudy_child **children,
                  size_t *n, struct tlsph_errors *err)
{
    *children = NULL;
    *n = 0;
    struct plan pl;
    size_t total = validate(study, max_children, &pl, err);
    if (total == 0) {
        if (err->count == 0)
            tlsph_errors_add(err, "", "the study has no children");
        return -1;
    }
    const json_t *base = json_object_get(study, "base");
    struct tstudy_child *c = calloc(total, sizeof *c);
    if (!c) {
        tlsph_errors_add(err, "", "out of memory expanding %zu children", total);
        plan_free(&pl);
        return -1;
    }
    for (size_t k = 0; k < total; k++) {
        c[k].scene = json_deep_copy(base);
        c[k].params = json_object();
        if (!c[k].scene || !c[k].params)
            goto oom;
        size_t rest = k;
        /* product: the first parameter varies slowest, so peel indices from the last */
        size_t idx[MAX_PARAMETERS];
        for (size_t j = pl.np; j-- > 0;) {
            size_t len = json_array_size(pl.p[j].values);
            if (pl.zip) {
                idx[j] = k;
            } else {
                idx[j] = rest % len;
                rest /= len;
            }
        }
        for (size_t j = 0; j < pl.np; j++) {
            json_t *v = json_array_get(pl.p[j].values, idx[j]);
            if (tstudy_pointer_set(c[k].scene, pl.p[j].pointer, json_deep_copy(v)) != 0 ||
                json_object_set_new(c[k].params, pl.p[j].pointer, json_deep_copy(v)) != 0)
                goto oom;
        }
    }
    plan_free(&pl);
    *children = c;
    *n = total;
    return 0;
oom:
    tlsph_errors_add(err, "", "out of memory expanding the study");
    tstudy_children_free(c, total);
    plan_free(&pl);
    return -1;
}

void tstudy_children_free(struct tstudy_child *c, size_t n)
{
    if (!c)
        return;
    for (size_t i = 0; i < n; i++) {
        json_decref(c[i].scene);
        json_decref(c[i].params);
    }
    free(c);
}

/* ------------------------------------------------------------ summary */

static json_t *real_or_null(double v)
{
    return isfinite(v) ? json_real(v) : json_null();
}

static json_t *cost_value(const json_t *cost, const char *key)
{
    json_t *v = json_is_object(cost) ? json_object_get(cost, key) : NULL;
    if (json_is_number(v))
        return json_deep_copy(v);
    return json_null();
}

json_t *tstudy_summary(const json_t *study, const struct tstudy_row *rows, size_t n)
{
    json_t *sweep = json_object_get(study, "sweep");
    json_t *params = json_object_get(sweep, "parameters");
    json_t *outputs = json_object_get(study, "outputs");
    json_t *columns = json_array(), *table = json_array();
    if (!columns || !table)
        goto fail;
    json_array_append_new(columns, json_string("seq"));
    json_array_append_new(columns, json_string("job_id"));
    json_array_append_new(columns, json_string("status"));
    size_t i;
    json_t *v;
    json_array_foreach(params, i, v) {
        json_t *p = json_object_get(v, "pointer");
        json_array_append_new(columns, json_is_string(p) ? json_copy(p) : json_string(""));
    }
    json_array_foreach(outputs, i, v) {
        json_t *p = json_object_get(v, "name");
        json_array_append_new(columns, json_is_string(p) ? json_copy(p) : json_string(""));
    }
    const char *cost_cols[] = {"particles", "steps", "wall_seconds", "particle_steps_per_second"};
    for (int k = 0; k < 4; k++)
        json_array_append_new(columns, json_string(cost_cols[k]));

    for (size_t r = 0; r < n; r++) {
        const struct tstudy_row *row = &rows[r];
        json_t *out = json_array();
        json_array_append_new(out, json_integer(row->seq));
        json_array_append_new(out, row->job_id ? json_string(row->job_id) : json_null());
        json_array_append_new(out, row->status ? json_string(row->status) : json_null());
        json_array_foreach(params, i, v) {
            const char *ptr = json_string_value(json_object_get(v, "pointer"));
            json_t *pv = ptr && json_is_object(row->params) ? json_object_get(row->params, ptr) : NULL;
            json_array_append_new(out, pv ? json_deep_copy(pv) : json_null());
        }
        json_array_foreach(outputs, i, v) {
            const char *series = json_string_value(json_object_get(v, "series"));
            json_t *jc = json_object_get(v, "component");
            int comp = json_is_integer(jc) ? (int)json_integer_value(jc) : 0;
            const char *reduce = json_string_value(json_object_get(v, "reduce"));
            double fin = NAN, mx = NAN, mn = NAN;
            char err[256];
            json_t *cell = json_null();
            if (row->h5path && series &&
                tres_series_reduce(row->h5path, series, comp, &fin, &mx, &mn, err,
                                   sizeof err) == TRES_OK) {
                json_decref(cell);
                if (reduce && strcmp(reduce, "max") == 0)
                    cell = real_or_null(mx);
                else if (reduce && strcmp(reduce, "min") == 0)
                    cell = real_or_null(mn);
                else
                    cell = real_or_null(fin);
            }
            json_array_append_new(out, cell);
        }
        for (int k = 0; k < 4; k++)
            json_array_append_new(out, cost_value(row->cost, cost_cols[k]));
        json_array_append_new(table, out);
    }
    json_t *o = json_object();
    if (!o)
        goto fail;
    json_object_set_new(o, "columns", columns);
    json_object_set_new(o, "rows", table);
    return o;
fail:
    json_decref(columns);
    json_decref(table);
    return NULL;
}

/* RFC 4180 field: quoted when it contains , " CR or LF (quotes doubled). */
static void csv_field(struct strbuf *b, const char *s)
{
    if (!strpbrk(s, ",\"\r\n")) {
        strbuf_add(b, s, strlen(s));
        return;
    }
    strbuf_add(b, "\"", 1);
    for (const char *q = s; *q; q++) {
        if (*q == '"')
            strbuf_add(b, "\"\"", 2);
        else
            strbuf_add(b, q, 1);
    }
    strbuf_add(b, "\"", 1);
}

static void csv_value(struct strbuf *b, const json_t *v)
{
    char buf[64];
    switch (json_typeof(v)) {
    case JSON_STRING:
        csv_field(b, json_string_value(v));
        break;
    case JSON_INTEGER:
        snprintf(buf, sizeof buf, "%" JSON_INTEGER_FORMAT, json_integer_value(v));
        strbuf_add(b, buf, strlen(buf));
        break;
    case JSON_REAL:
        strbuf_adds(b, numtext_real(buf, sizeof buf, json_real_value(v)));
        break;
    case JSON_TRUE:
        strbuf_add(b, "true", 4);
        break;
    case JSON_FALSE:
        strbuf_add(b, "false", 5);
        break;
    case JSON_NULL:
        break;
    default: { /* arrays and objects (swept values): compact JSON */
        char *s = json_dumps(v, JSON_COMPACT | JSON_ENCODE_ANY);
        if (s) {
            csv_field(b, s);
            free(s);
        } else {
            b->oom = true;
        }
    }
    }
}

char *tstudy_summary_csv(const json_t *summary)
{
    json_t *columns = json_object_get(summary, "columns"), *rows = json_object_get(summary, "rows");
    if (!json_is_array(columns) || !json_is_array(rows))
        return NULL;
    struct strbuf b = {0};
    size_t i, r;
    json_t *v, *row;
    json_array_foreach(columns, i, v) {
        if (i)
            strbuf_add(&b, ",", 1);
        csv_value(&b, v);
    }
    strbuf_add(&b, "\r\n", 2);
    json_array_foreach(rows, r, row) {
        json_array_foreach(row, i, v) {
            if (i)
                strbuf_add(&b, ",", 1);
            csv_value(&b, v);
        }
        strbuf_add(&b, "\r\n", 2);
    }
    return strbuf_take(&b);
}
