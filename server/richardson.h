/* Richardson extrapolation, the Grid Convergence Index and power-law fits
 * (server/richardson.c): the arithmetic of the convergence process, with no
 * JSON or HDF5 in sight so that tests can check it against hand-worked numbers.
 *
 * References: P. J. Roache, "Verification and Validation in Computational
 * Science and Engineering" (1998), ch. 5 (GCI, Fs = 1.25 with three or more
 * grids, 3 with two); I. B. Celik et al., "Procedure for estimation and
 * reporting of uncertainty due to discretization in CFD applications",
 * J. Fluids Eng. 130 (2008) 078001 (the three-grid procedure, the
 * oscillatory-convergence test e32/e21 < 0), as ASME V&V 20-2009 adopts it;
 * F. Stern, R. V. Wilson, H. W. Coleman, E. G. Paterson, "Comprehensive
 * approach to verification and validation of CFD simulations - Part 1",
 * J. Fluids Eng. 123 (2001) 793 (the uncertainty of an oscillating ladder:
 * half the range of its values). */
#ifndef TLSPHD_RICHARDSON_H
#define TLSPHD_RICHARDSON_H

#include <stddef.h>

#define TRICH_MAX 16               /* most resolutions of one ladder */
#define TRICH_FS 1.25              /* Roache's safety factor for >= 3 resolutions */
#define TRICH_ORDER_MIN 0.5        /* an observed order outside [min, max] is not */
#define TRICH_ORDER_MAX 6.0        /* taken as asymptotic (see trich_estimate) */
#define TRICH_ASYMPTOTIC_TOL 0.15  /* |GCI ratio - 1| allowed with >= 4 resolutions */

enum trich_kind {
    TRICH_CONVERGING,     /* monotone, asymptotic: every number below is given */
    TRICH_UNCHANGED,      /* the three finest values are equal: error 0, order unknown */
    TRICH_OSCILLATORY,    /* the differences change sign: no order, no Richardson estimate;
                           * the oscillation's half range instead (oscillation) */
    TRICH_DIVERGENT,      /* the differences do not shrink with the spacing */
    TRICH_NON_ASYMPTOTIC, /* order outside [ORDER_MIN, ORDER_MAX], or (>= 4 resolutions)
                           * the GCI ratio check fails: order given, no estimate */
    TRICH_TOO_FEW         /* fewer than 3 values */
};

/* One output's estimate.  Arrays are indexed like the input (finest first);
 * NAN where there is no number (the kind says why). */
struct trich_estimate {
    enum trich_kind kind;
    size_t n;
    size_t first;            /* index of the finest value used (earlier ones are missing) */
    double ratio;            /* r = h[first + 1] / h[first] */
    double order;            /* observed order p of the finest triplet used */
    double order_coarse;     /* p of the next triplet (>= 4 resolutions) */
    double asymptotic_ratio; /* Roache's GCI_23 / (r^p GCI_12) with each triplet's own p
                              * (>= 4 resolutions; with exactly 3 it would equal f1/f2) */
    double extrapolated;     /* f_ext = f1 + (f1 - f2) / (r^p - 1) */
    double safety_factor;    /* Fs */
    double error[TRICH_MAX]; /* |f_i - f_ext|, same unit as f */
    double relative[TRICH_MAX]; /* |f_i - f_ext| / |f_ext| */
    double gci[TRICH_MAX];   /* Fs |f_i - f_ext| / |f_i| (the fine-grid GCI for i = 0) */
    /* TRICH_OSCILLATORY only (NAN otherwise): half the range of the three finest
     * values, (max - min) / 2, Stern et al.'s uncertainty of an oscillating
     * ladder (same unit as f), and that over |f| of the finest */
    double oscillation, oscillation_relative;
};

/* h[0] < h[1] < ... (finest first, constant ratio: the caller checks), f the
 * output at each; n <= TRICH_MAX.  Non-finite values count as missing: the
 * estimate starts at the finest finite value (e->first; finer runs may not
 * have finished) and uses the consecutive finite values from there; fewer
 * than three give TRICH_TOO_FEW.  Returns the kind. */
enum trich_kind trich_estimate(const double *h, const double *f, size_t n,
                               struct trich_estimate *e);
/* "converging", "unchanged", "oscillatory", ... (the JSON names). */
const char *trich_kind_name(enum trich_kind k);
/* One sentence for the user: why there is or is no number. */
const char *trich_kind_reason(enum trich_kind k);

/* Least-squares fit of y = c h^-q in log-log over the pairs with h, y > 0
 * and finite.  rms_log_residual is the RMS of ln(y) - ln(fit) (about the
 * relative scatter; 0 with two points).  Returns 0, or -1 with fewer than two
 * usable points or equal spacings. */
struct trich_power_fit {
    double q, c, rms_log_residual;
    size_t n;
};
int trich_fit_power(const double *h, const double *y, size_t n, struct trich_power_fit *fit);
double trich_power_eval(const struct trich_power_fit *fit, double h);

/* The spacing at which the GCI, modelled as Fs |f1 - f_ext| (h / h1)^p /
 * |f_ext| with h1 = h[e->first] (h as given to trich_estimate), equals target
 * (relative, > 0), from a TRICH_CONVERGING estimate.  +INFINITY when the error
 * is already 0; NAN when e has no order. */
double trich_spacing_for(const struct trich_estimate *e, const double *h, double target);

#endif
