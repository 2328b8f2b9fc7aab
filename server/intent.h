/* Intent files (server/intent.c): what makes creating and removing job
 * directories crash-safe beside the database.
 *
 * A submission creates one directory per job and then inserts every row in
 * one transaction; a removal deletes the rows and then the directories.  A
 * crash (kill -9, power) between the two leaves directories without rows:
 * hundreds for an interrupted study.  So before the first directory is
 * touched, the ids are written durably to an intent file
 *   <jobs_dir>/.intent-<random hex>   one id per line
 * (the leading '.' keeps it apart from job directories), and the file is
 * removed once the directories and rows agree.  At start-up intent_replay
 * reads every intent file left behind: a listed id that has a row was
 * committed and keeps its directory; one without a row belongs to a
 * submission that never committed, or a removal that did, and its directory
 * is removed.  A directory that has no row and is in no intent file was not
 * made by an interrupted operation: see startup.h. */
#ifndef TLSPHD_INTENT_H
#define TLSPHD_INTENT_H

#include <limits.h>
#include <stddef.h>

struct intent {
    char path[PATH_MAX]; /* the intent file, "" when none is open */
};

/* Writes the n ids (job ids, job_id_valid) to a new intent file durably
 * (temporary file, fsync, rename, fsync of jobs_dir, which is made when
 * missing).  0, or -1 with err. */
int intent_begin(struct intent *in, const char *jobs_dir, const char *const *ids, size_t n,
                 char *err, size_t errsize);
/* Removes the intent file (a leftover is harmless: replay finds the rows). */
void intent_end(struct intent *in);

/* Does job id have a row?  1 yes, 0 no, -1 the queue did not answer. */
typedef int intent_has_row_fn(void *ctx, const char *id);
/* Replays every intent file under jobs_dir (see above): *removed gets the
 * number of directories removed.  0, or -1 with err (the files that could
 * not be replayed stay for the next start). */
int intent_replay(const char *jobs_dir, intent_has_row_fn *has_row, void *ctx, long *removed,
                  char *err, size_t errsize);

#endif
