/* One complete run: time loop, stability contract, frames, time series,
 * progress and the cost record.  This is the contract the CLI and the daemon use. */
#ifndef TLSPH_RUN_H
#define TLSPH_RUN_H

#include <signal.h>
#include <stdio.h>

#include "util/errors.h"
#include "run/model.h"
#include "run/protocol.h"

struct tlsph_run_options {
    const char *output_dir;             /* must exist */
    int progress_fd;                    /* -1: no progress lines */
    volatile sig_atomic_t *cancel;      /* non-zero: stop after finishing the current frame */
    FILE *log;                          /* human-readable log lines, or NULL */
};

/* Runs m to its end time.  Returns a tlsph_exit code; on TLSPH_EXIT_UNSTABLE d
 * holds the diagnostic, on TLSPH_EXIT_IO err says why.  Emits the started,
 * progress and final events of run/protocol.h on o->progress_fd. */
int tlsph_run(struct tlsph_model *m, const struct tlsph_run_options *o,
              struct tlsph_diagnostic *d, struct tlsph_errors *err);

#endif
