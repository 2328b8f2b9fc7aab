/* Local rebuild of the pairs and corrections around a split (local_rebuild.h). */
#include "crack/local_rebuild.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "crack/split_carry.h"
#include "sph/correction.h"
#include "sph/neighbors.h"
#include "util/mat3.h"

/* A set of particle indices (open addressing, key + 1 stored, 0 = empty):
 * the walk's visited set, sized by what it visits, not by the body. */
struct index_set {
    size_t *slot;
    size_t cap, used;
};

static size_t hash_index(size_t i)
{
    uint64_t x = (uint64_t)i * 0x9E3779B97F4A7C15ull;
    return (size_t)(x ^ (x >> 29));
}

/* 1 when added, 0 when present, -1 out of memory. */
static int set_add(struct index_set *s, size_t i)
{
    if (2 * (s->used + 1) > s->cap) {
        const size_t cap = s->cap ? 2 * s->cap : 64;
        size_t *slot = calloc(cap, sizeof *slot);
        if (!slot)
            return -1;
        for (size_t q = 0; q < s->cap; q++)
            if (s->slot[q])
                for (size_t h = hash_index(s->slot[q] - 1) & (cap - 1);; h = (h + 1) & (cap - 1))
                    if (!slot[h]) {
                        slot[h] = s->slot[q];
                        break;
                    }
        free(s->slot);
        s->slot = slot;
        s->cap = cap;
    }
    for (size_t h = hash_index(i) & (s->cap - 1);; h = (h + 1) & (s->cap - 1)) {
        if (s->slot[h] == i + 1)
            return 0;
        if (!s->slot[h]) {
            s->slot[h] = i + 1;
            s->used++;
            return 1;
        }
    }
}

static int cmp_size(const void *a, const void *b)
{
    const size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return x < y ? -1 : x > y;
}

static int cmp_i32(const void *a, const void *b)
{
    const int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return x < y ? -1 : x > y;
}

static int in_sorted(const size_t *a, size_t n, size_t key)
{
    return bsearch(&key, a, n, sizeof *a, cmp_size) != NULL;
}

/* The new index space of the view: at = old end of the body's range. */
struct space {
    const struct tlsph_rebuild_view *v;
    size_t at;
};

/* The parent slot s of old index i, or k. */
static size_t parent_slot(const struct tlsph_rebuild_view *v, size_t i)
{
    size_t s = 0;
    while (s < v->k && v->parent[s] != i)
        s++;
    return s;
}

/* Reference position of new index q. */
static const double *pos(const struct space *sp, size_t q)
{
    const struct tlsph_rebuild_view *v = sp->v;
    if (q >= sp->at + v->k)
        return v->m->p.X + 3 * (q - v->k);
    if (q >= sp->at)
        return v->X2 + 3 * (q - sp->at);
    const size_t s = parent_slot(v, q);
    return s < v->k ? v->X1 + 3 * s : v->m->p.X + 3 * q;
}

/* Old index whose data (h, old pairs) new index q carries. */
static size_t orig(const struct space *sp, size_t q)
{
    if (q >= sp->at + sp->v->k)
        return q - sp->v->k;
    if (q >= sp->at)
        return sp->v->parent[q - sp->at];
    return q;
}

static size_t map_old(const struct space *sp, size_t i)
{
    return i < sp->at ? i : i + sp->v->k;
}

static double box_distance2(const double x[3], const double lo[3], const double hi[3])
{
    double d2 = 0.0;
    for (int c = 0; c < 3; c++) {
        const double d = x[c] < lo[c] ? lo[c] - x[c] : (x[c] > hi[c] ? x[c] - hi[c] : 0.0);
        d2 += d * d;
    }
    return d2;
}

static double distance2(const double *a, const double *b)
{
    const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return dx * dx + dy * dy + dz * dz;
}

/* Does old particle i lie in the affected region (local_rebuild.h)? */
static int in_region(const struct tlsph_rebuild_view *v, const double *Xi, double r_seed,
                     double r_facet, const double (*box)[2][3], size_t nbox)
{
    const double *X = v->m->p.X;
    for (size_t s = 0; s < v->k; s++)
        if (distance2(Xi, X + 3 * v->parent[s]) < r_seed * r_seed)
            return 1;
    for (size_t f = 0; f < nbox; f++)
        if (box_distance2(Xi, box[f][0], box[f][1]) < r_facet * r_facet)
            return 1;
    return 0;
}

