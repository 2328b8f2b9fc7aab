/* The study summary as a table for people (`tlsph study table`; --csv is the
 * one for programs):
 *  - units in the header: a swept pointer's from the scene schema's "x-unit"
 *    ("/time/end [s]"), the cost columns' own ("wall [s]", "speed [1/s]" =
 *    particle steps per second); outputs have none (the summary does not say
 *    which series an output reduces);
 *  - numbers alike within a column: integers as they are; reals with
 *    STUDY_TABLE_DIGITS significant digits, in fixed notation aligned on the
 *    decimal point when every one lies in [1e-3, 1e4), else all in scientific
 *    notation;
 *  - at most max_width characters a line: job ids shortened to their first
 *    8 characters, then pointers to their last segments, then the columns
 *    split into blocks (each repeating seq) one under the other. */
#ifndef TLSPH_CLIENT_STUDY_TABLE_H
#define TLSPH_CLIENT_STUDY_TABLE_H

#include <jansson.h>
#include <stdio.h>

#define STUDY_TABLE_DIGITS 4
#define STUDY_TABLE_WIDTH 100

/* Prints summary ({"columns": [...], "rows": [[...], ...]}) to f; schema (the
 * scene schema, may be NULL) gives the pointers' units.  A note on what was
 * shortened goes to note (may be NULL).  Returns 0, -1 when out of memory. */
int study_table_print(FILE *f, FILE *note, const json_t *summary, const json_t *schema, size_t max_width);

#endif
