/* Gauges and sections (see measures.h).  Sections are Lagrangian: their
 * particles are chosen once from the reference positions, so a section follows
 * the material through necking and fracture, as an extensometer does.  Means
 * are weighted by the reference volume; a failed particle contributes its zero
 * stress, so the section's mean stress falls as the crack crosses it.  Probes
 * are Lagrangian too and weighted by mass: they follow the centre of mass of
 * the material they picked, which a particle's own motion (one particle of a
 * lattice, which a crack or a contact may shake) would not. */
#include "bc/selector.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/mat3.h"
#include "io/measures.h"
#include "run/model.h"

static void group_centroid(const struct tlsph_model *m, const struct tlsph_group *g,
                           double c[3])
{
    c[0] = c[1] = c[2] = 0.0;
    for (size_t a = 0; a < g->n; a++)
        for (int d = 0; d < 3; d++)
            c[d] += m->p.X[3 * (size_t)g->index[a] + d];
    for (int d = 0; d < 3; d++)
        c[d] /= (double)(g->n ? g->n : 1);
}

static int init_gauge(struct tlsph_model *m, size_t k, struct tlsph_errors *err)
{
    const struct tlsph_gauge *g = &m->scene.gauges[k];
    double c0[3], c1[3], *a = m->measures.gauge_axis[k];
    group_centroid(m, &m->groups[g->group[0]], c0);
    group_centroid(m, &m->groups[g->group[1]], c1);
    for (int d = 0; d < 3; d++)
        a[d] = c1[d] - c0[d];
    const double dist = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!(dist > 0.0)) {
        char p[TLSPH_POINTER_MAX];
        snprintf(p, sizeof p, "/output/gauges/%zu/between", k);
        tlsph_errors_add(err, p,
                         "the groups '%s' and '%s' have the same centroid: the gauge has no axis",
                         m->scene.bcs[g->group[0]].name, m->scene.bcs[g->group[1]].name);
        return -1;
    }
    for (int d = 0; d < 3; d++)
        a[d] /= dist;
    m->measures.gauge_length[k] = g->length > 0.0 ? g->length : dist;
    return 0;
}

static int in_section(const struct tlsph_section *c, const double X[3])
{
    const double d = (X[0] - c->point[0]) * c->normal[0] + (X[1] - c->point[1]) * c->normal[1] +
                     (X[2] - c->point[2]) * c->normal[2];
    return fabs(d) <= 0.5 * c->thickness;
}

static int init_section(struct tlsph_model *m, size_t k, struct tlsph_errors *err)
{
    const struct tlsph_section *c = &m->scene.sections[k];
    struct tlsph_measures *ms = &m->measures;
    size_t n = 0;
    for (size_t i = 0; i < m->p.n; i++)
        n += (size_t)in_section(c, m->p.X + 3 * i);
    char p[TLSPH_POINTER_MAX];
    snprintf(p, sizeof p, "/output/sections/%zu", k);
    if (n == 0) {
        tlsph_errors_add(err, p,
                         "section '%s' holds no particle (no reference position within "
                         "thickness/2 = %g m of the plane)",
                         c->name, 0.5 * c->thickness);
        return -1;
    }
    if (!(ms->section_index[k] = tlsph_alloc(m, n, sizeof(int32_t)))) {
        tlsph_errors_add(err, p, "out of memory");
        return -1;
    }
    ms->section_count[k] = 0;
    ms->section_volume[k] = 0.0;
    for (size_t i = 0; i < m->p.n; i++)
        if (in_section(c, m->p.X + 3 * i)) {
            ms->section_index[k][ms->section_count[k]++] = (int32_t)i;
            ms->section_volume[k] += m->p.vol0[i];
        }
    return 0;
}

/* The particles sel picks into a new list (*index, *count); none is an error
 * at pointer p naming the measure. */
