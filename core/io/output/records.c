/* /cost and /diagnostics; see records.h.  Their attributes are one struct and
 * one table, so that creating and rewriting them cannot disagree. */
#include "io/output/records.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "io/output/h5_attr.h"
#include "io/output/h5_dataset.h"
#include "util/parallel.h"

/* Sizes of the strings rewritten at close (longer values are truncated). */
#define STATUS_LEN 32
#define QUANTITY_LEN 64
#define MESSAGE_LEN 256
#define DIAG_IDS 16 /* particle ids kept, -1 filling the unused ones */

/* Every attribute of both groups, named as in the file: the values to write. */
struct records {
    /* /cost */
    int64_t particles, pairs, steps;
    double wall_seconds, particle_steps_per_second;
    int64_t peak_memory_bytes;
    double bytes_per_particle;
    int64_t threads;
    int contact; /* the contact attributes exist (a run with contact) */
    int64_t contact_searches;
    double contact_search_share, contact_phase_share;
    int porous; /* the material_phase_share attribute exists (a porous model) */
    double material_phase_share;
    /* /diagnostics */
    const char *status;
    int64_t step;
    double time;
    const char *quantity;
    double value, limit;
    int64_t nids, ids[DIAG_IDS];
    const char *message;
};

enum record_group { COST, DIAGNOSTICS };
enum { ONLY_CONTACT = 1, ONLY_POROUS = 2 }; /* struct record_attr's only */
static const char *const group_path[] = {[COST] = "/cost", [DIAGNOSTICS] = "/diagnostics"};

struct record_attr {
    enum record_group group;
    const char *name;
    size_t offset;               /* of the value in struct records */
    enum tlsph_field_type type;  /* of a number */
    size_t count;                /* 0: scalar number; else a 1-D array of count */
    size_t string_size;          /* > 0: a const char * member, stored in this many bytes */
    int only;                    /* 0, or written only for a run with ONLY_CONTACT / ONLY_POROUS */
};

