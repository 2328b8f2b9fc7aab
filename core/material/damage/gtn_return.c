#include "material/damage/gtn_return.h"

#include <math.h>
#include <string.h>

#include "material/eos/eos.h"
#include "material/strength/strength.h"
#include "material/damage/bracket.h"
#include "material/damage/gtn.h"

#define TOLERANCE 1e-12
#define SQRT_2PI 2.5066282746310002

/* The end-of-step state at one iterate u = (dq, f, dM), with the residuals
 * and their Jacobian.  The void fraction rather than dv is the unknown: as
 * voids close under pressure f -> 0 is the difference of two numbers near f_n
 * when computed from dv, but dv from f loses nothing. */
struct eval {
    struct tlsph_porous_iterate head; /* R . R, converged (porous_step.h) */
    double R[3], dR[3][3]; /* residuals (R2, R3 divided by the strain scale), d R_i / d u_k */
    double size[3];        /* magnitude of the terms of each residual */
    double tau_q, dv, p, K_t, sigma_M, f, T, W, phi;
};

/* Chu-Needleman nucleation rate d f / d eps_M at matrix strain e (eq. 50). */
static double nucleation_rate(const double *g, double e)
{
    if (!(g[GTN_FN] > 0.0))
        return 0.0;
    const double z = (e - g[GTN_EN]) / g[GTN_SN];
    return g[GTN_FN] / (g[GTN_SN] * SQRT_2PI) * exp(-0.5 * z * z);
}

static void evaluate(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                     double scale, const double *u, void *state)
{
    struct eval *s = state;
    const double *g = m->damage.params;
    const double q1 = g[GTN_Q1], q2 = g[GTN_Q2], G3 = 3.0 * in->G;
    const double dq = u[0], dM = u[2];
    s->f = u[1];

    /* each quantity with its gradient with respect to u = (dq, f, dM) */
    const double d_f[3] = {0.0, 1.0, 0.0};
    s->tau_q = in->q_trial - G3 * dq;
    const double d_tau_q[3] = {-G3, 0.0, 0.0};
    /* plastic volume from f: (1 - f_n) exp(-dv) = 1 + N - f (1 - k_w omega dq) =: c;
     * written with log1p, dv keeps full precision as f -> 0 (voids closing) */
    const double kwo = g[GTN_KW] * in->omega, den = 1.0 - kwo * dq;
    const double N = tlsph_gtn_nucleated(g, in->eps_M, in->eps_M + dM);
    const double c = 1.0 + N - s->f * den;
    s->dv = log1p(-in->f) - log1p(N - s->f * den);
    const double d_dv[3] = {-s->f * kwo / c, den / c, -nucleation_rate(g, in->eps_M + dM) / c};
    const double dv = s->dv;
    const double Je = in->J * exp(-(in->lnJp + dv));
    m->eos->pressure(m, Je, in->e, &s->p, &s->K_t);
    s->W = s->tau_q * dq - in->J * s->p * dv;
    double d_p[3], d_W[3];
    for (int k = 0; k < 3; k++) {
        d_p[k] = s->K_t * d_dv[k]; /* dp/dJe = -K_t/Je, dJe/ddv = -Je */
        d_W[k] = d_tau_q[k] * dq - in->J * (s->K_t * dv + s->p) * d_dv[k];
    }
    d_W[0] += s->tau_q;
    s->T = in->T + in->heating * s->W;

    struct tlsph_flow fl;
    m->strength->flow(m, in->eps_M + dM, in->dt > 0.0 ? dM / in->dt : 0.0, s->T, &fl);
    s->sigma_M = fl.stress;
    double d_sM[3];
    const double sT = in->heating > 0.0 ? fl.d_temperature * in->heating : 0.0;
    for (int k = 0; k < 3; k++)
        d_sM[k] = sT * d_W[k];
    d_sM[2] += fl.d_strain + (in->dt > 0.0 ? fl.d_rate / in->dt : 0.0);

    const double fs = tlsph_gtn_fstar(g, s->f);
    const double fs_slope =
        s->f <= g[GTN_FC] ? 1.0 : (1.0 / q1 - g[GTN_FC]) / (g[GTN_FF] - g[GTN_FC]);
    const double D = q1 * fs;

    const double JsM = in->J * s->sigma_M;
    const double x = s->tau_q / JsM, y = -s->p / s->sigma_M, a = 1.5 * q2 * y;
    const double ch = cosh(a), sh = sinh(a);
    const double normal_v = 2.0 * x * dv, normal_q = 3.0 * q1 * q2 * fs * sh * dq;
    s->phi = x * x + 2.0 * D * ch - (1.0 + D * D);
    s->R[0] = s->phi;
    s->R[1] = (normal_v - normal_q) / scale;
    s->R[2] = ((1.0 - s->f) * dM - s->W / JsM) / scale;
    /* the size of the terms each residual is the difference of: its round-off floor */
    s->size[0] = x * x + 2.0 * D * ch + 1.0 + D * D;
    /* dv is the difference of two logarithms: its floor is theirs */
    const double dv_floor = fabs(log1p(-in->f)) + fabs(log1p(N - s->f * den));
    s->size[1] = (fabs(normal_v) + fabs(normal_q) + 2.0 * x * dv_floor) / scale;
    s->size[2] = ((1.0 - s->f) * dM + (fabs(s->tau_q * dq) + in->J * fabs(s->p) * (fabs(dv) + dv_floor)) / JsM) / scale;
    for (int k = 0; k < 3; k++) {
        const double dx = d_tau_q[k] / JsM - x * d_sM[k] / s->sigma_M;
        const double dy = -d_p[k] / s->sigma_M - y * d_sM[k] / s->sigma_M;
        const double dfs = fs_slope * d_f[k], dD = q1 * dfs;
        s->dR[0][k] = 2.0 * x * dx + 2.0 * dD * (ch - D) + 3.0 * q2 * D * sh * dy;
        s->dR[1][k] = (2.0 * dv * dx + 2.0 * x * d_dv[k] -
                       3.0 * q1 * q2 *
                           (dfs * sh * dq + fs * ch * 1.5 * q2 * dy * dq + (k == 0 ? fs * sh : 0.0))) /
                      scale;
        s->dR[2][k] = (-d_f[k] * dM + (k == 2 ? 1.0 - s->f : 0.0) - d_W[k] / JsM +
                       s->W * d_sM[k] / (JsM * s->sigma_M)) /
                      scale;
    }
    s->head.merit = s->R[0] * s->R[0] + s->R[1] * s->R[1] + s->R[2] * s->R[2];
    s->head.ok = 1;
    s->head.done = fabs(s->R[0]) <= TOLERANCE * s->size[0] &&
                   fabs(s->R[1]) <= TOLERANCE * s->size[1] &&
                   fabs(s->R[2]) <= TOLERANCE * s->size[2];
}

