/* The layout of the result file (output.h, docs/output.md): every group,
 * dataset and attribute, created before H5Fstart_swmr_write because SWMR
 * allows nothing to be created afterwards (see h5md.c). */
#ifdef HAVE_CONFIG_H
#include "config.h"
#endif
#ifndef PACKAGE_VERSION
#define PACKAGE_VERSION "0.1.0"
#endif

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/output/h5_attr.h"
#include "io/output/h5_dataset.h"
#include "io/output/output_internal.h"
#include "io/output/records.h"

#define FRAME_STEP_CHUNK 1024            /* rows per chunk of the frames' step and time */
#define FRAME_CHUNK_BYTES (512u * 1024u) /* target chunk size of frame values */

static hid_t make_group(hid_t loc, const char *name)
{
    return H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
}

/* Particles per chunk of a field with ncomp components of elsize bytes. */
static hsize_t particles_per_chunk(size_t n, int ncomp, size_t elsize)
{
    size_t per = FRAME_CHUNK_BYTES / ((size_t)ncomp * elsize);
    if (per < 1)
        per = 1;
    if (per >= n)
        return (hsize_t)n;
    /* Equal chunks, so the last one is not mostly padding (uncompressed
     * datasets store whole chunks). */
    size_t nchunks = (n + per - 1) / per;
    return (hsize_t)((n + nchunks - 1) / nchunks);
}

/* Gives group g (at group_path) the family's step and time: links to those of
 * the family's first group, or, in that first group, new datasets of
 * chunk_rows rows per chunk. */
static int add_timeline(struct output_timeline *tl, hid_t g, const char *group_path,
                        hsize_t chunk_rows)
{
    if (tl->step_path[0]) {
        if (H5Lcreate_hard(g, tl->step_path, g, "step", H5P_DEFAULT, H5P_DEFAULT) < 0 ||
            H5Lcreate_hard(g, tl->time_path, g, "time", H5P_DEFAULT, H5P_DEFAULT) < 0)
            return -1;
        return 0;
    }
    hsize_t chunk[1] = {chunk_rows};
    hid_t s = tlsph_h5_extendible(g, "step", H5T_STD_I64LE, 1, NULL, chunk, 0);
    hid_t t = tlsph_h5_extendible(g, "time", H5T_IEEE_F64LE, 1, NULL, chunk, 0);
    int rc = -1;
    if (s >= 0 && t >= 0 &&
        tlsph_h5_attr_string(s, "description", "time step index of each sample") == 0 &&
        tlsph_h5_describe(t, "s", "simulated time of each sample", NULL) == 0 &&
        (size_t)snprintf(tl->step_path, sizeof tl->step_path, "%s/step", group_path) <
            sizeof tl->step_path &&
        (size_t)snprintf(tl->time_path, sizeof tl->time_path, "%s/time", group_path) <
            sizeof tl->time_path)
        rc = 0;
    if (s >= 0)
        H5Dclose(s);
    if (t >= 0)
        H5Dclose(t);
    return rc;
}

/* An H5MD time-dependent element: a group holding the value dataset (first
 * axis unlimited: one row per sample) and its family's step and time. */
struct element {
    const char *name;
    hid_t ftype;
    int rank;          /* of value, 1..3 */
    hsize_t tail[2];   /* extents of value's other axes */
    hsize_t chunk[3];
    int compress;
    int changing;      /* the particle axis unlimited too (tlsph_h5_frames_dataset) */
    const char *units, *description, *components;
};

/* Creates element e in parent (at parent_path) and writes its path to path. */
static int create_element(hid_t parent, const char *parent_path, const struct element *e,
                          struct output_timeline *tl, hsize_t step_chunk, char *path, size_t size)
{
    if ((size_t)snprintf(path, size, "%s/%s", parent_path, e->name) >= size)
        return -1;
    hid_t g = make_group(parent, e->name);
    if (g < 0)
        return -1;
    hid_t v = e->changing ? tlsph_h5_frames_dataset(g, "value", e->ftype,
                                                    e->rank > 2 ? (int)e->tail[1] : 1,
                                                    e->tail[0], e->chunk[1], e->compress)
                          : tlsph_h5_extendible(g, "value", e->ftype, e->rank, e->tail,
                                                e->chunk, e->compress);
    int rc = -1;
    if (v >= 0 && tlsph_h5_describe(v, e->units, e->description, e->components) == 0 &&
        add_timeline(tl, g, path, step_chunk) == 0)
        rc = 0;
    if (v >= 0)
        H5Dclose(v);
    H5Gclose(g);
    return rc;
}

