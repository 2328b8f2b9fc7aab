/* Reading a JSON input file (scene or study) with a size cap. */
#ifndef TLSPH_CLIENT_JSONFILE_H
#define TLSPH_CLIENT_JSONFILE_H

#include <jansson.h>

/* Loads path ("-" = stdin) into *out.  Returns RC_IO (unreadable), RC_USAGE (not JSON)
 * or RC_OK; errors are printed. */
int jsonfile_load(const char *path, json_t **out);

#endif
