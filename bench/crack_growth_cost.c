/* The cost of a growing crack in a run (docs/crack-growth.md "The crack
 * driver"): the mode-I plate of tests/physics/test_crack_growth.c
 * (tests/support/crack_plate.h) at LX x LY mm in the plane (3 layers, 1 mm), run to END seconds with and
 * without "crack_growth".  Prints steps, tip advances, particles before and
 * after, the CPU time of each run and the driver's share (its searches and
 * advances; CPU time of the process: run it with OMP_NUM_THREADS=1).
 *
 * usage: crack_growth_cost LX LY END */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "crack/crack_driver.h"
#include "run/integrate.h"
#include "run/model.h"
#include "support/crack_plate.h"

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int run(double lx, double ly, double end, int grow)
{
    char text[4096];
    crack_plate_scene(text, sizeof text, lx, ly, end, grow);
    struct tlsph_scene scene;
    struct tlsph_model *m = NULL;
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    if (tlsph_scene_parse(text, strlen(text), &scene, &err) != 0 ||
        tlsph_model_create(&scene, &m, &err) != 0) {
        fprintf(stderr, "scene refused: %s\n", err.count ? err.items[0].message : "?");
        tlsph_errors_free(&err);
        return 1;
    }
    const size_t n0 = m->p.n;
    const double t0 = cpu_seconds();
    while (m->t < m->scene.end_time * (1.0 - 1e-12)) {
        tlsph_model_step(m);
        if (tlsph_crack_driver_step(m, NULL, &err) != 0) {
            fprintf(stderr, "growth failed: %s\n", err.items[0].message);
            break;
        }
    }
    const double cpu = cpu_seconds() - t0;
    const struct tlsph_crack_driver *d = m->crack_driver;
    printf("%-9s %5.0f x %3.0f mm: %ld steps, %zu advances, %zu -> %zu particles, grown %.1f mm, "
           "%.2f s CPU (%.1f us/step), driver %.4f s (%.2f %%)\n",
           grow ? "growth" : "no growth", lx, ly, m->step, d ? d->nevents : 0, n0, m->p.n,
           1e3 * tlsph_crack_driver_length(m), cpu, 1e6 * cpu / (double)m->step,
           d ? d->seconds : 0.0, d ? 100.0 * d->seconds / cpu : 0.0);
    tlsph_model_free(m);
    tlsph_errors_free(&err);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: %s LX_MM LY_MM END_S\n", argv[0]);
        return 2;
    }
    const double lx = atof(argv[1]), ly = atof(argv[2]), end = atof(argv[3]);
    return run(lx, ly, end, 0) || run(lx, ly, end, 1);
}
