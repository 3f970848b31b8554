/* hd_eps tables: p_beta(eps) as inverse CDFs on a logarithmic beta grid and their sampler
 * (their storage in the run database: db/hd_epsdb.c). */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "eps.h"

void hd_eps_table_free(hd_eps_table *t) {
  if (!t) return;
  free(t->q);
  free(t);
}

static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static hd_eps_table *table_alloc(int nbeta, int nu) {
  hd_eps_table *t = calloc(1, sizeof *t);
  if (!t) return NULL;
  t->nbeta = nbeta;
  t->nu = nu;
  t->q = malloc((size_t)nbeta * (size_t)nu * sizeof(double));
  if (!t->q) {
    free(t);
    return NULL;
  }
  return t;
}

static double node_beta(const hd_eps_table *t, int k) {
  return t->beta_min * pow(t->beta_max / t->beta_min, (double)k / (double)(t->nbeta - 1));
}

static int o_richardson(const hd_eps_sampler *s) {
  hd_eps_opts o;
  hd_eps_sampler_opts(s, &o);
  return o.richardson != 0;
}

/* One node: nu quantiles of `samples` direct draws at beta into row, with the work arrays x
 * (and xc, non-NULL exactly when the sampler does Richardson) of `samples` doubles. */
static void fill_row(hd_eps_sampler *s, double b, long samples, int nu, double *x, double *xc,
                     double *row, gsl_rng *rng) {
  if (!xc) {
    for (long i = 0; i < samples; i++) x[i] = hd_eps_sample(s, b, rng);
    gsl_sort(x, 1, (size_t)samples);
    for (int j = 0; j < nu; j++)
      row[j] = gsl_stats_quantile_from_sorted_data(x, 1, (size_t)samples, (double)j / (nu - 1));
    return;
  }
  /* Quantile-level Richardson (docs/mc-eps.md): Q = 2 Q_fine - Q_coarse from the two sorted
   * samples of paired paths, the O(sqrt(step)) bias of the law removed without the widening of
   * per-path extrapolation; made nondecreasing (running max) and >= 0. */
  for (long i = 0; i < samples; i++) hd_eps_sample_pair(s, b, b, &xc[i], &x[i], rng);
  gsl_sort(x, 1, (size_t)samples);
  gsl_sort(xc, 1, (size_t)samples);
  for (int j = 0; j < nu; j++) {
    double u = (double)j / (nu - 1);
    double v = 2 * gsl_stats_quantile_from_sorted_data(x, 1, (size_t)samples, u) -
               gsl_stats_quantile_from_sorted_data(xc, 1, (size_t)samples, u);
    if (v < 0) v = 0;
    if (j > 0 && v < row[j - 1]) v = row[j - 1];
    row[j] = v;
  }
}

int hd_eps_table_row(const hd_eps_table *t, hd_eps_sampler *s, double beta, double *row,
                     gsl_rng *rng, hd_error *err) {
  double *x = malloc((size_t)t->samples * sizeof(double));
  double *xc = o_richardson(s) ? malloc((size_t)t->samples * sizeof(double)) : NULL;
  int rc = HD_OK;
  if (!x || (o_richardson(s) && !xc))
    rc = hd_error_set(err, HD_ENOMEM, "eps table: out of memory");
  else
    fill_row(s, beta, t->samples, t->nu, x, xc, row, rng);
  free(x);
  free(xc);
  return rc;
}

int hd_eps_table_build(hd_eps_table **out, hd_eps_sampler *s, double beta_min, double beta_max,
                       int nbeta, int nu, long samples, gsl_rng *rng, hd_error *err) {
  *out = NULL;
  if (!(beta_min > 0) || !(beta_max > beta_min) || !isfinite(beta_max))
    return hd_error_set(err, HD_EINPUT, "eps table: need 0 < beta_min < beta_max < inf");
  if (nbeta < 2 || nbeta > 10000 || nu < 2 || nu > 100000)
    return hd_error_set(err, HD_EINPUT, "eps table: need 2 <= nbeta <= 10000, 2 <= nu <= 1e5");
  if (samples < 2)
    return hd_error_set(err, HD_EINPUT, "eps table: need at least 2 samples per beta");
  hd_eps_table *t = table_alloc(nbeta, nu);
  double *x = malloc((size_t)samples * sizeof(double));
  double *xc = o_richardson(s) ? malloc((size_t)samples * sizeof(double)) : NULL;
  if (!t || !x || (o_richardson(s) && !xc)) {
    hd_eps_table_free(t);
    free(x);
    free(xc);
    return hd_error_set(err, HD_ENOMEM, "eps table: out of memory");
  }
  hd_eps_opts o;
  hd_eps_sampler_opts(s, &o);
  t->gamma = hd_eps_sampler_gamma_in(s);
  t->gamma_eff = hd_eps_sampler_gamma(s);
  t->beta_min = beta_min;
  t->beta_max = beta_max;
  t->log_span = log(beta_max / beta_min);
  t->samples = samples;
  t->step = hd_eps_sampler_step(s);
  t->adapt = o.adapt;
  t->richardson = o.richardson;
  double t0 = now_seconds();
  for (int k = 0; k < nbeta; k++)
    fill_row(s, node_beta(t, k), samples, nu, x, xc, t->q + k * nu, rng);
  t->seconds = now_seconds() - t0;
  free(x);
  free(xc);
  *out = t;
  return HD_OK;
}

