#include "material/damage/porous_return.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "material/damage/bracket.h"
#include "material/damage/porous.h"
#include "material/eos/eos.h"
#include "material/strength/strength.h"

#define TOLERANCE 1e-12
#define SQRT_2PI 2.5066282746310002
#define MATRIX_ITERATIONS 60

/* Everything at one iterate (a, b): the stress, the internal variables the
 * step ends with, the outer residuals and their consistent Jacobian. */
struct eval {
    struct tlsph_porous_iterate head; /* |F|^2, admissible, converged (porous_step.h) */
    double se, sm, p, K_t; /* Cauchy von Mises and mean stress, EOS pressure and modulus */
    double W, T;           /* plastic work per reference volume, temperature */
    double dM, f, sM;      /* internal state at the end: matrix strain increment, f, sigma_M */
    double N, kappa, c0;   /* nucleated part, k_w omega Omega b, f_n + growth part */

    double F[2], dF[2][2]; /* residuals (F1 / scale, F2) and d F_i / d (a, b)_k */
    double G0, dG0[2];     /* F1 - lambda F2 with the f* dependence taken out, for Newton */
    double size[2];        /* size of the terms of each residual */
    double floor[2];       /* what the resolution of the unknowns moves it by */
    double r_work, r_size; /* with the matrix strain pinned: the work residual and its terms */
};

/* Void fraction nucleated while the matrix strain goes from e0 to e1: the
 * exact integral of eq. 47-48's A_N, f_N/2 [erf(z1/sqrt 2) - erf(z0/sqrt 2)]. */
static double nucleated(const double *g, double e0, double e1)
{
    if (!(g[POR_FN] > 0.0))
        return 0.0;
    const double k = 1.0 / (g[POR_SN] * sqrt(2.0));
    return 0.5 * g[POR_FN] * (erf((e1 - g[POR_EN]) * k) - erf((e0 - g[POR_EN]) * k));
}

/* A_N of eq. 48 at matrix strain e. */
static double nucleation_rate(const double *g, double e)
{
    if (!(g[POR_FN] > 0.0))
        return 0.0;
    const double z = (e - g[POR_EN]) / g[POR_SN];
    return g[POR_FN] / (g[POR_SN] * SQRT_2PI) * exp(-0.5 * z * z);
}

/* The matrix at the end of the step: the work equation
 *   r(dM) = (1 - f(dM)) sigma_M(eps_n + dM) dM - w = 0,  f(dM) = (c0 + N(dM))/(1 - kappa)
 * (w the work per current volume, > 0) by Newton kept inside the bracket
 * [lo, hi] that r(0) = -w < 0 starts, bisecting when a step leaves it.  Sets
 * e->dM, f, N, sM and the slopes the Jacobian needs; returns 0 when no
 * admissible root was found. */
struct matrix_slopes {
    double r_dM;   /* d r / d dM */
    double f_dM;   /* d f / d dM */
    double h;      /* d sigma_M / d dM (strain and rate hardening) */
    double sM_T;   /* d sigma_M / d T */
};

static int matrix_state(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                        double w, struct eval *e, struct matrix_slopes *sl)
{
    const double *g = m->damage.params;
    const double one_k = 1.0 - e->kappa;
    double lo = 0.0, hi = INFINITY, x = 0.0;
    struct tlsph_flow fl;
    /* first guess: the flow stress and the void fraction of the start */
    m->strength->flow(m, in->eps_M, 0.0, e->T, &fl);
    x = w / ((1.0 - e->c0 / one_k) * fl.stress);
    if (!(x > 0.0) || !isfinite(x))
        x = w / fmax(fl.stress, 1.0);
    for (int it = 0; it < MATRIX_ITERATIONS; it++) {
        e->N = nucleated(g, in->eps_M, in->eps_M + x);
        e->f = (e->c0 + e->N) / one_k;
        m->strength->flow(m, in->eps_M + x, in->dt > 0.0 ? x / in->dt : 0.0, e->T, &fl);
        sl->h = fl.d_strain + (in->dt > 0.0 ? fl.d_rate / in->dt : 0.0);
        sl->sM_T = fl.d_temperature;
        sl->f_dM = nucleation_rate(g, in->eps_M + x) / one_k;
        e->sM = fl.stress;
        e->dM = x;
        const double r = (1.0 - e->f) * fl.stress * x - w;
        sl->r_dM = -sl->f_dM * fl.stress * x + (1.0 - e->f) * (sl->h * x + fl.stress);
        if (fabs(r) <= 1e-14 * w && e->f < 1.0)
            return 1;
        if (r < 0.0)
            lo = x;
        else
            hi = x;
        if (hi - lo <= 4e-16 * hi)
            return e->f < 1.0 && isfinite(sl->r_dM);
        double next = x - r / sl->r_dM;
        if (!(next > lo && next < hi) || !isfinite(next))
            next = isfinite(hi) ? 0.5 * (lo + hi) : 2.0 * fmax(x, lo);
        x = next;
    }
    return 0;
}

