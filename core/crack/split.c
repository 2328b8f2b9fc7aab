/* Particle splitting, eqs. 21-32 of paper 003 (split.h): validate, plan
 * everything that can fail (the new pairs, the groups', sections' and probes' arrays,
 * the particle capacity), then commit, which cannot fail. */
#include "crack/split.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "crack/local_rebuild.h"
#include "crack/split_forces.h"
#include "crack/split_state.h"
#include "io/measures.h"

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static int finite3(const double a[3])
{
    return isfinite(a[0]) && isfinite(a[1]) && isfinite(a[2]);
}

int tlsph_split_angles(const double V1[3], const double V2[3], const double delta[3],
                       double phi[2])
{
    if (!finite3(V1) || !finite3(V2) || !finite3(delta))
        return -1;
    const double l1 = sqrt(dot3(V1, V1)), l2 = sqrt(dot3(V2, V2)), ld = sqrt(dot3(delta, delta));
    if (!(l1 > 0.0) || !(l2 > 0.0) || !(ld > 0.0) || fabs(dot3(delta, V2)) > 1e-9 * ld * l2)
        return -1;
    /* theta = angle between the open crack behind the tip (-V1) and V2 */
    const double a[3] = {-V1[0] / l1, -V1[1] / l1, -V1[2] / l1};
    const double b[3] = {V2[0] / l2, V2[1] / l2, V2[2] / l2};
    const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]};
    const double theta = atan2(sqrt(dot3(c, c)), dot3(a, b));
    const double two_pi = 2.0 * M_PI;
    /* the sector of angle theta lies on the side of V2 towards -V1 */
    phi[0] = dot3(delta, a) > 0.0 ? theta : two_pi - theta;
    phi[1] = two_pi - phi[0];
    return 0;
}

/* Is i one of the parents?  Their slot, or k. */
static size_t slot_of(const struct tlsph_split *sp, size_t i)
{
    size_t s = 0;
    while (s < sp->n && sp->index[s] != i)
        s++;
    return s;
}

/* The measurements that hold particles: the sections, the probes, then the extents. */
#define NMEASURE_LISTS (3 * TLSPH_MAX_MEASURES)

static int32_t **measure_list(struct tlsph_measures *ms, size_t k, size_t **count)
{
    if (k < TLSPH_MAX_MEASURES) {
        *count = &ms->section_count[k];
        return &ms->section_index[k];
    }
    k -= TLSPH_MAX_MEASURES;
    if (k < TLSPH_MAX_MEASURES) {
        *count = &ms->probe_count[k];
        return &ms->probe_index[k];
    }
    k -= TLSPH_MAX_MEASURES;
    *count = &ms->extent_count[k];
    return &ms->extent_index[k];
}

/* Index arrays that gain halves: one per group, section and probe, prepared
 * before the commit (NULL where the array only shifts in place). */
struct lists {
    int32_t **group;   /* [nbcs] */
    size_t *group_add; /* halves joining each group */
    double **area;     /* [nbcs]: a pressure group's new area vectors [3 (n + add)] */
    double **load;     /* and its new stored loads, alike */
    int32_t *measure[NMEASURE_LISTS];
    size_t measure_add[NMEASURE_LISTS];
};

static void lists_free(struct lists *l, size_t ngroups)
{
    for (size_t g = 0; l->group && g < ngroups; g++)
        free(l->group[g]);
    for (size_t g = 0; l->area && g < ngroups; g++) {
        free(l->area[g]);
        free(l->load[g]);
    }
    free(l->group);
    free(l->group_add);
    free(l->area);
    free(l->load);
    for (size_t k = 0; k < NMEASURE_LISTS; k++)
        free(l->measure[k]);
}

static size_t count_parents(const struct tlsph_split *sp, const int32_t *index, size_t n)
{
    size_t c = 0;
    for (size_t a = 0; a < n; a++)
        c += slot_of(sp, (size_t)index[a]) < sp->n;
    return c;
}

