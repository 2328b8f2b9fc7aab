/* Final states the queue has not taken yet (server/finals.c).
 *
 * When an engine ends, the supervisor writes the job's final state.  On a
 * full disk (or a busy or failing database) that write fails, and a job whose
 * engine is gone would stay `running` for good: nothing else ever finishes
 * it.  So a state that cannot be written is kept here and written again on
 * every retry until the queue takes it; the first failure that is SQLite's
 * "database or disk is full" also frees the reserve file (storage.h) and
 * tries again at once.  /healthz reports the jobs still waiting and why.
 *
 * Threads: the supervisor thread records and retries; finals_pending may be
 * read from any thread.  A daemon that stops with states still waiting
 * leaves those jobs `running`; the next start's recovery (tq_recover)
 * requeues or fails them. */
#ifndef TLSPHD_FINALS_H
#define TLSPHD_FINALS_H

#include <stddef.h>

struct tq;
struct tcfg;
struct finals; /* opaque */

/* storage: the configuration whose reserve may be freed (NULL: none).  NULL
 * when out of memory. */
struct finals *finals_new(const struct tcfg *storage);
void finals_free(struct finals *f);

/* Writes the final state (tq_finish) now, or keeps it for finals_retry.
 * message and cost may be NULL.  0 written, 1 kept, -1 lost (out of memory). */
int finals_record(struct finals *f, struct tq *q, const char *id, const char *status,
                  const char *outcome, const char *message, const char *cost);
/* Writes the states kept so far, in order; returns how many still wait. */
size_t finals_retry(struct finals *f, struct tq *q);
/* How many wait, and why the last write failed (into why, "" when none
 * wait).  Any thread. */
size_t finals_pending(struct finals *f, char *why, size_t size);

#endif
