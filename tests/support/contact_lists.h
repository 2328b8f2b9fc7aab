/* Test support: the contact search's candidate lists against brute force. */
#ifndef TLSPH_TEST_CONTACT_LISTS_H
#define TLSPH_TEST_CONTACT_LISTS_H

#include <stddef.h>

#include "run/model.h"

/* May the pair i, j be a candidate (besides its distance)? */
typedef int (*contact_admit)(const struct tlsph_model *m, size_t i, size_t j);

/* Fails the test unless every particle's candidates are exactly the j != i
 * that admit accepts and that lie closer than R_i + R_j + skin (R of their
 * bodies); returns the number of candidate entries. */
size_t check_candidates(const struct tlsph_model *m, contact_admit admit);

#endif
