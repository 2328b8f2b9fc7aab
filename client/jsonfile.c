/* Input files are read whole (at most HTTP_MAX_BODY bytes) and parsed with jansson;
 * parse errors are reported as file:line:column. */
#include "jsonfile.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "exitcodes.h"
#include "http.h"

int jsonfile_load(const char *path, json_t **out)
{
    *out = NULL;
    int is_stdin = strcmp(path, "-") == 0;
    FILE *f = is_stdin ? stdin : fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "tlsph: cannot open %s: %s\n", path, strerror(errno));
        return RC_IO;
    }
    size_t cap = 65536, len = 0;
    char *buf = malloc(cap);
    int rc = buf ? RC_OK : RC_IO;
    while (rc == RC_OK) {
        if (len == cap) {
            if (cap >= HTTP_MAX_BODY) {
                fprintf(stderr, "tlsph: %s is larger than %zu MiB\n", path, HTTP_MAX_BODY >> 20);
                rc = RC_IO;
                break;
            }
            char *nb = realloc(buf, cap * 2);
            if (!nb) {
                rc = RC_IO;
                break;
            }
            buf = nb;
            cap *= 2;
        }
        size_t k = fread(buf + len, 1, cap - len, f);
        len += k;
        if (k == 0) {
            if (ferror(f)) {
                fprintf(stderr, "tlsph: cannot read %s: %s\n", path, strerror(errno));
                rc = RC_IO;
            }
            break;
        }
    }
    if (!is_stdin)
        fclose(f);
    if (!buf)
        fprintf(stderr, "tlsph: out of memory\n");
    if (rc == RC_OK) {
        json_error_t err;
        *out = json_loadb(buf, len, JSON_REJECT_DUPLICATES, &err);
        if (!*out) {
            fprintf(stderr, "tlsph: %s:%d:%d: not valid JSON: %s\n", path, err.line, err.column, err.text);
            rc = RC_USAGE;
        }
    }
    free(buf);
    return rc;
}
