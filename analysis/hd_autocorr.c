/* hd_tau_int: integrated autocorrelation time with Sokal's automatic window. */
#include <math.h>

#include "hd_fit.h"

double hd_tau_int(const double *r, size_t n, double c) {
  if (n < 4) return 0.5;
  double mean = 0;
  for (size_t i = 0; i < n; i++) mean += r[i];
  mean /= (double)n;
  double c0 = 0;
  for (size_t i = 0; i < n; i++) c0 += (r[i] - mean) * (r[i] - mean);
  c0 /= (double)n;
  if (!(c0 > 0)) return 0.5;
  double tau = 0.5;
  for (size_t k = 1; k < n / 2; k++) {
    double ck = 0;
    for (size_t i = 0; i + k < n; i++) ck += (r[i] - mean) * (r[i + k] - mean);
    tau += ck / (double)n / c0;
    if ((double)k >= c * tau) break;
  }
  return tau;
}
