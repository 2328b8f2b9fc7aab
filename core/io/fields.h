/* Every per-particle output field and every time-series column is declared
 * once, here; the HDF5 writer, the XDMF sidecar and the docs walk these tables
 * and never list names themselves. */
#ifndef TLSPH_FIELDS_H
#define TLSPH_FIELDS_H

#include <stddef.h>

#include "run/model.h"

enum tlsph_field_kind {
    TLSPH_FIELD_REFERENCE, /* written once */
    TLSPH_FIELD_FRAME      /* written every frame */
};

enum tlsph_field_type { TLSPH_FLOAT64, TLSPH_FLOAT32, TLSPH_INT64, TLSPH_INT32 };

struct tlsph_field {
    const char *name;        /* dataset name under /particles/solid */
    enum tlsph_field_kind kind;
    enum tlsph_field_type type; /* type stored in the file */
    int ncomp;               /* 1, 3 or 6 */
    const char *units;       /* SI, e.g. "Pa" */
    const char *components;  /* "x y z", "xx xy xz yy yz zz" or NULL for scalars */
    const char *description;
    /* Is the field present in this model? (NULL = always) */
    int (*present)(const struct tlsph_model *m);
    /* Fills out[n*ncomp] (double for float types, int64 for integer types). */
    void (*extract)(const struct tlsph_model *m, void *out);
};

extern const struct tlsph_field tlsph_fields[];
extern const size_t tlsph_nfields;

/* A time-series column: the run samples these every scene.series_every steps.
 * Columns are present when their module is (present == NULL: always). */
struct tlsph_series_column {
    const char *name;
    int ncomp;               /* 1 or 3 */
    const char *units;
    const char *description;
    int (*present)(const struct tlsph_model *m);
    void (*value)(const struct tlsph_model *m, double *out); /* global columns: ncomp values */
};

extern const struct tlsph_series_column tlsph_global_series[];
extern const size_t tlsph_nglobal_series;

int tlsph_series_present(const struct tlsph_series_column *c, const struct tlsph_model *m);
/* Writes the current values of the present global columns (concatenated components). */
void tlsph_global_series_values(const struct tlsph_model *m, double *out);
/* Number of doubles tlsph_global_series_values writes for this model. */
size_t tlsph_global_series_width(const struct tlsph_model *m);

/* Columns that repeat per item of the scene, written as
 * /observables/<family>/<item>/<column>: boundary groups that carry load
 * (fixed and velocity conditions), gauges, sections, walls, with contact,
 * bodies, rigid bodies, probes, and growing crack tips. */
enum tlsph_family_id { TLSPH_FAMILY_GROUPS, TLSPH_FAMILY_GAUGES, TLSPH_FAMILY_SECTIONS,
                       TLSPH_FAMILY_WALLS, TLSPH_FAMILY_CONTACTS, TLSPH_FAMILY_RIGID,
                       TLSPH_FAMILY_PROBES, TLSPH_FAMILY_CRACK_TIPS,
                       TLSPH_FAMILY_EXTENTS, TLSPH_NFAMILIES };

struct tlsph_series_family {
    const char *name;
    int always;              /* its HDF5 group exists even when no item has series */
    const struct tlsph_series_column *columns;
    size_t ncolumns;
    size_t (*count)(const struct tlsph_model *m);
    /* name of item k (k < count), or NULL when item k has no series */
    const char *(*item)(const struct tlsph_model *m, size_t k);
    /* writes item k's present columns, concatenated (tlsph_family_width doubles) */
    void (*values)(const struct tlsph_model *m, size_t k, double *out);
};

extern const struct tlsph_series_family tlsph_series_families[TLSPH_NFAMILIES];
/* Doubles one item of family f writes in this model (its present columns). */
size_t tlsph_family_width(const struct tlsph_series_family *f, const struct tlsph_model *m);

#endif