/* Solves A d = b (3x3, Gaussian elimination with partial pivoting); 0 if singular. */
static int solve3(double A[3][3], double b[3], double d[3])
{
    for (int c = 0; c < 3; c++) {
        int piv = c;
        for (int r = c + 1; r < 3; r++)
            if (fabs(A[r][c]) > fabs(A[piv][c]))
                piv = r;
        if (!(fabs(A[piv][c]) > 0.0) || !isfinite(A[piv][c]))
            return 0;
        if (piv != c) {
            for (int k = 0; k < 3; k++) {
                const double t = A[c][k];
                A[c][k] = A[piv][k];
                A[piv][k] = t;
            }
            const double t = b[c];
            b[c] = b[piv];
            b[piv] = t;
        }
        for (int r = c + 1; r < 3; r++) {
            const double l = A[r][c] / A[c][c];
            for (int k = c; k < 3; k++)
                A[r][k] -= l * A[c][k];
            b[r] -= l * b[c];
        }
    }
    for (int r = 2; r >= 0; r--) {
        double s = b[r];
        for (int k = r + 1; k < 3; k++)
            s -= A[r][k] * d[k];
        d[r] = s / A[r][r];
    }
    return isfinite(d[0]) && isfinite(d[1]) && isfinite(d[2]);
}

/* The iterates stay where the state means something: the deviator does not
 * reverse (dq <= q_tr/(3G)), 0 <= f < 1 (f >= 0 also excludes a spurious root
 * with f < 0, where "negative voids" shrink in tension), and dM stays
 * positive (some hardening laws have an infinite slope at eps_M = 0). */
static void keep_admissible(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                            double scale, double u[3])
{
    (void)m;
    const double dq_max = in->q_trial / (3.0 * in->G);
    u[0] = fmin(fmax(u[0], 0.0), dq_max);
    u[1] = fmin(fmax(u[1], 0.0), 1.0 - 1e-9);
    u[2] = fmax(u[2], 1e-12 * scale);
}
/* First guess: the return with the matrix flow stress and the void fraction
 * frozen at their start-of-step values and the EOS linearised (bulk modulus
 * K_t).  In the plane x = q/(J sigma_M), y = sigma_m/sigma_M the elastic
 * law is x = x_tr - 3G dq/(J sigma_M), y = y_tr - K_t dv/sigma_M; on the
 * surface x(y) = sqrt(1 + D^2 - 2D cosh(3/2 q2 y)), and normality leaves one
 * equation in y,
 *   g(y) = 2 x(y) (y_tr - y) J/(3G) - (x_tr - x(y)) Phi_y(y)/K_t = 0,
 * with a sign change between y = 0 (g >= 0: Phi_y = 0) and the trial value or
 * the cap of the surface, whichever comes first (g <= 0): a bracketed root,
 * found by the Illinois variant of regula falsi (tlsph_porous_frozen_root).  This replaces the paper's
 * constant-triaxiality estimate (Algorithm 2 lines 10-17), which ignores the
 * pressure the plastic dilatation relieves and can start Newton near the
 * spurious root with f < 0. */
