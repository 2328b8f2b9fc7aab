#ifndef TLSPH_PARALLEL_H
#define TLSPH_PARALLEL_H

#include <stddef.h>

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

/* The part [*a, *b) of [lo, hi) that the calling thread of a parallel region
 * works on: contiguous shares in thread order, the first (hi - lo) % threads
 * of them one item longer (libgomp's split for schedule(static), so a loop
 * over the share visits what `omp for schedule(static)` would give the thread).
 * Two loops over the same range in one region that both take their share
 * here give every thread the same items, so the second may read what the
 * first wrote for them without a barrier.  Outside a parallel region (or
 * without OpenMP) the whole range. */
static inline void tlsph_static_share(size_t lo, size_t hi, size_t *a, size_t *b)
{
#ifdef _OPENMP
    const size_t threads = (size_t)omp_get_num_threads(), t = (size_t)omp_get_thread_num();
#else
    const size_t threads = 1, t = 0;
#endif
    size_t q = (hi - lo) / threads, r = (hi - lo) % threads;
    if (t < r) {
        q++;
        r = 0;
    }
    *a = lo + q * t + r;
    *b = *a + q;
}

#endif
