/* fmean_stats: batch-merged means and covariances (see fmean_stats.h). */
#include "fmean_stats.h"

#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <string.h>

void hd_fmean_moments_init(hd_fmean_moments *m, int k) {
  memset(m, 0, sizeof *m);
  m->k = k < 1 ? 1 : (k > HD_FMEAN_MOMENTS_MAX ? HD_FMEAN_MOMENTS_MAX : k);
}

void hd_fmean_moments_add_batch(hd_fmean_moments *m, const double *const *cols, size_t n) {
  if (n == 0) return;
  double bm[HD_FMEAN_MOMENTS_MAX], bcd[HD_FMEAN_MOMENTS_MAX][HD_FMEAN_MOMENTS_MAX];
  for (int i = 0; i < m->k; i++) bm[i] = gsl_stats_mean(cols[i], 1, n);
  for (int i = 0; i < m->k; i++)
    for (int j = i; j < m->k; j++) {
      /* gsl_stats_covariance_m normalises by n - 1; undo it to get the co-deviation sum. */
      double c =
          n > 1 ? gsl_stats_covariance_m(cols[i], 1, cols[j], 1, n, bm[i], bm[j]) * (double)(n - 1)
                : 0.0;
      bcd[i][j] = bcd[j][i] = c;
    }
  double na = m->n, nb = (double)n, nt = na + nb;
  double delta[HD_FMEAN_MOMENTS_MAX];
  for (int i = 0; i < m->k; i++) delta[i] = bm[i] - m->mean[i];
  for (int i = 0; i < m->k; i++)
    for (int j = 0; j < m->k; j++) m->cd[i][j] += bcd[i][j] + delta[i] * delta[j] * na * nb / nt;
  for (int i = 0; i < m->k; i++) m->mean[i] += delta[i] * nb / nt;
  m->n = nt;
}

double hd_fmean_moments_var(const hd_fmean_moments *m, int i) {
  return m->n > 1.0 ? m->cd[i][i] / (m->n - 1.0) : NAN;
}

void hd_fmean_moments_ratio(const hd_fmean_moments *m, int num, int den, double *r,
                            double *stderr_r) {
  double md = m->mean[den];
  double R = m->mean[num] / md;
  double vn = hd_fmean_moments_var(m, num), vd = hd_fmean_moments_var(m, den);
  double c = m->n > 1.0 ? m->cd[num][den] / (m->n - 1.0) : NAN;
  double v = (vn - 2.0 * R * c + R * R * vd) / (m->n * md * md);
  *r = R;
  *stderr_r = sqrt(v > 0.0 ? v : 0.0);
}