static void first_guess(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                        double sM, double p_tr, double K_t, double u[3])
{
    const double *g = m->damage.params;
    const double q1 = g[GTN_Q1], q2 = g[GTN_Q2];
    const double fs = tlsph_gtn_fstar(g, in->f), D = q1 * fs;
    const double JsM = in->J * sM, x_tr = in->q_trial / JsM, y_tr = -p_tr / sM;
    const double cG = JsM / (3.0 * in->G), cK = sM / K_t; /* strain per unit of x, of y */
    double x;
    const double y =
        tlsph_porous_frozen_root(1.0 + D * D, 2.0 * D, q1, q2, fs, x_tr, y_tr, cG, cK, &x);
    const double dq = fmax(x_tr - x, 0.0) * JsM / (3.0 * in->G);
    const double dv = (y_tr - y) * cK;
    const double W = (in->q_trial - 3.0 * in->G * dq) * dq - in->J * (p_tr + K_t * dv) * dv;
    u[0] = dq;
    u[2] = fmax(W, 0.0) / ((1.0 - in->f) * JsM);
    u[1] = (1.0 - (1.0 - in->f) * exp(-dv) + tlsph_gtn_nucleated(g, in->eps_M, in->eps_M + u[2])) /
           (1.0 - g[GTN_KW] * in->omega * dq);
}

/* The Newton step at a state: dR d = -R. */
static int direction(const void *state, double *d)
{
    const struct eval *e = state;
    double A[3][3], b[3];
    for (int i = 0; i < 3; i++) {
        b[i] = -e->R[i];
        for (int k = 0; k < 3; k++)
            A[i][k] = e->dR[i][k];
    }
    return solve3(A, b, d);
}

static double trial_phi(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                        double yield, double *p, double *K_t)
{
    const double *g = m->damage.params;
    m->eos->pressure(m, in->J * exp(-in->lnJp), in->e, p, K_t);
    const double D = g[GTN_Q1] * tlsph_gtn_fstar(g, in->f);
    const double x = in->q_trial / (in->J * yield);
    return x * x + 2.0 * D * cosh(1.5 * g[GTN_Q2] * (-*p / yield)) - (1.0 + D * D);
}

static const struct tlsph_porous_solver solver =
    TLSPH_POROUS_SOLVER(3, TLSPH_GTN_MAX_ITERATIONS, struct eval);

/* Void closure (gtn_return.h): the same system with f pinned at 0, so that
 * dv = log(1 - f_n) - log(1 + N) squeezes out every void, on the unknowns
 * (dq, dM); the normality residual drops out (its f column is the closure). */
static void closed_evaluate(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                            double scale, const double *u, void *state)
{
    struct eval *s = state;
    const double full[3] = {u[0], 0.0, u[1]};
    evaluate(m, in, scale, full, state);
    s->head.merit = s->R[0] * s->R[0] + s->R[2] * s->R[2];
    s->head.done = fabs(s->R[0]) <= TOLERANCE * s->size[0] && fabs(s->R[2]) <= TOLERANCE * s->size[2];
}

/* The Newton step of residuals i and j of e in unknowns k and l (Cramer's
 * rule): d = -[dR_ik dR_il; dR_jk dR_jl]^-1 (R_i, R_j); 0 when singular. */
static int newton2(const struct eval *e, int i, int j, int k, int l, double d[2])
{
    const double a = e->dR[i][k], b = e->dR[i][l], c = e->dR[j][k], dd = e->dR[j][l];
    const double det = a * dd - b * c;
    if (!(fabs(det) > 0.0) || !isfinite(det))
        return 0;
    d[0] = (-e->R[i] * dd + e->R[j] * b) / det;
    d[1] = (-e->R[j] * a + e->R[i] * c) / det;
    return isfinite(d[0]) && isfinite(d[1]);
}

static int closed_direction(const void *state, double *d)
{
    return newton2(state, 0, 2, 0, 2, d);
}

static void closed_admissible(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                              double scale, double *u)
{
    double full[3] = {u[0], 0.0, u[1]};
    keep_admissible(m, in, scale, full);
    u[0] = full[0];
    u[1] = full[2];
}

