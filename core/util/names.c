/* The naming rule (names.h). */
#include <stddef.h>
#include <string.h>

#include "util/names.h"

static int name_start(char c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
}

static int name_char(char c)
{
    return name_start(c) || (c >= '0' && c <= '9') || c == '-' || c == '.';
}

int tlsph_name_ok_n(const char *s, size_t len)
{
    if (!s || len == 0 || len > TLSPH_NAME_CHARS_MAX || !name_start(s[0]))
        return 0;
    for (size_t i = 1; i < len; i++)
        if (!name_char(s[i]))
            return 0;
    return 1;
}

int tlsph_name_ok(const char *name)
{
    return name && tlsph_name_ok_n(name, strnlen(name, TLSPH_NAME_CHARS_MAX + 1));
}