/* The affected old particles, ascending, by a walk over the old pairs from the
 * parents.  0, or -1 out of memory. */
static int affected_old(const struct tlsph_rebuild_view *v, const struct tlsph_crack_surface *cs,
                        size_t first_new_facet, size_t **out, size_t *nout)
{
    const struct tlsph_model *m = v->m;
    const struct tlsph_particles *p = &m->p;
    const size_t b = v->body;
    double hmax = 0.0, shift = 0.0;
    for (size_t i = m->body_begin[b]; i < m->body_end[b]; i++)
        hmax = fmax(hmax, p->h[i]);
    for (size_t s = 0; s < v->k; s++) {
        shift = fmax(shift, sqrt(distance2(v->X1 + 3 * s, p->X + 3 * v->parent[s])));
        shift = fmax(shift, sqrt(distance2(v->X2 + 3 * s, p->X + 3 * v->parent[s])));
    }
    const double r_seed = 2.0 * hmax + shift, r_facet = 2.0 * hmax;
    const size_t nbox = cs && cs->nfacets > first_new_facet ? cs->nfacets - first_new_facet : 0;
    double (*box)[2][3] = malloc((nbox ? nbox : 1) * sizeof *box);
    struct index_set seen = {0};
    size_t *list = NULL, n = 0, cap = 0;
    int rc = -1;
    if (!box)
        goto done;
    for (size_t f = 0; f < nbox; f++)
        for (int c = 0; c < 3; c++) {
            const double(*T)[3] = cs->facet[first_new_facet + f];
            box[f][0][c] = fmin(T[0][c], fmin(T[1][c], T[2][c]));
            box[f][1][c] = fmax(T[0][c], fmax(T[1][c], T[2][c]));
        }
    /* list doubles as the walk's queue: entries before `head` are expanded */
    for (size_t s = 0; s < v->k; s++) {
        const int added = set_add(&seen, v->parent[s]);
        if (added < 0)
            goto done;
        if (added) {
            if (n == cap) {
                cap = cap ? 2 * cap : 64;
                size_t *grown = realloc(list, cap * sizeof *list);
                if (!grown)
                    goto done;
                list = grown;
            }
            list[n++] = v->parent[s];
        }
    }
    for (size_t head = 0; head < n; head++) {
        const size_t q = list[head];
        for (int64_t e = m->pairs.start[q]; e < m->pairs.start[q + 1]; e++) {
            const size_t j = (size_t)m->pairs.j[e];
            if (!in_region(v, p->X + 3 * j, r_seed, r_facet, (const double(*)[2][3])box, nbox))
                continue;
            const int added = set_add(&seen, j);
            if (added < 0)
                goto done;
            if (!added)
                continue;
            if (n == cap) {
                cap *= 2;
                size_t *grown = realloc(list, cap * sizeof *list);
                if (!grown)
                    goto done;
                list = grown;
            }
            list[n++] = j;
        }
    }
    qsort(list, n, sizeof *list, cmp_size);
    *out = list;
    *nout = n;
    list = NULL;
    rc = 0;
done:
    free(list);
    free(box);
    free(seen.slot);
    return rc;
}

void tlsph_rebuild_plan_free(struct tlsph_rebuild_plan *plan)
{
    free(plan->start);
    free(plan->j);
    free(plan->dw);
    free(plan->w);
    free(plan->rows);
    memset(plan, 0, sizeof *plan);
}

/* Appends the partners of affected row a (new index) to out (room for
 * old(a) + nrows); returns their count, sorted, and in *outside how many are
 * not affected. */
