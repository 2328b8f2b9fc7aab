/* Looks up "x-unit" along a JSON pointer through a JSON Schema (schema_units.h). */
#include "schema_units.h"

#include <regex.h>
#include <stdlib.h>
#include <string.h>

#define MAX_DEPTH 32 /* $ref chains and nesting: the scene schema needs < 10 */

/* The node a local "$ref" ("#/$defs/body") names, or node itself. */
static const json_t *deref(const json_t *root, const json_t *node)
{
    for (int i = 0; i < MAX_DEPTH && json_is_object(node); i++) {
        const char *ref = json_string_value(json_object_get(node, "$ref"));
        if (!ref || strncmp(ref, "#/", 2) != 0)
            return node;
        const json_t *t = root;
        char seg[256];
        for (const char *p = ref + 2; *p && t;) {
            size_t n = strcspn(p, "/");
            if (n >= sizeof seg)
                return NULL;
            memcpy(seg, p, n);
            seg[n] = '\0';
            t = json_object_get(t, seg);
            p += n + (p[n] == '/');
        }
        node = t;
    }
    return node;
}

static int matches(const char *pattern, const char *s)
{
    regex_t re;
    if (regcomp(&re, pattern, REG_EXTENDED | REG_NOSUB) != 0)
        return 0;
    int m = regexec(&re, s, 0, NULL, 0) == 0;
    regfree(&re);
    return m;
}

static int is_index(const char *s)
{
    return *s && strspn(s, "0123456789") == strlen(s);
}

/* seg: the pointer's unescaped segments, NUL-separated, n of them left.  An
 * array's unit holds for its items ("origin": [x, y, z] in m): inherited. */
static const char *unit_at(const json_t *root, const json_t *node, const char *seg, size_t n,
                           const char *inherited, int depth)
{
    node = deref(root, node);
    if (!json_is_object(node) || depth > MAX_DEPTH)
        return NULL;
    const char *own = json_string_value(json_object_get(node, "x-unit"));
    if (n == 0 && (own || inherited))
        return own ? own : inherited;
    const char *combinators[] = {"allOf", "oneOf", "anyOf"};
    for (int c = 0; c < 3; c++) {
        size_t i;
        json_t *sub;
        json_array_foreach(json_object_get(node, combinators[c]), i, sub)
        {
            const char *u = unit_at(root, sub, seg, n, inherited, depth + 1);
            if (u)
                return u;
        }
    }
    if (n == 0)
        return NULL;
    const char *next = seg + strlen(seg) + 1;
    const json_t *child = json_object_get(json_object_get(node, "properties"), seg);
    if (!child) {
        const char *pat;
        json_t *sub;
        json_object_foreach(json_object_get(node, "patternProperties"), pat, sub) if (matches(pat, seg))
        {
            child = sub;
            break;
        }
    }
    if (!child && json_is_object(json_object_get(node, "additionalProperties")))
        child = json_object_get(node, "additionalProperties");
    if (child)
        return unit_at(root, child, next, n - 1, NULL, depth + 1);
    if (is_index(seg) && json_is_object(json_object_get(node, "items")))
        return unit_at(root, json_object_get(node, "items"), next, n - 1, own ? own : inherited, depth + 1);
    return NULL;
}

const char *schema_unit(const json_t *schema, const char *pointer)
{
    if (!schema || !pointer || pointer[0] != '/')
        return NULL;
    /* "/a/b~1c" -> "a\0b/c\0" */
    size_t len = strlen(pointer), n = 0;
    char *segs = malloc(len + 1);
    if (!segs)
        return NULL;
    char *o = segs;
    for (const char *p = pointer + 1;; p++) {
        if (*p == '/' || *p == '\0') {
            *o++ = '\0';
            n++;
            if (*p == '\0')
                break;
        } else if (p[0] == '~' && (p[1] == '0' || p[1] == '1')) {
            *o++ = p[1] == '0' ? '~' : '/';
            p++;
        } else {
            *o++ = *p;
        }
    }
    const char *u = unit_at(schema, schema, segs, n, NULL, 0);
    free(segs);
    return u;
}
