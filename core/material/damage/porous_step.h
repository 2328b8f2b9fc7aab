/* What the two porous returns share: paper 000's GTN (gtn_return.h, three
 * unknowns) and paper 003's Gurson family (porous_return.h, Aravas's two).
 * Both start from the same trial state of the Hencky setting
 * (material_point.h), relax the deviator along its own direction and add the
 * plastic volume change to the trace of Ep; both start Newton from the return
 * with the matrix and the voids frozen, and fall back on the same
 * continuation.  The pieces here are that common part, written once.
 *
 * Units: SI. */
#ifndef TLSPH_DAMAGE_POROUS_STEP_H
#define TLSPH_DAMAGE_POROUS_STEP_H

#include "material/material_point.h"
#include "scene/scene.h"

/* The data of one porous return. */
struct tlsph_porous_input {
    double q_trial; /* von Mises value of the trial Kirchhoff deviator, Pa */
    double omega;   /* Nahshon-Hutchinson omega of the trial deviator, in [0, 1] */
    double J;       /* det F, 1 */
    double lnJp;    /* tr Ep at the start of the step: log of the plastic volume ratio, 1 */
    double e;       /* specific internal energy for the EOS, J/kg */
    double G;       /* shear modulus, Pa */
    double eps_M;   /* matrix equivalent plastic strain at the start of the step, 1 */
    double f;       /* void volume fraction at the start of the step, 1 */
    double T;       /* temperature at the start of the step, K (ignored without heating) */
    double dt;      /* time step, s (0 treats the plastic rate as 0) */
    double heating; /* chi/(rho0 C_p), K per J/m^3 of reference volume; 0 = no heating */
    double yield;   /* sigma_y(eps_M, 0, T) when known (> 0), else 0 */
};

/* The trial state of a point, in the eigenbasis of C. */
struct tlsph_porous_trial {
    double tau[9]; /* trial deviator 2G dev(H - Ep), Pa */
    double Epb[9]; /* plastic strain at the start, 1 */
    double q;      /* von Mises value of tau, Pa */
};

/* What a plastic return decided, for tlsph_porous_commit. */
struct tlsph_porous_flow {
    double dq;       /* equivalent deviatoric plastic strain increment, 1 */
    double dv;       /* plastic volume change tr dEp, 1 */
    double dM;       /* matrix plastic strain increment, 1 */
    double f, T;     /* void fraction and temperature at the end */
    double work;     /* plastic work, J/m^3 of reference volume */
    int iterations, converged;
};

/* The trial state t of the point (k, s) and the return's input in; in->omega
 * is left 0 (each model has its own). */
void tlsph_porous_trial(const struct tlsph_material *mat, const struct tlsph_point_kinematics *k,
                        double e, double dt, const struct tlsph_point_state *s,
                        struct tlsph_porous_trial *t, struct tlsph_porous_input *in);

/* Applies a plastic step: the deviator relaxes along its direction by dq, the
 * trace of Ep grows by dv, eps_M by dM; stores Ep, eps_p, rate, T (with thermal
 * coupling), f and the work and solver counts in r.  Returns the von Mises
 * value of the relaxed deviator. */
double tlsph_porous_commit(const struct tlsph_material *mat, const struct tlsph_point_kinematics *k,
                           double dt, const struct tlsph_porous_flow *fl,
                           struct tlsph_porous_trial *t, struct tlsph_point_state *s,
                           struct tlsph_point_result *r);

/* The stress a porous point carries after its return, into r: the relaxed
 * deviator t->tau (von Mises tau_q) minus J p, with the triaxiality; or, when
 * the point has failed, no stress, and the elastic energy left (at the
 * plastic volume log lnJp_end = tr Ep) booked as damage work. */
void tlsph_porous_finish(const struct tlsph_point_kinematics *k, double G, double lnJp_end,
                         double tau_q, double p, double K_t, int failed,
                         struct tlsph_porous_trial *t, struct tlsph_point_result *r);

/* The trial of `in` with its elastic strain scaled by s (deviator and log
 * elastic volume), for the continuation. */
struct tlsph_porous_input tlsph_porous_scaled_trial(const struct tlsph_porous_input *in, double s);

/* The strain scale of the normality residual: (q_tr + J |p|)/(3G). */
double tlsph_porous_strain_scale(const struct tlsph_porous_input *in, double p);

