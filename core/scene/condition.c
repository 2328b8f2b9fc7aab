/* Selector conditions: libmatheval has no comparison or logical operators, so a
 * selector expression such as "x < 0.001 && y >= 0" is rewritten into plain
 * arithmetic that evaluates to 1 (selected) or 0 before it is compiled:
 *
 *   A <  B  ->  (1-step((A)-(B)))        A <= B  ->  step((B)-(A))
 *   A >  B  ->  (1-step((B)-(A)))        A >= B  ->  step((A)-(B))
 *   P && Q  ->  ((P)*(Q))                P || Q  ->  (1-(1-(P))*(1-(Q)))
 *
 * using libmatheval's step(u) = 1 for u >= 0, else 0.  Precedence: || binds
 * loosest, then &&, then one comparison per operand (no chains like a<b<c);
 * parentheses group conditions.  Comparisons inside function arguments are not
 * supported and reported. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/parse_internal.h"

static char *fmt(const char *f, ...) __attribute__((format(printf, 1, 2)));
static char *fmt(const char *f, ...)
{
    va_list ap;
    va_start(ap, f);
    int n = vsnprintf(NULL, 0, f, ap);
    va_end(ap);
    if (n < 0)
        return NULL;
    char *s = malloc((size_t)n + 1);
    if (!s)
        return NULL;
    va_start(ap, f);
    vsnprintf(s, (size_t)n + 1, f, ap);
    va_end(ap);
    return s;
}

static char *dup_range(const char *s, size_t a, size_t b)
{
    while (a < b && (s[a] == ' ' || s[a] == '\t'))
        a++;
    while (b > a && (s[b - 1] == ' ' || s[b - 1] == '\t'))
        b--;
    char *r = malloc(b - a + 1);
    if (!r)
        return NULL;
    memcpy(r, s + a, b - a);
    r[b - a] = '\0';
    return r;
}

/* Position of the first top-level (depth 0) occurrence of op, or -1. */
static long find_top(const char *s, const char *op)
{
    int depth = 0;
    const size_t len = strlen(op);
    for (size_t i = 0; s[i]; i++) {
        if (s[i] == '(')
            depth++;
        else if (s[i] == ')')
            depth--;
        else if (depth == 0 && strncmp(s + i, op, len) == 0)
            return (long)i;
    }
    return -1;
}

static int has_condition_chars(const char *s)
{
    return strpbrk(s, "<>&|") != NULL;
}

/* Whole string is one parenthesised group "( ... )". */
static int wrapped(const char *s)
{
    size_t n = strlen(s);
    if (n < 2 || s[0] != '(' || s[n - 1] != ')')
        return 0;
    int depth = 0;
    for (size_t i = 0; i < n; i++) {
        depth += s[i] == '(' ? 1 : s[i] == ')' ? -1 : 0;
        if (depth == 0 && i + 1 < n)
            return 0;
    }
    return 1;
}

static char *rewrite(const char *s, char *msg, size_t size, int depth);

/* Splits s at the first top-level op and combines the rewritten halves. */
static char *split(const char *s, long at, size_t oplen, const char *pattern, char *msg,
                   size_t size, int depth)
{
    char *l = dup_range(s, 0, (size_t)at), *r = dup_range(s, (size_t)at + oplen, strlen(s));
    char *lr = NULL, *rr = NULL, *out = NULL;
    if (!l || !r)
        goto done;
    if (!*l || !*r) {
        snprintf(msg, size, "operator '%.*s' needs an operand on each side", (int)oplen, s + at);
        goto done;
    }
    lr = rewrite(l, msg, size, depth + 1);
    rr = lr ? rewrite(r, msg, size, depth + 1) : NULL;
    if (lr && rr)
        out = strcmp(pattern, "||") == 0 ? fmt("(1-(1-(%s))*(1-(%s)))", lr, rr)
                                         : fmt("((%s)*(%s))", lr, rr);
done:
    free(l);
    free(r);
    free(lr);
    free(rr);
    return out;
}

static char *rewrite(const char *s, char *msg, size_t size, int depth)
{
    if (depth > 200) {
        snprintf(msg, size, "condition nested too deeply");
        return NULL;
    }
    long at = find_top(s, "||");
    if (at >= 0)
        return split(s, at, 2, "||", msg, size, depth);
    at = find_top(s, "&&");
    if (at >= 0)
        return split(s, at, 2, "&&", msg, size, depth);
    long lt = find_top(s, "<"), gt = find_top(s, ">");
    if (lt >= 0 || gt >= 0) {
        const long pos = lt < 0 ? gt : gt < 0 ? lt : (lt < gt ? lt : gt);
        const int less = s[pos] == '<', eq = s[pos + 1] == '=';
        const size_t oplen = eq ? 2 : 1;
        char *l = dup_range(s, 0, (size_t)pos);
        char *r = dup_range(s, (size_t)pos + oplen, strlen(s));
        char *out = NULL;
        if (!l || !r)
            goto cmp_done;
        if (!*l || !*r) {
            snprintf(msg, size, "comparison '%.*s' needs an operand on each side", (int)oplen,
                     s + pos);
            goto cmp_done;
        }
        if (find_top(r, "<") >= 0 || find_top(r, ">") >= 0) {
            snprintf(msg, size, "chained comparisons (a < b < c) are not supported; use &&");
            goto cmp_done;
        }
        if (has_condition_chars(l) || has_condition_chars(r)) {
            snprintf(msg, size, "a comparison operand may not itself contain a condition");
            goto cmp_done;
        }
        if (less && !eq)
            out = fmt("(1-step((%s)-(%s)))", l, r);
        else if (less)
            out = fmt("step((%s)-(%s))", r, l);
        else if (!eq)
            out = fmt("(1-step((%s)-(%s)))", r, l);
        else
            out = fmt("step((%s)-(%s))", l, r);
    cmp_done:
        free(l);
        free(r);
        return out;
    }
    if (!has_condition_chars(s))
        return strdup(s);
    if (wrapped(s)) {
        char *inner = dup_range(s, 1, strlen(s) - 1);
        if (!inner)
            return NULL;
        char *r = rewrite(inner, msg, size, depth + 1);
        free(inner);
        if (!r)
            return NULL;
        char *out = fmt("(%s)", r);
        free(r);
        return out;
    }
    snprintf(msg, size,
             "misplaced '<', '>', '&' or '|': conditions may not appear inside function "
             "arguments or arithmetic; use &&, || and parentheses");
    return NULL;
}

char *tlsph_condition_rewrite(const char *text, char *msg, size_t msg_size)
{
    if (msg_size)
        msg[0] = '\0';
    return rewrite(text, msg, msg_size, 0);
}