static int write_reference_field(struct tlsph_output *o, hid_t solid, const struct tlsph_field *f,
                                 const struct tlsph_model *m)
{
    const struct tlsph_h5_type t = tlsph_h5_type(f->type);
    const hsize_t dims[2] = {o->n, (hsize_t)f->ncomp};
    const hsize_t chunk[2] = {particles_per_chunk(o->n, f->ncomp, t.size), (hsize_t)f->ncomp};
    hid_t ds = tlsph_h5_chunked(solid, f->name, t.file, f->ncomp > 1 ? 2 : 1, dims, NULL, chunk, 1);
    if (ds < 0)
        return -1;
    tlsph_output_extract(o, f, m);
    int rc = -1;
    if (H5Dwrite(ds, t.mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, o->scratch) >= 0 &&
        tlsph_h5_describe(ds, f->units, f->description, f->components) == 0)
        rc = 0;
    if (H5Dclose(ds) < 0)
        rc = -1;
    return rc;
}

static int create_frame_field(struct tlsph_output *o, hid_t solid, const struct tlsph_field *f)
{
    const struct tlsph_h5_type t = tlsph_h5_type(f->type);
    const hsize_t ncomp = (hsize_t)f->ncomp;
    const struct element e = {
        .name = f->name,
        .ftype = t.file,
        .rank = f->ncomp > 1 ? 3 : 2,
        .tail = {o->n, ncomp},
        .chunk = {1, particles_per_chunk(o->n, f->ncomp, t.size), ncomp},
        /* float64 positions barely compress; reference fields (per frame with a
         * changing count) are compressed as when written once */
        .compress = f->type != TLSPH_FLOAT64 || f->kind == TLSPH_FIELD_REFERENCE,
        .changing = o->changing,
        .units = f->units,
        .description = f->description,
        .components = f->components,
    };
    char path[TLSPH_OUTPUT_PATH_MAX];
    if (create_element(solid, "/particles/solid", &e, &o->frame_timeline, FRAME_STEP_CHUNK, path,
                       sizeof path) < 0)
        return -1;
    o->frames[o->nframe_fields++] = (struct output_frame_value){f, H5I_INVALID_HID};
    return 0;
}

/* The layout for changing counts: /particles/solid/count, each frame's
 * particle count, on the frame fields' step and time. */
static int create_count(struct tlsph_output *o, hid_t solid)
{
    const struct element e = {
        .name = "count",
        .ftype = H5T_STD_I64LE,
        .rank = 1,
        .chunk = {FRAME_STEP_CHUNK, 0, 0},
        .units = "1",
        .description = "number of particles of each frame: the first count entries of the "
                       "frame's row of every field are its particles",
    };
    char path[TLSPH_OUTPUT_PATH_MAX];
    return create_element(solid, "/particles/solid", &e, &o->frame_timeline, FRAME_STEP_CHUNK,
                          path, sizeof path);
}

/* One series column in group parent (path parent_path). */
static int create_series(struct tlsph_output *o, hid_t parent, const char *parent_path,
                         const struct tlsph_series_column *c, size_t offset)
{
    const hsize_t ncomp = (hsize_t)c->ncomp;
    const struct element e = {
        .name = c->name,
        .ftype = H5T_IEEE_F64LE,
        .rank = c->ncomp > 1 ? 2 : 1,
        .tail = {ncomp, 0},
        .chunk = {TLSPH_SERIES_CHUNK, ncomp, 0},
        .compress = 0,
        .units = c->units,
        .description = c->description,
        .components = c->ncomp == 3 ? "x y z" : NULL,
    };
    char path[512];
    if (create_element(parent, parent_path, &e, &o->series_timeline, TLSPH_SERIES_CHUNK, path,
                       sizeof path) < 0)
        return -1;
    struct output_series_value *s = &o->series[o->nseries];
    size_t len = strlen(path) + sizeof "/value";
    if (!(s->path = malloc(len)))
        return -1;
    snprintf(s->path, len, "%s/value", path);
    s->ncomp = c->ncomp;
    s->offset = offset;
    s->value = H5I_INVALID_HID;
    o->nseries++;
    return 0;
}

