#include "support/contact_lists.h"

#include <check.h>
#include <stdlib.h>
#include <string.h>

#include "contact/state.h"

static int cmp_int32(const void *a, const void *b)
{
    const int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

size_t check_candidates(const struct tlsph_model *m, contact_admit admit)
{
    const struct tlsph_contact *c = m->contact;
    const size_t n = m->p.n;
    size_t total = 0;
    int32_t *want = malloc(n * sizeof *want), *got = malloc(n * sizeof *got);
    ck_assert(want && got);
    for (size_t i = 0; i < n; i++) {
        size_t k = 0;
        const double ri = c->bodies[m->p.body[i]].radius + c->skin;
        for (size_t j = 0; j < n; j++) {
            if (j == i || !admit(m, i, j))
                continue;
            const double reach = ri + c->bodies[m->p.body[j]].radius;
            double r2 = 0.0;
            for (int d = 0; d < 3; d++)
                r2 += (m->p.x[3 * j + d] - m->p.x[3 * i + d]) *
                      (m->p.x[3 * j + d] - m->p.x[3 * i + d]);
            if (r2 < reach * reach)
                want[k++] = (int32_t)j;
        }
        const size_t have = (size_t)(c->start[i + 1] - c->start[i]);
        ck_assert_msg(have == k, "particle %zu: %zu candidates, brute force %zu", i, have, k);
        memcpy(got, c->j + c->start[i], have * sizeof *got);
        qsort(got, have, sizeof *got, cmp_int32);
        ck_assert(memcmp(got, want, k * sizeof *got) == 0);
        total += k;
    }
    free(want);
    free(got);
    return total;
}
