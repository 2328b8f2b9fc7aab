/* The /cost and /diagnostics groups of the result file: created with
 * placeholder values when the file is laid out (SWMR forbids creating anything
 * later) and rewritten in place at close.  Attribute list: output.h. */
#ifndef TLSPH_OUTPUT_RECORDS_H
#define TLSPH_OUTPUT_RECORDS_H

#include <hdf5.h>

#include "io/output/output.h"

/* Creates both groups in file; the cost placeholders are the model's particle
 * and pair counts, -1 and NaN, the status "running".  Returns 0 or -1. */
int tlsph_records_create(hid_t file, const struct tlsph_model *m);
/* Rewrites /cost from cost (left alone when NULL) and /diagnostics from status
 * (NULL: "unknown") and d (NULL: the placeholders stay).  Returns 0 or -1. */
int tlsph_records_write(hid_t file, const struct tlsph_cost *cost, const char *status,
                        const struct tlsph_diagnostic *d);

#endif