/* The new index list: old entries shifted past `at` by k, then the half of
 * every parent listed (half 2 of parent slot s is at + s). */
static void remap_list(const struct tlsph_split *sp, size_t at, const int32_t *in, size_t n,
                       int32_t *out)
{
    size_t extra = n;
    for (size_t a = 0; a < n; a++) {
        const size_t i = (size_t)in[a];
        const size_t s = slot_of(sp, i);
        out[a] = (int32_t)(i < at ? i : i + sp->n);
        if (s < sp->n && out != in)
            out[extra++] = (int32_t)(at + s);
    }
}

static int prepare_lists(struct tlsph_model *m, const struct tlsph_split *sp, struct lists *l,
                         struct tlsph_errors *err)
{
    const size_t ng = m->scene.nbcs;
    l->group = calloc(ng ? ng : 1, sizeof *l->group);
    l->group_add = calloc(ng ? ng : 1, sizeof *l->group_add);
    l->area = calloc(ng ? ng : 1, sizeof *l->area);
    l->load = calloc(ng ? ng : 1, sizeof *l->load);
    if (!l->group || !l->group_add || !l->area || !l->load)
        goto oom;
    for (size_t g = 0; g < ng; g++) {
        const struct tlsph_group *gr = &m->groups[g];
        if (!gr->index || !(l->group_add[g] = count_parents(sp, gr->index, gr->n)))
            continue;
        if (!(l->group[g] = malloc((gr->n + l->group_add[g]) * sizeof **l->group)))
            goto oom;
        if (gr->area && (!(l->area[g] = malloc(3 * (gr->n + l->group_add[g]) * sizeof(double))) ||
                         !(l->load[g] = malloc(3 * (gr->n + l->group_add[g]) * sizeof(double)))))
            goto oom;
    }
    for (size_t k = 0; k < NMEASURE_LISTS; k++) {
        size_t *count;
        int32_t *const *index = measure_list(&m->measures, k, &count);
        if (!*index || !(l->measure_add[k] = count_parents(sp, *index, *count)))
            continue;
        if (!(l->measure[k] = malloc((*count + l->measure_add[k]) * sizeof(int32_t))))
            goto oom;
    }
    return 0;
oom:
    tlsph_errors_add(err, "", "split: out of memory");
    return -1;
}

/* A pressure group's per-entry 3-vectors (area vectors, stored loads) after
 * its index list gained the halves (remap_list's order: the old entries, then
 * half 2 of every parent listed): a parent's vector v becomes v share (half 1)
 * and v - v share (half 2).  share is the volume (and mass) share of half 1:
 * the area vector is the particle's V_i / s along its surface normal
 * (bc/surface.h), so both halves keep that rule, the normal is the parent's
 * (they sit +-delta from it on the same surface), and the group's total area
 * vector and force are kept to one rounding; refitting the normals would see
 * the cut supports at the new faces and change the total. */
static void share_vectors(const struct tlsph_split *sp, const int32_t *in, size_t n,
                          const double *old, double *out, double share)
{
    size_t extra = n;
    for (size_t a = 0; a < n; a++) {
        const int parent = slot_of(sp, (size_t)in[a]) < sp->n;
        for (int c = 0; c < 3; c++) {
            const double v = old[3 * a + c], v1 = parent ? v * share : v;
            out[3 * a + c] = v1;
            if (parent)
                out[3 * extra + c] = v - v1;
        }
        extra += parent;
    }
}