static int pick_list(struct tlsph_model *m, struct tlsph_selector *sel, const char *what,
                     const char *name, const char *p, int32_t **index, size_t *count,
                     struct tlsph_errors *err)
{
    const size_t n = tlsph_selector_pick(m, sel, NULL);
    if (n == 0) {
        tlsph_errors_add(err, p, "%s '%s' selects no particle", what, name);
        return -1;
    }
    if (!(*index = tlsph_alloc(m, n, sizeof(int32_t)))) {
        tlsph_errors_add(err, p, "out of memory");
        return -1;
    }
    *count = tlsph_selector_pick(m, sel, *index);
    return 0;
}

static int init_probe(struct tlsph_model *m, size_t k, struct tlsph_errors *err)
{
    struct tlsph_probe *q = &m->scene.probes[k];
    struct tlsph_measures *ms = &m->measures;
    char p[TLSPH_POINTER_MAX];
    snprintf(p, sizeof p, "/output/probes/%zu/select", k);
    if (pick_list(m, &q->select, "probe", q->name, p, &ms->probe_index[k], &ms->probe_count[k],
                  err) != 0)
        return -1;
    ms->probe_mass[k] = 0.0;
    for (size_t a = 0; a < ms->probe_count[k]; a++)
        ms->probe_mass[k] += m->p.mass[ms->probe_index[k][a]];
    return 0;
}

static int init_extent(struct tlsph_model *m, size_t k, struct tlsph_errors *err)
{
    struct tlsph_extent *x = &m->scene.extents[k];
    char p[TLSPH_POINTER_MAX];
    snprintf(p, sizeof p, "/output/extents/%zu/select", k);
    return pick_list(m, &x->select, "extent", x->name, p, &m->measures.extent_index[k],
                     &m->measures.extent_count[k], err);
}

int tlsph_measures_init(struct tlsph_model *m, struct tlsph_errors *err)
{
    int bad = 0;
    for (size_t k = 0; k < m->scene.ngauges; k++)
        bad |= init_gauge(m, k, err) != 0;
    for (size_t k = 0; k < m->scene.nsections; k++)
        bad |= init_section(m, k, err) != 0;
    for (size_t k = 0; k < m->scene.nprobes; k++)
        bad |= init_probe(m, k, err) != 0;
    for (size_t k = 0; k < m->scene.nextents; k++)
        bad |= init_extent(m, k, err) != 0;
    return bad ? -1 : 0;
}

void tlsph_measures_free(struct tlsph_measures *ms)
{
    for (size_t k = 0; k < TLSPH_MAX_MEASURES; k++) {
        free(ms->section_index[k]);
        ms->section_index[k] = NULL;
        free(ms->probe_index[k]);
        ms->probe_index[k] = NULL;
        free(ms->extent_index[k]);
        ms->extent_index[k] = NULL;
    }
}

void tlsph_probe_values(const struct tlsph_model *m, size_t k, double out[6])
{
    const struct tlsph_measures *ms = &m->measures;
    double sum[6] = {0};
    for (size_t a = 0; a < ms->probe_count[k]; a++) {
        const size_t i = (size_t)ms->probe_index[k][a];
        const double mi = m->p.mass[i];
        for (int d = 0; d < 3; d++) {
            sum[d] += mi * (m->p.x[3 * i + d] - m->p.X[3 * i + d]);
            sum[3 + d] += mi * m->p.v[3 * i + d];
        }
    }
    for (int c = 0; c < 6; c++)
        out[c] = sum[c] / ms->probe_mass[k];
}

void tlsph_gauge_values(const struct tlsph_model *m, size_t k, double out[2])
{
    const struct tlsph_gauge *g = &m->scene.gauges[k];
    const struct tlsph_group *g0 = &m->groups[g->group[0]], *g1 = &m->groups[g->group[1]];
    const double *a = m->measures.gauge_axis[k];
    double load = 0.0, elongation = 0.0;
    for (int d = 0; d < 3; d++) {
        load += 0.5 * (g1->reaction[d] - g0->reaction[d]) * a[d];
        elongation += (g1->displacement[d] - g0->displacement[d]) * a[d];
    }
    out[0] = load / g->area;
    out[1] = elongation / m->measures.gauge_length[k];
}