/* The iterate (a, b): returns 0 when it has no admissible internal state. */
static int iterate(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                   double scale, double a, double b, int closing, double pinned_dM, struct eval *e)
{
    const double *g = m->damage.params;
    const double q1 = g[POR_Q1], q2 = g[POR_Q2], q3 = g[POR_Q3], J = in->J;

    /* stress (eqs. 82-83 in the engine's elastic law) */
    e->se = (in->q_trial - 3.0 * in->G * b) / J;
    const double se_b = -3.0 * in->G / J;
    m->eos->pressure(m, J * exp(-(in->lnJp + a)), in->e, &e->p, &e->K_t);
    e->sm = -e->p;
    const double sm_a = -e->K_t; /* dp/da = K_t: the plastic dilatation relieves the pressure */
    e->W = J * (e->se * b + e->sm * a);
    const double W_a = J * (e->sm + a * sm_a), W_b = J * (e->se + b * se_b);
    e->T = in->T + in->heating * e->W;

    /* shear term of eqs. 49-54: kappa = k_w omega Omega(T) b */
    double kappa_a = 0.0, kappa_b = 0.0;
    e->kappa = 0.0;
    if (g[POR_SHEAR] != POROUS_SHEAR_NONE && g[POR_KW] > 0.0 && e->se > 0.0) {
        const double kw = g[POR_KW] * in->omega;
        double slope;
        const double Om = tlsph_porous_switch(g, e->sm / e->se, &slope);
        const double T_a = sm_a / e->se, T_b = -e->sm / (e->se * e->se) * se_b;
        e->kappa = kw * Om * b;
        kappa_a = kw * b * slope * T_a;
        kappa_b = kw * (Om + b * slope * T_b);
    }
    if (!(e->kappa < 1.0))
        return 0;
    /* growth: f_n + (1 - f_n)(1 - exp(-a)); negative when the step closes
     * more than the voids it starts with (nucleation may make up for it) */
    e->c0 = in->f - (1.0 - in->f) * expm1(-a);
    const double c0_a = (1.0 - in->f) * exp(-a);

    /* internal variables and their derivatives with respect to (a, b) */
    struct matrix_slopes sl = {0};
    double dM_a = 0.0, dM_b = 0.0, f_k[2];
    const double sM_T = in->heating > 0.0 ? 1.0 : 0.0; /* switch for the heating chain */
    if (isfinite(pinned_dM)) {
        /* the matrix strain given (pinned_return): sigma_M fixed but for the
         * heating, and the work equation left as a residual */
        const double one_k = 1.0 - e->kappa;
        struct tlsph_flow fl;
        m->strength->flow(m, in->eps_M + pinned_dM, in->dt > 0.0 ? pinned_dM / in->dt : 0.0, e->T, &fl);
        e->dM = pinned_dM;
        e->N = nucleated(g, in->eps_M, in->eps_M + pinned_dM);
        e->f = (e->c0 + e->N) / one_k;
        e->sM = fl.stress;
        sl.sM_T = fl.d_temperature;
        f_k[0] = (c0_a + e->f * kappa_a) / one_k;
        f_k[1] = e->f * kappa_b / one_k;
        e->r_work = ((1.0 - e->f) * e->sM * pinned_dM - e->W / J) / scale;
        e->r_size = ((1.0 - e->f) * e->sM * pinned_dM + fabs(e->W) / J) / scale;
    } else if (e->W > 0.0) {
        if (!matrix_state(m, in, e->W / J, e, &sl))
            return 0;
        const double one_k = 1.0 - e->kappa;
        const double fa = (c0_a + e->f * kappa_a) / one_k, fb = e->f * kappa_b / one_k;
        const double heat = sM_T * sl.sM_T * in->heating * e->dM * (1.0 - e->f);
        const double r_a = -fa * e->sM * e->dM + heat * W_a - W_a / J;
        const double r_b = -fb * e->sM * e->dM + heat * W_b - W_b / J;
        dM_a = -r_a / sl.r_dM;
        dM_b = -r_b / sl.r_dM;
        f_k[0] = fa + sl.f_dM * dM_a; /* total d f/d(a, b) */
        f_k[1] = fb + sl.f_dM * dM_b;
    } else {
        /* no work, no matrix flow: dM = 0 (a state the return never ends in) */
        struct tlsph_flow fl;
        m->strength->flow(m, in->eps_M, 0.0, e->T, &fl);
        e->dM = 0.0;
        e->N = 0.0;
        e->sM = fl.stress;
        e->f = e->c0 / (1.0 - e->kappa);
        sl.sM_T = fl.d_temperature;
        f_k[0] = (c0_a + e->f * kappa_a) / (1.0 - e->kappa);
        f_k[1] = e->f * kappa_b / (1.0 - e->kappa);
    }
    /* f within the solver's tolerance of 0 (relative to the terms c0 + N it is
     * the difference of) is 0: the voids have closed; a closing iterate
     * (closed_at) has chosen a so that they are */
    if (closing || fabs(e->f) <= TOLERANCE * (fabs(e->c0) + e->N)) {
        e->f = 0.0;
        f_k[0] = f_k[1] = 0.0;
    }
    if (!(e->f >= 0.0 && e->f < 1.0) || !(e->sM > 0.0))
        return 0;
    const double W_k[2] = {W_a, W_b}, dM_k[2] = {dM_a, dM_b};
    double sM_k[2];
    for (int k = 0; k < 2; k++)
        sM_k[k] = sl.h * dM_k[k] + sM_T * sl.sM_T * in->heating * W_k[k];

    /* the yield function and normality (eqs. 43, 89) */
    const double sM = e->sM, x = e->se / sM, y = e->sm / sM, A = 1.5 * q2 * y;
    const double ch = cosh(A), sh = sinh(A);
    const double fs = tlsph_porous_fstar(g, e->f), fs_f = tlsph_porous_fstar_slope(g, e->f);
    const double x_k[2] = {-x * sM_k[0] / sM, se_b / sM - x * sM_k[1] / sM};
    const double y_k[2] = {sm_a / sM - y * sM_k[0] / sM, -y * sM_k[1] / sM};
    const double c = 3.0 * q1 * q2;
    e->F[1] = x * x + 2.0 * q1 * fs * ch - 1.0 - q3 * fs * fs;
    e->F[0] = (2.0 * x * a - c * fs * sh * b) / scale;
    /* Each derivative is a part through the stress and sigma_M (A) plus one
     * through f* (B fs_k).  Under high pressure with f* near 0, cosh makes B of
     * both residuals huge and the two rows of the Jacobian nearly parallel
     * (measured: a determinant cancelling to 1e-12 of its terms, Newton
     * stalling, in a sheared block at 12 GPa pressure).  Newton therefore
     * works on F1 - lambda F2, lambda = B1/B2, whose derivative A1 - lambda A2
     * is formed without the f* parts: the same roots, a well-conditioned
     * system. */
    const double B1 = -c * sh * b / scale, B2 = 2.0 * q1 * ch - 2.0 * q3 * fs;
    const double lambda = fabs(B2) > 0.0 ? B1 / B2 : 0.0;
    e->G0 = e->F[0] - lambda * e->F[1];
    for (int k = 0; k < 2; k++) {
        const double fs_k = fs_f * f_k[k];
        const double A2 = 2.0 * x * x_k[k] + c * fs * sh * y_k[k];
        const double A1 = (2.0 * x_k[k] * a + (k == 0 ? 2.0 * x : -c * fs * sh) -
                           c * b * fs * ch * 1.5 * q2 * y_k[k]) /
                          scale;
        e->dF[1][k] = A2 + B2 * fs_k;
        e->dF[0][k] = A1 + B1 * fs_k;
        e->dG0[k] = A1 - lambda * A2;
    }
    /* round-off floors: the size of the terms of each residual, and what the
     * resolution of the unknowns moves it by -- b relative, a absolute: the EOS
     * sees a only through J exp(-(tr Ep + a)), resolved to a few ulps of 1 */
    e->size[1] = x * x + 2.0 * q1 * fs * ch + 1.0 + q3 * fs * fs;
    e->size[0] = (fabs(2.0 * x * a) + fabs(c * fs * sh * b)) / scale;
    for (int i = 0; i < 2; i++)
        e->floor[i] = 4.0 * DBL_EPSILON * (fabs(e->dF[i][0]) * (1.0 + fabs(a)) + fabs(e->dF[i][1] * b));
    e->head.merit = e->G0 * e->G0 + e->F[1] * e->F[1];
    return isfinite(e->head.merit);
}

