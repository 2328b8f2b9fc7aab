/* The size of a job's result file, see output_size.h. */
#include "output_size.h"

#include <stdio.h>
#include <stdlib.h>

#include "io/fields.h"

static double type_bytes(enum tlsph_field_type t)
{
    switch (t) {
    case TLSPH_FLOAT64:
    case TLSPH_INT64:
        return 8;
    case TLSPH_FLOAT32:
    case TLSPH_INT32:
        return 4;
    }
    return 8;
}

int output_size_estimate(const struct tlsph_scene *scene, struct output_size *out,
                         struct tlsph_errors *err)
{
    out->particles = 0;
    for (size_t b = 0; b < scene->nbodies; b++) {
        double *points = NULL;
        size_t n = 0;
        if (tlsph_body_lattice(scene, b, scene->max_particles, &points, &n, err) != 0)
            return -1;
        free(points);
        out->particles += n;
    }
    out->reference_bytes = out->frame_bytes = 0;
    for (size_t f = 0; f < tlsph_nfields; f++) {
        const double b = type_bytes(tlsph_fields[f].type) * tlsph_fields[f].ncomp;
        if (tlsph_fields[f].kind == TLSPH_FIELD_REFERENCE)
            out->reference_bytes += b;
        else
            out->frame_bytes += b;
    }
    out->records = scene->frames + 1;
    out->bytes = (double)out->particles *
                 (out->reference_bytes + (double)out->records * out->frame_bytes);
    return 0;
}

const char *output_size_text(char *buf, size_t size, double bytes)
{
    static const char *const unit[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
    int u = 0;
    while (bytes >= 1024 && u < 5) {
        bytes /= 1024;
        u++;
    }
    snprintf(buf, size, u ? "%.1f %s" : "%.0f %s", bytes, unit[u]);
    return buf;
}
