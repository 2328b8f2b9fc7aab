/* Numbers as text, one way everywhere the daemon writes them
 * (server/numtext.c): the shortest decimal that reads back as the same
 * double, so 0.05 is "0.05" in a JSON answer, a CSV table and a stored scene
 * alike (jansson alone prints every real with 17 digits:
 * 0.050000000000000003).
 *
 * numtext_real writes %.15g, %.16g or %.17g, the first that strtod reads
 * back exactly (a normal double carries 15.95 significant decimal digits, so
 * a shorter decimal that reads back is what %.15g prints once %g has dropped
 * its trailing zeros; a subnormal one carries fewer and is searched from
 * %.1g on).
 * Exponents are written the way jansson writes them ("1e-7", "1e20"), so a
 * CSV cell is the same text as its JSON twin; only an integral real gets
 * ".0" in JSON ("1.0", so that a JSON reader still sees a real) where CSV
 * writes "1".  numtext_json_dumps is json_dumps with every real so written. */
#ifndef TLSPHD_NUMTEXT_H
#define TLSPHD_NUMTEXT_H

#include <stddef.h>

#include <jansson.h>

/* Room for any double numtext_real writes ("-2.2250738585072014e-308" + ".0"). */
#define NUMTEXT_REAL_MAX 32

/* The shortest round-trip text of v into buf (NUMTEXT_REAL_MAX bytes suffice);
 * "nan", "inf" or "-inf" for non-finite values.  Returns buf. */
char *numtext_real(char *buf, size_t size, double v);
/* json_dumps(json, flags) with shortest reals (malloc'ed, the caller frees),
 * NULL when jansson fails or out of memory. */
char *numtext_json_dumps(const json_t *json, size_t flags);

#endif
