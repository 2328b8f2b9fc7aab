/* The key-table reader (see keys.h).  Messages are json_check.h's, so that a
 * key read from a table is reported exactly as the hand-written checks did. */
#include "scene/keys.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Longest table: the allowed-key list is built on the stack. */
#define KEYS_MAX 32
/* Longest choice or model name, with its NUL. */
#define CHOICE_MAX 64

void tlsph_key_error(struct tlsph_errors *err, const char *pointer, const char *key,
                     const char *fmt, ...)
{
    char p[TLSPH_POINTER_MAX], msg[1024];
    tlsph_pointer_join(p, sizeof p, pointer, key);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    tlsph_errors_add(err, p, "%s", msg);
}

const struct tlsph_key *tlsph_key_find(const struct tlsph_key_table *t, const char *name)
{
    for (size_t i = 0; i < t->nkeys; i++)
        if (strcmp(t->keys[i].name, name) == 0)
            return &t->keys[i];
    return NULL;
}

void tlsph_keys_names(const struct tlsph_key_table *t, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < t->nkeys && len + 1 < size; i++) {
        const int w = snprintf(buf + len, size - len, "%s%s", i ? ", " : "", t->keys[i].name);
        len += w > 0 ? (size_t)w : 0;
    }
}

int tlsph_keys_unknown(const json_t *obj, const struct tlsph_key_table *t, const char *pointer,
                       struct tlsph_errors *err)
{
    const char *names[KEYS_MAX + 1];
    size_t n = 0;
    for (size_t i = 0; i < t->nkeys && n < KEYS_MAX; i++)
        names[n++] = t->keys[i].name;
    names[n] = NULL;
    return jc_unknown_keys(obj, names, pointer, err) != 0 ? -1 : 0;
}

static void *slot(const struct tlsph_key_target *to, const struct tlsph_key *k)
{
    return k->offset == TLSPH_KEY_NOWHERE ? NULL : (char *)to->base + k->offset;
}

static void store_int(void *at, const struct tlsph_key *k, long v)
{
    if (!at)
        return;
    if (k->size == sizeof(int)) {
        const int i = (int)v;
        memcpy(at, &i, sizeof i);
    } else {
        memcpy(at, &v, sizeof v);
    }
}

static const char *said(const struct tlsph_key *k)
{
    if (k->said)
        return k->said;
    return strcmp(k->unit, "1") == 0 ? "(dimensionless)" : k->unit;
}

void tlsph_keys_defaults(const struct tlsph_key_table *t, void *base)
{
    const struct tlsph_key_target to = {.base = base};
    for (size_t i = 0; i < t->nkeys; i++) {
        const struct tlsph_key *k = &t->keys[i];
        if (k->flags & (TLSPH_KEY_CALLER | TLSPH_KEY_REFUSED))
            continue;
        if (k->kind == TLSPH_KEY_OBJECT && k->table) {
            tlsph_keys_defaults(k->table, base);
            continue;
        }
        void *at = slot(&to, k);
        if (!(k->flags & TLSPH_KEY_DEFAULT) || !at)
            continue;
        switch (k->kind) {
        case TLSPH_KEY_NUMBER: memcpy(at, &k->def, sizeof k->def); break;
        case TLSPH_KEY_INTEGER: store_int(at, k, (long)k->def); break;
        case TLSPH_KEY_BOOLEAN:
        case TLSPH_KEY_CHOICE: {
            const int v = (int)k->def;
            memcpy(at, &v, sizeof v);
            break;
        }
        case TLSPH_KEY_STRING: snprintf(at, k->size, "%s", k->def_text); break;
        case TLSPH_KEY_OBJECT:
        case TLSPH_KEY_ARRAY:
        case TLSPH_KEY_EXPRESSION: break;
        }
    }
}

static int read_choice(const json_t *obj, const struct tlsph_key *k, int required,
                       const char *pointer, void *at, struct tlsph_errors *err)
{
    char v[CHOICE_MAX];
    const size_t size = k->size && k->size < sizeof v ? k->size : sizeof v;
    const int r = jc_string(obj, k->name, required, pointer, v, size, err);
    if (r != 0)
        return r;
    for (const struct tlsph_key_choice *c = k->choices; c->name; c++)
        if (strcmp(c->name, v) == 0) {
            if (at)
                memcpy(at, &c->value, sizeof c->value);
            return 0;
        }
    char list[400] = "";
    size_t len = 0;
    for (const struct tlsph_key_choice *c = k->choices; c->name && len + 1 < sizeof list; c++)
        len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", c == k->choices ? "" : ", ",
                                c->name);
    tlsph_key_error(err, pointer, k->name, "unknown %s '%s' (accepted: %s)", k->noun, v, list);
    return -1;
}

