/* hd_fit_haff_log: eq. (31) by gsl_multifit_nlinear (trust region). */
#include <gsl/gsl_blas.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_vector.h>
#include <math.h>

#include "hd_fit.h"

/* Data handed to the model callbacks. */
typedef struct haff_data {
  const double *t, *tau;
  size_t n;
  double c; /* (1 - alpha^2) / 2, so gamma = c / D_e */
} haff_data;

double hd_haff_tau(double t, double alpha, double D_e, double nu0) {
  double c = 0.5 * (1.0 - alpha * alpha);
  if (c == 0.0) return nu0 * t;
  double g = c / D_e;
  return log1p(g * nu0 * t) / g;
}

/* Parameters x = (ln D_e, ln nu0). */
static int haff_f(const gsl_vector *x, void *params, gsl_vector *f) {
  const haff_data *d = params;
  double De = exp(gsl_vector_get(x, 0)), nu = exp(gsl_vector_get(x, 1));
  for (size_t i = 0; i < d->n; i++) {
    double g = d->c / De;
    gsl_vector_set(f, i, log1p(g * nu * d->t[i]) / g - d->tau[i]);
  }
  return GSL_SUCCESS;
}

static int haff_df(const gsl_vector *x, void *params, gsl_matrix *J) {
  const haff_data *d = params;
  double De = exp(gsl_vector_get(x, 0)), nu = exp(gsl_vector_get(x, 1));
  for (size_t i = 0; i < d->n; i++) {
    double u = d->c * nu * d->t[i] / De;
    /* d tau / d ln D_e = D_e * (1/c) [ln(1+u) - u/(1+u)],  d tau / d ln nu0 = nu0 t / (1+u) */
    gsl_matrix_set(J, i, 0, De / d->c * (log1p(u) - u / (1.0 + u)));
    gsl_matrix_set(J, i, 1, nu * d->t[i] / (1.0 + u));
  }
  return GSL_SUCCESS;
}

/* alpha == 1: tau = nu0 t, least squares through the origin. */
static int fit_elastic(const double *t, const double *tau, size_t n, hd_haff_fit *out,
                       hd_error *err) {
  if (n < 2) return hd_error_set(err, HD_EINPUT, "haff fit: need at least 2 points, got %zu", n);
  double stt = 0, sty = 0;
  for (size_t i = 0; i < n; i++) stt += t[i] * t[i], sty += t[i] * tau[i];
  if (!(stt > 0)) return hd_error_set(err, HD_EINPUT, "haff fit: all times are zero");
  double nu = sty / stt, chi2 = 0;
  for (size_t i = 0; i < n; i++) chi2 += (tau[i] - nu * t[i]) * (tau[i] - nu * t[i]);
  out->D_e = out->D_e_err = NAN;
  out->nu0 = nu;
  out->dof = n - 1;
  out->chi2 = chi2;
  out->nu0_err = sqrt(chi2 / (double)out->dof / stt);
  out->tq = gsl_cdf_tdist_Pinv(0.995, (double)out->dof);
  out->iter = 0;
  return HD_OK;
}

