/* Small table-free helpers for validating jansson values with JSON pointers.
 * Each helper adds a precise error (pointer + message naming the field and its
 * accepted range) and returns -1 on failure, 0 on success, 1 when an optional
 * key is absent (out left unchanged). */
#ifndef TLSPH_JSON_CHECK_H
#define TLSPH_JSON_CHECK_H

#include <jansson.h>

#include "util/errors.h"

enum jc_bound { JC_OPEN, JC_CLOSED, JC_NONE };

struct jc_range {
    double min, max;
    enum jc_bound lo, hi; /* JC_NONE = unbounded on that side */
};

/* "object", "array", "string", "integer", "number", "boolean" or "null". */
const char *jc_type_name(const json_t *v);
/* Reports every key of obj not in allowed (NULL-terminated). Returns count of unknown keys. */
int jc_unknown_keys(const json_t *obj, const char *const *allowed, const char *pointer,
                    struct tlsph_errors *err);
int jc_number(const json_t *obj, const char *key, int required, struct jc_range r,
              const char *units, const char *pointer, double *out, struct tlsph_errors *err);
/* jc_number, with above_max (when not NULL) saying why values above the maximum
 * are refused: "'key' = x: <above_max>; must be <range>". */
int jc_number_why(const json_t *obj, const char *key, int required, struct jc_range r,
                  const char *units, const char *above_max, const char *pointer, double *out,
                  struct tlsph_errors *err);
int jc_integer(const json_t *obj, const char *key, int required, long min, long max,
               const char *pointer, long *out, struct tlsph_errors *err);
int jc_boolean(const json_t *obj, const char *key, int required, const char *pointer, int *out,
               struct tlsph_errors *err);
/* Copies into out (size bytes); rejects empty strings and longer ones. */
int jc_string(const json_t *obj, const char *key, int required, const char *pointer, char *out,
              size_t size, struct tlsph_errors *err);
/* A JSON array of exactly n numbers. */
int jc_vector(const json_t *obj, const char *key, int required, int n, const char *units,
              const char *pointer, double *out, struct tlsph_errors *err);
/* Reports key (when present in obj) as having no effect without the key
 * `needs` (an optional term's parameter given without the term).  Returns 1
 * when reported, 0 otherwise. */
int jc_misplaced(const json_t *obj, const char *key, const char *needs, const char *pointer,
                 struct tlsph_errors *err);
/* Object member that must itself be an object; returns it or NULL (error added when required
 * or when present with the wrong type). */
const json_t *jc_object(const json_t *obj, const char *key, int required, const char *pointer,
                        struct tlsph_errors *err);

#define JC_POSITIVE ((struct jc_range){0.0, 0.0, JC_OPEN, JC_NONE})
#define JC_NONNEGATIVE ((struct jc_range){0.0, 0.0, JC_CLOSED, JC_NONE})
#define JC_ANY ((struct jc_range){0.0, 0.0, JC_NONE, JC_NONE})
#define JC_BETWEEN(a, b) ((struct jc_range){(a), (b), JC_CLOSED, JC_CLOSED})

#endif
