/* Job ids (server/jobid.c): the one definition of what an id looks like.
 *
 * The daemon issues ids of JOB_ID_LEN lowercase hex digits (128 random bits),
 * and only an id of exactly that form ever becomes part of a path (the job
 * directory) or is looked up for a request: job_id_valid.  The queue stores
 * any key of 1..JOB_ID_LEN characters of [0-9A-Za-z_-] (job_key_valid), a
 * superset that lets tests and tools use readable keys; the queue binds every
 * value, so a key never needs to be safe as a path. */
#ifndef TLSPHD_JOBID_H
#define TLSPHD_JOBID_H

#include <stdbool.h>

#define JOB_ID_LEN 32

/* Fills out with a fresh id from getrandom.  0, or -1 with errno. */
int job_id_new(char out[JOB_ID_LEN + 1]);
/* Exactly JOB_ID_LEN characters of [0-9a-f] (NULL: false). */
bool job_id_valid(const char *id);
/* 1..JOB_ID_LEN characters of [0-9A-Za-z_-] (NULL: false). */
bool job_key_valid(const char *key);

#endif