int hd_fit_haff_log(const double *t, const double *tau, size_t n, double alpha, hd_haff_fit *out,
                    hd_error *err) {
  for (size_t i = 0; i < n; i++)
    if (!isfinite(t[i]) || !isfinite(tau[i]) || t[i] < 0)
      return hd_error_set(err, HD_EINPUT, "haff fit: point %zu is not finite or has t < 0", i);
  if (!(alpha >= 0 && alpha <= 1))
    return hd_error_set(err, HD_EINPUT, "haff fit: alpha = %g is not in [0, 1]", alpha);
  if (alpha == 1.0) return fit_elastic(t, tau, n, out, err);
  if (n < 3) return hd_error_set(err, HD_EINPUT, "haff fit: need at least 3 points, got %zu", n);

  /* starting guess: slope through the origin over the first tenth (>= 3 points) */
  size_t m = n / 10 < 3 ? 3 : n / 10;
  double stt = 0, sty = 0;
  for (size_t i = 0; i < m; i++) stt += t[i] * t[i], sty += t[i] * tau[i];
  double nu_guess = sty / stt;
  if (!(stt > 0) || !(nu_guess > 0)) {
    stt = sty = 0;
    for (size_t i = 0; i < n; i++) stt += t[i] * t[i], sty += t[i] * tau[i];
    nu_guess = sty / stt;
  }
  if (!(nu_guess > 0) || !isfinite(nu_guess))
    return hd_error_set(err, HD_EINPUT, "haff fit: tau does not grow with t (no collisions?)");

  haff_data d = {t, tau, n, 0.5 * (1.0 - alpha * alpha)};
  gsl_multifit_nlinear_fdf fdf = {0};
  fdf.f = haff_f;
  fdf.df = haff_df;
  fdf.fvv = NULL;
  fdf.n = n;
  fdf.p = 2;
  fdf.params = &d;
  gsl_multifit_nlinear_parameters par = gsl_multifit_nlinear_default_parameters();
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  gsl_multifit_nlinear_workspace *w =
      gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &par, n, 2);
  gsl_matrix *cov = gsl_matrix_alloc(2, 2);
  int rc = HD_OK;
  if (!w || !cov) {
    rc = hd_error_set(err, HD_ENOMEM, "haff fit: out of memory");
    goto done;
  }
  double x0[2] = {log(3.0), log(nu_guess)};
  gsl_vector_view xv = gsl_vector_view_array(x0, 2);
  int info = 0;
  int st = gsl_multifit_nlinear_init(&xv.vector, &fdf, w);
  if (st == GSL_SUCCESS)
    st = gsl_multifit_nlinear_driver(500, 1e-12, 1e-12, 0.0, NULL, NULL, &info, w);
  if (st != GSL_SUCCESS) {
    rc = hd_error_set(err, HD_EINPUT, "haff fit: no convergence (%s)", gsl_strerror(st));
    goto done;
  }
  gsl_vector *x = gsl_multifit_nlinear_position(w);
  gsl_vector *f = gsl_multifit_nlinear_residual(w);
  gsl_matrix *J = gsl_multifit_nlinear_jac(w);
  gsl_multifit_nlinear_covar(J, 0.0, cov);
  double chi2;
  gsl_blas_ddot(f, f, &chi2);
  out->dof = n - 2;
  double s = sqrt(chi2 / (double)out->dof);
  out->D_e = exp(gsl_vector_get(x, 0));
  out->nu0 = exp(gsl_vector_get(x, 1));
  /* covariance of (ln D_e, ln nu0) -> of (D_e, nu0): diag(D_e, nu0) C diag(D_e, nu0), exact
   * for the linearised model at the optimum */
  out->D_e_err = out->D_e * sqrt(gsl_matrix_get(cov, 0, 0)) * s;
  out->nu0_err = out->nu0 * sqrt(gsl_matrix_get(cov, 1, 1)) * s;
  out->chi2 = chi2;
  out->tq = gsl_cdf_tdist_Pinv(0.995, (double)out->dof);
  out->iter = gsl_multifit_nlinear_niter(w);
  if (!isfinite(out->D_e) || !isfinite(out->nu0))
    rc = hd_error_set(err, HD_EINPUT, "haff fit: diverged (D_e or nu0 not finite)");
  /* tau(t) without the curvature of cooling (e.g. collisions piling up at one instant) drives
   * gamma -> 0: D_e runs off to 1e60 (and its error to 0 or inf).  No body has D_e > HD_HAFF_DE_MAX
   * quadratic degrees of freedom here, so such a fit is reported as failed, not returned. */
  else if (!(out->D_e < HD_HAFF_DE_MAX) || !isfinite(out->D_e_err))
    rc = hd_error_set(err, HD_EINPUT,
                      "haff fit: diverged (D_e = %.3g +- %.3g: no cooling curvature in tau(t))",
                      out->D_e, out->D_e_err);
done:
  gsl_matrix_free(cov);
  if (w) gsl_multifit_nlinear_free(w);
  gsl_set_error_handler(old);
  return rc;
}
