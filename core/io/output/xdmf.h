/* The XDMF 2 sidecar (DIR/result.xmf) that lets ParaView's "XDMF Reader" open
 * the H5MD-style result file: a temporal collection of Polyvertex grids, one per
 * frame, whose geometry and attributes are HyperSlabs of frame k of the
 * /particles/solid/<field>/value datasets.  Reference fields are attached to
 * every frame unchanged (with a changing count: their frame k, like the
 * others).  Written by core/io/output/h5md.c after every frame. */
#ifndef TLSPH_XDMF_H
#define TLSPH_XDMF_H

#include <stddef.h>

#include "io/fields.h"

/* Rewrites xmf_path atomically (xmf_path.tmp, then rename) describing nframes
 * frames at times[0..nframes-1] of n particles stored in h5_name (a path
 * relative to the .xmf).  fields[0..nfields-1] are the fields present in the
 * file; the geometry is the frame field named "position" (else the first
 * 3-component frame field in metres).  counts NULL: one count n per run;
 * else the layout for changing counts (output.h): frame k has counts[k]
 * particles, every field is stored per frame, and n is the particle extent
 * of the datasets (each frame's grid is the first counts[k] entries of its
 * row).  Returns 0, or -1 with errno set. */
int tlsph_xdmf_write(const char *xmf_path, const char *h5_name, size_t n, size_t nframes,
                     const double *times, const size_t *counts,
                     const struct tlsph_field *const *fields, size_t nfields);

#endif
