/* The writer's last guard: no dataset of a result file holds a value that is
 * not finite.  The stability contract (core/run/stability.c) stops a run before
 * its state turns non-finite in the quantities it checks; this guard covers
 * everything the file stores, derived values and series included, in the type
 * stored (a float32 dataset cannot hold 1e39: the cast would give Inf).  A
 * frame or sample that holds such a value is refused whole, before any of it is
 * written. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "io/output/output_internal.h"

static int finite_at(const void *buf, size_t k, enum tlsph_field_type t, double *value)
{
    switch (t) {
    case TLSPH_FLOAT64: *value = ((const double *)buf)[k]; return isfinite(*value);
    case TLSPH_FLOAT32: *value = ((const float *)buf)[k]; return isfinite(*value);
    case TLSPH_INT64:
    case TLSPH_INT32: break;
    }
    return 1;
}

int tlsph_output_check_frame_field(struct tlsph_output *o, const struct tlsph_field *f,
                                   const struct tlsph_model *m)
{
    if (f->type != TLSPH_FLOAT64 && f->type != TLSPH_FLOAT32)
        return 0;
    struct tlsph_output_refusal *r = &o->refusal;
    const size_t nc = (size_t)f->ncomp;
    r->nids = 0;
    for (size_t i = 0; i < o->n && r->nids < sizeof r->ids / sizeof *r->ids; i++)
        for (size_t c = 0; c < nc; c++) {
            double v;
            if (finite_at(o->scratch, i * nc + c, f->type, &v))
                continue;
            if (r->nids == 0)
                r->value = v;
            r->ids[r->nids++] = m->p.id[i];
            break;
        }
    if (r->nids == 0)
        return 0;
    snprintf(r->dataset, sizeof r->dataset, "/particles/solid/%s/value", f->name);
    return TLSPH_OUTPUT_REFUSED;
}

int tlsph_output_check_series_row(struct tlsph_output *o, const double *row)
{
    for (size_t k = 0; k < o->width; k++) {
        if (isfinite(row[k]))
            continue;
        struct tlsph_output_refusal *r = &o->refusal;
        memset(r, 0, sizeof *r);
        r->value = row[k];
        for (size_t i = 0; i < o->nseries; i++) {
            const struct output_series_value *s = &o->series[i];
            if (k >= s->offset && k < s->offset + (size_t)s->ncomp) {
                snprintf(r->dataset, sizeof r->dataset, "%s", s->path);
                break;
            }
        }
        return TLSPH_OUTPUT_REFUSED;
    }
    return 0;
}
