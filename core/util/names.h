/* The naming rule: one definition for every name a user gives that becomes
 * part of an HDF5 path in the result file or of a series name in the API
 * (materials, bodies, boundary conditions, gauges, sections).
 *
 *   1 to 63 characters, each a letter A-Z a-z, a digit, '_', '-' or '.', the
 *   first a letter or '_' (the JSON Schema pattern TLSPH_NAME_PATTERN).
 *
 * Why these characters: '/' separates HDF5 groups and series-name segments,
 * so a name holding one would land in another group (or collide with a name
 * that writes '_' in its place); "." and ".." name a group or its parent in
 * paths and URLs, and a leading letter or '_' keeps every name from being
 * one of them; a space or any other character would need quoting in URLs,
 * CSV headers and shells.  With the rule, two different names are two
 * different HDF5 groups, and every series the engine writes can be listed,
 * fetched and used as a study output by the daemon, which checks its series
 * names with the same function (server/results_h5.c).
 *
 * Shared by the engine (core/scene/names.c) and the daemon. */
#ifndef TLSPH_NAMES_H
#define TLSPH_NAMES_H

#include <stddef.h>

#define TLSPH_NAME_CHARS_MAX 63 /* characters of a name (without the NUL) */
#define TLSPH_NAME_PATTERN   "^[A-Za-z_][A-Za-z0-9_.-]{0,62}$"
/* The rule in words, for error messages. */
#define TLSPH_NAME_RULE                                                     \
    "1 to 63 characters, each a letter A-Z a-z, a digit, '_', '-' or '.', " \
    "the first a letter or '_'"

/* 1 when name follows the rule, 0 otherwise (NULL included). */
int tlsph_name_ok(const char *name);
/* 1 when the first len bytes of s follow the rule (s need not end there). */
int tlsph_name_ok_n(const char *s, size_t len);

#endif
