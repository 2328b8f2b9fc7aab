#include "util/errors.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void tlsph_errors_init(struct tlsph_errors *e)
{
    memset(e, 0, sizeof *e);
}

void tlsph_errors_free(struct tlsph_errors *e)
{
    for (size_t i = 0; i < e->count; i++) {
        free(e->items[i].pointer);
        free(e->items[i].message);
    }
    free(e->items);
    memset(e, 0, sizeof *e);
}

void tlsph_errors_add(struct tlsph_errors *e, const char *pointer, const char *fmt, ...)
{
    if (e->count == e->cap) {
        size_t cap = e->cap ? 2 * e->cap : 8;
        struct tlsph_error *items = realloc(e->items, cap * sizeof *items);
        if (!items) {
            e->out_of_memory = 1;
            return;
        }
        e->items = items;
        e->cap = cap;
    }
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    char *p = strdup(pointer ? pointer : "");
    char *m = strdup(buf);
    if (!p || !m) {
        free(p);
        free(m);
        e->out_of_memory = 1;
        return;
    }
    e->items[e->count].pointer = p;
    e->items[e->count].message = m;
    e->count++;
}

void tlsph_pointer_join(char *out, size_t size, const char *base, const char *segment)
{
    size_t n = 0;
    if (size == 0)
        return;
    for (const char *s = base; *s && n + 1 < size; s++)
        out[n++] = *s;
    if (n + 1 < size)
        out[n++] = '/';
    for (const char *s = segment; *s && n + 1 < size; s++) {
        if (*s == '~' || *s == '/') {
            if (n + 2 >= size)
                break;
            out[n++] = '~';
            out[n++] = *s == '~' ? '0' : '1';
        } else {
            out[n++] = *s;
        }
    }
    out[n] = '\0';
}

void tlsph_pointer_index(char *out, size_t size, const char *base, size_t index)
{
    char seg[32];
    snprintf(seg, sizeof seg, "%zu", index);
    tlsph_pointer_join(out, size, base, seg);
}

json_t *tlsph_errors_to_json(const struct tlsph_errors *e)
{
    json_t *arr = json_array();
    if (!arr)
        return NULL;
    for (size_t i = 0; i < e->count; i++) {
        json_t *o = json_pack("{s:s, s:s}", "pointer", e->items[i].pointer, "detail",
                              e->items[i].message);
        if (!o || json_array_append_new(arr, o) != 0) {
            json_decref(arr);
            return NULL;
        }
    }
    return arr;
}
