/* Error lists: every validation or run-time problem is a {JSON pointer, message}
 * pair.  Library code never prints or exits; it fills one of these lists and
 * returns a status, and the CLI or the daemon decides how to show it.
 *
 * Ownership: the list owns its strings; tlsph_errors_free releases them. */
#ifndef TLSPH_ERRORS_H
#define TLSPH_ERRORS_H

#include <stddef.h>
#include <jansson.h>

/* Enough for any pointer the scene validator builds (nesting is bounded). */
#define TLSPH_POINTER_MAX 512

struct tlsph_error {
    char *pointer; /* RFC 6901 JSON pointer into the scene ("" = whole document) */
    char *message; /* human-readable, names the field and the accepted range */
};

struct tlsph_errors {
    size_t count, cap;
    struct tlsph_error *items;
    int out_of_memory; /* set when an error could not be recorded */
};

void tlsph_errors_init(struct tlsph_errors *e);
void tlsph_errors_free(struct tlsph_errors *e);
/* printf-style; never fails visibly (sets out_of_memory instead). */
void tlsph_errors_add(struct tlsph_errors *e, const char *pointer, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* Appends "/segment" to base with RFC 6901 escaping (~ -> ~0, / -> ~1).
 * Writes at most size bytes (truncates, always terminated). */
void tlsph_pointer_join(char *out, size_t size, const char *base, const char *segment);
void tlsph_pointer_index(char *out, size_t size, const char *base, size_t index);
/* [{"pointer": ..., "detail": ...}, ...]; NULL on allocation failure. */
json_t *tlsph_errors_to_json(const struct tlsph_errors *e);

#endif
