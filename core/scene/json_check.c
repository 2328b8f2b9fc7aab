#include "scene/json_check.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const char *jc_type_name(const json_t *v)
{
    switch (json_typeof(v)) {
    case JSON_OBJECT: return "object";
    case JSON_ARRAY: return "array";
    case JSON_STRING: return "string";
    case JSON_INTEGER: return "integer";
    case JSON_REAL: return "number";
    case JSON_TRUE:
    case JSON_FALSE: return "boolean";
    case JSON_NULL: return "null";
    }
    return "unknown";
}

int jc_unknown_keys(const json_t *obj, const char *const *allowed, const char *pointer,
                    struct tlsph_errors *err)
{
    const char *key;
    json_t *val;
    int n = 0;
    json_object_foreach((json_t *)obj, key, val) {
        int ok = 0;
        for (const char *const *a = allowed; *a && !ok; a++)
            ok = strcmp(*a, key) == 0;
        if (!ok) {
            char p[512];
            tlsph_pointer_join(p, sizeof p, pointer, key);
            char list[400] = "";
            size_t len = 0;
            for (const char *const *a = allowed; *a && len + 1 < sizeof list; a++)
                len += (size_t)snprintf(list + len, sizeof list - len, "%s%s",
                                        a == allowed ? "" : ", ", *a);
            tlsph_errors_add(err, p, "unknown field '%s' (allowed here: %s)", key, list);
            n++;
        }
    }
    return n;
}

static void describe_range(char *buf, size_t size, struct jc_range r)
{
    if (r.lo == JC_NONE && r.hi == JC_NONE)
        snprintf(buf, size, "any finite number");
    else if (r.hi == JC_NONE)
        snprintf(buf, size, "%s %g", r.lo == JC_OPEN ? ">" : ">=", r.min);
    else if (r.lo == JC_NONE)
        snprintf(buf, size, "%s %g", r.hi == JC_OPEN ? "<" : "<=", r.max);
    else
        snprintf(buf, size, "in %s%g, %g%s", r.lo == JC_OPEN ? "(" : "[", r.min, r.max,
                 r.hi == JC_OPEN ? ")" : "]");
}

static int in_range(double x, struct jc_range r)
{
    if (!isfinite(x))
        return 0;
    if (r.lo == JC_OPEN && !(x > r.min))
        return 0;
    if (r.lo == JC_CLOSED && !(x >= r.min))
        return 0;
    if (r.hi == JC_OPEN && !(x < r.max))
        return 0;
    if (r.hi == JC_CLOSED && !(x <= r.max))
        return 0;
    return 1;
}

/* obj[key], with its JSON pointer written to p.  NULL when absent: a required
 * key is then reported missing, with detail (e.g. "(m)"; NULL: none) after its
 * name, and the caller returns required ? -1 : 1. */
static const json_t *member(const json_t *obj, const char *key, int required, const char *detail,
                            const char *pointer, char p[512], struct tlsph_errors *err)
{
    tlsph_pointer_join(p, 512, pointer, key);
    const json_t *v = json_object_get(obj, key);
    if (!v && required)
        tlsph_errors_add(err, p, "required field '%s'%s%s is missing", key, detail ? " " : "",
                         detail ? detail : "");
    return v;
}

/* Reports v at p as not of the expected kind (e.g. "an integer"); returns -1. */
static int wrong_type(const char *p, const char *key, const char *expected, const json_t *v,
                      struct tlsph_errors *err)
{
    tlsph_errors_add(err, p, "'%s' must be %s, got %s", key, expected, jc_type_name(v));
    return -1;
}

int jc_number(const json_t *obj, const char *key, int required, struct jc_range r,
              const char *units, const char *pointer, double *out, struct tlsph_errors *err)
{
    return jc_number_why(obj, key, required, r, units, NULL, pointer, out, err);
}

