/* fmean_stats: running means and covariances of up to 4 variables, accumulated batch by batch
 * (each batch summarised with gsl_stats, batches merged exactly by Chan et al.'s update), and
 * the delta-method error of a ratio of means.  Used by the fmean Monte Carlo. */
#ifndef HD_FMEAN_STATS_H
#define HD_FMEAN_STATS_H

#include <stddef.h>

/* Maximum number of variables in one hd_fmean_moments. */
#define HD_FMEAN_MOMENTS_MAX 4

/* Sample count, means and co-deviation sums of k variables. */
typedef struct hd_fmean_moments {
  int k;                                                 /* number of variables, 1..MAX */
  double n;                                              /* samples so far */
  double mean[HD_FMEAN_MOMENTS_MAX];                     /* sample means */
  double cd[HD_FMEAN_MOMENTS_MAX][HD_FMEAN_MOMENTS_MAX]; /* sum (x_i - mean_i)(x_j - mean_j) */
} hd_fmean_moments;

/* Empties m for k variables (1 <= k <= HD_FMEAN_MOMENTS_MAX). */
void hd_fmean_moments_init(hd_fmean_moments *m, int k);

/* Adds a batch of n samples: cols[i][s] is variable i of sample s (n may be 0). */
void hd_fmean_moments_add_batch(hd_fmean_moments *m, const double *const *cols, size_t n);

/* The unbiased sample variance of variable i (NaN if n < 2). */
double hd_fmean_moments_var(const hd_fmean_moments *m, int i);

/* The ratio R = mean[num] / mean[den] and its first-order (delta-method) standard error
 * sqrt((var_num - 2 R cov + R^2 var_den) / (n mean_den^2)). */
void hd_fmean_moments_ratio(const hd_fmean_moments *m, int num, int den, double *r,
                            double *stderr_r);

#endif
