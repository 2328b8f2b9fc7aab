/* Slurm's job states, see slurm_state.h. */
#include "slurm_state.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run/protocol.h"

static const struct slurm_state states[] = {
    {"PENDING", SLURM_WAITING, NULL, "waiting in the Slurm queue"},
    {"CONFIGURING", SLURM_WAITING, NULL, "its nodes are being set up"},
    {"REQUEUED", SLURM_WAITING, NULL, "requeued by Slurm"},
    {"REQUEUE_HOLD", SLURM_WAITING, NULL, "requeued by Slurm and held"},
    {"REQUEUE_FED", SLURM_WAITING, NULL, "requeued by Slurm"},
    {"RESV_DEL_HOLD", SLURM_WAITING, NULL, "held: its reservation was deleted"},
    {"RUNNING", SLURM_RUNNING, NULL, "running"},
    {"COMPLETING", SLURM_RUNNING, NULL, "completing"},
    {"SUSPENDED", SLURM_RUNNING, NULL, "suspended by Slurm"},
    {"STOPPED", SLURM_RUNNING, NULL, "stopped by Slurm"},
    {"SIGNALING", SLURM_RUNNING, NULL, "being signalled"},
    {"STAGE_OUT", SLURM_RUNNING, NULL, "staging out"},
    {"RESIZING", SLURM_RUNNING, NULL, "being resized"},
    {"COMPLETED", SLURM_ENDED, NULL, "completed"},
    {"FAILED", SLURM_ENDED, NULL, "failed"},
    {"TIMEOUT", SLURM_FAILED, "timed_out", "killed by Slurm at its time limit"},
    {"DEADLINE", SLURM_FAILED, "timed_out", "killed by Slurm at its deadline"},
    {"OUT_OF_MEMORY", SLURM_FAILED, "crashed", "killed by Slurm for exceeding its memory"},
    {"SPECIAL_EXIT", SLURM_FAILED, "crashed", "ended in Slurm's special-exit state"},
    {"CANCELLED", SLURM_CANCELLED, NULL, "cancelled"},
    {"NODE_FAIL", SLURM_REQUEUE, NULL, "its node failed"},
    {"PREEMPTED", SLURM_REQUEUE, NULL, "preempted"},
    {"BOOT_FAIL", SLURM_REQUEUE, NULL, "its node failed to boot"},
};

const struct slurm_state *slurm_state_of(const char *name)
{
    static const struct slurm_state unknown = {"?", SLURM_UNKNOWN, NULL, "in a state tlsphd does not know"};
    for (size_t i = 0; i < sizeof states / sizeof states[0]; i++)
        if (name && !strcmp(states[i].name, name))
            return &states[i];
    return &unknown;
}

enum slurm_verdict slurm_verdict(int exit_rc, const struct slurm_state *st, bool waited)
{
    if (st && (st->phase == SLURM_FAILED || st->phase == SLURM_CANCELLED))
        return SLURM_END_BY_SLURM;
    if (st && st->phase == SLURM_REQUEUE)
        return SLURM_REQUEUE_NODE;
    const bool engine_said = exit_rc == TLSPH_EXIT_SUCCESS || exit_rc == TLSPH_EXIT_INVALID ||
                             exit_rc == TLSPH_EXIT_UNSTABLE || exit_rc == TLSPH_EXIT_IO;
    const bool slurm_ended = !st || st->phase == SLURM_ENDED;
    if (exit_rc >= 0 && (engine_said || slurm_ended))
        return SLURM_END_BY_EXIT;
    if (exit_rc < 0 && !slurm_ended)
        return SLURM_WATCH;
    if (!waited)
        return SLURM_WAIT;
    return exit_rc >= 0 ? SLURM_END_BY_EXIT : st ? SLURM_END_NO_STATUS : SLURM_REQUEUE_GONE;
}

/* The next '|'-separated field of *s into dst (cut to size). */
static void field(const char **s, char *dst, size_t size)
{
    const char *bar = strchr(*s, '|');
    const size_t len = bar ? (size_t)(bar - *s) : strlen(*s);
    snprintf(dst, size, "%.*s", (int)len, *s);
    *s += bar ? len + 1 : len;
}

int slurm_queue_parse(const char *text, struct slurm_queue_row **rows, size_t *n)
{
    *rows = NULL;
    *n = 0;
    size_t cap = 0;
    char line[512];
    for (const char *p = text ? text : ""; *p;) {
        const char *nl = strchr(p, '\n');
        const size_t len = nl ? (size_t)(nl - p) : strlen(p);
        snprintf(line, sizeof line, "%.*s", (int)len, p);
        p += nl ? len + 1 : len;
        struct slurm_queue_row r;
        memset(&r, 0, sizeof r);
        const char *s = line;
        field(&s, r.id, sizeof r.id);
        field(&s, r.state, sizeof r.state);
        field(&s, r.reason, sizeof r.reason);
        field(&s, r.nodes, sizeof r.nodes);
        field(&s, r.name, sizeof r.name);
        if (!r.id[0] || !r.state[0])
            continue;
        if (*n == cap) {
            cap = cap ? 2 * cap : 64;
            struct slurm_queue_row *a = realloc(*rows, cap * sizeof *a);
            if (!a) {
                free(*rows);
                *rows = NULL;
                *n = 0;
                return -1;
            }
            *rows = a;
        }
        (*rows)[(*n)++] = r;
    }
    return 0;
}

const struct slurm_queue_row *slurm_queue_find(const struct slurm_queue_row *rows, size_t n,
                                               const char *id)
{
    for (size_t i = 0; i < n; i++)
        if (!strcmp(rows[i].id, id))
            return &rows[i];
    return NULL;
}