#define NUMBER(group, member, t) {group, #member, offsetof(struct records, member), t, 0, 0, 0}
#define STRING(group, member, size) \
    {group, #member, offsetof(struct records, member), TLSPH_FLOAT64, 0, size, 0}
/* a /cost attribute of runs with contact only */
#define CONTACT(member, t) \
    {COST, #member, offsetof(struct records, member), t, 0, 0, ONLY_CONTACT}
/* a /cost attribute of runs with a porous damage model only */
#define POROUS(member, t) {COST, #member, offsetof(struct records, member), t, 0, 0, ONLY_POROUS}

/* In the order of creation. */
static const struct record_attr record_attrs[] = {
    NUMBER(COST, particles, TLSPH_INT64),
    NUMBER(COST, pairs, TLSPH_INT64),
    NUMBER(COST, steps, TLSPH_INT64),
    NUMBER(COST, wall_seconds, TLSPH_FLOAT64),
    NUMBER(COST, particle_steps_per_second, TLSPH_FLOAT64),
    NUMBER(COST, peak_memory_bytes, TLSPH_INT64),
    NUMBER(COST, bytes_per_particle, TLSPH_FLOAT64),
    NUMBER(COST, threads, TLSPH_INT64),
    CONTACT(contact_searches, TLSPH_INT64),
    CONTACT(contact_search_share, TLSPH_FLOAT64),
    CONTACT(contact_phase_share, TLSPH_FLOAT64),
    POROUS(material_phase_share, TLSPH_FLOAT64),
    STRING(DIAGNOSTICS, status, STATUS_LEN),
    NUMBER(DIAGNOSTICS, step, TLSPH_INT64),
    NUMBER(DIAGNOSTICS, time, TLSPH_FLOAT64),
    STRING(DIAGNOSTICS, quantity, QUANTITY_LEN),
    NUMBER(DIAGNOSTICS, value, TLSPH_FLOAT64),
    NUMBER(DIAGNOSTICS, limit, TLSPH_FLOAT64),
    NUMBER(DIAGNOSTICS, nids, TLSPH_INT64),
    {DIAGNOSTICS, "ids", offsetof(struct records, ids), TLSPH_INT64, DIAG_IDS, 0, 0},
    STRING(DIAGNOSTICS, message, MESSAGE_LEN),
};

/* Writes the attributes of group from r into file: creates the group and
 * them, or rewrites them in place. */
static int write_group(hid_t file, enum record_group group, int rewrite, const struct records *r)
{
    const char *path = group_path[group];
    hid_t g = rewrite ? H5Gopen2(file, path, H5P_DEFAULT)
                      : H5Gcreate2(file, path, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0)
        return -1;
    int rc = 0;
    for (size_t i = 0; i < sizeof record_attrs / sizeof record_attrs[0] && rc == 0; i++) {
        const struct record_attr *a = &record_attrs[i];
        if (a->group != group || (a->only == ONLY_CONTACT && !r->contact) ||
            (a->only == ONLY_POROUS && !r->porous))
            continue;
        const void *v = (const char *)r + a->offset;
        const struct tlsph_h5_type t = tlsph_h5_type(a->type);
        if (a->string_size) {
            const char *s = *(const char *const *)v;
            rc = rewrite ? tlsph_h5_rewrite_string(g, a->name, s)
                         : tlsph_h5_attr_string_sized(g, a->name, s, a->string_size);
        } else {
            rc = rewrite ? tlsph_h5_rewrite(g, a->name, t.mem, v)
                         : tlsph_h5_attr_values(g, a->name, t.file, t.mem, a->count, v);
        }
    }
    if (H5Gclose(g) < 0)
        rc = -1;
    return rc;
}

/* The diagnostics of a run that has not (or not yet) failed. */
static void no_diagnostic(struct records *r, const char *status)
{
    r->status = status;
    r->step = -1;
    r->time = r->value = r->limit = NAN;
    r->quantity = r->message = "";
    r->nids = 0;
    for (int i = 0; i < DIAG_IDS; i++)
        r->ids[i] = -1;
}

int tlsph_records_create(hid_t file, const struct tlsph_model *m)
{
    struct records r = {.particles = (int64_t)m->p.n,
                        .pairs = (int64_t)m->pairs.npairs,
                        .steps = -1,
                        .wall_seconds = NAN,
                        .particle_steps_per_second = NAN,
                        .peak_memory_bytes = -1,
                        .bytes_per_particle = NAN,
                        .threads = tlsph_threads(),
                        .contact = m->contact != NULL,
                        .contact_searches = -1,
                        .contact_search_share = NAN,
                        .contact_phase_share = NAN,
                        .porous = m->p.void_fraction != NULL,
                        .material_phase_share = NAN};
    no_diagnostic(&r, "running");
    if (write_group(file, COST, 0, &r) < 0 || write_group(file, DIAGNOSTICS, 0, &r) < 0)
        return -1;
    return 0;
}

int tlsph_records_write(hid_t file, const struct tlsph_cost *cost, const char *status,
                        const struct tlsph_diagnostic *d)
{
    struct records r = {0};
    if (cost) {
        r.particles = (int64_t)cost->particles;
        r.pairs = (int64_t)cost->pairs;
        r.steps = cost->steps;
        r.wall_seconds = cost->wall_seconds;
        r.particle_steps_per_second = cost->particle_steps_per_second;
        r.peak_memory_bytes = (int64_t)cost->peak_memory_bytes;
        r.bytes_per_particle = cost->bytes_per_particle;
        r.threads = cost->threads;
        r.contact = cost->contact;
        r.contact_searches = cost->contact_searches;
        r.contact_search_share = cost->contact_search_share;
        r.contact_phase_share = cost->contact_phase_share;
        r.porous = cost->porous;
        r.material_phase_share = cost->material_phase_share;
        if (write_group(file, COST, 1, &r) < 0)
            return -1;
    }
    no_diagnostic(&r, status ? status : "unknown");
    if (d) {
        const size_t nids = d->nids < DIAG_IDS ? d->nids : DIAG_IDS;
        r.step = d->step;
        r.time = d->time;
        r.quantity = d->quantity;
        r.value = d->value;
        r.limit = d->limit;
        r.nids = (int64_t)nids;
        for (size_t i = 0; i < nids; i++)
            r.ids[i] = d->ids[i];
        r.message = d->message;
    }
    return write_group(file, DIAGNOSTICS, 1, &r);
}
