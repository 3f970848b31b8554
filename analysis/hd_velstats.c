/* Sonine a2 and kurtosis with delta-method errors. */
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>

#include "hd_velstats.h"

/* ratio R = <y^2>/<y>^2 of the non-negative values y (squared magnitudes) and its delta-method
 * standard error: var R = [var(y^2)/m1^4 - 4 m2 cov(y^2, y)/m1^5 + 4 m2^2 var(y)/m1^6] / n. */
static void moment_ratio(const double *y, size_t n, double *R, double *Rerr) {
  double m1 = 0, m2 = 0, m3 = 0, m4 = 0;
  for (size_t i = 0; i < n; i++) {
    double v = y[i], v2 = v * v;
    m1 += v, m2 += v2, m3 += v2 * v, m4 += v2 * v2;
  }
  double dn = (double)n;
  m1 /= dn, m2 /= dn, m3 /= dn, m4 /= dn;
  double var_u = m4 - m2 * m2, cov_uw = m3 - m2 * m1, var_w = m2 - m1 * m1;
  double v =
      (var_u / pow(m1, 4) - 4 * m2 * cov_uw / pow(m1, 5) + 4 * m2 * m2 * var_w / pow(m1, 6)) / dn;
  *R = m2 / (m1 * m1);
  *Rerr = sqrt(fmax(v, 0.0));
}

int hd_velstats_1d(const double *x, size_t n, int centre, hd_velstats *out, hd_error *err) {
  if (n < 2) return hd_error_set(err, HD_EINPUT, "velocity statistics: need >= 2 values");
  double *y = malloc(n * sizeof *y), *z = malloc(n * sizeof *z);
  if (!y || !z) {
    free(y), free(z);
    return hd_error_set(err, HD_ENOMEM, "velocity statistics: out of memory");
  }
  double mean = centre ? gsl_stats_mean(x, 1, n) : 0.0, s2 = 0;
  for (size_t i = 0; i < n; i++) {
    double c = x[i] - mean;
    y[i] = c * c;
    s2 += y[i];
  }
  s2 /= (double)n;
  if (!(s2 > 0)) {
    free(y), free(z);
    return hd_error_set(err, HD_EINPUT, "velocity statistics: zero variance");
  }
  out->n = n, out->dim = 1, out->mean = mean, out->mean_x = mean, out->mean_y = NAN;
  out->scale = sqrt(s2);
  moment_ratio(y, n, &out->ratio, &out->ratio_err);
  out->kurt = out->ratio - 3.0;
  out->a2 = out->ratio / 3.0 - 1.0;
  out->a2_err = out->ratio_err / 3.0;
  for (size_t i = 0; i < n; i++) z[i] = (x[i] - mean) / out->scale;
  out->ks_d = hd_ks_gauss(z, n);
  out->ks_p = hd_ks_pvalue(out->ks_d, n);
  free(y), free(z);
  return HD_OK;
}

int hd_velstats_2d(const double *vx, const double *vy, size_t n, hd_velstats *out, hd_error *err) {
  if (n < 2) return hd_error_set(err, HD_EINPUT, "velocity statistics: need >= 2 vectors");
  double *y = malloc(n * sizeof *y);
  if (!y) return hd_error_set(err, HD_ENOMEM, "velocity statistics: out of memory");
  double mx = gsl_stats_mean(vx, 1, n), my = gsl_stats_mean(vy, 1, n), s2 = 0;
  for (size_t i = 0; i < n; i++) {
    y[i] = (vx[i] - mx) * (vx[i] - mx) + (vy[i] - my) * (vy[i] - my);
    s2 += y[i];
  }
  s2 /= (double)n;
  if (!(s2 > 0)) {
    free(y);
    return hd_error_set(err, HD_EINPUT, "velocity statistics: zero variance");
  }
  out->n = n, out->dim = 2, out->mean = 0, out->mean_x = mx, out->mean_y = my;
  out->scale = sqrt(s2 / 2.0);
  moment_ratio(y, n, &out->ratio, &out->ratio_err);
  out->kurt = out->ratio - 2.0;
  out->a2 = out->ratio / 2.0 - 1.0;
  out->a2_err = out->ratio_err / 2.0;
  out->ks_d = out->ks_p = NAN;
  free(y);
  return HD_OK;
}
