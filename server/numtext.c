/* Numbers as text, see numtext.h. */
#include "numtext.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "strbuf.h"

char *numtext_real(char *buf, size_t size, double v)
{
    /* below DBL_MIN (subnormal) fewer digits are significant: search from 1 */
    const int from = v != 0 && fabs(v) < DBL_MIN ? 1 : 15;
    for (int prec = from; prec <= 17; prec++) {
        snprintf(buf, size, "%.*g", prec, v);
        if (!isfinite(v) || strtod(buf, NULL) == v)
            break;
    }
    if (!isfinite(v))
        return buf;
    /* the exponent as jansson writes it: "1e-07" -> "1e-7", "1e+20" -> "1e20" */
    char *e = strchr(buf, 'e');
    if (e) {
        char *digits = e + 1 + (e[1] == '-' || e[1] == '+');
        char *first = digits + strspn(digits, "0");
        if (!*first)
            first--;
        char *to = e + 1 + (e[1] == '-');
        memmove(to, first, strlen(first) + 1);
    }
    return buf;
}

/* The real token tok[0..n) (as jansson wrote it, 17 digits) into b as
 * numtext_real writes the same value. */
static void add_real(struct strbuf *b, const char *tok, size_t n)
{
    char in[NUMTEXT_REAL_MAX + 8], out[NUMTEXT_REAL_MAX + 8];
    if (n >= sizeof in) {
        strbuf_add(b, tok, n);
        return;
    }
    memcpy(in, tok, n);
    in[n] = '\0';
    numtext_real(out, sizeof out, strtod(in, NULL));
    strbuf_adds(b, out);
    if (!strpbrk(out, ".e")) /* keep it a real: "1" -> "1.0", as jansson writes it */
        strbuf_adds(b, ".0");
}

char *numtext_json_dumps(const json_t *json, size_t flags)
{
    char *raw = json_dumps(json, flags);
    if (!raw)
        return NULL;
    struct strbuf b = {0};
    bool in_string = false;
    const char *p = raw, *copied = raw;
    while (*p) {
        if (in_string) {
            if (*p == '\\' && p[1])
                p++;
            else if (*p == '"')
                in_string = false;
            p++;
            continue;
        }
        if (*p == '"') {
            in_string = true;
            p++;
            continue;
        }
        if (*p != '-' && (*p < '0' || *p > '9')) {
            p++;
            continue;
        }
        /* a number token outside strings: integers pass, reals are shortened */
        const char *end = p + strspn(p, "-+0123456789.eE");
        if (memchr(p, '.', (size_t)(end - p)) || memchr(p, 'e', (size_t)(end - p)) ||
            memchr(p, 'E', (size_t)(end - p))) {
            strbuf_add(&b, copied, (size_t)(p - copied));
            add_real(&b, p, (size_t)(end - p));
            copied = end;
        }
        p = end;
    }
    strbuf_add(&b, copied, (size_t)(p - copied));
    free(raw);
    return strbuf_take(&b);
}
