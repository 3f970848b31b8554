/* cli_grid: averaging runs at matching cpd (hd_cli_grid_make, hd_cli_interp). */
#include "cli_grid.h"

#include <math.h>
#include <stdlib.h>

/* Index of the first and last finite entry of x[0..n), or 0 when none (returns 0). */
static int finite_ends(const double *x, size_t n, size_t *a, size_t *b) {
  size_t i = 0, j = n;
  while (i < n && isnan(x[i])) i++;
  while (j > i && isnan(x[j - 1])) j--;
  if (i == j) return 0;
  *a = i, *b = j - 1;
  return 1;
}

/* The distinct finite values of x[0..n) in [lo, hi], counted (out NULL) or copied to out. */
static size_t distinct_in(const double *x, size_t n, double lo, double hi, double *out) {
  size_t m = 0;
  double last = NAN;
  for (size_t i = 0; i < n; i++) {
    if (isnan(x[i]) || x[i] < lo || x[i] > hi || x[i] == last) continue;
    if (out) out[m] = x[i];
    m++, last = x[i];
  }
  return m;
}

int hd_cli_grid_make(const double *const *cpd, const size_t *n, size_t m, hd_cli_grid *g,
                     hd_error *err) {
  g->n = 0, g->cpd = NULL, g->lo = -INFINITY, g->hi = INFINITY, g->longest = -INFINITY;
  for (size_t k = 0; k < m; k++) {
    size_t a, b;
    if (!finite_ends(cpd[k], n[k], &a, &b))
      return hd_error_set(err, HD_EINPUT, "run %zu of the group has no sample with a cpd", k + 1);
    g->lo = fmax(g->lo, cpd[k][a]), g->hi = fmin(g->hi, cpd[k][b]);
    g->longest = fmax(g->longest, cpd[k][b]);
  }
  if (m == 0 || !(g->lo <= g->hi))
    return hd_error_set(err, HD_EINPUT,
                        "the runs share no cpd range (latest start %g, earliest end %g)", g->lo,
                        g->hi);
  size_t best = 0, nb = 0;
  for (size_t k = 0; k < m; k++) {
    size_t c = distinct_in(cpd[k], n[k], g->lo, g->hi, NULL);
    if (c > nb) nb = c, best = k;
  }
  g->cpd = malloc((nb ? nb : 1) * sizeof *g->cpd);
  if (!g->cpd) return hd_error_set(err, HD_ENOMEM, "out of memory");
  g->n = distinct_in(cpd[best], n[best], g->lo, g->hi, g->cpd);
  return HD_OK;
}

void hd_cli_grid_free(hd_cli_grid *g) {
  free(g->cpd);
  g->cpd = NULL, g->n = 0;
}

double hd_cli_interp(const double *x, const double *y, size_t stride, size_t n, double c, int logy,
                     size_t *hint) {
  size_t i = *hint < n ? *hint : 0;
  if (i > 0 && !(x[i] <= c)) i = 0; /* not ascending from the hint: search from the start */
  /* i: the last finite sample with x <= c (the first of a repeated x equal to c) */
  size_t lo = n;
  for (; i < n; i++) {
    if (isnan(x[i])) continue;
    if (x[i] > c) break;
    if (lo == n || x[i] != x[lo]) lo = i;
  }
  if (lo == n) return NAN; /* c before the first sample */
  *hint = lo;
  if (x[lo] == c) return y[lo * stride];
  size_t hi = i;
  while (hi < n && isnan(x[hi])) hi++;
  if (hi == n) return NAN; /* c after the last sample */
  double w = (c - x[lo]) / (x[hi] - x[lo]), a = y[lo * stride], b = y[hi * stride];
  if (logy && a > 0 && b > 0) return exp(log(a) + w * (log(b) - log(a)));
  return a + w * (b - a);
}