/* Group `group` of /h5md naming a program or a person (version may be NULL). */
static int h5md_entity(hid_t h5md, const char *group, const char *name, const char *version)
{
    hid_t g = make_group(h5md, group);
    if (g < 0)
        return -1;
    int rc = 0;
    if (tlsph_h5_attr_string(g, "name", name) < 0 ||
        (version && tlsph_h5_attr_string(g, "version", version) < 0))
        rc = -1;
    H5Gclose(g);
    return rc;
}

/* /h5md: the H5MD version, creator and author. */
static int create_h5md(hid_t file)
{
    const int version[2] = {1, 1};
    hid_t h5md = make_group(file, "h5md");
    if (h5md < 0)
        return -1;
    int rc = 0;
    if (tlsph_h5_attr_values(h5md, "version", H5T_STD_I32LE, H5T_NATIVE_INT, 2, version) < 0 ||
        h5md_entity(h5md, "creator", "tlsph", PACKAGE_VERSION) < 0 ||
        h5md_entity(h5md, "author", "tlsph", NULL) < 0)
        rc = -1;
    H5Gclose(h5md);
    return rc;
}

/* The names of the active modules as a JSON array (malloc'ed; NULL when out of
 * memory). */
static char *modules_json(const struct tlsph_model *m)
{
    json_t *arr = json_array();
    int ok = arr != NULL;
    for (int i = 0; ok && i < m->nmodules; i++)
        ok = json_array_append_new(arr, json_string(m->modules[i] ? m->modules[i] : "")) == 0;
    char *text = ok ? json_dumps(arr, JSON_COMPACT) : NULL;
    json_decref(arr);
    return text;
}

/* /parameters: the scene and the active modules as JSON text, and setup
 * statistics (how well the discretisation resolves every particle). */
static int create_parameters(hid_t file, const struct tlsph_model *m)
{
    char *modules = modules_json(m);
    hid_t par = make_group(file, "parameters");
    int rc = -1;
    if (modules && par >= 0 &&
        tlsph_h5_string_dataset(par, "scene", m->scene.json_text ? m->scene.json_text : "{}",
                                "the scene as submitted (JSON)") == 0 &&
        tlsph_h5_string_dataset(par, "modules", modules,
                                "active modules (JSON array of names)") == 0 &&
        tlsph_h5_attr_int64(par, "dimension", m->scene.dimension) == 0 &&
        tlsph_h5_attr_string(par, "engine_version", PACKAGE_VERSION) == 0 &&
        tlsph_h5_attr_string(par, "units_system", "SI") == 0 &&
        tlsph_h5_attr_int64(par, "particles", (int64_t)m->p.n) == 0 &&
        tlsph_h5_attr_int64(par, "pairs", (int64_t)m->pairs.npairs) == 0 &&
        tlsph_h5_attr_int64(par, "deficient_supports", (int64_t)m->deficient_supports) == 0 &&
        tlsph_h5_attr_int64(par, "isolated_particles", (int64_t)m->isolated) == 0 &&
        tlsph_h5_attr_double(par, "max_L_condition", m->max_L_condition) == 0 &&
        tlsph_h5_attr_double(par, "initial_time_step", m->dt) == 0)
        rc = 0;
    if (par >= 0)
        H5Gclose(par);
    free(modules);
    return rc;
}

/* H5MD requires a box; particles are not in a periodic domain. */
static int create_box(hid_t solid)
{
    const char boundary[3][5] = {"none", "none", "none"};
    hid_t box = make_group(solid, "box");
    if (box < 0)
        return -1;
    hid_t strtype = tlsph_h5_string_type(sizeof boundary[0], H5T_STR_NULLTERM);
    int rc = -1;
    if (strtype >= 0 && tlsph_h5_attr_int64(box, "dimension", 3) == 0 &&
        tlsph_h5_attr_values(box, "boundary", strtype, strtype, 3, boundary) == 0)
        rc = 0;
    if (strtype >= 0)
        H5Tclose(strtype);
    H5Gclose(box);
    return rc;
}