static void evaluate(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                     double scale, const double *u, void *state)
{
    struct eval *e = state;
    e->head.ok = iterate(m, in, scale, u[0], u[1], 0, NAN, e);
    e->head.done = e->head.ok && fabs(e->F[0]) <= TOLERANCE * e->size[0] + e->floor[0] &&
                   fabs(e->F[1]) <= TOLERANCE * e->size[1] + e->floor[1];
}

int tlsph_porous_residual(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                          double scale, double a, double b, double F[2], double dF[2][2])
{
    struct eval e;
    if (!iterate(m, in, scale, a, b, 0, NAN, &e))
        return 0;
    for (int i = 0; i < 2; i++) {
        F[i] = e.F[i];
        for (int k = 0; k < 2; k++)
            dF[i][k] = e.dF[i][k];
    }
    return 1;
}

/* The unknowns stay where the state means something: the deviator does not
 * reverse (0 <= b <= q_tr/(3G)), and the voids do not close beyond what the
 * step can nucleate: f = f_n + growth + nucleated >= 0 needs
 * a >= ln(1 - f_n) - ln(1 + N), bounded here by the most N can be (f_N); the
 * iterate itself refuses f < 0.  Under strong pressure the voids of the step
 * start can close while new ones nucleate: the root then has
 * f_n + growth < 0 < f (measured: a sheared block of sm_gurson at 3.5 GPa
 * pressure, f_n = 2.9e-6). */
static void keep_admissible(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                            double scale, double *u)
{
    (void)scale;
    const double fN = fmax(m->damage.params[POR_FN], 0.0);
    /* no voids and none to nucleate: no plastic volume change at all (J2) */
    u[0] = in->f == 0.0 && fN == 0.0 ? 0.0 : fmax(u[0], log1p(-in->f) - log1p(fN));
    u[1] = fmin(fmax(u[1], 0.0), in->q_trial / (3.0 * in->G));
}

/* First guess: the return with sigma_M and f frozen at the start and the EOS
 * linearised (tlsph_porous_frozen_root), as (a, b). */
static void first_guess(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                        double sM, double p_tr, double K_t, double u[2])
{
    const double *g = m->damage.params;
    const double q1 = g[POR_Q1], q2 = g[POR_Q2], q3 = g[POR_Q3];
    const double fs = tlsph_porous_fstar(g, in->f);
    const double x_tr = in->q_trial / (in->J * sM), y_tr = -p_tr / sM;
    const double cG = in->J * sM / (3.0 * in->G), cK = sM / K_t;
    double x;
    const double y = tlsph_porous_frozen_root(1.0 + q3 * fs * fs, 2.0 * q1 * fs, q1, q2, fs, x_tr,
                                              y_tr, cG, cK, &x);
    /* not beyond closing the voids of the start: f >= 0 there whatever nucleates */
    u[0] = fmax((y_tr - y) * cK, log1p(-in->f));
    u[1] = fmax(x_tr - x, 0.0) * cG;
}