/* The dense matrix's radial return at the start-of-step flow stress, with the
 * pressure after the voids are squeezed out. */
static void closed_guess(const struct tlsph_material *m, const struct tlsph_porous_input *in, double sM,
                         double p_tr, double K_t, double *u)
{
    (void)m;
    const double dv = log1p(-in->f);
    const double dq = fmax(in->q_trial - in->J * sM, 0.0) / (3.0 * in->G);
    const double W = (in->q_trial - 3.0 * in->G * dq) * dq - in->J * (p_tr + K_t * dv) * dv;
    u[0] = dq;
    u[1] = fmax(W, 0.0) / (in->J * sM);
}

/* The closed solution stands only where voids of TLSPH_VOIDS_CLOSED could
 * not hold its pressure either: beyond the cap of that surface (its point at
 * zero deviator), 2 q1 f cosh(3/2 q2 p/sigma_M) > 1 + (q1 f)^2.  The closed
 * state has squeezed out every void, so any end state with f >= that
 * fraction would carry a still higher pressure: the porous solution, if the
 * solver could resolve it, has fewer voids than that.  Below the cap (a
 * small f under shear or tension, nucleation starting from f = 0) the porous
 * solution stands. */
static int beyond_closed_cap(const double *g, double p, double sigma_M, double f_closed)
{
    const double D = g[GTN_Q1] * f_closed;
    return p > 0.0 && 2.0 * D * cosh(1.5 * g[GTN_Q2] * p / sigma_M) > 1.0 + D * D;
}

static const struct tlsph_porous_solver closed_solver = {
    .n = 2, .budget = TLSPH_GTN_MAX_ITERATIONS, .size = sizeof(struct eval), .trial_phi = trial_phi,
    .first_guess = closed_guess, .admissible = closed_admissible, .evaluate = closed_evaluate,
    .direction = closed_direction};

static int nested_return(const struct tlsph_material *m, const struct tlsph_porous_input *in, double p_tr,
                         int fixed_f, double u[3], struct eval *e, int *evals, int *off);

/* The closed return: (dq, 0, dM) in u and its state in e when it converges
 * and stands (always, or beyond the cap of the surface with f_closed); 0
 * otherwise. */
static int closed_return(const struct tlsph_material *m, const struct tlsph_porous_input *in, double yield,
                         double p_tr, double K_tr, int always, double f_closed, double u[3], struct eval *e,
                         struct eval *scratch, int *evals)
{
    double c[2];
    if (tlsph_porous_solve(&closed_solver, m, in, yield, p_tr, K_tr, c, e, scratch, evals)) {
        u[0] = c[0];
        u[1] = 0.0;
        u[2] = c[1];
    } else {
        /* a root just past Johnson-Cook's rate kink (measured: the copper
         * Taylor bar, dM = 1.41e-8 against rate_0 dt = 1.25e-8; Newton
         * stalls at |R1| 1.2 times its floor): the bracket in dM, dq from
         * yield at f = 0 */
        int off;
        closed_guess(m, in, yield, p_tr, K_tr, c);
        u[0] = c[0];
        u[1] = 0.0;
        u[2] = c[1];
        if (!nested_return(m, in, p_tr, 1, u, e, evals, &off))
            return 0;
    }
    return always || beyond_closed_cap(m->damage.params, e->p, e->sigma_M, f_closed);
}

/* Yield R1 and residual j (1: normality, 2: equal work) solved for the
 * unknowns dq and u[j] (f, dM) by Newton with backtracking on R1^2 + Rj^2
 * from u, the third unknown pinned (dM or f): with sigma_M fixed (j = 1) or
 * f fixed (j = 2) this system is smooth.  Once both residuals are at their
 * round-off floors, Newton goes on while the residuals keep falling by half:
 * the brackets around this solve read the pinned unknown's residual, and
 * (dq, f) off by R1's tolerance alone move R3 by ten to a hundred times its
 * own floor (measured at a rate kink), noise instead of a sign.  Returns 1
 * when converged. */