/* /particles/solid: the box, the reference fields (written now) and the frame
 * fields (written by tlsph_output_frame); with a changing count every field
 * is a frame field, and the count follows them. */
static int create_particles(struct tlsph_output *o, const struct tlsph_model *m)
{
    hid_t parts = make_group(o->file, "particles");
    if (parts < 0)
        return -1;
    hid_t solid = make_group(parts, "solid");
    int rc = solid < 0 || create_box(solid) < 0 ? -1 : 0;
    for (size_t i = 0; i < o->npresent && rc == 0; i++) {
        const struct tlsph_field *f = o->present[i];
        rc = f->kind == TLSPH_FIELD_REFERENCE && !o->changing
                 ? write_reference_field(o, solid, f, m)
                 : create_frame_field(o, solid, f);
    }
    if (rc == 0 && o->changing)
        rc = create_count(o, solid);
    if (solid >= 0)
        H5Gclose(solid);
    H5Gclose(parts);
    return rc;
}

/* Every present column of columns[0..ncolumns-1] in group g (at path). */
static int create_columns(struct tlsph_output *o, const struct tlsph_model *m, hid_t g,
                          const char *path, const struct tlsph_series_column *columns,
                          size_t ncolumns, size_t *offset)
{
    for (size_t c = 0; c < ncolumns; c++) {
        if (!tlsph_series_present(&columns[c], m))
            continue;
        if (create_series(o, g, path, &columns[c], *offset) < 0)
            return -1;
        *offset += (size_t)columns[c].ncomp;
    }
    return 0;
}

/* /observables/<family>/<item>: the item's present columns. */
static int create_item(struct tlsph_output *o, const struct tlsph_model *m, hid_t fam,
                       const struct tlsph_series_family *f, const char *item, size_t *offset)
{
    /* item is a name by the naming rule (util/names.h, checked at validation):
     * a link name of its own, different from every other item's */
    char path[TLSPH_NAME_MAX + 64];
    snprintf(path, sizeof path, "/observables/%s/%s", f->name, item);
    hid_t g = make_group(fam, item);
    if (g < 0)
        return -1;
    int rc = create_columns(o, m, g, path, f->columns, f->ncolumns, offset);
    H5Gclose(g);
    return rc;
}

/* /observables/<family>/<item>/<column> for every item with series and every
 * present column; the family's group only when it has an item or is "always". */
static int create_family(struct tlsph_output *o, const struct tlsph_model *m, hid_t obs,
                         const struct tlsph_series_family *f, size_t *offset)
{
    hid_t fam = f->always ? make_group(obs, f->name) : H5I_INVALID_HID;
    int rc = f->always && fam < 0 ? -1 : 0;
    for (size_t k = 0; k < f->count(m) && rc == 0; k++) {
        const char *item = f->item(m, k);
        if (!item)
            continue;
        if (fam < 0 && (fam = make_group(obs, f->name)) < 0)
            rc = -1;
        else
            rc = create_item(o, m, fam, f, item, offset);
    }
    if (fam >= 0)
        H5Gclose(fam);
    return rc;
}

static int create_observables(struct tlsph_output *o, const struct tlsph_model *m)
{
    size_t offset = 0;
    hid_t obs = make_group(o->file, "observables");
    if (obs < 0)
        return -1;
    int rc = create_columns(o, m, obs, "/observables", tlsph_global_series,
                            tlsph_nglobal_series, &offset);
    for (size_t f = 0; f < TLSPH_NFAMILIES && rc == 0; f++)
        rc = create_family(o, m, obs, &tlsph_series_families[f], &offset);
    H5Gclose(obs);
    return rc;
}

int tlsph_output_layout(struct tlsph_output *o, const struct tlsph_model *m)
{
    if (create_h5md(o->file) < 0 || create_parameters(o->file, m) < 0 ||
        create_particles(o, m) < 0 || create_observables(o, m) < 0 ||
        tlsph_records_create(o->file, m) < 0)
        return -1;
    return 0;
}