static size_t row_pairs(const struct space *sp, const struct tlsph_crack_surface *cs,
                        const size_t *rows, size_t nrows, size_t a, int32_t *out,
                        size_t *outside)
{
    const struct tlsph_model *m = sp->v->m;
    const double *h = m->p.h;
    const double *Xa = pos(sp, a);
    const double ha = h[orig(sp, a)];
    size_t n = 0, far = 0;
    /* candidates: the affected set, then the old partners outside it */
    const size_t oa = orig(sp, a);
    const int64_t e0 = m->pairs.start[oa], e1 = m->pairs.start[oa + 1];
    for (size_t r = 0; r < nrows + (size_t)(e1 - e0); r++) {
        size_t q;
        if (r < nrows) {
            q = rows[r];
            if (q == a)
                continue;
        } else {
            q = map_old(sp, (size_t)m->pairs.j[e0 + (int64_t)(r - nrows)]);
            if (in_sorted(rows, nrows, q))
                continue;
        }
        const double *Xq = pos(sp, q);
        if (!tlsph_pair_in_support(Xa, Xq, ha, h[orig(sp, q)]))
            continue;
        if (cs && tlsph_crack_surface_cuts_pair(cs, Xa, a, Xq, q))
            continue;
        out[n++] = (int32_t)q;
        far += r >= nrows;
    }
    qsort(out, n, sizeof *out, cmp_i32);
    *outside = far;
    return n;
}

int tlsph_rebuild_plan(const struct tlsph_rebuild_view *v, const struct tlsph_crack_surface *cs,
                       size_t first_new_facet, struct tlsph_rebuild_plan *plan,
                       struct tlsph_errors *err)
{
    memset(plan, 0, sizeof *plan);
    const struct tlsph_model *m = v->m;
    const struct space sp = {v, m->body_end[v->body]};
    const size_t n_old = m->p.n, n_new = n_old + v->k;
    size_t *old_rows = NULL, nold = 0;
    int32_t **row = NULL;
    size_t *row_n = NULL;
    if (affected_old(v, cs, first_new_facet, &old_rows, &nold) != 0)
        goto oom;
    plan->k = v->k;
    plan->nrows = nold + v->k;
    plan->rows = malloc(plan->nrows * sizeof *plan->rows);
    row = calloc(plan->nrows, sizeof *row);
    row_n = calloc(plan->nrows, sizeof *row_n);
    if (!plan->rows || !row || !row_n)
        goto oom;
    memcpy(plan->rows, old_rows, nold * sizeof *old_rows);
    for (size_t s = 0; s < v->k; s++)
        plan->rows[nold + s] = sp.at + s; /* above every old row of the body: still sorted */
    /* the rows' status before (the halves did not exist) */
    for (size_t r = 0; r < nold; r++) {
        double cond;
        plan->old_deficient += (size_t)tlsph_correction_row_status(m, old_rows[r], &cond);
        plan->old_isolated += m->pairs.start[old_rows[r] + 1] == m->pairs.start[old_rows[r]];
    }
    size_t npairs = (size_t)m->pairs.start[n_old];
    for (size_t r = 0; r < plan->nrows; r++) {
        const size_t a = plan->rows[r], oa = orig(&sp, a);
        const size_t old_count = (size_t)(m->pairs.start[oa + 1] - m->pairs.start[oa]);
        if (!(row[r] = malloc((old_count + plan->nrows) * sizeof **row)))
            goto oom;
        size_t outside;
        row_n[r] = row_pairs(&sp, cs, plan->rows, plan->nrows, a, row[r], &outside);
        /* partners outside the set keep their rows: a's must be its old ones
         * (a half had none) */
        size_t old_outside = 0;
        if (a < sp.at)
            for (int64_t e = m->pairs.start[oa]; e < m->pairs.start[oa + 1]; e++)
                old_outside += !in_sorted(plan->rows, plan->nrows, map_old(&sp, (size_t)m->pairs.j[e]));
        if (outside != old_outside) {
            tlsph_errors_add(err, "",
                             "split of particle %lld: a pair outside the rebuilt region would "
                             "change (particle %lld); the region is too small",
                             (long long)m->p.id[v->parent[0]], (long long)m->p.id[oa]);
            goto fail;
        }
        if (a < sp.at)
            npairs -= old_count;
        npairs += row_n[r];
    }
    if (npairs > (size_t)INT64_MAX)
        goto oom;
    plan->npairs = npairs;
    plan->start = malloc((n_new + 1) * sizeof *plan->start);
    plan->j = malloc((npairs ? npairs : 1) * sizeof *plan->j);
    plan->dw = malloc((npairs ? npairs : 1) * sizeof *plan->dw);
    if (m->pairs.w)
        plan->w = malloc((npairs ? npairs : 1) * sizeof *plan->w);
    if (!plan->start || !plan->j || !plan->dw || (m->pairs.w && !plan->w))
        goto oom;
    /* the new CSR: affected rows from the plan, the others copied (indices
     * mapped, dw and w kept: their particles did not move) */
    size_t r = 0, e = 0;
    plan->start[0] = 0;
    for (size_t q = 0; q < n_new; q++) {
        if (r < plan->nrows && plan->rows[r] == q) {
            memcpy(plan->j + e, row[r], row_n[r] * sizeof *plan->j);
            e += row_n[r++];
        } else {
            const size_t o = orig(&sp, q);
            for (int64_t k = m->pairs.start[o]; k < m->pairs.start[o + 1]; k++, e++) {
                plan->j[e] = (int32_t)map_old(&sp, (size_t)m->pairs.j[k]);
                plan->dw[e] = m->pairs.dw[k];
                if (plan->w)
                    plan->w[e] = m->pairs.w[k];
            }
        }
        plan->start[q + 1] = (int64_t)e;
    }
    for (size_t q = 0; q < plan->nrows; q++)
        free(row[q]);
    free(row);
    free(row_n);
    free(old_rows);
    return 0;
oom:
    tlsph_errors_add(err, "", "out of memory rebuilding the pairs around a split");
fail:
    for (size_t q = 0; row && q < plan->nrows; q++)
        free(row[q]);
    free(row);
    free(row_n);
    free(old_rows);
    tlsph_rebuild_plan_free(plan);
    return -1;
}

