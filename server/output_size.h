/* The size of a job's result file, estimated at submission
 * (server/output_size.c), for the per-job quota and the free-space check.
 *
 *   bytes = N * (R + (F + 1) * P)
 *
 * N particles (the engine's own lattice count of every body, the count the
 * run will have), F + 1 frame records (frame 0 and `output.frames` more,
 * docs/output.md), R the bytes per particle of the reference fields written
 * once and P those of the per-frame fields, both summed over the engine's
 * field table (core/io/fields.c: components x the size of the type stored).
 * Every field of the table is counted, also those a scene's modules do not
 * write (plastic strain, temperature, damage, void fraction: 28 of 116 bytes
 * per particle and frame), and compression is ignored, so the estimate is an
 * upper bound on the field data; the time series (a row of a few dozen
 * numbers per sample) and HDF5's own metadata are left out. */
#ifndef TLSPHD_OUTPUT_SIZE_H
#define TLSPHD_OUTPUT_SIZE_H

#include <stddef.h>

#include "scene/scene.h"
#include "util/errors.h"

struct output_size {
    size_t particles;       /* N */
    long records;           /* F + 1 */
    double reference_bytes; /* R, B per particle */
    double frame_bytes;     /* P, B per particle and frame */
    double bytes;           /* the estimate, B */
};

/* Estimates the result file of a parsed scene: 0, or -1 with err (a body
 * the engine cannot lay out). */
int output_size_estimate(const struct tlsph_scene *scene, struct output_size *out,
                         struct tlsph_errors *err);
/* "23.4 GiB" style text of bytes into buf. */
const char *output_size_text(char *buf, size_t size, double bytes);

#endif
