/* The result file of a run: DIR/result.h5 (H5MD-style, SWMR-readable while the
 * run writes) and DIR/result.xmf (XDMF 2 sidecar for ParaView's "XDMF Reader").
 *
 * Layout (all datasets carry a "units" attribute; see docs/output.md):
 *   /h5md                             attrs version=[1,1], creator/name, creator/version
 *   /parameters                       datasets scene (JSON text), modules (JSON array text);
 *                                     attrs dimension, engine_version, units_system
 *   /particles/solid/<field>          reference fields: dataset [N] or [N, C]
 *   /particles/solid/<field>/{step,time,value}  frame fields: value [F, N] or [F, N, C]
 *   /observables/<column>/{step,time,value}     time series: value [T] or [T, 3]
 *   /observables/groups/<bc>/<column>/{step,time,value}
 *   /cost                             attrs particles, pairs, steps, wall_seconds,
 *                                     particle_steps_per_second, peak_memory_bytes,
 *                                     bytes_per_particle (placeholders until close)
 *   /diagnostics                      attrs status, and when unstable: step, time, quantity,
 *                                     value, limit, nids, ids, message (rewritten at close)
 * Frame datasets grow along an unlimited first axis; everything is created before
 * SWMR writing starts, so nothing is created afterwards.
 *
 * A run whose particle count changes (particle splitting, crack/split.h) gets
 * the layout for changing counts instead, chosen at open: every field, the
 * reference fields included, is a frame field /particles/solid/<field>/value
 * [F, Nmax] or [F, Nmax, C] whose particle axis is unlimited too, and
 *   /particles/solid/count/{step,time,value}  int64 [F]: frame k's count n_k
 * Frame k's particles are entries 0 .. n_k - 1 of row k (in the model's index
 * order; `id` names them); the entries past n_k hold the fill value (0, or -1
 * for the integer fields id and body). */
#ifndef TLSPH_OUTPUT_H
#define TLSPH_OUTPUT_H

#include "util/errors.h"
#include "run/model.h"

struct tlsph_output; /* opaque */

struct tlsph_cost {
    size_t particles, pairs;
    long steps;
    double wall_seconds;
    double particle_steps_per_second;
    size_t peak_memory_bytes; /* peak resident set of the process */
    double bytes_per_particle;
    int threads;              /* OpenMP threads of the run's parallel loops */
    /* Only with contact (contact set; the others write none of these):
     * searches made, and the shares of wall_seconds spent in the contact
     * searches and in the whole contact phase (searches included), 1. */
    int contact;
    long contact_searches;
    double contact_search_share, contact_phase_share;
    /* Only with a porous damage model (porous set): the share of wall_seconds
     * spent in the constitutive phase (every point update, the porous returns
     * included), 1. */
    int porous;
    double material_phase_share;
};

/* No dataset of the file ever holds a value that is not finite (float32
 * datasets: nor one beyond float32's range, which would be stored as Inf).
 * tlsph_output_frame and tlsph_output_series check every value before they
 * write any and refuse the whole frame or sample instead, returning
 * TLSPH_OUTPUT_REFUSED; the file is left as it was, and tlsph_output_refusal
 * says what was refused.  The run then stops with a diagnostic
 * (core/run/run.c). */
#define TLSPH_OUTPUT_REFUSED 1

struct tlsph_output_refusal {
    char dataset[128];  /* its path in the file, e.g. "/particles/solid/stress/value" */
    double value;       /* the first such value, as it would be stored */
    size_t nids;
    int64_t ids[16];    /* frame fields: the first particles holding one (ids, not indices) */
};

/* Creates dir/result.h5 (truncating) and dir/result.xmf. Returns NULL and adds an
 * error; then neither file is left in dir (a file that could not be set up holds
 * no outcome).  The layout for changing counts when
 * tlsph_output_count_may_change(m). */
struct tlsph_output *tlsph_output_open(const char *dir, const struct tlsph_model *m,
                                       struct tlsph_errors *err);
/* The same with the layout chosen by the caller: changing_count 1 for the
 * layout for changing counts, 0 for one count per run. */
struct tlsph_output *tlsph_output_open_with(const char *dir, const struct tlsph_model *m,
                                            int changing_count, struct tlsph_errors *err);
/* 1 when m's particle count may change during its run: a model with growing
 * cracks (crack/crack_driver.h), whose tip fibres are split; else 0 (fibres
 * alone split nothing; a library caller that splits opens with
 * tlsph_output_open_with). */
int tlsph_output_count_may_change(const struct tlsph_model *m);
/* Appends one frame of every present frame field, then flushes; rewrites the .xmf
 * (via a temporary file and rename) when the last rewrite is more than 2 s old;
 * tlsph_output_close always rewrites it.  Returns 0, TLSPH_OUTPUT_REFUSED (nothing
 * written) or -1 (I/O error, or, in a file with one count per run, a particle
 * count other than at open: particle splitting, crack/split.h, changes it). */
int tlsph_output_frame(struct tlsph_output *o, const struct tlsph_model *m);
/* Appends one sample of every time-series column.  Rows are buffered and written
 * (and flushed) when 1024 are pending, at every frame, after ~1 s of wall time and
 * at close; a second sample at the same step replaces the first.  Returns 0,
 * TLSPH_OUTPUT_REFUSED (the sample is dropped) or -1 (I/O error). */
int tlsph_output_series(struct tlsph_output *o, const struct tlsph_model *m);
/* What the last TLSPH_OUTPUT_REFUSED refused. */
const struct tlsph_output_refusal *tlsph_output_refusal(const struct tlsph_output *o);
/* Records cost and outcome, closes everything. status: "successful", "unstable",
 * "cancelled", "io_error". d may be NULL. Returns 0 or -1 (the handle is freed either way). */
int tlsph_output_close(struct tlsph_output *o, const struct tlsph_model *m,
                       const struct tlsph_cost *cost, const char *status,
                       const struct tlsph_diagnostic *d);
/* Frees without writing the closing records (used on abort paths). */
void tlsph_output_abort(struct tlsph_output *o);

#endif
