/* Contact and rigid-body state across a split (split_state.h). */
#include "crack/split_state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/state.h"
#include "rigid/state.h"

enum fill {
    FILL_COPY,  /* the parent's value */
    FILL_INF,   /* +infinity for the parent and both halves (a search is due) */
    FILL_SHARE, /* a 3-vector shared by mass: half 1 gets share, half 2 the rest */
    FILL_ZERO   /* rebuilt by the next search */
};

struct side_array {
    void **ptr;
    size_t elem;
    enum fill fill;
};

/* The arrays of n entries the contact phase and the rigid bodies hold. */
static size_t side_arrays(struct tlsph_model *m, struct side_array *out)
{
    size_t n = 0;
    struct tlsph_contact *c = m->contact;
    if (c) {
        if (c->touch)
            out[n++] = (struct side_array){(void **)&c->touch, sizeof *c->touch, FILL_COPY};
        if (c->reach)
            out[n++] = (struct side_array){(void **)&c->reach, sizeof *c->reach, FILL_COPY};
        out[n++] = (struct side_array){(void **)&c->x_search, 3 * sizeof(double), FILL_INF};
        out[n++] = (struct side_array){(void **)&c->key, sizeof *c->key, FILL_ZERO};
        out[n++] = (struct side_array){(void **)&c->order, sizeof *c->order, FILL_ZERO};
        out[n++] = (struct side_array){(void **)&c->f_old, 3 * sizeof(double), FILL_SHARE};
    }
    struct tlsph_rigid *r = m->rigid;
    if (r) {
        out[n++] = (struct side_array){(void **)&r->x_search, 3 * sizeof(double), FILL_INF};
        out[n++] = (struct side_array){(void **)&r->f, 3 * sizeof(double), FILL_SHARE};
        out[n++] = (struct side_array){(void **)&r->f_old, 3 * sizeof(double), FILL_SHARE};
    }
    return n;
}

void tlsph_split_state_free(struct tlsph_split_state *st)
{
    for (size_t q = 0; q < st->count; q++)
        free(st->fresh[q]);
    free(st->contact_start);
    tlsph_fibres_release(&st->fibres);
    memset(st, 0, sizeof *st);
}

int tlsph_split_state_prepare(struct tlsph_model *m, size_t body, size_t k,
                              struct tlsph_split_state *st)
{
    memset(st, 0, sizeof *st);
    st->body = body;
    if (m->fibres && m->fibres[body].n &&
        tlsph_fibres_split_prepare(&m->fibres[body], k, &st->fibres) != 0)
        return -1;
    struct side_array a[TLSPH_SPLIT_STATE_MAX];
    const size_t count = side_arrays(m, a), n = m->p.n + k;
    for (size_t q = 0; q < count; q++, st->count++)
        if (!(st->fresh[q] = malloc(n * a[q].elem))) {
            tlsph_split_state_free(st);
            return -1;
        }
    if (m->contact && !(st->contact_start = malloc((n + 1) * sizeof *st->contact_start))) {
        tlsph_split_state_free(st);
        return -1;
    }
    return 0;
}

/* Maps the candidate indices of a list in place. */
static void map_list(int32_t *j, size_t count, size_t at, size_t k)
{
    for (size_t e = 0; e < count; e++)
        if ((size_t)j[e] >= at)
            j[e] += (int32_t)k;
}

void tlsph_split_state_commit(struct tlsph_model *m, struct tlsph_split_state *st, size_t n,
                              size_t at, const size_t *parent, size_t k, double share)
{
    struct side_array a[TLSPH_SPLIT_STATE_MAX];
    const size_t count = side_arrays(m, a);
    for (size_t q = 0; q < count; q++) {
        const size_t el = a[q].elem;
        char *dst = st->fresh[q];
        const char *src = *a[q].ptr;
        memcpy(dst, src, at * el);
        memcpy(dst + (at + k) * el, src + at * el, (n - at) * el);
        for (size_t s = 0; s < k; s++) {
            char *h1 = dst + parent[s] * el, *h2 = dst + (at + s) * el;
            switch (a[q].fill) {
            case FILL_COPY:
                memcpy(h2, h1, el);
                break;
            case FILL_ZERO:
                memset(h2, 0, el);
                break;
            case FILL_INF:
                for (int c = 0; c < 3; c++)
                    ((double *)h1)[c] = ((double *)h2)[c] = INFINITY;
                break;
            case FILL_SHARE:
                for (int c = 0; c < 3; c++) {
                    const double f = ((double *)h1)[c], f1 = f * share;
                    ((double *)h1)[c] = f1;
                    ((double *)h2)[c] = f - f1;
                }
                break;
            }
        }
        free(*a[q].ptr);
        *a[q].ptr = dst;
        st->fresh[q] = NULL;
        m->bytes_allocated += k * el;
    }
    struct tlsph_contact *c = m->contact;
    if (c) {
        /* the halves' rows are empty until the search */
        int64_t *start = st->contact_start;
        memcpy(start, c->start, (at + 1) * sizeof *start);
        for (size_t s = 1; s <= k; s++)
            start[at + s] = start[at];
        memcpy(start + at + k + 1, c->start + at + 1, (n - at) * sizeof *start);
        map_list(c->j, (size_t)start[n + k], at, k);
        free(c->start);
        c->start = start;
        st->contact_start = NULL;
        m->bytes_allocated += k * sizeof *start;
        if (c->touch) {
            /* both halves are crack-face particles now: flagged anew, so the
             * next search takes their pairs across the faces and settles
             * their reach (contact/touch.c) */
            for (size_t s = 0; s < k; s++) {
                c->touching += c->touch[parent[s]] == 0;
                c->touch[parent[s]] |= TLSPH_TOUCH_SURFACE | TLSPH_TOUCH_NEW;
                c->touch[at + s] |= TLSPH_TOUCH_SURFACE | TLSPH_TOUCH_NEW;
                c->touching++;
            }
            c->settle_pending = 1;
        }
    }
    struct tlsph_rigid *r = m->rigid;
    if (r)
        map_list(r->cand, (size_t)r->start[r->nb], at, k);
    st->count = 0;
}

void tlsph_split_state_fibres(struct tlsph_model *m, struct tlsph_split_state *st, size_t at,
                              const size_t *parent, size_t k)
{
    if (!m->fibres)
        return;
    for (size_t b = 0; b < m->scene.nbodies; b++) {
        struct tlsph_fibres *f = &m->fibres[b];
        if (!f->n)
            continue;
        if (b != st->body) {
            tlsph_fibres_shift(f, at, k);
            continue;
        }
        const size_t added = tlsph_fibres_split_commit(f, &st->fibres, parent, k, at, m->p.X);
        m->bytes_allocated += k * sizeof *f->particle +
                              added * (sizeof *f->start + sizeof *f->centre);
    }
}