int tlsph_keys_object(const json_t *obj, const char *name, int required,
                      const struct tlsph_key_table *t, const char *pointer,
                      const struct tlsph_key_target *to, struct tlsph_errors *err)
{
    const json_t *sub = jc_object(obj, name, required, pointer, err);
    if (!sub)
        return json_object_get(obj, name) || required ? -1 : 1;
    char p[TLSPH_POINTER_MAX];
    tlsph_pointer_join(p, sizeof p, pointer, name);
    return tlsph_keys_read(sub, t, p, to, err);
}

/* The object obj[k->name] with k's table: 1 absent, 0 read, -1 reported. */
static int read_object(const json_t *obj, const struct tlsph_key *k, const char *pointer,
                       const struct tlsph_key_target *to, struct tlsph_errors *err)
{
    return tlsph_keys_object(obj, k->name, (k->flags & TLSPH_KEY_REQUIRED) != 0, k->table, pointer,
                             to, err);
}

/* One key that is not the caller's: 0 valid or absent, -1 reported. */
static int read_key(const json_t *obj, const struct tlsph_key *k, const char *pointer,
                    const struct tlsph_key_target *to, struct tlsph_errors *err)
{
    if (k->with && !json_object_get(obj, k->with))
        return jc_misplaced(obj, k->name, k->with, pointer, err) ? -1 : 0;
    const int required = (k->flags & TLSPH_KEY_REQUIRED) != 0;
    void *at = slot(to, k);
    int r = 1;
    switch (k->kind) {
    case TLSPH_KEY_NUMBER: {
        double x;
        r = jc_number_why(obj, k->name, required, k->range, said(k), k->above_max, pointer, &x,
                          err);
        if (r != 0)
            break;
        if (at)
            memcpy(at, &x, sizeof x);
        if ((k->flags & TLSPH_KEY_BELOW_E) && to->youngs_modulus > 0.0 && x >= to->youngs_modulus) {
            tlsph_key_error(err, pointer, k->name,
                            "'%s' = %g Pa must be below the Young's modulus E = %g Pa", k->name, x,
                            to->youngs_modulus);
            r = -1;
        }
        break;
    }
    case TLSPH_KEY_INTEGER: {
        long v;
        r = jc_integer(obj, k->name, required, (long)k->range.min, (long)k->range.max, pointer, &v,
                       err);
        if (r == 0)
            store_int(at, k, v);
        break;
    }
    case TLSPH_KEY_BOOLEAN: {
        int v;
        r = jc_boolean(obj, k->name, required, pointer, &v, err);
        if (r == 0 && at)
            memcpy(at, &v, sizeof v);
        break;
    }
    case TLSPH_KEY_CHOICE: r = read_choice(obj, k, required, pointer, at, err); break;
    case TLSPH_KEY_STRING:
        if (at)
            r = jc_string(obj, k->name, required, pointer, at, k->size, err);
        if (r == 0 && at && (k->flags & TLSPH_KEY_NAME)) {
            char p[TLSPH_POINTER_MAX];
            tlsph_pointer_join(p, sizeof p, pointer, k->name);
            r = tlsph_scene_check_name(at, k->noun ? k->noun : k->name, p, err);
        }
        break;
    case TLSPH_KEY_OBJECT: r = read_object(obj, k, pointer, to, err); break;
    case TLSPH_KEY_ARRAY:
    case TLSPH_KEY_EXPRESSION: break;
    }
    if (r == 0 && to->terms)
        *to->terms |= k->term;
    return r < 0 ? -1 : 0;
}

int tlsph_keys_values(const json_t *obj, const struct tlsph_key_table *t, const char *pointer,
                      const struct tlsph_key_target *to, struct tlsph_errors *err)
{
    tlsph_keys_defaults(t, to->base);
    int bad = 0;
    for (size_t i = 0; i < t->nkeys; i++)
        if (!(t->keys[i].flags & (TLSPH_KEY_CALLER | TLSPH_KEY_REFUSED)))
            bad |= read_key(obj, &t->keys[i], pointer, to, err) != 0;
    return bad ? -1 : 0;
}

int tlsph_keys_read(const json_t *obj, const struct tlsph_key_table *t, const char *pointer,
                    const struct tlsph_key_target *to, struct tlsph_errors *err)
{
    int bad = tlsph_keys_unknown(obj, t, pointer, err) != 0;
    bad |= tlsph_keys_values(obj, t, pointer, to, err) != 0;
    return bad ? -1 : 0;
}

int tlsph_keys_member(const json_t *obj, const struct tlsph_key_table *parent, const char *name,
                      const char *pointer, const struct tlsph_key_target *to,
                      struct tlsph_errors *err)
{
    const struct tlsph_key *k = tlsph_key_find(parent, name);
    return k && k->kind == TLSPH_KEY_OBJECT && k->table ? read_object(obj, k, pointer, to, err)
                                                        : -1;
}
