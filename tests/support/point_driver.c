#include "support/point_driver.h"

#include <check.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

struct tlsph_material material(const char *json)
{
    char text[4096];
    snprintf(text, sizeof text,
             "{\"dimension\":3,\"time\":{\"end\":1e-6},\"materials\":{\"m\":%s},"
             "\"bodies\":[{\"name\":\"b\",\"material\":\"m\",\"spacing\":0.001,"
             "\"geometry\":{\"box\":{\"min\":[0,0,0],\"max\":[0.002,0.002,0.002]}}}]}",
             json);
    struct tlsph_errors err;
    tlsph_errors_init(&err);
    struct tlsph_scene s;
    const int rc = tlsph_scene_parse(text, strlen(text), &s, &err);
    for (size_t k = 0; k < err.count; k++)
        fprintf(stderr, "scene error: %s: %s\n", err.items[k].pointer, err.items[k].message);
    tlsph_errors_free(&err);
    ck_assert_msg(rc == 0, "test material rejected");
    struct tlsph_material m = s.materials[0]; /* no owned memory: vtables are static */
    tlsph_scene_free(&s);
    return m;
}

double von_mises(const double *s)
{
    const double a = s[0] - s[3], b = s[3] - s[5], c = s[5] - s[0];
    return sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (s[1] * s[1] + s[2] * s[2] + s[4] * s[4]));
}

void diag_F(double ea, double et, double *F)
{
    memset(F, 0, 9 * sizeof *F);
    F[0] = exp(ea);
    F[4] = F[8] = exp(et);
}

void uniaxial_step(const struct tlsph_material *m, double ea, double *et, double dt,
                   struct tlsph_point_state *s, struct tlsph_point_result *r)
{
    double F[9];
    struct tlsph_point_state trial;
    for (int it = 0; it < 50; it++) {
        trial = *s;
        diag_F(ea, *et, F);
        tlsph_point_update(m, F, 0.0, dt, &trial, r);
        const double f = r->sigma[3];
        if (fabs(f) <= 1e-7 * fabs(r->sigma[0]) + 1e-3)
            break;
        const double h = 1e-8;
        struct tlsph_point_state t2 = *s;
        struct tlsph_point_result r2;
        diag_F(ea, *et + h, F);
        tlsph_point_update(m, F, 0.0, dt, &t2, &r2);
        *et -= f * h / (r2.sigma[3] - f);
    }
    ck_assert_msg(fabs(r->sigma[3]) <= 1e-6 * fabs(r->sigma[0]) + 1e-2,
                  "lateral stress not relaxed: %g vs %g", r->sigma[3], r->sigma[0]);
    ck_assert(r->converged);
    *s = trial;
}

double plastic_increment(const struct tlsph_point_state *old, const struct tlsph_point_state *now,
                         double *dv)
{
    double d[6];
    for (int c = 0; c < 6; c++)
        d[c] = now->plastic_strain[c] - old->plastic_strain[c];
    *dv = d[0] + d[3] + d[5];
    const double dd[3] = {d[0] - *dv / 3.0, d[3] - *dv / 3.0, d[5] - *dv / 3.0};
    /* off-diagonal components count twice in |dev dEp|^2 */
    const double off = d[1] * d[1] + d[2] * d[2] + d[4] * d[4];
    return sqrt(2.0 / 3.0 * (dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2] + 2.0 * off));
}
