/* A growable NUL-terminated string (server/strbuf.c): CSV tables, request
 * bodies, engine progress lines, files read whole.
 *
 * Out of memory is sticky: the first failed growth sets oom, later appends do
 * nothing, and strbuf_take reports it once at the end, so a caller appends
 * without checking each call.  A zeroed struct is an empty buffer. */
#ifndef TLSPHD_STRBUF_H
#define TLSPHD_STRBUF_H

#include <stdbool.h>
#include <stddef.h>

struct strbuf {
    char *p;     /* NULL until the first append, then always NUL-terminated */
    size_t len;  /* bytes before the terminator */
    size_t cap;  /* bytes allocated */
    bool oom;    /* an append failed; the contents are incomplete */
};

/* Appends n bytes of s (which may hold NULs). */
void strbuf_add(struct strbuf *b, const char *s, size_t n);
void strbuf_adds(struct strbuf *b, const char *s);
void strbuf_printf(struct strbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Empties the buffer, keeping its memory (and clearing oom). */
void strbuf_reset(struct strbuf *b);
/* The text (malloc'ed, the caller frees; "" when nothing was appended), or
 * NULL after an out-of-memory; the buffer is empty afterwards either way. */
char *strbuf_take(struct strbuf *b);
void strbuf_free(struct strbuf *b);
/* Reads the rest of fd into b; 0, or -1 with errno (read error or oom). */
int strbuf_read_fd(struct strbuf *b, int fd);
/* The whole file at path (malloc'ed, NUL-terminated; *len bytes when len is
 * not NULL), or NULL with errno. */
char *strbuf_read_file(const char *path, size_t *len);

#endif