static void commit_lists(struct tlsph_model *m, const struct tlsph_split *sp, size_t at,
                         double share, struct lists *l)
{
    for (size_t g = 0; g < m->scene.nbcs; g++) {
        struct tlsph_group *gr = &m->groups[g];
        if (!gr->index)
            continue;
        if (!l->group[g]) {
            remap_list(sp, at, gr->index, gr->n, gr->index);
            continue;
        }
        if (l->area[g]) { /* before the indices change: the parents by their old index */
            share_vectors(sp, gr->index, gr->n, gr->area, l->area[g], share);
            share_vectors(sp, gr->index, gr->n, gr->load, l->load[g], share);
            free(gr->area);
            free(gr->load);
            gr->area = l->area[g];
            gr->load = l->load[g];
            l->area[g] = l->load[g] = NULL;
            m->bytes_allocated += 6 * l->group_add[g] * sizeof(double);
        }
        remap_list(sp, at, gr->index, gr->n, l->group[g]);
        free(gr->index);
        gr->index = l->group[g];
        l->group[g] = NULL;
        gr->n += l->group_add[g];
        m->bytes_allocated += l->group_add[g] * sizeof *gr->index;
    }
    for (size_t k = 0; k < NMEASURE_LISTS; k++) {
        size_t *count;
        int32_t **index = measure_list(&m->measures, k, &count);
        if (!*index)
            continue;
        if (!l->measure[k]) {
            remap_list(sp, at, *index, *count, *index);
            continue;
        }
        remap_list(sp, at, *index, *count, l->measure[k]);
        free(*index);
        *index = l->measure[k];
        l->measure[k] = NULL;
        *count += l->measure_add[k];
        m->bytes_allocated += l->measure_add[k] * sizeof(int32_t);
    }
}

/* Copies particle src's every field to dst (both indices in use). */
static void copy_particle(struct tlsph_particles *p, size_t dst, size_t src)
{
    struct tlsph_grow_array a[TLSPH_MAX_PARTICLE_ARRAYS];
    const size_t count = tlsph_particle_arrays(p, a);
    for (size_t q = 0; q < count; q++) {
        char *base = *a[q].ptr;
        memcpy(base + dst * a[q].elem, base + src * a[q].elem, a[q].elem);
    }
}

/* The field assignment of split.h for parent i (half 1 stays at i) and half 2
 * at q; the forces are set afterwards (rest_of_force, pair forces). */
static void split_fields(struct tlsph_particles *p, size_t i, size_t q, const double phi[2],
                         const double delta[3], int64_t id1, int64_t id2)
{
    copy_particle(p, q, i);
    const double share = phi[0] / (phi[0] + phi[1]);
    const double m1 = p->mass[i] * share, V1 = p->vol0[i] * share;
    p->mass[q] = p->mass[i] - m1;
    p->vol0[q] = p->vol0[i] - V1;
    p->mass[i] = m1;
    p->vol0[i] = V1;
    const double *F = p->F + 9 * i;
    for (int c = 0; c < 3; c++) {
        const double Fd = F[3 * c] * delta[0] + F[3 * c + 1] * delta[1] + F[3 * c + 2] * delta[2];
        p->X[3 * i + c] += delta[c];
        p->X[3 * q + c] -= delta[c];
        p->x[3 * i + c] += Fd;
        p->x[3 * q + c] -= Fd;
    }
    p->id[i] = id1;
    p->id[q] = id2;
}

static int validate(const struct tlsph_model *m, const struct tlsph_split *sp, double phi[2],
                    size_t *body, struct tlsph_errors *err)
{
    if (m->links) {
        tlsph_errors_add(err, "", "split: not yet with virtual links (their per-pair state is "
                         "not remapped)");
        return -1;
    }
    if (sp->n == 0 || !sp->index) {
        tlsph_errors_add(err, "", "split: no particle given");
        return -1;
    }
    if (tlsph_split_angles(sp->V1, sp->V2, sp->delta, phi) != 0) {
        tlsph_errors_add(err, "", "split: V1, V2 and delta must be finite and non-zero, delta "
                         "normal to V2");
        return -1;
    }
    if (m->p.n + sp->n > (size_t)INT32_MAX) {
        tlsph_errors_add(err, "", "split: too many particles");
        return -1;
    }
    for (size_t s = 0; s < sp->n; s++) {
        const size_t i = sp->index[s];
        if (i >= m->p.n || (s && (size_t)m->p.body[i] != *body) || slot_of(sp, i) != s) {
            tlsph_errors_add(err, "", "split: particle index %zu out of range, repeated or of "
                             "another body", i);
            return -1;
        }
        *body = (size_t)m->p.body[i];
    }
    return 0;
}

