/* Every per-particle output field and every time-series column is declared
 * once, here; the HDF5 writer, the XDMF sidecar and the docs walk these tables
 * and never list names themselves. */
#ifndef TLSPH_FIELDS_H
#define TLSPH_FIELDS_H

#include <stddef.h>

#include "model.h"

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
 * Global columns are present when their module is (present == NULL: always);
 * group columns repeat for each boundary group that carries load (fixed and
 * velocity conditions) under the name "<group>/<column>". */
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
extern const struct tlsph_series_column tlsph_group_series[];
extern const size_t tlsph_ngroup_series;

int tlsph_series_present(const struct tlsph_series_column *c, const struct tlsph_model *m);
/* Does boundary condition k produce group series (reaction force, displacement)? */
int tlsph_group_has_series(const struct tlsph_model *m, size_t k);
/* Writes the current values of the present global columns (concatenated components). */
void tlsph_global_series_values(const struct tlsph_model *m, double *out);
/* Writes the current values of group k's columns. */
void tlsph_group_series_values(const struct tlsph_model *m, size_t k, double *out);
/* Number of doubles tlsph_global_series_values writes for this model. */
size_t tlsph_global_series_width(const struct tlsph_model *m);
size_t tlsph_group_series_width(void);

/* Gauge columns (both always present, 2 values) and section columns (those of
 * present modules) repeat per scene gauge / section under
 * "gauges/<name>/<column>" and "sections/<name>/<column>". */
extern const struct tlsph_series_column tlsph_gauge_series[];
extern const size_t tlsph_ngauge_series;
extern const struct tlsph_series_column tlsph_section_series[];
extern const size_t tlsph_nsection_series;
size_t tlsph_section_series_width(const struct tlsph_model *m);
void tlsph_gauge_series_values(const struct tlsph_model *m, size_t k, double *out);
void tlsph_section_series_values(const struct tlsph_model *m, size_t k, double *out);

#endif
