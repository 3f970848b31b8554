/* hd_fit: the fits of the analysis programs (docs/analysis.md gives every definition).
 *  - hd_fit_haff_log: eq. (31) of the dimer paper, tau(t) = (1/gamma) ln(1 + gamma nu0 t),
 *    gamma = (1 - alpha^2) / (2 D_e), by GSL nonlinear least squares (trust region);
 *  - hd_fit_linear_t: y = a0 + a1 x by ordinary least squares with Student-t confidence
 *    intervals, plus the same intervals widened for autocorrelated residuals;
 *  - hd_tau_int: integrated autocorrelation time of a series (Sokal's automatic window).
 * These functions never print; they return an hd_status and fill err on failure. */
#ifndef HD_FIT_H
#define HD_FIT_H

#include <stddef.h>

#include "hd_error.h"

/* Result of hd_fit_haff_log. */
typedef struct hd_haff_fit {
  double D_e;     /* effective dimension D_e (NaN when alpha == 1: not identifiable) */
  double D_e_err; /* its standard error: sqrt(covar) * sqrt(chi2/dof) */
  double nu0;     /* effective initial collision frequency nu0_eff (per particle) */
  double nu0_err; /* its standard error, scaled like D_e_err */
  double chi2;    /* sum of squared residuals at the optimum */
  size_t dof;     /* n - number of parameters */
  double tq;      /* Student-t quantile t_{0.995, dof}: 99% interval = value +- tq * err */
  size_t iter;    /* iterations of the trust-region driver */
} hd_haff_fit;

/* Fits tau(t) = (1/gamma) ln(1 + gamma nu0 t), gamma = (1 - alpha^2)/(2 D_e), to n points
 * (t[i], tau[i]) with D_e and nu0 free (internally log-parametrised so both stay positive).
 * Starting guess: nu0 from the slope through the origin of the first tenth of the points,
 * D_e = 3.  alpha == 1 fits tau = nu0 t only (D_e = NaN).  Needs n >= 3 (2 for alpha == 1),
 * t >= 0 and tau increasing on average.  Returns HD_OK, or HD_EINPUT (too few points, no
 * convergence, non-finite data, or a diverged fit: D_e >= HD_HAFF_DE_MAX or a non-finite
 * D_e_err) with err set. */
#define HD_HAFF_DE_MAX 1000.0
int hd_fit_haff_log(const double *t, const double *tau, size_t n, double alpha, hd_haff_fit *out,
                    hd_error *err);

/* The model of hd_fit_haff_log: (1/gamma) ln(1 + gamma nu0 t), or nu0 t when alpha == 1. */
double hd_haff_tau(double t, double alpha, double D_e, double nu0);

/* Result of hd_fit_linear_t. All intervals are at the requested confidence level. */
typedef struct hd_linfit {
  size_t n;                          /* points used */
  double a0, a1;                     /* intercept and slope (OLS) */
  double a0_err, a1_err;             /* OLS standard errors (residual variance from chi2/(n-2)) */
  double tq;                         /* t quantile with n-2 dof at (1+level)/2 */
  double a0_lo, a0_hi, a1_lo, a1_hi; /* OLS Student-t intervals: a +- tq * err */
  double tau_int; /* integrated autocorrelation time of the residuals (0.5 = iid) */
  double n_eff;   /* n / (2 max(0.5, tau_int)), the effective number of independent points (<= n) */
  double a0_err_ac, a1_err_ac;                   /* standard errors * sqrt(max(1, 2 tau_int)) */
  double tq_ac;                                  /* t quantile with max(n_eff - 2, 1) dof */
  double a0_lo_ac, a0_hi_ac, a1_lo_ac, a1_hi_ac; /* autocorrelation-corrected intervals */
  double chi2;                                   /* residual sum of squares */
} hd_linfit;

/* Fits y = a0 + a1 x to n >= 3 points by OLS (gsl_fit_linear) and fills the Student-t
 * intervals at confidence `level` in (0, 1) (0.99 for the paper's Table II), both the plain
 * OLS ones and the ones corrected for serial correlation of the residuals (hd_tau_int).
 * Returns HD_OK or HD_EINPUT (n < 3, all x equal, level out of range). */
int hd_fit_linear_t(const double *x, const double *y, size_t n, double level, hd_linfit *out,
                    hd_error *err);

/* Integrated autocorrelation time tau = 1/2 + sum_{k=1}^{M} rho(k) of the series r[0..n-1]
 * (mean removed), with Sokal's window: the smallest M with M >= c * tau(M) (c = 5 is usual).
 * Returns 0.5 for n < 4 or a constant series. */
double hd_tau_int(const double *r, size_t n, double c);

#endif
