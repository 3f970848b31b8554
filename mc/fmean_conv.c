/* fmean_conv: convergence of the heuristic Monte Carlo against its quadrature (see fmean.h). */
#include <gsl/gsl_fit.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_sf_psi.h>
#include <math.h>
#include <time.h>

#include "fmean.h"

static double conv_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int hd_fmean_convergence(double a_over_d, unsigned long seed, double max_seconds,
                         unsigned long n_max, hd_fmean_conv_row *rows, size_t max_rows,
                         size_t *n_rows, double *slope, double *slope_err, hd_error *err) {
  hd_error_clear(err);
  *n_rows = 0;
  *slope = *slope_err = NAN;
  if (!(a_over_d > 0.0) || !isfinite(a_over_d))
    return hd_error_set(err, HD_EINPUT, "a/d must be a positive number (got %g)", a_over_d);
  if (!(max_seconds > 0.0))
    return hd_error_set(err, HD_EINPUT, "the time budget must be positive (got %g)", max_seconds);
  double fq, fq_err;
  int st = hd_fmean_quadrature(a_over_d, &fq, &fq_err);
  if (st) return hd_error_set(err, st, "quadrature failed at a/d = %g", a_over_d);

  hd_fmean_opts o;
  hd_fmean_opts_default(&o);
  o.model = HD_FMEAN_HEURISTIC;
  o.a_over_d = a_over_d;
  double t0 = conv_now(), cost = 0.0; /* cost: seconds per sample, from the rows so far */
  double drawn = 0.0;
  unsigned long run_id = 0;
  for (unsigned long n = 1000; *n_rows < max_rows && (n_max == 0 || n <= n_max); n *= 10) {
    unsigned long reps = n >= 1000000UL ? 1UL : 1000000UL / n;
    double elapsed = conv_now() - t0;
    if (*n_rows > 0 && elapsed + cost * (double)n * (double)reps > max_seconds) break;
    hd_fmean_conv_row *r = &rows[*n_rows];
    double sum2 = 0.0;
    for (unsigned long k = 0; k < reps; k++) {
      hd_fmean_result res;
      o.samples = n;
      o.seed = seed + run_id++;
      st = hd_fmean_run(&o, &res, err);
      if (st) return st;
      double e = res.f_mean - fq;
      sum2 += e * e;
      if (k == 0) {
        r->f_mc = res.f_mean;
        r->f_stderr = res.f_stderr;
        r->abs_err = fabs(e);
        r->seconds = res.seconds;
      }
    }
    drawn += (double)n * (double)reps;
    cost = (conv_now() - t0) / drawn;
    r->n = n;
    r->reps = reps;
    r->rms_err = sqrt(sum2 / (double)reps);
    (*n_rows)++;
  }
  if (*n_rows < 2) return HD_OK;

  /* log rms over R replicates = log sigma + (1/2) log(chi2_R / R): subtract its mean
   * (psi(R/2) + ln(2/R))/2 and weight by the inverse of its variance psi'(R/2)/4. */
  double x[64], y[64], w[64];
  size_t m = *n_rows < 64 ? *n_rows : 64;
  for (size_t i = 0; i < m; i++) {
    double R = (double)rows[i].reps;
    x[i] = log((double)rows[i].n);
    y[i] = log(rows[i].rms_err) - 0.5 * (gsl_sf_psi(0.5 * R) + log(2.0 / R));
    w[i] = 1.0 / (0.25 * gsl_sf_psi_1(0.5 * R));
  }
  double c0, c1, cov00, cov01, cov11, chisq;
  gsl_fit_wlinear(x, 1, w, 1, y, 1, m, &c0, &c1, &cov00, &cov01, &cov11, &chisq);
  *slope = c1;
  *slope_err = sqrt(cov11);
  return HD_OK;
}
