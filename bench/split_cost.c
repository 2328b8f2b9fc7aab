/* Cost of particle splitting (core/crack/split.h) against a full rebuild:
 *   bench/split_cost NX NY NZ EVENTS
 * builds a plate of NX x NY x NZ particles (spacing 1 mm, fibres along z),
 * grows a straight crack along y = the middle row from the left edge by
 * splitting EVENTS fibres one after the other (facets up to each), and prints
 * one JSON line: particles before and after, pairs, the mean and largest
 * CPU time of a split event (plan, growth, commit, the force update of the
 * affected rows and their partners), and
 * that of one full rebuild of the same final state (the reference search, the
 * crack filter and every correction matrix) and of one force pass.  Run
 * with OMP_NUM_THREADS=1. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "crack/split.h"
#include "run/model.h"
#include "sph/correction.h"
#include "sph/forces.h"
#include "sph/neighbors.h"

#define H 0.001

/* CPU time of the process, s: one thread (OMP_NUM_THREADS=1), so on a loaded
 * machine it measures the work, not the wait. */
static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void add_crack(struct tlsph_crack_surface *cs, double yt, double x0, double x1, double zt)
{
    const double T1[3][3] = {{x0, yt, -H}, {x1, yt, -H}, {x1, yt, zt + H}};
    const double T2[3][3] = {{x0, yt, -H}, {x1, yt, zt + H}, {x0, yt, zt + H}};
    if (tlsph_crack_surface_add(cs, T1) || tlsph_crack_surface_add(cs, T2)) {
        fprintf(stderr, "crack surface refused a facet\n");
        exit(1);
    }
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: %s NX NY NZ EVENTS\n", argv[0]);
        return 2;
    }
    const int nx = atoi(argv[1]), ny = atoi(argv[2]), nz = atoi(argv[3]), events = atoi(argv[4]);
    if (nx < 2 || ny < 2 || nz < 1 || events < 1 || events >= nx) {
        fprintf(stderr, "need NX, NY >= 2, NZ >= 1, 1 <= EVENTS < NX\n");
        return 2;
    }
    char text[1024];
    snprintf(text, sizeof text,
             "{\"dimension\":3,\"time\":{\"end\":1e-6},\"contact\":{\"enabled\":false},"
             "\"materials\":{\"m\":{\"density\":7800,\"youngs_modulus\":2e11,\"poisson_ratio\":0.3}},"
             "\"bodies\":[{\"name\":\"plate\",\"material\":\"m\",\"spacing\":%g,"
             "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[%g,%g,%g]}}}]}",
             H, nx * H, ny * H, nz * H);
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tlsph_scene scene;
    struct tlsph_model *m = NULL;
    if (tlsph_scene_parse(text, strlen(text), &scene, &err) != 0 || tlsph_model_create(&scene, &m, &err) != 0) {
        fprintf(stderr, "%s\n", err.count ? err.items[0].message : "setup failed");
        return 1;
    }
    const size_t n0 = m->p.n;
    const double yt = (ny / 2 + 0.5) * H, x0 = 0.5 * H;
    struct tlsph_crack_surface cs;
    tlsph_crack_surface_init(&cs, 2.4 * H);
    double total = 0.0, worst = 0.0;
    size_t fib[64];
    for (int e = 0; e < events; e++) {
        const double xf = x0 + e * H;
        size_t k = 0;
        for (size_t i = 0; i < m->p.n && k < 64; i++)
            if (fabs(m->p.X[3 * i] - xf) < 1e-9 && fabs(m->p.X[3 * i + 1] - yt) < 1e-9)
                fib[k++] = i;
        const size_t first = cs.nfacets;
        add_crack(&cs, yt, e ? xf - H : -2 * H, xf, nz * H);
        struct tlsph_split sp = {fib, k, {1, 0, 0}, {1, 0, 0}, {0, 1e-5, 0}};
        const double t0 = cpu_seconds();
        if (tlsph_split_particles(m, &sp, &cs, first, NULL, NULL, &err) != 0) {
            fprintf(stderr, "%s\n", err.count ? err.items[0].message : "split failed");
            return 1;
        }
        const double dt = cpu_seconds() - t0;
        total += dt;
        worst = fmax(worst, dt);
    }
    /* one force pass over the body (the split's update covers a few rows) */
    const double tf = cpu_seconds();
    (void)tlsph_forces(m);
    const double force = cpu_seconds() - tf;
    /* a full rebuild of the final state: search, crack filter, corrections */
    const double t0 = cpu_seconds();
    int64_t *start;
    int32_t *nbr;
    if (tlsph_build_pairs(m->p.X, m->p.h, m->p.body, m->p.n, &start, &nbr) != 0)
        return 1;
    int64_t e = 0;
    for (size_t i = 0; i < m->p.n; i++) {
        const int64_t k0 = start[i], k1 = start[i + 1];
        start[i] = e;
        for (int64_t q = k0; q < k1; q++)
            if (!tlsph_crack_surface_blocks(&cs, m->p.X + 3 * i, m->p.X + 3 * (size_t)nbr[q], NULL))
                nbr[e++] = nbr[q];
    }
    start[m->p.n] = e;
    free(m->pairs.start);
    free(m->pairs.j);
    m->pairs.start = start;
    m->pairs.j = nbr;
    m->pairs.npairs = (size_t)e;
    free(m->pairs.dw);
    if (!(m->pairs.dw = malloc((e ? (size_t)e : 1) * sizeof *m->pairs.dw)))
        return 1;
    tlsph_correction_build(m);
    const double full = cpu_seconds() - t0;
    printf("{\"particles\":%zu,\"after\":%zu,\"pairs\":%zu,\"events\":%d,"
           "\"split_mean_s\":%.3g,\"split_max_s\":%.3g,\"force_pass_s\":%.3g,\"full_rebuild_s\":%.3g}\n",
           n0, m->p.n, (size_t)e, events, total / events, worst, force, full);
    tlsph_crack_surface_release(&cs);
    tlsph_model_free(m);
    tlsph_errors_free(&err);
    return 0;
}
