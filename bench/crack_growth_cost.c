/* The cost of a growing crack in a run (docs/crack-growth.md "The crack
 * driver"): the mode-I plate of tests/physics/test_crack_growth.c scaled to
 * LX x LY mm in the plane (3 layers, 1 mm), run to END seconds with and
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

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int run(double lx, double ly, double end, int grow)
{
    char text[4096];
    const double x0 = -0.010, x1 = x0 + 1e-3 * lx, y1 = 0.5e-3 * ly;
    snprintf(text, sizeof text,
             "{\"dimension\":3,\"parameters\":{\"vmax\":5,\"tau\":5e-6},"
             "\"time\":{\"end\":%g,\"cfl\":0.3},"
             "\"discretization\":{\"hourglass\":{\"enabled\":true,\"coefficient\":1.0}},"
             "\"contact\":{\"enabled\":false},"
             "\"materials\":{\"steel\":{\"density\":7850,\"youngs_modulus\":2.1e11,"
             "\"poisson_ratio\":0.3,\"strength\":{\"type\":\"linear_hardening\","
             "\"yield_stress\":3e8,\"hardening_modulus\":5e8},"
             "\"damage\":{\"type\":\"johnson_cook\",\"d1\":0.08,\"d2\":0,\"d3\":0}}},"
             "\"bodies\":[{\"name\":\"plate\",\"material\":\"steel\",\"spacing\":0.001,"
             "\"thickness_axis\":\"z\","
             "\"geometry\":{\"box\":{\"min\":[%g,%g,0],\"max\":[%g,%g,0.003]}}}],"
             "\"cracks\":[{\"polygon\":[[-0.011,0,-0.001],[0,0,-0.001],[0,0,0.004],"
             "[-0.011,0,0.004]]}],%s"
             "\"boundary_conditions\":["
             "{\"type\":\"velocity\",\"name\":\"bottom\",\"select\":{\"box\":"
             "{\"min\":[-1,-1,-1],\"max\":[1,%g,1]}},"
             "\"velocity\":[null,\"-vmax*(1-exp(-t/tau))\",null]},"
             "{\"type\":\"velocity\",\"name\":\"top\",\"select\":{\"box\":"
             "{\"min\":[-1,%g,-1],\"max\":[1,1,1]}},"
             "\"velocity\":[null,\"vmax*(1-exp(-t/tau))\",null]}]}",
             end, x0, -y1, x1, y1, grow ? "\"crack_growth\":{\"tips\":[[0,0,0.0015]]}," : "",
             -y1 + 1.5e-3, y1 - 1.5e-3);
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