double hd_eps_row_quantile(const double *row, int nu, double u) {
  double y = u * (nu - 1);
  int j = (int)y;
  if (j >= nu - 1) return row[nu - 1];
  if (j < 0) return row[0];
  return row[j] + (y - j) * (row[j + 1] - row[j]);
}

/* Q_k(u) by linear interpolation in u. */
static double node_quantile(const hd_eps_table *t, int k, double u) {
  return hd_eps_row_quantile(t->q + k * t->nu, t->nu, u);
}

double hd_eps_table_quantile(const hd_eps_table *t, double beta, double u) {
  if (isnan(beta) || !(beta > 0)) return NAN;
  if (beta <= t->beta_min) return node_quantile(t, 0, u); /* no scaling law: docs/mc-eps.md */
  if (beta >= t->beta_max) {
    double g = t->gamma_eff;
    if (isinf(beta)) return g;
    return g + (node_quantile(t, t->nbeta - 1, u) - g) * sqrt(t->beta_max / beta);
  }
  /* the same double as log(beta_max / beta_min) computed here (-fno-math-errno: log is pure) */
  double span = t->log_span != 0 ? t->log_span : log(t->beta_max / t->beta_min);
  double y = log(beta / t->beta_min) / span * (t->nbeta - 1);
  int k = (int)y;
  if (k >= t->nbeta - 1) k = t->nbeta - 2;
  double f = y - k;
  return (1 - f) * node_quantile(t, k, u) + f * node_quantile(t, k + 1, u);
}

double hd_eps_table_sample(const hd_eps_table *t, double beta, gsl_rng *rng) {
  return hd_eps_table_quantile(t, beta, gsl_rng_uniform(rng));
}

/* int_0^1 Q_k(u) Q_l(u) du for the piecewise-linear quantile rows k and l (same u grid). */
static double row_cross(const hd_eps_table *t, int k, int l) {
  const double *a = t->q + k * t->nu, *b = t->q + l * t->nu;
  double s = 0;
  for (int j = 0; j + 1 < t->nu; j++)
    s += 2 * a[j] * b[j] + a[j] * b[j + 1] + a[j + 1] * b[j] + 2 * a[j + 1] * b[j + 1];
  return s / (6.0 * (t->nu - 1));
}

/* E e^-E <eps^2>(E) on one node interval [beta_k, beta_k+1] (params: table, k, the three cross
 * moments A_kk, A_k,k+1, A_k+1,k+1); with Q = (1-f) Q_k + f Q_k+1, f linear in ln beta. */
typedef struct moment_seg {
  const hd_eps_table *t;
  int k;
  double akk, akl, all;
} moment_seg;

static double moment_integrand(double e, void *par) {
  const moment_seg *m = par;
  const hd_eps_table *t = m->t;
  double f = 0;
  if (m->k >= 0) {
    f = log(e / t->beta_min) / log(t->beta_max / t->beta_min) * (t->nbeta - 1) - m->k;
    if (f < 0) f = 0;
    if (f > 1) f = 1;
  }
  double e2 = (1 - f) * (1 - f) * m->akk + 2 * f * (1 - f) * m->akl + f * f * m->all;
  return e * exp(-e) * e2;
}

double hd_eps_table_moment(const hd_eps_table *t) {
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(200);
  if (!w) return NAN;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  double total = 0;
  int bad = 0;
  gsl_function F = {moment_integrand, NULL};
  /* below beta_min: the beta_min node as is (k = -1 means no interpolation) */
  double a00 = row_cross(t, 0, 0);
  moment_seg m0 = {t, -1, a00, a00, a00};
  F.params = &m0;
  double r, er;
  bad |= gsl_integration_qags(&F, 0, t->beta_min, 0, 1e-10, 200, w, &r, &er) != GSL_SUCCESS;
  total += r;
  double akk = a00;
  for (int k = 0; k + 1 < t->nbeta; k++) {
    double all = row_cross(t, k + 1, k + 1);
    moment_seg m = {t, k, akk, row_cross(t, k, k + 1), all};
    F.params = &m;
    double lo = node_beta(t, k), hi = node_beta(t, k + 1);
    bad |= gsl_integration_qags(&F, lo, hi, 0, 1e-10, 200, w, &r, &er) != GSL_SUCCESS;
    total += r;
    akk = all;
  }
  gsl_set_error_handler(old);
  gsl_integration_workspace_free(w);
  return bad ? NAN : total;
}

int hd_eps_table_balance(hd_eps_table *t, double *scale, hd_error *err) {
  double m = hd_eps_table_moment(t);
  if (!isfinite(m) || !(m > 0))
    return hd_error_set(err, HD_EINPUT, "eps table: detailed-balance moment %g not positive", m);
  double c = 1 / sqrt(m);
  for (size_t i = 0; i < (size_t)t->nbeta * (size_t)t->nu; i++) t->q[i] *= c;
  if (scale) *scale = c;
  return HD_OK;
}

hd_eps_table *hd_eps_table_alloc(int nbeta, int nu) {
  return table_alloc(nbeta, nu);
}

double hd_eps_table_beta(const hd_eps_table *t, int k) {
  return node_beta(t, k);
}
