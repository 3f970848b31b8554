/* hd_fit_linear_t: OLS line with Student-t intervals, plain and autocorrelation-corrected. */
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>
#include <math.h>
#include <stdlib.h>

#include "hd_fit.h"

int hd_fit_linear_t(const double *x, const double *y, size_t n, double level, hd_linfit *out,
                    hd_error *err) {
  if (n < 3) return hd_error_set(err, HD_EINPUT, "linear fit: need at least 3 points, got %zu", n);
  if (!(level > 0 && level < 1))
    return hd_error_set(err, HD_EINPUT, "linear fit: confidence level %g not in (0, 1)", level);
  double xmin = x[0], xmax = x[0];
  for (size_t i = 0; i < n; i++) {
    if (!isfinite(x[i]) || !isfinite(y[i]))
      return hd_error_set(err, HD_EINPUT, "linear fit: point %zu is not finite", i);
    xmin = fmin(xmin, x[i]), xmax = fmax(xmax, x[i]);
  }
  if (!(xmax > xmin)) return hd_error_set(err, HD_EINPUT, "linear fit: all x are equal");
  double c0, c1, c00, c01, c11, ss;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  int st = gsl_fit_linear(x, 1, y, 1, n, &c0, &c1, &c00, &c01, &c11, &ss);
  gsl_set_error_handler(old);
  if (st != GSL_SUCCESS) return hd_error_set(err, HD_EINPUT, "linear fit: %s", gsl_strerror(st));
  double *r = malloc(n * sizeof *r);
  if (!r) return hd_error_set(err, HD_ENOMEM, "linear fit: out of memory");
  for (size_t i = 0; i < n; i++) r[i] = y[i] - c0 - c1 * x[i];
  double tau = hd_tau_int(r, n, 5.0);
  free(r);
  double p = 0.5 * (1.0 + level);
  out->n = n;
  out->a0 = c0, out->a1 = c1;
  out->a0_err = sqrt(c00), out->a1_err = sqrt(c11);
  out->chi2 = ss;
  out->tq = gsl_cdf_tdist_Pinv(p, (double)(n - 2));
  out->a0_lo = c0 - out->tq * out->a0_err, out->a0_hi = c0 + out->tq * out->a0_err;
  out->a1_lo = c1 - out->tq * out->a1_err, out->a1_hi = c1 + out->tq * out->a1_err;
  out->tau_int = tau;
  /* anticorrelated residuals can give tau < 0.5, even < 0 (alternating signs): they are taken
   * as independent, so that n_eff never exceeds n nor turns negative, and the intervals are
   * never narrower than OLS */
  double te = fmax(0.5, tau);
  out->n_eff = (double)n / (2.0 * te);
  double infl = sqrt(2.0 * te);
  out->a0_err_ac = out->a0_err * infl, out->a1_err_ac = out->a1_err * infl;
  out->tq_ac = gsl_cdf_tdist_Pinv(p, fmax(out->n_eff - 2.0, 1.0));
  out->a0_lo_ac = c0 - out->tq_ac * out->a0_err_ac,
  out->a0_hi_ac = c0 + out->tq_ac * out->a0_err_ac;
  out->a1_lo_ac = c1 - out->tq_ac * out->a1_err_ac,
  out->a1_hi_ac = c1 + out->tq_ac * out->a1_err_ac;
  return HD_OK;
}