int jc_number_why(const json_t *obj, const char *key, int required, struct jc_range r,
                  const char *units, const char *above_max, const char *pointer, double *out,
                  struct tlsph_errors *err)
{
    char p[512], detail[256];
    snprintf(detail, sizeof detail, "(%s)", units);
    const json_t *v = member(obj, key, required, detail, pointer, p, err);
    if (!v)
        return required ? -1 : 1;
    if (!json_is_number(v)) {
        snprintf(detail, sizeof detail, "a number (%s)", units);
        return wrong_type(p, key, detail, v, err);
    }
    double x = json_number_value(v);
    if (!in_range(x, r)) {
        char d[128];
        describe_range(d, sizeof d, r);
        const int above = r.hi != JC_NONE && (r.hi == JC_OPEN ? x >= r.max : x > r.max);
        if (above && above_max)
            tlsph_errors_add(err, p, "'%s' = %g: %s; must be %s", key, x, above_max, d);
        else
            tlsph_errors_add(err, p, "'%s' = %g %s is out of range: must be %s", key, x, units,
                             d);
        return -1;
    }
    *out = x;
    return 0;
}

int jc_integer(const json_t *obj, const char *key, int required, long min, long max,
               const char *pointer, long *out, struct tlsph_errors *err)
{
    char p[512];
    const json_t *v = member(obj, key, required, NULL, pointer, p, err);
    if (!v)
        return required ? -1 : 1;
    if (!json_is_integer(v))
        return wrong_type(p, key, "an integer", v, err);
    json_int_t x = json_integer_value(v);
    if (x < min || x > max) {
        tlsph_errors_add(err, p, "'%s' = %lld is out of range: must be in [%ld, %ld]", key,
                         (long long)x, min, max);
        return -1;
    }
    *out = (long)x;
    return 0;
}

int jc_boolean(const json_t *obj, const char *key, int required, const char *pointer, int *out,
               struct tlsph_errors *err)
{
    char p[512];
    const json_t *v = member(obj, key, required, NULL, pointer, p, err);
    if (!v)
        return required ? -1 : 1;
    if (!json_is_boolean(v))
        return wrong_type(p, key, "true or false", v, err);
    *out = json_is_true(v);
    return 0;
}

int jc_string(const json_t *obj, const char *key, int required, const char *pointer, char *out,
              size_t size, struct tlsph_errors *err)
{
    char p[512];
    const json_t *v = member(obj, key, required, NULL, pointer, p, err);
    if (!v)
        return required ? -1 : 1;
    if (!json_is_string(v))
        return wrong_type(p, key, "a string", v, err);
    const char *s = json_string_value(v);
    size_t len = json_string_length(v);
    if (len == 0 || len >= size || strlen(s) != len) {
        tlsph_errors_add(err, p, "'%s' must be a non-empty string of at most %zu characters", key,
                         size - 1);
        return -1;
    }
    memcpy(out, s, len + 1);
    return 0;
}

int jc_vector(const json_t *obj, const char *key, int required, int n, const char *units,
              const char *pointer, double *out, struct tlsph_errors *err)
{
    char p[512], detail[256];
    snprintf(detail, sizeof detail, "(%d numbers, %s)", n, units);
    const json_t *v = member(obj, key, required, detail, pointer, p, err);
    if (!v)
        return required ? -1 : 1;
    if (!json_is_array(v) || json_array_size(v) != (size_t)n) {
        tlsph_errors_add(err, p, "'%s' must be an array of %d numbers (%s)", key, n, units);
        return -1;
    }
    for (int k = 0; k < n; k++) {
        const json_t *e = json_array_get(v, (size_t)k);
        if (!json_is_number(e) || !isfinite(json_number_value(e))) {
            char q[512];
            tlsph_pointer_index(q, sizeof q, p, (size_t)k);
            tlsph_errors_add(err, q, "component %d of '%s' must be a finite number (%s)", k, key,
                             units);
            return -1;
        }
        out[k] = json_number_value(e);
    }
    return 0;
}

const json_t *jc_object(const json_t *obj, const char *key, int required, const char *pointer,
                        struct tlsph_errors *err)
{
    char p[512];
    tlsph_pointer_join(p, sizeof p, pointer, key);
    const json_t *v = json_object_get(obj, key);
    if (!v) {
        if (required)
            tlsph_errors_add(err, p, "required object '%s' is missing", key);
        return NULL;
    }
    if (!json_is_object(v)) {
        wrong_type(p, key, "an object", v, err);
        return NULL;
    }
    return v;
}

int jc_misplaced(const json_t *obj, const char *key, const char *needs, const char *pointer,
                 struct tlsph_errors *err)
{
    if (!json_object_get(obj, key))
        return 0;
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, pointer, key);
    tlsph_errors_add(err, p, "'%s' has no effect without '%s'", key, needs);
    return 1;
}