static int pinned_newton(const struct tlsph_material *m, const struct tlsph_porous_input *in, double scale,
                         int j, double u[3], struct eval *e, int *evals)
{
    const int pin = 3 - j;
    const double pinned = u[pin]; /* the caller's, below keep_admissible's floor too */
    keep_admissible(m, in, scale, u);
    u[pin] = pinned;
    evaluate(m, in, scale, u, e);
    ++*evals;
    for (int it = 0; it < TLSPH_GTN_MAX_ITERATIONS; it++) {
        const int within = fabs(e->R[0]) <= TOLERANCE * e->size[0] && fabs(e->R[j]) <= TOLERANCE * e->size[j];
        double step[2];
        if (!newton2(e, 0, j, 0, j, step))
            return within;
        const double merit = e->R[0] * e->R[0] + e->R[j] * e->R[j];
        int moved = 0;
        for (double lambda = 1.0; lambda >= (within ? 1.0 : 1e-6) && !moved; lambda *= 0.5) {
            double v[3] = {u[0] + lambda * step[0], u[1], u[2]};
            v[j] += lambda * step[1];
            struct eval t;
            keep_admissible(m, in, scale, v);
            v[pin] = pinned;
            evaluate(m, in, scale, v, &t);
            ++*evals;
            const double tm = t.R[0] * t.R[0] + t.R[j] * t.R[j];
            if (isfinite(tm) && tm <= (within ? 0.25 : 1.0 - 1e-4 * lambda) * merit) {
                memcpy(u, v, sizeof v);
                *e = t;
                moved = 1;
            }
        }
        if (!moved)
            return within;
    }
    return fabs(e->R[0]) <= TOLERANCE * e->size[0] && fabs(e->R[j]) <= TOLERANCE * e->size[j];
}

/* The fallback for a flow stress with a kink: Johnson-Cook has no rate effect
 * below the reference rate and 1 + C ln(rate/rate_0) above, so its slope in
 * dM jumps there (by C sigma_0/dt, 1.3e14 Pa per unit strain for copper at a
 * step of 3e-8 s), and when the step's root lies just past the kink Newton
 * on the whole system bounces across it (measured: a copper bar pulled at
 * 40 m/s, the root at rate 1.009/s against rate_0 = 1/s; 248 evaluations, no
 * convergence).  Here the equal-work residual R3 is solved in dM alone by
 * Illinois regula falsi, a bracketing method that a kink does not disturb,
 * with (dq, f) solved at each dM (pinned_newton, smooth at fixed sigma_M).
 * A dM whose flow stress leaves the trial deviator inside the surface even
 * at dq = 0 has no (dq, f): it is too large, an upper end without a value,
 * and the bracket then bisects.  Returns 1 when converged, with u and e. */
enum { TOO_LARGE = 1, SOLVED = 0, LOST = -1, TOO_SMALL = -2 };

/* The yield residual at fixed (f, dM), solved for dq in [0, q_tr/(3G)] by
 * Newton kept inside a bracket: with sigma_M fixed but for the heating (a
 * weak, smooth coupling), R1 falls as dq grows.  TOO_LARGE where the point
 * lies inside the surface even at dq = 0 (dM hardens past the trial state),
 * TOO_SMALL where it lies outside even with the whole deviator gone (the
 * pressure is beyond the cap at this flow stress: dM must grow). */
static int yield_at(const struct tlsph_material *m, const struct tlsph_porous_input *in, double scale,
                    double u[3], struct eval *e, int *evals)
{
    double lo = 0.0, hi = in->q_trial / (3.0 * in->G);
    double v[3] = {lo, u[1], u[2]};
    evaluate(m, in, scale, v, e);
    ++*evals;
    if (!(e->R[0] > 0.0)) {
        memcpy(u, v, sizeof v);
        return fabs(e->R[0]) <= TOLERANCE * e->size[0] ? SOLVED : TOO_LARGE;
    }
    v[0] = hi;
    evaluate(m, in, scale, v, e);
    ++*evals;
    if (e->R[0] > 0.0)
        return TOO_SMALL;
    v[0] = fmin(fmax(u[0], lo), hi);
    /* polished past the tolerance until R1 stops falling: the bracket above
     * reads R3 at this dq, and dq's error of R1's tolerance alone moves R3 by
     * 1e-12 of its scale (measured), a hundred times R3's own floor */
    double best = INFINITY;
    for (int it = 0; it < 100; it++) {
        evaluate(m, in, scale, v, e);
        ++*evals;
        if (fabs(e->R[0]) <= TOLERANCE * e->size[0]) {
            if (e->R[0] == 0.0 || !(fabs(e->R[0]) < 0.5 * best)) {
                memcpy(u, v, sizeof v);
                return SOLVED;
            }
            best = fabs(e->R[0]);
        }
        if (e->R[0] > 0.0)
            lo = v[0];
        else
            hi = v[0];
        if (hi - lo <= 4e-16 * hi)
            break; /* e is the state at v, the bracket's resolution */
        const double newton = v[0] - e->R[0] / e->dR[0][0];
        v[0] = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
    }
    memcpy(u, v, sizeof v);
    return fabs(e->R[0]) <= TOLERANCE * e->size[0] ? SOLVED : LOST;
}

/* Where the bracket in dM stands at u: SOLVED with the other unknowns
 * solved for (dq and f by Newton, or dq alone at the f of u when fixed_f),
 * or which way dM is off when there is no solution. */