void tlsph_rebuild_commit(struct tlsph_model *m, struct tlsph_rebuild_plan *plan)
{
    struct tlsph_pairs *pr = &m->pairs;
    /* m->p.n is already the new count: start grew by k entries */
    const size_t old_bytes = (m->p.n - plan->k) * sizeof *pr->start +
                             pr->npairs * (sizeof *pr->j + sizeof *pr->dw + (pr->w ? sizeof *pr->w : 0));
    const size_t new_bytes = m->p.n * sizeof *pr->start +
                             plan->npairs * (sizeof *pr->j + sizeof *pr->dw + (pr->w ? sizeof *pr->w : 0));
    free(pr->start);
    free(pr->j);
    free(pr->dw);
    free(pr->w);
    pr->start = plan->start;
    pr->j = plan->j;
    pr->dw = plan->dw;
    pr->w = plan->w;
    pr->npairs = plan->npairs;
    plan->start = NULL;
    plan->j = NULL;
    plan->dw = plan->w = NULL;
    m->bytes_allocated = m->bytes_allocated - old_bytes + new_bytes;
    size_t deficient = 0, isolated = 0;
    for (size_t r = 0; r < plan->nrows; r++) {
        const size_t i = plan->rows[r];
        double cond;
        isolated += pr->start[i + 1] == pr->start[i];
        if (tlsph_correction_row_rcond(m, i, &cond, TLSPH_L_RCOND_CUT))
            deficient++;
        else
            m->max_L_condition = fmax(m->max_L_condition, cond);
        /* F as the material saw it, carried onto the new support (split_carry.h):
         * p.Linv becomes L^-1 G before the refold below uses it */
        tlsph_split_carry_row(m, i);
        /* P_tilde = P L^-T folds the old L: refold it, P = sigma cof(F) (=
         * J sigma F^-T, the stress of the last evaluation), so that the next
         * step's first energy half (kinematics.h) and forces see the new L */
        double S[9], adj[9], P[9];
        sym6_to_mat3(m->p.sigma + 6 * i, S);
        mat3_adjugate(m->p.F + 9 * i, adj);
        mat3_mul_bt(S, adj, P);
        mat3_mul_bt(P, m->p.Linv + 9 * i, m->p.P_tilde + 9 * i);
    }
    m->deficient_supports = m->deficient_supports - plan->old_deficient + deficient;
    m->isolated = m->isolated - plan->old_isolated + isolated;
}
