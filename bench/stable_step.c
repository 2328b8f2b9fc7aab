/* The stable step measured along a run (tests/support/stable_step.h): steps the
 * scene to each given time and prints, as one JSON object per line, the step
 * the engine uses (dt), its estimate before the CFL factor (dt_cfl) and the
 * measured leapfrog limit dt_crit = 2 / omega_max of the linearised force
 * evaluation at that state.  No output files are written.
 *
 * usage: bench/stable_step SCENE.json TIME... (s)  [ITERATIONS=60 in the environment] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "run/integrate.h"
#include "util/mat3.h"
#include "run/model.h"
#include "support/stable_step.h"

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: %s SCENE.json TIME...\n", argv[0]);
        return 2;
    }
    const char *it_env = getenv("ITERATIONS");
    const int iters = it_env ? atoi(it_env) : 60;
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tlsph_scene scene;
    struct tlsph_model *m = NULL;
    if (tlsph_scene_load_file(argv[1], &scene, &err) != 0 ||
        tlsph_model_create(&scene, &m, &err) != 0) {
        for (size_t k = 0; k < err.count; k++)
            fprintf(stderr, "error: %s: %s\n", err.items[k].pointer, err.items[k].message);
        tlsph_errors_free(&err);
        return 1;
    }
    tlsph_errors_free(&err);
    /* STRETCH="a b c": before anything, the body deformed homogeneously to
     * x = diag(a, b, c) X and evaluated (an elastic state of given stretches) */
    const char *st = getenv("STRETCH");
    double ab[3];
    if (st && sscanf(st, "%lf %lf %lf", &ab[0], &ab[1], &ab[2]) == 3) {
        for (size_t k = 0; k < 3 * m->p.n; k++)
            m->p.x[k] = ab[k % 3] * m->p.X[k];
        tlsph_evaluate(m, 0.0);
    }
    int rc = 0;
    for (int a = 2; a < argc && rc == 0; a++) {
        const double t = atof(argv[a]);
        struct tlsph_diagnostic d;
        while (m->t < t * (1.0 - 1e-12)) {
            tlsph_model_step(m);
            if (tlsph_model_check(m, &d) != 0) {
                fprintf(stderr, "unstable at step %ld: %s\n", m->step, d.message);
                rc = 1;
                break;
            }
        }
        if (rc)
            break;
        /* ELASTIC_PROBE=1: the first strength parameter (the initial yield
         * stress of linear_hardening, A of johnson_cook) raised 1e3-fold during
         * the measurement, so that no perturbation flows: the elastic tangent
         * of the deformed state (the cached flow stresses are dropped: 0 =
         * unknown, recomputed) */
        const int probe = getenv("ELASTIC_PROBE") && atoi(getenv("ELASTIC_PROBE"));
        if (probe) {
            for (size_t k = 0; k < m->scene.nmaterials; k++)
                m->scene.materials[k].strength_params[0] *= 1e3;
            if (m->p.yield_stress)
                for (size_t k = 0; k < m->p.n; k++)
                    m->p.yield_stress[k] = 0.0;
        }
        struct stable_step_measure s;
        const int measured = stable_step_measure(m, iters, &s);
        if (probe)
            for (size_t k = 0; k < m->scene.nmaterials; k++)
                m->scene.materials[k].strength_params[0] /= 1e3;
        if (measured != 0) {
            fprintf(stderr, "cannot measure this scene (contact, rigid bodies, links)\n");
            rc = 1;
            break;
        }
        /* the "elastic" estimate of the same state (the run's own dt_cfl is the
         * estimate it was given, from the step's own flow) */
        const double dt_elastic = stable_step_estimate(m, 0);
        const size_t i = s.where;
        /* the smallest principal stretch of the particle the mode sits on */
        const double *F = m->p.F + 9 * i;
        double C[9], lam[3], Q[9];
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                C[3 * r + c] = F[r] * F[c] + F[3 + r] * F[3 + c] + F[6 + r] * F[6 + c];
        sym3_eigen(C, lam, Q);
        const double stretch = sqrt(fmin(lam[0], fmin(lam[1], lam[2])));
        printf("{\"t\":%.6g,\"step\":%ld,\"dt\":%.6g,\"dt_cfl\":%.6g,\"dt_crit\":%.6g,"
               "\"xi\":%.4g,\"dt_crit_damped\":%.6g,\"dt_cfl_elastic\":%.6g,"
               "\"crit_over_cfl\":%.4f,\"crit_over_dt\":%.4f,\"spread\":%.2g,\"where\":%zu,"
               "\"stretch\":%.4f,\"eps_p\":%.4g,\"hg_scale\":%.4g,\"J\":%.4f}\n",
               m->t, m->step, m->dt, m->dt_cfl, s.dt_crit, s.xi, s.dt_crit_damped, dt_elastic,
               s.dt_crit / m->dt_cfl, s.dt_crit / m->dt, s.spread, i, stretch,
               m->p.eps_p ? m->p.eps_p[i] : 0.0, m->p.hg_scale ? m->p.hg_scale[i] : 1.0,
               mat3_det(m->p.F + 9 * i));
        fflush(stdout);
    }
    tlsph_model_free(m);
    return rc;
}
