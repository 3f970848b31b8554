/* Kolmogorov-Smirnov distance from the standard normal and the Kolmogorov distribution. */
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_sort.h>
#include <math.h>

#include "hd_velstats.h"

double hd_ks_gauss(double *z, size_t n) {
  if (n == 0) return NAN;
  gsl_sort(z, 1, n);
  double d = 0, dn = (double)n;
  for (size_t i = 0; i < n; i++) {
    double F = gsl_cdf_ugaussian_P(z[i]);
    d = fmax(d, fmax((double)(i + 1) / dn - F, F - (double)i / dn));
  }
  return d;
}

double hd_kolmogorov_q(double lambda) {
  if (lambda <= 0.2) return 1.0; /* the series sums to 1 - O(1e-10) there and converges slowly */
  double sum = 0, sign = 1;
  for (int k = 1; k <= 200; k++) {
    double term = sign * exp(-2.0 * k * k * lambda * lambda);
    sum += term;
    if (fabs(term) < 1e-16 * fabs(sum)) break;
    sign = -sign;
  }
  sum *= 2.0;
  return fmin(1.0, fmax(0.0, sum));
}

double hd_ks_pvalue(double d, size_t n) {
  double sn = sqrt((double)n);
  return hd_kolmogorov_q((sn + 0.12 + 0.11 / sn) * d);
}
