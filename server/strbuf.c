/* A growable string, see strbuf.h. */
#include "strbuf.h"

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define STRBUF_FIRST 1024

/* Room for `more` bytes plus the terminator; false (and oom) when it cannot. */
static bool grow(struct strbuf *b, size_t more)
{
    if (b->oom)
        return false;
    if (b->p && b->len + more < b->cap)
        return true;
    size_t cap = b->cap ? b->cap : STRBUF_FIRST;
    while (cap <= b->len + more) {
        if (cap > (size_t)-1 / 2) {
            b->oom = true;
            return false;
        }
        cap *= 2;
    }
    char *q = realloc(b->p, cap);
    if (!q) {
        b->oom = true;
        return false;
    }
    b->p = q;
    b->cap = cap;
    return true;
}

void strbuf_add(struct strbuf *b, const char *s, size_t n)
{
    if (!grow(b, n))
        return;
    if (n)
        memcpy(b->p + b->len, s, n);
    b->len += n;
    b->p[b->len] = '\0';
}

void strbuf_adds(struct strbuf *b, const char *s)
{
    strbuf_add(b, s, strlen(s));
}

void strbuf_printf(struct strbuf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0) {
        b->oom = true;
        return;
    }
    if (!grow(b, (size_t)n))
        return;
    va_start(ap, fmt);
    vsnprintf(b->p + b->len, b->cap - b->len, fmt, ap);
    va_end(ap);
    b->len += (size_t)n;
}

void strbuf_reset(struct strbuf *b)
{
    b->len = 0;
    b->oom = false;
    if (b->p)
        b->p[0] = '\0';
}

char *strbuf_take(struct strbuf *b)
{
    char *out = b->oom ? NULL : b->p ? b->p : strdup("");
    if (b->oom)
        free(b->p);
    b->p = NULL;
    b->len = b->cap = 0;
    b->oom = false;
    return out;
}

void strbuf_free(struct strbuf *b)
{
    free(b->p);
    b->p = NULL;
    b->len = b->cap = 0;
    b->oom = false;
}

int strbuf_read_fd(struct strbuf *b, int fd)
{
    for (;;) {
        if (!grow(b, 65536)) {
            errno = ENOMEM;
            return -1;
        }
        ssize_t n = read(fd, b->p + b->len, b->cap - b->len - 1);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            return -1;
        if (n == 0)
            return 0;
        b->len += (size_t)n;
        b->p[b->len] = '\0';
    }
}

char *strbuf_read_file(const char *path, size_t *len)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return NULL;
    struct strbuf b = {0};
    const int rc = strbuf_read_fd(&b, fd);
    const int e = errno;
    close(fd);
    if (rc != 0) {
        strbuf_free(&b);
        errno = e;
        return NULL;
    }
    if (len)
        *len = b.len;
    return strbuf_take(&b);
}
