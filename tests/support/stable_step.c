#include "support/stable_step.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run/integrate.h"

/* Every particle array a force evaluation writes, with its width per particle. */
struct saved_array {
    double *live;
    double *copy;
    size_t width;
};

#define MAX_SAVED 32

struct saved_state {
    struct tlsph_model scalars; /* shallow: the pointers are the live ones */
    struct saved_array a[MAX_SAVED];
    int count;
};

static int save_array(struct saved_state *s, double *live, size_t width, size_t n)
{
    if (!live)
        return 0;
    double *copy = malloc(width * n * sizeof *copy);
    if (!copy)
        return -1;
    memcpy(copy, live, width * n * sizeof *copy);
    s->a[s->count++] = (struct saved_array){live, copy, width};
    return 0;
}

static void free_saved(struct saved_state *s)
{
    for (int k = 0; k < s->count; k++)
        free(s->a[k].copy);
    s->count = 0;
}

static int save(struct tlsph_model *m, struct saved_state *s)
{
    struct tlsph_particles *p = &m->p;
    const size_t n = p->n;
    s->scalars = *m;
    s->count = 0;
    const struct {
        double *live;
        size_t width;
    } arrays[] = {
        {p->x, 3},
        {p->v, 3},
        {p->f, 3},
        {p->F, 9},
        {p->Fdot, 9},
        {p->P_tilde, 9},
        {p->sigma, 6},
        {p->e, 1},
        {p->f_hourglass, 3},
        {p->f_viscous, 3},
        {p->eps_p, 1},
        {p->plastic_strain, 6},
        {p->eps_p_rate, 1},
        {p->yield_stress, 1},
        {p->hg_scale, 1},
        {p->T, 1},
        {p->damage, 1},
        {p->damage_init, 1},
        {p->void_fraction, 1},
        {p->void_fstar, 1},
        {p->void_nucleated, 1},
        {p->void_shear, 1},
        {p->crack_gradient, 9},
    };
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        if (save_array(s, arrays[k].live, arrays[k].width, n) != 0) {
            free_saved(s);
            return -1;
        }
    return 0;
}

static void restore(struct tlsph_model *m, const struct saved_state *s)
{
    for (int k = 0; k < s->count; k++)
        memcpy(s->a[k].live, s->a[k].copy, s->a[k].width * m->p.n * sizeof(double));
    *m = s->scalars;
}

/* out = -(f(y + eps u) - f(y - eps u)) / (2 eps) / m, per component, y the
 * positions (live = p.x, y0 their saved copy) or the velocities (p.v) */
static void apply(struct tlsph_model *m, const struct saved_state *s, double *live,
                  const double *y0, const double *u, double eps, double dt, double *fplus,
                  double *out)
{
    const size_t n3 = 3 * m->p.n;
    for (size_t k = 0; k < n3; k++)
        live[k] = y0[k] + eps * u[k];
    tlsph_evaluate(m, dt);
    memcpy(fplus, m->p.f, n3 * sizeof *fplus);
    restore(m, s);
    for (size_t k = 0; k < n3; k++)
        live[k] = y0[k] - eps * u[k];
    tlsph_evaluate(m, dt);
    for (size_t k = 0; k < n3; k++)
        out[k] = -(fplus[k] - m->p.f[k]) / (2.0 * eps) / m->p.mass[k / 3];
    restore(m, s);
}

double stable_step_estimate(struct tlsph_model *m, int estimate)
{
    struct saved_state s;
    if (save(m, &s) != 0)
        return NAN;
    m->scene.step_estimate = estimate;
    tlsph_evaluate(m, m->dt);
    const double dt_cfl = m->dt_cfl;
    restore(m, &s);
    free_saved(&s);
    return dt_cfl;
}

/* Power iteration on y -> apply(y): the largest eigenvalue (Rayleigh quotient in
 * the mass norm) after iters products, u left as the top vector.  scale: the
 * perturbation's largest entry. */