/* The return with sigma_M and f* frozen and the EOS linearised (bulk modulus
 * K_t), in the plane x = sigma_e/sigma_M, y = sigma_m/sigma_M: the surface
 * x(y) = sqrt(top - two_D cosh(3/2 q2 y)) (top = 1 + q3 f*^2, two_D = 2 q1 f*),
 * and normality leaves one equation in y,
 *   g(y) = 2 x(y) (y_tr - y) cK - (x_tr - x(y)) 3 q1 q2 f* sinh(3/2 q2 y) cG = 0
 * (cK = sigma_M/K_t, cG = J sigma_M/(3G): strain per unit of y and of x), whose
 * root is bracketed by y = 0 (g >= 0) and the trial value or the cap of the
 * surface, whichever comes first (g <= 0): Illinois regula falsi.  Returns y
 * and sets *x = x(y). */
double tlsph_porous_frozen_root(double top, double two_D, double q1, double q2, double fs,
                                double x_tr, double y_tr, double cG, double cK, double *x);

/* The void fraction below which crushed voids count as closed, and the one
 * whose cap decides where a step no solver resolves is taken closed rather
 * than stopping the run (both returns; gtn_return.h explains the closure and
 * the two choices). */
#define TLSPH_VOIDS_CLOSED 1e-9
#define TLSPH_VOIDS_CLOSED_UNRESOLVED 1e-6

/* The solver both returns share: Newton with a backtracking line search from
 * the frozen first guess, then continuation.  A return describes its system
 * by this table; its iterate state (of .size bytes) begins with a struct
 * tlsph_porous_iterate that .evaluate fills. */
struct tlsph_porous_iterate {
    double merit; /* |R|^2 of the scaled residuals */
    int ok;       /* the iterate has a state (admissible, finite) */
    int done;     /* every residual is below its round-off floor */
};

struct tlsph_porous_solver {
    int n;       /* unknowns (at most 4) */
    int budget;  /* residual evaluations per Newton solve */
    size_t size; /* bytes of an iterate state */
    /* The yield function of the trial state at matrix flow stress `yield`,
     * with the EOS pressure and tangent modulus there. */
    double (*trial_phi)(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                        double yield, double *p, double *K_t);
    /* The first guess u from the frozen return (tlsph_porous_frozen_root). */
    void (*first_guess)(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                        double yield, double p, double K_t, double *u);
    /* Clamps u into the admissible set. */
    void (*admissible)(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                       double scale, double *u);
    /* The state at u (residuals scaled by `scale`, their Jacobian, the head). */
    void (*evaluate)(const struct tlsph_material *m, const struct tlsph_porous_input *in,
                     double scale, const double *u, void *state);
    /* The Newton step d at a state; 0 when the Jacobian is singular. */
    int (*direction)(const void *state, double *d);
};

/* The trial state's yield function (.trial_phi) at the matrix flow stress
 * sigma_M(eps_M, 0, T), which is in->yield when known and is looked up
 * otherwise; *yield gets it, *p and *K_t the trial EOS pressure and modulus. */
double tlsph_porous_trial_phi(const struct tlsph_porous_solver *sv,
                              const struct tlsph_material *m,
                              const struct tlsph_porous_input *in, double *yield, double *p,
                              double *K_t);

/* Solves the plastic step of a trial state whose yield function at `yield` is
 * positive (p_tr, K_tr: the trial EOS pressure and modulus): the first guess,
 * Newton (at most .budget evaluations, |R|^2 decreasing by Armijo's rule,
 * halving the step down to 1e-6), and when that fails the continuation
 * through trial states scaled k/n (n = 4, 16, 64), each solve started from the
 * last; the last solve is the step's own system, so a converged result is the
 * exact implicit step.  u: the unknowns (.n), state: the iterate state at u
 * (scratch: a second state of .size bytes).  Adds the residual evaluations to
 * *evals; returns 1 when converged. */
/* A return's solver table from its static functions trial_phi, first_guess,
 * keep_admissible, evaluate and direction, with n unknowns, a budget of
 * evaluations and its iterate state type. */
#define TLSPH_POROUS_SOLVER(n_, budget_, state_)                                                   \
    {.n = (n_), .budget = (budget_), .size = sizeof(state_), .trial_phi = trial_phi,             \
     .first_guess = first_guess, .admissible = keep_admissible, .evaluate = evaluate,            \
     .direction = direction}

int tlsph_porous_solve(const struct tlsph_porous_solver *sv, const struct tlsph_material *m,
                       const struct tlsph_porous_input *in, double yield, double p_tr,
                       double K_tr, double *u, void *state, void *scratch, int *evals);

#endif
