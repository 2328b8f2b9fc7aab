/* Name lists, "a, b, c": how a family's table of descriptors
 * (core/material/{eos,strength,damage}/registry.c) spells the names of its rows.
 * The table's X-macro writes the list once, as one string literal, and the list
 * serves twice: error messages quote it, and it is the table's index, the k-th
 * name naming the k-th row. */
#ifndef TLSPH_NAME_LIST_H
#define TLSPH_NAME_LIST_H

/* An X-macro's row as ", id": LIST(TLSPH_LISTED) is ", a, b, c", and + 2
 * drops the first separator. */
#define TLSPH_LISTED(id) ", " #id

/* The position (0, 1, ...) of name in list, or -1 when no name of the list is
 * exactly name. */
int tlsph_name_list_index(const char *list, const char *name);

#endif