/* The Newton step at a state (eqs. 93-94), on (F1 - lambda F2, F2). */
static int direction(const void *state, double *d)
{
    const struct eval *e = state;
    const double det = e->dG0[0] * e->dF[1][1] - e->dG0[1] * e->dF[1][0];
    if (!(fabs(det) > 0.0) || !isfinite(det))
        return 0;
    d[0] = (-e->G0 * e->dF[1][1] + e->F[1] * e->dG0[1]) / det;
    d[1] = (-e->F[1] * e->dG0[0] + e->G0 * e->dF[1][0]) / det;
    return isfinite(d[0]) && isfinite(d[1]);
}

static double trial_phi(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                        double yield, double *p, double *K_t)
{
    const double *g = m->damage.params;
    m->eos->pressure(m, in->J * exp(-in->lnJp), in->e, p, K_t);
    const double fs = tlsph_porous_fstar(g, in->f);
    const double x = in->q_trial / (in->J * yield);
    return x * x + 2.0 * g[POR_Q1] * fs * cosh(1.5 * g[POR_Q2] * (-*p / yield)) -
           (1.0 + g[POR_Q3] * fs * fs);
}

static const struct tlsph_porous_solver solver =
    TLSPH_POROUS_SOLVER(2, TLSPH_POROUS_MAX_ITERATIONS, struct eval);

/* The fallback when Newton and continuation fail: the same two equations
 * solved one after the other.  Under pressures of many sigma_M with f near
 * 0, cosh(3/2 q2 y) is huge (1e7 at 12 GPa over 1 GPa): the yield function is
 * then steep in a (through f) and its zero set a narrow curved valley in
 * (a, b), along which Newton's linear model fails within a fraction of a step
 * (measured: a sheared sm_gurson block, 12 GPa pressure, f 1e-10).  Here a is
 * kept on the valley floor, F2(a, b) = 0, by a 1-D Newton in a at each b, and
 * normality F1 - lambda F2 = F1 there is solved by Newton in b along the floor
 * (its slope dG/db - dG/da F2_b/F2_a).  Both are safeguarded by halving; at
 * most REDUCED_BUDGET evaluations.  Returns 1 when converged (e, u). */
#define REDUCED_BUDGET 400

static int project(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                   double scale, double u[2], struct eval *e, int *used)
{
    keep_admissible(m, in, scale, u);
    evaluate(m, in, scale, u, e);
    (*used)++;
    if (!e->head.ok)
        return 0;
    for (int it = 0; it < 40 && *used < REDUCED_BUDGET; it++) {
        if (fabs(e->F[1]) <= TOLERANCE * e->size[1] + e->floor[1])
            return 1;
        double da = -e->F[1] / e->dF[1][0];
        int moved = 0;
        for (int h = 0; h < 40 && *used < REDUCED_BUDGET && !moved; h++, da *= 0.5) {
            struct eval t;
            double v[2] = {u[0] + da, u[1]};
            keep_admissible(m, in, scale, v);
            evaluate(m, in, scale, v, &t);
            (*used)++;
            if (t.head.ok && fabs(t.F[1]) < fabs(e->F[1])) {
                u[0] = v[0];
                *e = t;
                moved = 1;
            }
        }
        if (!moved)
            return fabs(e->F[1]) <= TOLERANCE * e->size[1] + e->floor[1];
    }
    return fabs(e->F[1]) <= TOLERANCE * e->size[1] + e->floor[1];
}

/* Normality along the valley floor by a bracketed secant in b (Illinois
 * regula falsi, bisection when it stalls), the fallback when the Newton of
 * reduced_solve fails.  That Newton follows the slope of F1 along the floor,
 * and F1 there need not be monotone: in a crushed corner of a sheared
 * sm_gurson block (8.2 GPa, f 1.4e-8, J 0.936; test_gurson case 8) F1 along
 * the floor is -7e-10 at b = 0, falls to -4e-8 near b = 5e-6 and crosses zero
 * at b = 1.2e-5, and from b = 1.3e-6 Newton walked downhill in |F1| to the
 * end b = 0 and stopped there.  The ends of the floor (bmin below, the full
 * relaxation q_tr/(3G)) bracket a root whenever F1 differs in sign there;
 * this finds it, within REDUCED_BUDGET evaluations of its own.  Returns 1 when
 * converged (e, u). */