/* Largest principal value of a symmetric stress stored xx xy xz yy yz zz. */
static double max_principal(const double *s)
{
    const double A[9] = {s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5]};
    double lam[3], Q[9];
    sym3_eigen(A, lam, Q);
    return fmax(lam[0], fmax(lam[1], lam[2]));
}

void tlsph_section_values(const struct tlsph_model *m, size_t k,
                          double out[TLSPH_SECTION_NVALUES])
{
    const struct tlsph_measures *ms = &m->measures;
    const double *n = m->scene.sections[k].normal;
    double sum[TLSPH_SECTION_NVALUES] = {0};
    for (size_t a = 0; a < ms->section_count[k]; a++) {
        const size_t i = (size_t)ms->section_index[k][a];
        const double *s = m->p.sigma + 6 * i, V = m->p.vol0[i];
        const double sn = n[0] * (s[0] * n[0] + s[1] * n[1] + s[2] * n[2]) +
                          n[1] * (s[1] * n[0] + s[3] * n[1] + s[4] * n[2]) +
                          n[2] * (s[2] * n[0] + s[4] * n[1] + s[5] * n[2]);
        sum[TLSPH_SECTION_MAX_PRINCIPAL] += V * max_principal(s);
        sum[TLSPH_SECTION_NORMAL] += V * sn;
        if (m->p.eps_p)
            sum[TLSPH_SECTION_PLASTIC] += V * m->p.eps_p[i];
        if (m->p.damage)
            sum[TLSPH_SECTION_DAMAGE] += V * m->p.damage[i];
    }
    for (int c = 0; c < TLSPH_SECTION_NVALUES; c++)
        out[c] = sum[c] / ms->section_volume[k];
}

/* The axial coordinate of x along the extent's axis, and its squared distance
 * from the axis line. */
static double axial(const struct tlsph_extent *e, const double *x, double *r2)
{
    double d[3], s = 0.0;
    for (int c = 0; c < 3; c++) {
        d[c] = x[c] - e->point[c];
        s += d[c] * e->axis[c];
    }
    *r2 = 0.0;
    for (int c = 0; c < 3; c++) {
        const double q = d[c] - s * e->axis[c];
        *r2 += q * q;
    }
    return s;
}

void tlsph_extent_values(const struct tlsph_model *m, size_t k, double *out)
{
    const struct tlsph_extent *e = &m->scene.extents[k];
    const struct tlsph_measures *ms = &m->measures;
    const int32_t *index = ms->extent_index[k];
    const size_t n = ms->extent_count[k];
    /* lowest and highest centre and edge along the axis */
    double lo_c = INFINITY, lo = INFINITY, hi = -INFINITY, r2;
    for (size_t a = 0; a < n; a++) {
        const size_t i = (size_t)index[a];
        const double s = axial(e, m->p.x + 3 * i, &r2), h2 = 0.5 * tlsph_particle_spacing(m, i);
        lo_c = fmin(lo_c, s);
        lo = fmin(lo, s - h2);
        hi = fmax(hi, s + h2);
    }
    /* the radius at the outer edge, over all or over the lowest layer: the
     * centres within half their own spacing of the lowest centre (strictly, as
     * bench/taylor_metrics.py's "z < z.min() + h/2") */
    double rmax = -INFINITY;
    for (size_t a = 0; a < n; a++) {
        const size_t i = (size_t)index[a];
        const double s = axial(e, m->p.x + 3 * i, &r2), h2 = 0.5 * tlsph_particle_spacing(m, i);
        if (!e->lowest_layer || s < lo_c + h2)
            rmax = fmax(rmax, sqrt(r2) + h2);
    }
    out[TLSPH_EXTENT_RADIUS] = rmax;
    out[TLSPH_EXTENT_DIAMETER] = 2.0 * rmax;
    out[TLSPH_EXTENT_LOWER] = lo;
    out[TLSPH_EXTENT_UPPER] = hi;
    out[TLSPH_EXTENT_LENGTH] = hi - lo;
}
