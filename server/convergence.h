/* The convergence process (server/convergence.c, convergence_result.c): a
 * base scene run at a ladder of particle spacings as a study, and, from the
 * children's results, per output the observed order, the Richardson limit,
 * each resolution's error estimate and GCI (richardson.h), the measured cost
 * of each run, a fitted cost model wall = c h^-q and, given a target, the
 * predicted spacing, particle count, wall time and memory.
 *
 * Input (the "inputs" of POST /processes/convergence/execution):
 *   {"base": SCENE,
 *    "ladder": {"spacings": [0.004, 0.002, 0.001]}                 (>= 3, constant ratio)
 *            | {"spacing": 0.004, "ratio": 2, "count": 3}          (coarsest, ratio > 1)
 *              + optional "pointers": ["/bodies/0/spacing", ...]   (default: every body's
 *                                                                   "spacing")
 *    "outputs": [{"name": "quarter_period", "series": "kinetic_energy",
 *                 "reduce": "final"|"max"|"min"|"time_of_threshold",
 *                 "component": 0, "threshold": 5e-4,
 *                 "direction": "rising"|"falling"|"either"}, ...],  (>= 1)
 *    "target": {"relative_error": 0.01}}                            (optional)
 * "spacing" is the value of the first pointer; every other pointer keeps its
 * ratio to the first one in the base scene (bodies refined together).
 *
 * The job is stored as a study (its children are ordinary run jobs, coarsest
 * first) whose input carries the normalised request under "convergence"; the
 * result is recomputed from the children's result files and cost records on
 * every request, so it survives a restart with them. */
#ifndef TLSPHD_CONVERGENCE_H
#define TLSPHD_CONVERGENCE_H

#include <jansson.h>
#include <stddef.h>

#include "study.h"
#include "util/errors.h"

#define TCONV_MIN_RUNS 3
#define TCONV_MAX_RUNS 8
#define TCONV_MIN_RATIO 1.1     /* Celik et al. recommend r > 1.3 */
#define TCONV_RATIO_TOL 0.01    /* each h[i+1]/h[i] within 1 % of the ladder's ratio */

/* Validates inputs and builds the study to store (new reference: base,
 * sweep (zip over the pointers), outputs (those a study can tabulate) and
 * "convergence" (the normalised request)).  Errors carry pointers relative to
 * the inputs ("/ladder/spacings/2").  NULL on error. */
json_t *tconv_study(const json_t *inputs, struct tlsph_errors *err);

/* The stored input is a convergence study (it has a "convergence" member). */
int tconv_is_convergence(const json_t *stored);

/* One output's value from a child's result file: NAN when the file, the
 * series or (time_of_threshold) a crossing is missing; err says which. */
double tconv_output_value(const json_t *output, const char *h5path, char *err, size_t errsize);
/* The time at which v first crosses threshold (linear interpolation between
 * samples; direction "rising", "falling" or "either"), NAN when it never does. */
double tconv_crossing_time(const double *t, const double *v, size_t n, double threshold,
                           const char *direction);

/* The convergence result of a stored convergence study from its children
 * (rows as for tstudy_summary; unfinished or failed children give no value):
 * see docs/api.md.  NULL when out of memory. */
json_t *tconv_result(const json_t *stored, const struct tstudy_row *rows, size_t n);
/* The same as a table {"columns", "rows"} (one row per output and run), for
 * tstudy_summary_csv. */
json_t *tconv_result_table(const json_t *result);

#endif