static int bracketed_solve(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                           double yield, double scale, double u[2], struct eval *e, int *evals)
{
    const double bmax = in->q_trial / (3.0 * in->G);
    /* The floor starts where the deviator alone is within the surface, x <= 1
     * at f = 0: sigma_M only grows with b, so b >= (q_tr - J sigma_M,n)/(3G)
     * is enough (below it F2 > 0 for every a: no floor to follow). */
    const double bmin = fmin(fmax((in->q_trial - in->J * yield) / (3.0 * in->G), 0.0), bmax);
    /* a start where f >= 0 whatever b and nucleation (the voids of the step
     * start closed, c0 = 0): the admissible edge moves with b */
    const double a0 = fmax(u[0], log1p(-in->f));
    int used = 0, ok = 0;
    double bl = bmin, bh = bmax, al, ah, gl, gh;
    struct eval t;
    double v[2] = {a0, bl};
    if (!project(m, in, scale, v, &t, &used))
        goto out;
    gl = t.G0;
    al = v[0];
    v[0] = a0;
    v[1] = bh;
    if (!project(m, in, scale, v, &t, &used))
        goto out;
    gh = t.G0;
    ah = v[0];
    if ((gl < 0.0) == (gh < 0.0))
        goto out; /* no sign change: nothing the bracket can find */
    int side = 0; /* the end the last step moved: halve the other's G0 (Illinois) */
    while (used < REDUCED_BUDGET && bh - bl > 4.0 * DBL_EPSILON * bmax) {
        double b = bl - gl * (bh - bl) / (gh - gl);
        if (!(b > bl && b < bh))
            b = 0.5 * (bl + bh);
        /* a from the chord between the ends' floor points, or, the floor
         * being steep in a, from the end with more voids */
        v[0] = al + (ah - al) * (b - bl) / (bh - bl);
        v[1] = b;
        if (!project(m, in, scale, v, &t, &used)) {
            v[0] = fmax(fmax(al, ah), a0);
            v[1] = b;
            if (!project(m, in, scale, v, &t, &used))
                break;
        }
        u[0] = v[0];
        u[1] = v[1];
        *e = t;
        if (t.head.done) {
            ok = 1;
            break;
        }
        if ((t.G0 < 0.0) == (gl < 0.0)) {
            bl = b, gl = t.G0, al = v[0];
            if (side < 0)
                gh *= 0.5;
            side = -1;
        } else {
            bh = b, gh = t.G0, ah = v[0];
            if (side > 0)
                gl *= 0.5;
            side = 1;
        }
    }
out:
    *evals += used;
    return ok;
}

static int reduced_solve(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                         double yield, double p_tr, double K_tr, double u[2], struct eval *e,
                         int *evals)
{
    const double scale = tlsph_porous_strain_scale(in, p_tr);
    int used = 0, ok = 0;
    first_guess(m, in, yield, p_tr, K_tr, u);
    u[0] = fmax(u[0], log1p(-in->f)); /* start where f >= 0 whatever nucleates */
    if (project(m, in, scale, u, e, &used)) {
        while (!e->head.done && used < REDUCED_BUDGET) {
            const double slope = e->dG0[1] - e->dG0[0] * e->dF[1][1] / e->dF[1][0];
            double db = -e->G0 / slope;
            int moved = 0;
            for (int h = 0; h < 40 && used < REDUCED_BUDGET && !moved; h++, db *= 0.5) {
                struct eval t;
                /* start a on the valley's tangent */
                double v[2] = {u[0] - e->dF[1][1] / e->dF[1][0] * db, u[1] + db};
                if (project(m, in, scale, v, &t, &used) && fabs(t.G0) < fabs(e->G0)) {
                    u[0] = v[0];
                    u[1] = v[1];
                    *e = t;
                    moved = 1;
                }
            }
            if (!moved || !isfinite(slope))
                break;
        }
        ok = e->head.done;
    }
    if (!ok)
        ok = bracketed_solve(m, in, yield, scale, u, e, &used);
    *evals += used;
    return ok;
}

/* Void closure (porous_return.h).  With every void squeezed out, f = 0 at
 * the end: a = ln(1 - f_n) - ln(1 + N) (N, the voids nucleated in the step,
 * depends on the matrix strain: fixed-point passes, a contraction by the
 * small slope of N), and the yield condition of the dense matrix,
 * x = sigma_e/sigma_M = 1, fixes b.  Returns x^2 - 1 at b (NaN if the state
 * cannot be formed), with e and (a, b) in u. */
static double closed_at(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                        double scale, double b, double u[2], struct eval *e, int *evals)
{
    double N = 0.0;
    for (int pass = 0; pass < 8; pass++) {
        u[0] = log1p(-in->f) - log1p(N);
        u[1] = b;
        ++*evals;
        if (!iterate(m, in, scale, u[0], b, 1, NAN, e))
            return NAN;
        const int settled = fabs(e->N - N) <= 1e-15 * (in->f + e->N);
        N = e->N;
        if (settled)
            break;
    }
    const double x = e->se / e->sM;
    return x * x - 1.0;
}

/* x falls monotonically in b (sigma_e falls, sigma_M does not), from x_tr at
 * b = 0 to 0 at the full relaxation q_tr/(3G): Illinois regula falsi on
 * x^2 - 1.  Returns 1 with e and (a, b) in u. */
