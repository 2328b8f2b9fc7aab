/* The energy balance around a particle split (core/crack/split.h,
 * docs/crack-growth.md "The balance across a split"):
 *   bench/split_balance CFL SPLIT CASE STEPS
 * builds tests/engine/test_split.c's free plate and block (hourglass and
 * viscosity on) at time step factor CFL, runs 30 steps, and then
 *   CASE 0: cuts the crack from outside the plate to the fibre at x = 5 mm in
 *           one event (momentum_after_split's split, a 45-degree turn);
 *   CASE 1: splits the fibre at x = 4 mm (crack up to it), runs 30 steps, and
 *           splits the fibre at 5 mm with its own facet (a fibre's advance);
 * the split done only when SPLIT is 1 (0: the same steps without it).  Then
 * prints, for each of STEPS steps, the change of the balance and of each
 * energy term, the change of the Verlet term dt^2/8 sum |f|^2/m over the step
 * (both at the step's dt), and the balance's change minus it (the part that
 * velocity Verlet's kinetic energy identity does not explain), one line
 * each.  Run with OMP_NUM_THREADS=1. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "crack/crack_surface.h"
#include "crack/split.h"
#include "run/integrate.h"
#include "run/model.h"
#include "support/split_plate.h"

#define H 0.001
#define DELTA 1e-5

static const char *scene_format =
    "{\"dimension\":3,\"time\":{\"end\":1.0,\"max_steps\":1000,\"cfl\":%g}," SPLIT_PLATE_AFTER_TIME;

/* Adds the crack from x0 to x1 in the plane y = yt (through the thickness)
 * and splits the fibre at (x1, yt) with V2 = (c, s, 0), delta normal to it. */
static int split_at(struct tlsph_model *m, struct tlsph_crack_surface *cs, double yt, double x0,
                    double x1, double c, double s)
{
    const double z0 = -H, z1 = 4 * H;
    const double T1[3][3] = {{x0, yt, z0}, {x1, yt, z0}, {x1, yt, z1}};
    const double T2[3][3] = {{x0, yt, z0}, {x1, yt, z1}, {x0, yt, z1}};
    const size_t first = cs->nfacets;
    if (tlsph_crack_surface_add(cs, T1) != TLSPH_CRACK_OK ||
        tlsph_crack_surface_add(cs, T2) != TLSPH_CRACK_OK)
        return -1;
    size_t parent[8], k = 0;
    for (size_t i = m->body_begin[0]; i < m->body_end[0] && k < 8; i++)
        if (fabs(m->p.X[3 * i] - x1) < 1e-9 && fabs(m->p.X[3 * i + 1] - yt) < 1e-9)
            parent[k++] = i;
    struct tlsph_split sp = {parent, k, {1, 0, 0}, {c, s, 0}, {-DELTA * s, DELTA * c, 0}};
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    const int rc = tlsph_split_particles(m, &sp, cs, first, NULL, NULL, &err);
    if (rc != 0)
        fprintf(stderr, "split refused: %s\n", err.count ? err.items[0].message : "?");
    tlsph_errors_free(&err);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: %s CFL SPLIT(0|1) CASE(0|1) STEPS\n", argv[0]);
        return 2;
    }
    const double cfl = atof(argv[1]);
    const int split = atoi(argv[2]), which = atoi(argv[3]), steps = atoi(argv[4]);
    char text[2048];
    snprintf(text, sizeof text, scene_format, cfl);
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tlsph_scene scene;
    struct tlsph_model *m = NULL;
    if (tlsph_scene_parse(text, strlen(text), &scene, &err) != 0 ||
        tlsph_model_create(&scene, &m, &err) != 0) {
        fprintf(stderr, "%s\n", err.count ? err.items[0].message : "setup failed");
        return 1;
    }
    tlsph_errors_free(&err);
    for (int s = 0; s < 30; s++)
        tlsph_model_step(m);
    struct tlsph_crack_surface cs;
    if (tlsph_crack_surface_init(&cs, 2.4 * H) != TLSPH_CRACK_OK)
        return 1;
    const double yt = split_plate_lattice(m, 1, 0.004), xa = split_plate_lattice(m, 0, 0.005);
    const double r = sqrt(0.5);
    int rc = 0;
    if (which == 1) {
        const double xb = split_plate_lattice(m, 0, 0.004);
        rc = split_at(m, &cs, yt, -H, xb, 1.0, 0.0);
        for (int s = 0; rc == 0 && s < 30; s++)
            tlsph_model_step(m);
        if (rc == 0 && split)
            rc = split_at(m, &cs, yt, xb, xa, r, r);
    } else if (split) {
        rc = split_at(m, &cs, yt, -H, xa, r, r);
    }
    if (rc != 0)
        return 1;
    const double dt0 = tlsph_next_dt(m);
    printf("{\"cfl\":%g,\"split\":%d,\"case\":%d,\"dt\":%.4g,\"scale\":%.4g,"
           "\"verlet_term\":%.4g}\n",
           cfl, split, which, dt0, m->energy.scale, split_plate_verlet_term(m, dt0));
    for (int s = 1; s <= steps; s++) {
        /* both half kicks of a step use its dt: the term of f_n at that dt */
        const double term = split_plate_verlet_term(m, tlsph_next_dt(m));
        const struct tlsph_energy a = m->energy;
        tlsph_model_step(m);
        const struct tlsph_energy *e = &m->energy;
        const double next = split_plate_verlet_term(m, m->dt);
        const double moved = tlsph_energy_balance(e) - tlsph_energy_balance(&a);
        printf("{\"step\":%d,\"balance\":%.4g,\"kinetic\":%.4g,\"internal\":%.4g,"
               "\"hourglass\":%.4g,\"viscous\":%.4g,\"verlet_term\":%.4g,\"residual\":%.3g}\n",
               s, moved, e->kinetic - a.kinetic, e->internal - a.internal,
               e->hourglass - a.hourglass, e->viscous - a.viscous, next - term,
               moved - (next - term));
    }
    tlsph_crack_surface_release(&cs);
    tlsph_model_free(m);
    return 0;
}
