/* Job ids are checked before they go into a URL; other path segments and query
 * values are percent-encoded (series names keep their '/'). */
#include "urls.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exitcodes.h"

int id_valid(const char *id)
{
    size_t n = 0;
    for (; id[n]; n++)
        if (!((id[n] >= '0' && id[n] <= '9') || (id[n] >= 'a' && id[n] <= 'f')))
            return 0;
    return n == 32;
}

int id_check(const char *id)
{
    if (id_valid(id))
        return RC_OK;
    fprintf(stderr, "tlsph: '%s' is not a job id (32 lowercase hex digits)\n", id);
    return RC_USAGE;
}

char *url_escape(const char *s, int keep_slash)
{
    static const char hex[] = "0123456789ABCDEF";
    size_t n = strlen(s);
    char *out = malloc(3 * n + 1), *o = out;
    if (!out)
        return NULL;
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        unsigned char c = *p;
        if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' ||
            c == '.' || c == '_' || c == '~' || (keep_slash && c == '/')) {
            *o++ = (char)c;
        } else {
            *o++ = '%';
            *o++ = hex[c >> 4];
            *o++ = hex[c & 15];
        }
    }
    *o = '\0';
    return out;
}

char *url_series_path(const char *id, const char *name, int csv)
{
    char *esc = url_escape(name, 1);
    if (!esc)
        return NULL;
    size_t n = strlen(esc) + 96;
    char *p = malloc(n);
    if (p)
        snprintf(p, n, "/jobs/%s/results/series/%s%s", id, esc, csv ? "?format=csv" : "");
    free(esc);
    return p;
}
