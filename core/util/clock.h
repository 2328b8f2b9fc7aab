/* Monotonic seconds, for durations, deadlines and rates (never for timestamps:
 * CLOCK_MONOTONIC has no epoch).  Header-only so that the engine, the daemon
 * and the client share one definition without a link dependency. */
#ifndef TLSPH_CLOCK_H
#define TLSPH_CLOCK_H

#include <time.h>

/* Seconds since an arbitrary fixed point (boot), nanosecond resolution. */
static inline double tlsph_monotonic_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif
