#ifndef TLSPH_PARALLEL_H
#define TLSPH_PARALLEL_H

/* Below this many loop items (particles) a step's loops run on one thread.
 * Every parallel loop ends in a join barrier. On free cores that costs a few
 * microseconds; on shared cores (two jobs, or the test suite run with make -j)
 * a barrier waits for a descheduled thread, i.e. a scheduler time slice of
 * milliseconds, and a 400-particle run of 8000 steps went from 1.3 s to over a
 * minute. Below a few thousand particles the second thread gains under 10 %
 * (elastic strip, 400 particles: 1.33 s on 1 thread, 1.21 s on 2), so small
 * runs give it up. */
#define TLSPH_PARALLEL_MIN_ITEMS 4096

#ifdef _OPENMP
#include <omp.h>
#endif

/* The OpenMP threads a parallel region of this run gets (tlsph-run --threads,
 * OMP_NUM_THREADS); 1 without OpenMP.  Reported in the cost record, so that a
 * run says what it ran on (the daemon's thread budget, docs/deployment.md). */
static inline int tlsph_threads(void)
{
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

#endif
