/* What the daemon checks before it serves (server/startup.c), so that it
 * never runs on a database it cannot trust or beside jobs it does not know.
 *
 * 1. The database file passes PRAGMA integrity_check (tq_check_file, which
 *    says why integrity_check and not quick_check).  A damaged file is
 *    refused.  With --recover it is moved aside, with its -wal and -shm, as
 *    tlsphd.sqlite.corrupt-<UTC time>, and a fresh database is made.
 * 2. The queue opens (created and migrated when new).
 * 3. Intent files left by a submission or removal that a crash interrupted
 *    are replayed (intent.h): directories of jobs that never got a row, or
 *    whose rows were deleted, are removed.
 * 4. Every job directory has a row.  One that does not was not made by an
 *    interrupted operation: the database was lost, emptied (a 0-byte file
 *    opens as an empty database), replaced by an older backup or moved
 *    aside.  Starting anyway would orphan those jobs without a word, so the
 *    start is refused, naming how many and one of them.  With --recover each
 *    becomes a run again, its row rebuilt from the directory:
 *      input      scene.json ("{}" when missing: the job cannot run again)
 *      status     from result.h5's /diagnostics status: successful ->
 *                 successful; unstable and io_error -> failed with that
 *                 outcome; cancelled -> dismissed; "running" or unreadable
 *                 (the run died) -> failed, interrupted; no result -> failed,
 *                 interrupted (it had not run, or was cancelled first: the
 *                 two look alike, and a recovery must not start work that
 *                 nobody may want any more; the message says to resubmit)
 *      created    the directory's time; finished: the result's
 *    A study's membership is not kept in its children's directories, so a
 *    recovered child is a run of its own; the study itself is lost.
 *
 * A refusal logs one line that says what was found and what to do, and main
 * exits with TLSPHD_EXIT_UNTRUSTED (docs/deployment.md). */
#ifndef TLSPHD_STARTUP_H
#define TLSPHD_STARTUP_H

#include <stddef.h>

struct tcfg;
struct tq;

/* Exit status of a start refused by these checks. */
#define TLSPHD_EXIT_UNTRUSTED 3

enum startup_rc {
    STARTUP_OK,      /* *q is the main thread's open queue */
    STARTUP_FAILED,  /* something did not work (err says what) */
    STARTUP_REFUSED  /* the data directory cannot be trusted (err says why and what to do) */
};

/* What was done, for main's log. */
struct startup_report {
    char moved_to[1200];  /* --recover: where the damaged database went ("" none) */
    char damage[400];     /* what integrity_check found */
    long interrupted;     /* directories of interrupted submissions/removals removed */
    long recovered;       /* --recover: rows rebuilt from directories */
};

enum startup_rc startup_check(const struct tcfg *cfg, struct tq **q, struct startup_report *rep,
                              char *err, size_t errsize);

#endif