static int closed_solve(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                        double p_tr, double u[2], struct eval *e, int *evals)
{
    const double scale = tlsph_porous_strain_scale(in, p_tr);
    double bl = 0.0, bh = in->q_trial / (3.0 * in->G);
    double gl = closed_at(m, in, scale, bl, u, e, evals);
    if (!isfinite(gl))
        return 0;
    if (gl <= 0.0)
        return 1; /* the deviator is within the dense surface: compaction alone */
    struct eval t;
    double v[2];
    double gh = closed_at(m, in, scale, bh, v, &t, evals);
    if (!(gh < 0.0))
        return 0;
    int side = 0;
    for (int it = 0; it < REDUCED_BUDGET && bh - bl > 4.0 * DBL_EPSILON * bh; it++) {
        double b = bl - gl * (bh - bl) / (gh - gl);
        if (!(b > bl && b < bh))
            b = 0.5 * (bl + bh);
        const double g = closed_at(m, in, scale, b, v, &t, evals);
        if (!isfinite(g))
            return 0;
        u[0] = v[0];
        u[1] = v[1];
        *e = t;
        if (fabs(g) <= TOLERANCE * (g + 2.0))
            return 1;
        if (g > 0.0) {
            bl = b, gl = g;
            if (side < 0)
                gh *= 0.5;
            side = -1;
        } else {
            bh = b, gh = g;
            if (side > 0)
                gl *= 0.5;
            side = 1;
        }
    }
    return bh - bl <= 4.0 * DBL_EPSILON * bh;
}

/* The closed state stands only where voids of TLSPH_VOIDS_CLOSED could not
 * hold its pressure either: beyond the cap of that surface,
 * 2 q1 f* cosh(3/2 q2 p/sigma_M) > 1 + q3 f*^2 (gtn_return.c has the
 * argument). */
static int beyond_closed_cap(const double *g, double p, double sigma_M, double f_closed)
{
    const double fs = tlsph_porous_fstar(g, f_closed);
    return p > 0.0 && 2.0 * g[POR_Q1] * fs * cosh(1.5 * g[POR_Q2] * p / sigma_M) > 1.0 + g[POR_Q3] * fs * fs;
}

enum { SOLVED, LOST, TOO_FEW, TOO_MANY };

/* The yield residual F2 at fixed a, solved for b in [0, q_tr/(3G)] by Newton
 * kept inside a bracket (F2 falls as b relaxes the deviator), and polished
 * past its tolerance until it stops falling: the bracket of grown_solve reads
 * F1 there.  TOO_MANY where the point lies inside the surface even at b = 0
 * (this dilatation relieves more than the trial state needs), TOO_FEW where
 * it lies outside even with the whole deviator gone (the tension is beyond
 * the cap of the surface at this a). */
static int yield_in_b(const struct tlsph_material *m, const struct tlsph_porous_input *in, double scale,
                      double a, double *b, struct eval *e, int *evals)
{
    double lo = 0.0, hi = in->q_trial / (3.0 * in->G);
    double u[2] = {a, lo};
    evaluate(m, in, scale, u, e);
    ++*evals;
    if (!e->head.ok)
        return LOST;
    if (!(e->F[1] > 0.0)) {
        *b = 0.0;
        return fabs(e->F[1]) <= TOLERANCE * e->size[1] + e->floor[1] ? SOLVED : TOO_MANY;
    }
    u[1] = hi;
    evaluate(m, in, scale, u, e);
    ++*evals;
    if (!e->head.ok)
        return LOST;
    if (e->F[1] > 0.0)
        return TOO_FEW;
    u[1] = fmin(fmax(*b, lo), hi);
    double best = INFINITY;
    int within = 0;
    for (int it = 0; it < 100; it++) {
        evaluate(m, in, scale, u, e);
        ++*evals;
        if (!e->head.ok)
            return LOST;
        within = fabs(e->F[1]) <= TOLERANCE * e->size[1] + e->floor[1];
        if (within) {
            if (e->F[1] == 0.0 || !(fabs(e->F[1]) < 0.5 * best))
                break;
            best = fabs(e->F[1]);
        }
        if (e->F[1] > 0.0)
            lo = u[1];
        else
            hi = u[1];
        if (hi - lo <= 4e-16 * hi)
            break;
        const double newton = u[1] - e->F[1] / e->dF[1][1];
        u[1] = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
    }
    *b = u[1];
    return within ? SOLVED : LOST;
}

/* Tension the small voids cannot relieve (gtn_return.h has the argument): the
 * spall behind an impact face (a copper bar at 150 m/s, f_n 8.3e-6,
 * p = -1.37 GPa, triaxiality 6.8) has no root near the start, and Newton
 * settles in a spurious minimum with a < 0.  Normality F1 is followed along
 * a, with yield solved for b at each a (yield_in_b): at a = 0 there is no
 * dilatation, F1 = -c f* sinh(..) b < 0 in tension; at the a that takes the
 * elastic volume back to J_e = 1 the pressure no longer pulls and F1 > 0
 * whatever b is (so that end needs no solve).  Illinois regula falsi between
 * them; an a without a yield solution says which way it is off.  Returns 1
 * when converged (u = (a, b), e). */
