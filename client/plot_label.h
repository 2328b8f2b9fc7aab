/* Axis labels that name the quantity: "kinetic energy [J]", "energy [J]" for
 * several energies, "reaction force x of groups/right [N]". */
#ifndef TLSPH_CLIENT_PLOT_LABEL_H
#define TLSPH_CLIENT_PLOT_LABEL_H

#include <stddef.h>

/* What one plotted line shows. */
typedef struct {
    const char *quantity;  /* "kinetic energy", "reaction force" */
    const char *component; /* "x", or NULL for a scalar */
    const char *owner;     /* "groups/right", or NULL for a global series */
    const char *units;     /* "J"; "" when unknown */
} plot_quantity;

/* Splits a series name "groups/right/reaction_force" into its quantity
 * ("reaction force": the last segment, '_' read as a space) and its owner
 * ("groups/right", "" for "kinetic_energy"). */
void plot_name_split(const char *series, char *owner, size_t owner_size, char *quantity,
                     size_t quantity_size);

/* The axis label of lines q[0..n-1] (n >= 1, one unit between them), at most
 * max_chars characters: the one line's full description; else the quantity
 * they share, or the words their quantities end with ("energy" for kinetic
 * and internal energy), or their list, or the quantity their unit measures;
 * then the unit in brackets.  Writes a NUL-terminated string into buf. */
void plot_axis_label(char *buf, size_t size, size_t max_chars, const plot_quantity *q, size_t n);

#endif
