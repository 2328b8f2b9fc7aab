/* Final states the queue has not taken yet, see finals.h. */
#include "finals.h"

#include <pthread.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "errmsg.h"
#include "jobid.h"
#include "queue.h"
#include "storage.h"

struct final_state {
    char id[JOB_ID_LEN + 1];
    char status[16], outcome[16];
    char *message, *cost;
};

struct finals {
    const struct tcfg *storage;
    struct final_state *v;
    size_t n, cap;
    pthread_mutex_t mu; /* n and why, for finals_pending */
    char why[256];
};

struct finals *finals_new(const struct tcfg *storage)
{
    struct finals *f = calloc(1, sizeof *f);
    if (!f)
        return NULL;
    f->storage = storage;
    pthread_mutex_init(&f->mu, NULL);
    return f;
}

static void state_free(struct final_state *s)
{
    free(s->message);
    free(s->cost);
    memset(s, 0, sizeof *s);
}

void finals_free(struct finals *f)
{
    if (!f)
        return;
    for (size_t i = 0; i < f->n; i++)
        state_free(&f->v[i]);
    free(f->v);
    pthread_mutex_destroy(&f->mu);
    free(f);
}

/* One write, and once more after freeing the reserve when the disk was full.
 * TQ_NOT_FOUND (the job is no longer running or accepted) counts as done. */
static bool write_state(struct finals *f, struct tq *q, const struct final_state *s)
{
    enum tq_rc rc = tq_finish(q, s->id, s->status, s->outcome, s->message, s->cost);
    if (rc == TQ_ERROR && tq_disk_full(q) && f->storage && storage_release_reserve(f->storage)) {
        tlog("supervisor: the disk is full; freed the reserve file to record job %s", s->id);
        rc = tq_finish(q, s->id, s->status, s->outcome, s->message, s->cost);
    }
    if (rc != TQ_ERROR)
        return true;
    pthread_mutex_lock(&f->mu);
    snprintf(f->why, sizeof f->why, "%s", tq_last_error(q));
    pthread_mutex_unlock(&f->mu);
    return false;
}

static void set_count(struct finals *f, size_t n)
{
    pthread_mutex_lock(&f->mu);
    f->n = n;
    if (n == 0)
        f->why[0] = '\0';
    pthread_mutex_unlock(&f->mu);
}

int finals_record(struct finals *f, struct tq *q, const char *id, const char *status,
                  const char *outcome, const char *message, const char *cost)
{
    struct final_state s;
    memset(&s, 0, sizeof s);
    snprintf(s.id, sizeof s.id, "%s", id);
    snprintf(s.status, sizeof s.status, "%s", status);
    snprintf(s.outcome, sizeof s.outcome, "%s", outcome ? outcome : "");
    s.message = message ? strdup(message) : NULL;
    s.cost = cost ? strdup(cost) : NULL;
    /* the ones still waiting first, so that states are written in order */
    if (f->n > 0)
        finals_retry(f, q);
    if (f->n == 0 && write_state(f, q, &s)) {
        state_free(&s);
        return 0;
    }
    if (f->n == f->cap) {
        const size_t cap = f->cap ? 2 * f->cap : 8;
        struct final_state *v = realloc(f->v, cap * sizeof *v);
        if (!v) {
            tlog("supervisor: job %s: out of memory keeping its final state (%s)", id, status);
            state_free(&s);
            return -1;
        }
        f->v = v;
        f->cap = cap;
    }
    f->v[f->n] = s;
    set_count(f, f->n + 1);
    tlog("supervisor: job %s: cannot record its final state (%s, %s) yet: %s; retrying", id,
         status, s.outcome, f->why);
    return 1;
}

size_t finals_retry(struct finals *f, struct tq *q)
{
    size_t done = 0;
    while (done < f->n && write_state(f, q, &f->v[done])) {
        tlog("supervisor: job %s: final state recorded (%s)", f->v[done].id, f->v[done].status);
        state_free(&f->v[done]);
        done++;
    }
    if (done) {
        memmove(f->v, f->v + done, (f->n - done) * sizeof *f->v);
        set_count(f, f->n - done);
    }
    return f->n;
}

size_t finals_pending(struct finals *f, char *why, size_t size)
{
    if (!f) {
        errmsg_set(why, size, "%s", "");
        return 0;
    }
    pthread_mutex_lock(&f->mu);
    const size_t n = f->n;
    errmsg_set(why, size, "%s", f->why);
    pthread_mutex_unlock(&f->mu);
    return n;
}