static int side_of(const struct tlsph_material *m, const struct tlsph_porous_input *in, double scale,
                   int fixed_f, double u[3], struct eval *e, int *evals)
{
    if (fixed_f)
        return yield_at(m, in, scale, u, e, evals);
    if (pinned_newton(m, in, scale, 1, u, e, evals))
        return SOLVED;
    return u[0] == 0.0 && e->R[0] < 0.0 ? TOO_LARGE : LOST;
}

static int nested_return(const struct tlsph_material *m, const struct tlsph_porous_input *in, double p_tr,
                         int fixed_f, double u[3], struct eval *e, int *evals, int *off)
{
    const double scale = tlsph_porous_strain_scale(in, p_tr);
    /* From the first yield of a law with an infinite slope at eps_M = 0
     * (A + B eps^n, n < 1) the root can lie far below Newton's floor of 1e-12
     * of the strain scale (measured: dM = 3e-17 for copper, n = 0.31, a
     * trial 5e-5 outside the surface); the bracket starts near the smallest
     * normal double and bisects in the logarithm while its ends are decades
     * apart.  At fixed f a dM can also be TOO_SMALL (yield_at): a lower end
     * without a value.  When the bracket closes on no root, *off says
     * whether it closed on the lower edge of the solvable dM with R3 > 0
     * there (TOO_SMALL) or on the upper edge with R3 < 0 (TOO_LARGE). */
    double lo = 1e-300, hi = fmax(u[2], 1e-12 * scale), rl = NAN, rh = NAN;
    double ul[3] = {u[0], u[1], lo}, uh[3] = {u[0], u[1], hi};
    struct eval el, eh;
    int lo_kind = side_of(m, in, scale, fixed_f, ul, &el, evals), hi_kind = LOST;
    *off = LOST;
    if (lo_kind == SOLVED) {
        if (!((rl = el.R[2]) < 0.0))
            return 0;
    } else if (lo_kind == TOO_LARGE) {
        /* inside the surface without deviatoric flow at the smallest dM */
        *off = TOO_LARGE;
        return 0;
    } else if (lo_kind != TOO_SMALL) {
        return 0;
    }
    for (int grow = 0;; grow++) {
        hi_kind = side_of(m, in, scale, fixed_f, uh, &eh, evals);
        if (hi_kind == TOO_LARGE)
            break;
        if (hi_kind == LOST || grow == 60)
            return 0;
        if (hi_kind == SOLVED && (rh = eh.R[2]) > 0.0)
            break;
        /* still short: move both ends up */
        lo = hi, lo_kind = hi_kind;
        rl = hi_kind == SOLVED ? rh : NAN;
        rh = NAN;
        memcpy(ul, uh, sizeof uh);
        hi *= 2.0;
        uh[2] = hi;
    }
    struct tlsph_bracket br = {.lo = lo, .hi = hi, .r_lo = rl, .r_hi = rh};
    int solved = 0;
    for (int it = 0; it < 200 && !tlsph_bracket_closed(&br); it++) {
        const double x = tlsph_bracket_next(&br, 1);
        double v[3] = {ul[0], ul[1], x};
        struct eval t;
        const int k = side_of(m, in, scale, fixed_f, v, &t, evals);
        if (k == LOST)
            return 0;
        if (k == SOLVED) {
            memcpy(u, v, sizeof v);
            *e = t;
            solved = 1;
            if (fabs(t.R[2]) <= TOLERANCE * t.size[2])
                return 1;
        }
        if (k == TOO_SMALL || (k == SOLVED && t.R[2] < 0.0)) {
            tlsph_bracket_lower(&br, x, k == SOLVED ? t.R[2] : NAN);
            lo_kind = k;
            memcpy(ul, v, sizeof v);
        } else {
            tlsph_bracket_upper(&br, x, k == SOLVED ? t.R[2] : NAN);
            hi_kind = k;
        }
    }
    /* the bracket closed to the resolution of dM: the last solved iterate is
     * the root to round-off, or the bracket sits on an edge of the
     * solvable dM */
    if (solved && tlsph_bracket_closed(&br) && e->head.ok && fabs(e->R[2]) <= 1e-8 * e->size[2])
        return 1;
    if (lo_kind == TOO_SMALL && hi_kind == SOLVED)
        *off = TOO_SMALL;
    else if (lo_kind == SOLVED && hi_kind == TOO_LARGE)
        *off = TOO_LARGE;
    return 0;
}