static int grown_solve(const struct tlsph_material *m, const struct tlsph_porous_input *in, double p_tr,
                       double u[2], struct eval *e, int *evals)
{
    const double scale = tlsph_porous_strain_scale(in, p_tr);
    double lo = 0.0, hi = log(in->J) - in->lnJp; /* J exp(-(lnJp + a)) = 1 */
    if (!(p_tr < 0.0) || !(hi > 0.0))
        return 0;
    double b = u[1], bl, bh = NAN, rl = NAN, rh = NAN;
    struct eval t;
    /* at a = 0 the tension may lie beyond the cap already (too few voids:
     * a lower end without a value) */
    const int k0 = yield_in_b(m, in, scale, lo, &b, &t, evals);
    if (k0 == SOLVED) {
        if (t.head.done) {
            u[0] = lo, u[1] = b, *e = t;
            return 1;
        }
        if (!((rl = t.F[0]) < 0.0))
            return 0;
    } else if (k0 != TOO_FEW) {
        return 0;
    }
    bl = b;
    struct tlsph_bracket br = {.lo = lo, .hi = hi, .r_lo = rl, .r_hi = rh};
    int solved = 0;
    for (int it = 0; it < 200 && !tlsph_bracket_closed(&br); it++) {
        const double x = tlsph_bracket_next(&br, 0);
        b = x - br.lo < br.hi - x || !isfinite(bh) ? bl : bh;
        const int k = yield_in_b(m, in, scale, x, &b, &t, evals);
        if (k == LOST)
            return 0;
        if (k != SOLVED) {
            tlsph_bracket_side(&br, x, k == TOO_FEW ? -1 : 1);
            continue;
        }
        u[0] = x, u[1] = b, *e = t;
        solved = 1;
        if (t.head.done)
            return 1;
        if (t.F[0] < 0.0) {
            tlsph_bracket_lower(&br, x, t.F[0]);
            bl = b;
        } else {
            tlsph_bracket_upper(&br, x, t.F[0]);
            bh = b;
        }
    }
    /* the bracket closed to the resolution of a */
    return solved && tlsph_bracket_closed(&br) && fabs(e->F[0]) <= 1e-8 * e->size[0] + e->floor[0];
}

/* The state at (a, b) with the matrix strain increment pinned at dM. */
static void evaluate_pinned(const struct tlsph_material *m, const struct tlsph_porous_input *in, double scale,
                            double dM, const double u[2], struct eval *e)
{
    e->head.ok = iterate(m, in, scale, u[0], u[1], 0, dM, e);
    e->head.done = e->head.ok && fabs(e->F[0]) <= TOLERANCE * e->size[0] + e->floor[0] &&
                   fabs(e->F[1]) <= TOLERANCE * e->size[1] + e->floor[1];
}

/* Normality and yield at a pinned dM, solved for (a, b) by Newton on
 * (G0, F2) with backtracking, polished while the merit keeps falling by a
 * quarter once converged (the bracket around it reads the work residual).
 * SOLVED; TOO_MANY where the iterate ends at b = 0 inside the surface (this dM
 * hardens the matrix past the trial state); LOST. */
static int pinned_newton(const struct tlsph_material *m, const struct tlsph_porous_input *in, double scale,
                         double dM, double u[2], struct eval *e, int *evals)
{
    keep_admissible(m, in, scale, u);
    evaluate_pinned(m, in, scale, dM, u, e);
    ++*evals;
    if (!e->head.ok)
        return LOST;
    for (int it = 0; it < TLSPH_POROUS_MAX_ITERATIONS; it++) {
        const int within = e->head.done;
        double d[2];
        int moved = 0;
        if (direction(e, d)) {
            for (double lambda = 1.0; lambda >= (within ? 1.0 : 1e-6) && !moved; lambda *= 0.5) {
                double v[2] = {u[0] + lambda * d[0], u[1] + lambda * d[1]};
                struct eval t;
                keep_admissible(m, in, scale, v);
                evaluate_pinned(m, in, scale, dM, v, &t);
                ++*evals;
                if (t.head.ok && isfinite(t.head.merit) &&
                    t.head.merit <= (within ? 0.25 : 1.0 - 1e-4 * lambda) * e->head.merit) {
                    u[0] = v[0], u[1] = v[1];
                    *e = t;
                    moved = 1;
                }
            }
        }
        if (!moved)
            return within ? SOLVED : u[1] == 0.0 && e->F[1] < 0.0 ? TOO_MANY : LOST;
    }
    return e->head.done ? SOLVED : LOST;
}

/* First yield under a flow stress with an infinite slope at eps_M = 0 and a
 * rate kink (Johnson-Cook, n < 1): a point of gtn_aravas (f0 = 0.0025) on a
 * copper bar, x_tr 0.995, Phi_tr 0.0035, whose root has a matrix strain of
 * a few rate_0 dt; the family's Newton, reduced and bracketed solves all
 * fail there.  As gtn does (nested_return in gtn_return.c), the work
 * equation is solved in dM alone by a bracket from dM = 1e-300, with
 * normality and yield solved for (a, b) at each pinned dM, where sigma_M is
 * fixed and the system smooth.  Returns 1 when converged (u, e). */