static double power(struct tlsph_model *m, const struct saved_state *s, double *live,
                    const double *y0, double scale, double dt, int iters, double *u, double *w,
                    double *fplus, double *spread)
{
    const size_t n = m->p.n, n3 = 3 * n;
    /* a deterministic start with every wavelength in it */
    unsigned long long state = 0x9e3779b97f4a7c15ull;
    for (size_t k = 0; k < n3; k++) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        u[k] = m->dim == 2 && k % 3 == 2 ? 0.0 : (double)(state >> 11) / 9007199254740992.0 - 0.5;
    }
    double lambda = 0.0, history[10] = {0};
    for (int it = 0; it < iters; it++) {
        double norm = 0.0, umax = 0.0;
        for (size_t k = 0; k < n3; k++) {
            norm += m->p.mass[k / 3] * u[k] * u[k];
            umax = fmax(umax, fabs(u[k]));
        }
        norm = sqrt(norm);
        if (!(norm > 0.0))
            return NAN;
        for (size_t k = 0; k < n3; k++)
            u[k] /= norm;
        apply(m, s, live, y0, u, scale * norm / umax, dt, fplus, w);
        double r = 0.0; /* u.M w with u.M u = 1 */
        for (size_t k = 0; k < n3; k++)
            r += m->p.mass[k / 3] * u[k] * w[k];
        lambda = r;
        history[it % 10] = fabs(lambda);
        memcpy(u, w, n3 * sizeof *u);
    }
    double lo = INFINITY, hi = 0.0;
    for (int k = 0; k < 10; k++) {
        lo = fmin(lo, history[k]);
        hi = fmax(hi, history[k]);
    }
    *spread = hi > 0.0 ? (hi - lo) / hi : 0.0;
    return lambda;
}

int stable_step_measure(struct tlsph_model *m, int iters, struct stable_step_measure *out)
{
    if (m->contact || m->rigid || m->links || iters < 20)
        return -1;
    const size_t n = m->p.n, n3 = 3 * n;
    struct saved_state s;
    if (save(m, &s) != 0)
        return -1;
    double *u = malloc(n3 * sizeof *u), *w = malloc(n3 * sizeof *w);
    double *fplus = malloc(n3 * sizeof *fplus);
    int rc = -1;
    if (!u || !w || !fplus)
        goto done;
    double hmin = INFINITY, vmax = 0.0;
    for (size_t i = 0; i < n; i++)
        hmin = fmin(hmin, m->p.h[i]);
    for (size_t k = 0; k < n3; k++)
        vmax = fmax(vmax, fabs(m->p.v[k]));
    const double dt = m->dt > 0.0 ? m->dt : m->scene.cfl * m->dt_cfl;
    /* the positions (saved first, then the velocities: save()'s order) */
    const double *x0 = s.a[0].copy, *v0 = s.a[1].copy;
    double spread_c = 0.0;
    /* damping: the velocity perturbation's largest entry 1e-7 of the largest speed */
    const double c_max = m->scene.viscosity ? power(m, &s, m->p.v, v0, 1e-7 * fmax(vmax, 10.0), dt,
                                                    iters, u, w, fplus, &spread_c)
                                            : 0.0;
    /* stiffness, last so that u is its top vector: displacements 1e-7 of h */
    const double lambda =
        power(m, &s, m->p.x, x0, 1e-7 * hmin, dt, iters, u, w, fplus, &out->spread);
    if (!isfinite(lambda) || !isfinite(c_max))
        goto done;
    out->spread = fmax(out->spread, spread_c);
    size_t where = 0;
    double amax = -1.0;
    for (size_t i = 0; i < n; i++) {
        const double a =
            u[3 * i] * u[3 * i] + u[3 * i + 1] * u[3 * i + 1] + u[3 * i + 2] * u[3 * i + 2];
        if (a > amax) {
            amax = a;
            where = i;
        }
    }
    out->omega_max = sqrt(fabs(lambda));
    out->dt_crit = 2.0 / out->omega_max;
    out->c_max = fabs(c_max);
    out->xi = out->c_max / (2.0 * out->omega_max);
    out->dt_crit_damped = out->dt_crit * (sqrt(1.0 + out->xi * out->xi) - out->xi);
    out->where = where;
    rc = 0;
done:
    free(u);
    free(w);
    free(fplus);
    restore(m, &s);
    free_saved(&s);
    return rc;
}