/* (dq, dM) at the fixed f of u: Newton, and where a kink in the flow stress
 * defeats it, the bracket in dM with dq from yield (nested_return).  SOLVED
 * with u and e; without a solution, which way f is off: TOO_LARGE (too many
 * voids: inside the surface without deviatoric flow at the smallest matrix
 * strain), TOO_SMALL (too few: beyond the surface's cap at the smallest
 * matrix strain, and no larger one found a solution), or LOST. */
static int at_void_fraction(const struct tlsph_material *m, const struct tlsph_porous_input *in, double p_tr,
                            double scale, double u[3], struct eval *e, int *evals)
{
    double v[3];
    memcpy(v, u, sizeof v);
    if (pinned_newton(m, in, scale, 2, u, e, evals))
        return SOLVED;
    int off;
    if (nested_return(m, in, p_tr, 1, v, e, evals, &off)) {
        memcpy(u, v, sizeof v);
        return SOLVED;
    }
    return off;
}

/* Tension the small voids cannot relieve.  With x near 1 normality reads
 * 2 (f - f_n) = 3 q1 q2 f sinh(3/2 q2 y) dq, which has a small positive f only
 * while 3 q1 q2 sinh(3/2 q2 y) dq < 2 (measured: the copper Taylor bar with
 * Mie-Grueneisen behind the shock, f_n 1.05e-7, p = -1.15 GPa, y = 4.3,
 * dq = 1.5e-3: the factor is 2.07).  The step's root then lies where the
 * voids have grown enough for their dilatation to relieve the tension, far
 * from the start; Newton slides towards the spurious root with f < 0 instead.
 * Here the normality residual R2 is followed along f, with (dq, dM) solved at
 * each f (yield and equal work, at_void_fraction): at f = f_n the step has no
 * plastic dilatation (R2 = -dq Phi_y < 0 in tension), and where the grown
 * voids have taken the elastic volume back to J_e = 1 the pressure no longer
 * pulls (Phi_y <= 0, R2 = 2 x dv > 0).  Between them Illinois regula falsi
 * finds a root, in the logarithm of f while the ends are decades apart.
 * Where that relief lies beyond the voids of failure, no end state short of
 * failure exists (0 returned; the caller's last resort follows).  Returns 1
 * when converged, with u and e. */
static int grown_return(const struct tlsph_material *m, const struct tlsph_porous_input *in, double p_tr,
                        double u[3], struct eval *e, int *evals)
{
    const double *g = m->damage.params;
    const double scale = tlsph_porous_strain_scale(in, p_tr);
    const double dv_relief = log(in->J) - in->lnJp; /* J exp(-(lnJp + dv)) = 1 */
    if (!(p_tr < 0.0) || !(dv_relief > 0.0))
        return 0;
    /* f_fail: where D = q1 f* reaches the failure residual (gtn.h) */
    const double D_fail = 1.0 - TLSPH_GTN_FAILURE_RESIDUAL;
    const double f_fail = D_fail / g[GTN_Q1] <= g[GTN_FC]
                              ? D_fail / g[GTN_Q1]
                              : g[GTN_FC] + (D_fail / g[GTN_Q1] - g[GTN_FC]) * (g[GTN_FF] - g[GTN_FC]) /
                                                (1.0 / g[GTN_Q1] - g[GTN_FC]);
    double lo = in->f, hi = fmin(1.0 - (1.0 - in->f) * exp(-dv_relief), f_fail);
    if (!(hi > lo))
        return 0;
    /* At the relief end R2 > 0 whatever (dq, dM) are (Phi_y <= 0 there), so
     * it needs no solve; its value is unknown until a solved iterate
     * replaces it, and the bracket bisects meanwhile. */
    double ul[3] = {u[0], lo, u[2]}, uh[3] = {u[0], hi, u[2]};
    struct eval el;
    if (at_void_fraction(m, in, p_tr, scale, ul, &el, evals) != SOLVED)
        return 0;
    double rl = el.R[1], rh = NAN;
    if (!(rl < 0.0))
        return 0;
    struct tlsph_bracket br = {.lo = lo, .hi = hi, .r_lo = rl, .r_hi = rh};
    int solved = 0;
    for (int it = 0; it < 200 && !tlsph_bracket_closed(&br); it++) {
        const double x = tlsph_bracket_next(&br, 1);
        /* each solve starts from the nearer solved end's solution */
        double v[3];
        memcpy(v, (x - br.lo < br.hi - x && isfinite(br.r_lo)) || !isfinite(br.r_hi) ? ul : uh, sizeof v);
        v[1] = x;
        struct eval t;
        const int k = at_void_fraction(m, in, p_tr, scale, v, &t, evals);
        if (k == LOST)
            return 0;
        if (k != SOLVED) {
            /* TOO_SMALL: the tension lies beyond the surface's cap, too few
             * voids to hold it; TOO_LARGE: the work of this much dilatation
             * hardens the matrix past the trial state, too many */
            tlsph_bracket_side(&br, x, k == TOO_SMALL ? -1 : 1);
            continue;
        }
        memcpy(u, v, sizeof v);
        *e = t;
        solved = 1;
        if (fabs(t.R[1]) <= TOLERANCE * t.size[1])
            return 1;
        if (t.R[1] < 0.0) {
            tlsph_bracket_lower(&br, x, t.R[1]);
            memcpy(ul, v, sizeof v);
        } else {
            tlsph_bracket_upper(&br, x, t.R[1]);
            memcpy(uh, v, sizeof v);
        }
    }
    /* the bracket closed to the resolution of f */
    return solved && tlsph_bracket_closed(&br) && fabs(e->R[1]) <= 1e-8 * e->size[1];
}

