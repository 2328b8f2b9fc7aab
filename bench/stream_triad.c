/* The machine's bound for one core: sustainable bandwidth and flop rate.
 *
 * Built by bench/bound.sh with the compiler and flags the engine was
 * configured with (so the flop rate is what the engine's own code generation
 * can reach), not part of make check.  One thread.
 *
 *   triad   a[i] = b[i] + s c[i] over three double arrays of n elements,
 *           24 bytes moved per element (two reads, one write; the write's
 *           read-for-ownership is not counted, as in STREAM), repeated until
 *           about 0.3 s have passed, the best of 5 repetitions.  Run at
 *           sizes from L1 to one far beyond the last-level cache (the
 *           main-memory figure).
 *   flops   32 independent multiply-add chains x = x * a + b per lane, the
 *           most the compiler makes of plain C at these flags: 2 flops per
 *           element per pass.
 *
 * usage: stream_triad [BIG_MIB]   (default 2048 MiB for the three big arrays)
 * Prints one line per measurement: "triad <bytes per array> <GB/s>",
 * "flops <Gflop/s>" (packed, as vectorised) and "flops_scalar <Gflop/s>". */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void)
{
    struct timespec ts;
    /* CPU time of this thread: on a shared machine the time slices another
     * process takes are not charged to the measurement */
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* noinline: the compiler must not fold repetitions of the triad together */
static __attribute__((noinline)) void triad(double *restrict a, const double *restrict b,
                                            const double *restrict c, double s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        a[i] = b[i] + s * c[i];
}

/* best bandwidth in GB/s of the triad on n elements */
static double triad_rate(double *a, double *b, double *c, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        a[i] = 0.0;
        b[i] = 1.0 + 1e-9 * (double)i;
        c[i] = 2.0;
    }
    double best = 0.0;
    for (int rep = 0; rep < 5; rep++) {
        long passes = 0;
        const double t0 = now();
        double t = t0;
        do {
            triad(a, b, c, 1.0 + 1e-12 * (double)passes, n);
            passes++;
            t = now();
        } while (t - t0 < 0.3);
        const double rate = 24.0 * (double)n * (double)passes / (t - t0) * 1e-9;
        if (rate > best)
            best = rate;
    }
    /* read a result, so that no pass is dead code */
    if (a[n / 2] < 0.0)
        printf("impossible\n");
    return best;
}

#define LANES 32
/* LANES chains x = x a + b, m passes; x local, so the chains stay in registers */
#define CHAINS(out, a, b, m)                \
    do {                                    \
        double x[LANES];                    \
        for (int l = 0; l < LANES; l++)     \
            x[l] = out[l];                  \
        for (long k = 0; k < m; k++)        \
            for (int l = 0; l < LANES; l++) \
                x[l] = x[l] * a + b;        \
        for (int l = 0; l < LANES; l++)     \
            out[l] = x[l];                  \
    } while (0)

static __attribute__((noinline)) void fma_chains(double *restrict out, double a, double b, long m)
{
    CHAINS(out, a, b, m);
}

/* the same chains one double at a time: what scalar code (most of the
 * engine's gather loops) can reach */
static __attribute__((noinline, optimize("no-tree-vectorize"))) void
fma_chains_scalar(double *restrict out, double a, double b, long m)
{
    CHAINS(out, a, b, m);
}

static double flop_rate(int scalar)
{
    double x[LANES];
    for (int l = 0; l < LANES; l++)
        x[l] = 1.0 + 0.01 * l;
    double best = 0.0;
    for (int rep = 0; rep < 5; rep++) {
        const long m = 20000000;
        const double t0 = now();
        if (scalar)
            fma_chains_scalar(x, 0.999999, 1e-7, m);
        else
            fma_chains(x, 0.999999, 1e-7, m);
        const double t = now() - t0;
        const double rate = 2.0 * LANES * (double)m / t * 1e-9;
        if (rate > best)
            best = rate;
    }
    double sum = 0.0;
    for (int l = 0; l < LANES; l++)
        sum += x[l];
    if (sum != sum)
        printf("impossible\n");
    return best;
}

int main(int argc, char **argv)
{
    const double big_mib = argc > 1 ? atof(argv[1]) : 2048.0;
    const size_t nbig = (size_t)(big_mib * 1048576.0 / 24.0);
    /* per array: 8 KiB (L1), 256 KiB (L2), 2 MiB (beyond L2), 16 MiB (a 40k-particle
     * run's arrays are ~50 MiB in all), 64 MiB, then the big size (main memory) */
    enum { NSIZES = 6 };
    const size_t sizes[NSIZES] = {1024, 32768, 262144, 2097152, 8388608, nbig};
    double *a = malloc(nbig * sizeof *a), *b = malloc(nbig * sizeof *b),
           *c = malloc(nbig * sizeof *c);
    if (!a || !b || !c) {
        fprintf(stderr, "stream_triad: cannot allocate %.0f MiB\n", big_mib);
        free(a);
        free(b);
        free(c);
        return 1;
    }
    for (int k = 0; k < NSIZES; k++)
        if (sizes[k] <= nbig)
            printf("triad %zu %.2f\n", sizes[k] * sizeof(double), triad_rate(a, b, c, sizes[k]));
    printf("flops %.2f\n", flop_rate(0));
    printf("flops_scalar %.2f\n", flop_rate(1));
    free(a);
    free(b);
    free(c);
    return 0;
}