static int pinned_return(const struct tlsph_material *m, const struct tlsph_porous_input *in, double yield,
                         double p_tr, double K_tr, double u[2], struct eval *e, int *evals)
{
    const double scale = tlsph_porous_strain_scale(in, p_tr);
    first_guess(m, in, yield, p_tr, K_tr, u);
    double ul[2] = {u[0], u[1]}, uh[2] = {u[0], u[1]};
    struct eval t;
    struct tlsph_bracket br = {.lo = 1e-300, .hi = fmax(1e-12 * scale, 1e-300), .r_lo = NAN, .r_hi = NAN};
    if (pinned_newton(m, in, scale, br.lo, ul, &t, evals) != SOLVED || !((br.r_lo = t.r_work) < 0.0))
        return 0;
    for (int grow = 0;; grow++) {
        memcpy(uh, ul, sizeof uh);
        const int k = pinned_newton(m, in, scale, br.hi, uh, &t, evals);
        if (k == TOO_MANY)
            break;
        if (k == LOST || grow == 80)
            return 0;
        if (t.r_work > 0.0) {
            br.r_hi = t.r_work;
            break;
        }
        br.lo = br.hi, br.r_lo = t.r_work;
        memcpy(ul, uh, sizeof ul);
        br.hi *= 4.0;
    }
    int solved = 0;
    for (int it = 0; it < 300 && !tlsph_bracket_closed(&br); it++) {
        const double x = tlsph_bracket_next(&br, 1);
        double v[2] = {ul[0], ul[1]};
        const int k = pinned_newton(m, in, scale, x, v, &t, evals);
        if (k == LOST)
            return 0;
        if (k == TOO_MANY) {
            tlsph_bracket_side(&br, x, 1);
            continue;
        }
        u[0] = v[0], u[1] = v[1], *e = t;
        solved = 1;
        if (fabs(t.r_work) <= TOLERANCE * t.r_size)
            return 1;
        if (t.r_work < 0.0) {
            tlsph_bracket_lower(&br, x, t.r_work);
            memcpy(ul, v, sizeof ul);
        } else {
            tlsph_bracket_upper(&br, x, t.r_work);
        }
    }
    return solved && tlsph_bracket_closed(&br) && fabs(e->r_work) <= 1e-8 * e->r_size;
}

int tlsph_porous_return(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                        struct tlsph_porous_result *out)
{
    double yield, p_tr, K_tr;
    const double phi_tr = tlsph_porous_trial_phi(&solver, m, in, &yield, &p_tr, &K_tr);
    *out = (struct tlsph_porous_result){.flow = {.f = in->f, .T = in->T, .converged = 1},
                                        .sigma_M = yield, .p = p_tr, .K_t = K_tr,
                                        .phi = phi_tr, .yield = yield};
    if (!(phi_tr > 0.0))
        return 0; /* inside or on the surface: elastic */
    out->yield = 0.0;

    double u[2];
    struct eval e, scratch;
    int evals = 0;
    /* A trial state beyond the closed cap is tried closed first: where the
     * closed state stands the porous one has fewer voids than the solvers
     * resolve, and they would spend hundreds of evaluations finding that out. */
    const double *g = m->damage.params;
    int closed = beyond_closed_cap(g, p_tr, yield, TLSPH_VOIDS_CLOSED) && closed_solve(m, in, p_tr, u, &e, &evals) &&
                 beyond_closed_cap(g, e.p, e.sM, TLSPH_VOIDS_CLOSED);
    int ok = closed || tlsph_porous_solve(&solver, m, in, yield, p_tr, K_tr, u, &e, &scratch, &evals);
    if (!closed && (!ok || e.f < TLSPH_VOIDS_CLOSED)) {
        /* crushed below the closed fraction (the step compacts, or its
         * closed state is beyond the cap), or the solvers lost in the cap's
         * steep valley: the closed state where it stands, else the reduced
         * solves */
        const int shrinking = ok && u[0] < 0.0; /* the step compacts: voids are being crushed */
        double c[2];
        struct eval d;
        const int solved = closed_solve(m, in, p_tr, c, &d, &evals);
        closed = solved && (shrinking || beyond_closed_cap(g, d.p, d.sM, TLSPH_VOIDS_CLOSED));
        if (!closed && !ok) {
            ok = reduced_solve(m, in, yield, p_tr, K_tr, u, &e, &evals) || grown_solve(m, in, p_tr, u, &e, &evals) ||
                 pinned_return(m, in, yield, p_tr, K_tr, u, &e, &evals);
            if (ok)
                /* the fallbacks' solutions obey the same closure rule */
                closed = solved && e.f < TLSPH_VOIDS_CLOSED && u[0] < 0.0;
            else
                /* no solver resolves the porous step, and it would end with
                 * fewer voids than 1e-6: closed rather than a stopped run.
                 * Or the point has fewer voids than TLSPH_VOIDS_CLOSED even
                 * with all the step nucleates: no voids to resolve (measured:
                 * a crushed m_gurson point of the stiffened plate, f = 0 at
                 * eps_M 2.18 under 5.7 GPa, nucleating 1e-16 per unit strain
                 * far past eps_N; the porous solvers failed after 693
                 * evaluations and stopped the run). */
                closed = solved && (beyond_closed_cap(g, d.p, d.sM, TLSPH_VOIDS_CLOSED_UNRESOLVED) ||
                                    in->f + d.N < TLSPH_VOIDS_CLOSED);
        }
        if (closed) {
            ok = 1;
            u[0] = c[0];
            u[1] = c[1];
            e = d;
        }
    }
    out->flow.iterations = evals;
    out->flow.converged = ok;
    if (!ok) {
        /* nothing of a failed solve is kept: the state stays that of the
         * start, finite, and the run is stopped by the stability contract */
        out->phi = phi_tr;
        return 1;
    }
    out->flow.dv = u[0];
    out->flow.dq = u[1];
    out->flow.dM = e.dM;
    out->flow.f = e.f; /* exactly 0 after a closing iterate */
    out->df_growth = closed ? -in->f - e.N : e.c0 - in->f; /* closure crushes the nucleated too */
    out->df_nucleated = e.N;
    out->df_shear = e.kappa * e.f;
    out->flow.T = e.T;
    out->sigma_M = e.sM;
    out->p = e.p;
    out->K_t = e.K_t;
    out->flow.work = e.W;
    out->phi = e.F[1]; /* x^2 - 1 after a closing iterate (f* = 0) */
    return 1;
}
