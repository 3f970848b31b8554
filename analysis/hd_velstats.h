/* hd_velstats: shape statistics of a velocity sample against the Gaussian (docs/analysis.md):
 * Sonine coefficient a2 and excess kurtosis with delta-method standard errors, and the
 * Kolmogorov-Smirnov distance of a scaled 1D sample from the standard normal with its p-value. */
#ifndef HD_VELSTATS_H
#define HD_VELSTATS_H

#include <stddef.h>

#include "hd_error.h"

/* Statistics of one sample (a 1D variable or a 2D vector). */
typedef struct hd_velstats {
  size_t n;              /* sample size (vectors for 2D) */
  int dim;               /* 1 or 2 */
  double mean;           /* mean removed before the moments (1D: of x; 2D: 0, see mean_x/mean_y) */
  double mean_x, mean_y; /* 2D: mean vector removed */
  double scale; /* per-component rms after centring: sqrt(<x^2>) (1D), sqrt(<|v|^2>/2) (2D) */
  double ratio; /* <c^4>/<c^2>^2, c the centred variable (|v| for 2D); Gaussian: 3 (1D), 2 (2D) */
  double ratio_err; /* delta-method standard error of ratio */
  double kurt;      /* excess: ratio - 3 (1D) or ratio - 2 (2D); 0 for a Gaussian */
  double a2;        /* Sonine coefficient a2 = D/(D+2) ratio - 1; 0 for a Gaussian */
  double a2_err;    /* its standard error = D/(D+2) ratio_err */
  double ks_d;      /* 1D: sup |F_n(c/scale) - Phi|; 2D: NaN */
  double ks_p;      /* its p-value (hd_ks_pvalue); 2D: NaN */
} hd_velstats;

/* Statistics of the 1D sample x[0..n-1], n >= 2.  centre != 0 removes the sample mean first
 * (translational components); centre == 0 keeps it (angular velocity, eq. 35).  The KS
 * distance is taken of (x - mean)/scale against N(0,1).  HD_EINPUT if n < 2 or the variance
 * is zero; HD_ENOMEM. */
int hd_velstats_1d(const double *x, size_t n, int centre, hd_velstats *out, hd_error *err);

/* Statistics of the 2D vectors (vx[i], vy[i]), centred on their mean vector (eq. 34):
 * ratio = <|v|^4>/<|v|^2>^2, a2 = ratio/2 - 1.  No KS (ks_d = ks_p = NaN). */
int hd_velstats_2d(const double *vx, const double *vy, size_t n, hd_velstats *out, hd_error *err);

/* Kolmogorov-Smirnov distance D_n = sup_x |F_n(x) - Phi(x)| of z[0..n-1] from the standard
 * normal.  z is sorted in place. */
double hd_ks_gauss(double *z, size_t n);

/* Q_KS(lambda) = 2 sum_{k>=1} (-1)^{k-1} exp(-2 k^2 lambda^2): the asymptotic probability that
 * sqrt(n) D_n exceeds lambda (1 for lambda <= 0.2 within 1e-9 of the series). */
double hd_kolmogorov_q(double lambda);

/* p-value of a KS distance d from n points: Q_KS((sqrt(n) + 0.12 + 0.11/sqrt(n)) d)
 * (Stephens' small-n correction).  With mean and variance estimated from the same sample the
 * true p-value is smaller (Lilliefors): this one is conservative. */
double hd_ks_pvalue(double d, size_t n);

#endif