int tlsph_split_particles(struct tlsph_model *m, const struct tlsph_split *sp,
                          const struct tlsph_crack_surface *cs, size_t first_new_facet,
                          tlsph_grow_alloc_fn alloc, void *ctx, struct tlsph_errors *err)
{
    double phi[2];
    size_t b = 0;
    if (validate(m, sp, phi, &b, err) != 0)
        return -1;
    const size_t k = sp->n, at = m->body_end[b];
    struct tlsph_particles *p = &m->p;
    struct lists lists = {0};
    struct tlsph_rebuild_plan plan = {0};
    struct tlsph_split_state state = {0};
    struct tlsph_split_forces forces = {0};
    double *Xh = malloc(6 * k * sizeof *Xh); /* X1 [3k] then X2 [3k] */
    if (!Xh) {
        tlsph_errors_add(err, "", "split: out of memory");
        return -1;
    }
    for (size_t s = 0; s < k; s++)
        for (int c = 0; c < 3; c++) {
            Xh[3 * s + c] = p->X[3 * sp->index[s] + c] + sp->delta[c];
            Xh[3 * (k + s) + c] = p->X[3 * sp->index[s] + c] - sp->delta[c];
        }
    const struct tlsph_rebuild_view view = {m, b, k, sp->index, Xh, Xh + 3 * k};
    if (tlsph_rebuild_plan(&view, cs, first_new_facet, &plan, err) != 0 ||
        prepare_lists(m, sp, &lists, err) != 0)
        goto fail;
    if (tlsph_split_state_prepare(m, b, k, &state) != 0 ||
        tlsph_split_forces_prepare(m, &plan, at, &forces) != 0) {
        tlsph_errors_add(err, "", "split: out of memory");
        goto fail;
    }
    if (tlsph_particles_reserve(m, p->n + k, alloc, ctx) != 0) {
        tlsph_errors_add(err, "", "split: out of memory growing to %zu particles", p->n + k);
        goto fail;
    }
    /* commit: nothing fails from here */
    const size_t n = p->n;
    const double share = phi[0] / (phi[0] + phi[1]);
    tlsph_split_forces_rest(m, b, &forces, sp->index, share);
    int64_t maxid = -1;
    for (size_t i = 0; i < p->n; i++)
        maxid = p->id[i] > maxid ? p->id[i] : maxid;
    tlsph_split_state_commit(m, &state, n, at, sp->index, k, share);
    tlsph_particles_open(m, at, k);
    for (size_t s = 0; s < k; s++)
        split_fields(p, sp->index[s], at + s, phi, sp->delta, maxid + 1 + 2 * (int64_t)s,
                     maxid + 2 + 2 * (int64_t)s);
    tlsph_split_state_fibres(m, &state, at, sp->index, k);
    m->body_end[b] += k;
    for (size_t c = b + 1; c < m->scene.nbodies; c++) {
        m->body_begin[c] += k;
        m->body_end[c] += k;
    }
    commit_lists(m, sp, at, share, &lists);
    tlsph_rebuild_commit(m, &plan);
    tlsph_split_forces_finish(m, b, &forces, at); /* the new supports' pair forces + the rest */
    lists_free(&lists, m->scene.nbcs);
    tlsph_rebuild_plan_free(&plan);
    tlsph_split_forces_free(&forces);
    tlsph_split_state_free(&state);
    free(Xh);
    return 0;
fail:
    tlsph_split_forces_free(&forces);
    tlsph_split_state_free(&state);
    lists_free(&lists, m->scene.nbcs);
    tlsph_rebuild_plan_free(&plan);
    free(Xh);
    return -1;
}