int tlsph_gtn_return(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                     struct tlsph_gtn_result *out)
{
    double yield, p_tr, K_tr;
    const double phi_tr = tlsph_porous_trial_phi(&solver, m, in, &yield, &p_tr, &K_tr);
    *out = (struct tlsph_gtn_result){.flow = {.f = in->f, .T = in->T, .converged = 1},
                                     .sigma_M = yield, .p = p_tr, .K_t = K_tr, .phi = phi_tr,
                                     .yield = yield};
    if (!(phi_tr > 0.0))
        return 0; /* inside or on the yield surface: elastic step */
    out->yield = 0.0;

    double u[3];
    struct eval e, scratch;
    int evals = 0;
    const double *g = m->damage.params;
    const int no_nucleation = !(g[GTN_FN] > 0.0);
    int ok = 0;
    if ((in->f == 0.0 && no_nucleation) || beyond_closed_cap(g, p_tr, yield, TLSPH_VOIDS_CLOSED))
        /* closed voids stay closed without nucleation; a trial beyond the
         * closed cap is tried closed first (the porous solution there has
         * fewer voids than 1e-9) */
        ok = closed_return(m, in, yield, p_tr, K_tr, in->f == 0.0 && no_nucleation, TLSPH_VOIDS_CLOSED, u, &e,
                           &scratch, &evals);
    if (!ok) {
        ok = tlsph_porous_solve(&solver, m, in, yield, p_tr, K_tr, u, &e, &scratch, &evals);
        if (!ok || e.f < TLSPH_VOIDS_CLOSED) {
            /* crushed below the closed fraction (the step compacts, or its
             * closed state is beyond the cap), or no solution: the dense
             * matrix's return */
            const int shrinking = ok && e.dv < 0.0; /* the step compacts: voids are being crushed */
            struct eval d;
            double c[3];
            if (closed_return(m, in, yield, p_tr, K_tr, shrinking, TLSPH_VOIDS_CLOSED, c, &d, &scratch, &evals)) {
                ok = 1;
                memcpy(u, c, sizeof c);
                e = d;
            }
        }
    }
    if (!ok) {
        first_guess(m, in, yield, p_tr, K_tr, u);
        int off;
        ok = nested_return(m, in, p_tr, 0, u, &e, &evals, &off);
    }
    if (!ok) {
        first_guess(m, in, yield, p_tr, K_tr, u);
        ok = grown_return(m, in, p_tr, u, &e, &evals);
    }
    if (!ok && closed_return(m, in, yield, p_tr, K_tr, 1, TLSPH_VOIDS_CLOSED_UNRESOLVED, u, &e,
                             &scratch, &evals))
        /* no solver resolves the porous step, and it would end with fewer
         * voids than 1e-6: closed rather than a stopped run.  Or the point
         * has fewer voids than TLSPH_VOIDS_CLOSED even with all the step
         * nucleates: no voids to resolve (as in porous_return.c; measured
         * here: f = 1e-10 at eps_M 2.18 under 11 GPa, nucleating 1e-16 per
         * unit strain, the porous solver failed at f 4e-11 after 159
         * evaluations, nested_return after 30 more: a stopped run) */
        ok = beyond_closed_cap(g, e.p, e.sigma_M, TLSPH_VOIDS_CLOSED_UNRESOLVED) ||
             in->f + tlsph_gtn_nucleated(g, in->eps_M, in->eps_M + u[2]) < TLSPH_VOIDS_CLOSED;
    out->flow.iterations = evals;
    out->flow.converged = ok;
    out->flow.dq = u[0];
    out->flow.dv = e.dv;
    out->flow.dM = u[2];
    out->flow.f = e.f;
    out->flow.T = e.T;
    out->sigma_M = e.sigma_M;
    out->p = e.p;
    out->K_t = e.K_t;
    out->flow.work = e.W;
    out->phi = e.phi;
    return 1;
}
