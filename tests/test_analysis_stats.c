/* Tests of the velocity statistics (analysis/hd_velstats.h), the Kolmogorov distribution and
 * the homogeneity detector (db/hd_homog.h) on synthetic samples with fixed seeds. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "hd_fit.h"
#include "hd_homog.h"
#include "hd_velstats.h"

/* Known values of the Kolmogorov distribution (tables, e.g. Smirnov 1948): the 5% and 1%
 * points of sqrt(n) D are 1.3581 and 1.6276; Q(0.5) = 0.9639; Q(1) = 0.2700. */
static void kolmogorov_values(void **state) {
  (void)state;
  assert_true(fabs(hd_kolmogorov_q(1.3581) - 0.05) < 2e-4);
  assert_true(fabs(hd_kolmogorov_q(1.6276) - 0.01) < 1e-4);
  assert_true(fabs(hd_kolmogorov_q(0.5) - 0.9639) < 2e-4);
  assert_true(fabs(hd_kolmogorov_q(1.0) - 0.2700) < 2e-4);
  assert_true(hd_kolmogorov_q(0.1) == 1.0);
  assert_true(hd_kolmogorov_q(5.0) < 1e-20);
}

/* A Gaussian sample of n = 200000 (n = 20000 under the sanitizers): a2 and kurtosis within
 * 3.3 standard errors of 0 (two-sided 0.1%), the delta-method error within 20% of the exact
 * Gaussian values SE(a2) = sqrt(8/(3n)) (1D) and 1/sqrt(n) (2D) (the estimate uses 8th
 * moments: over replicas its relative scatter is 3% at n = 2e5 and 8% at n = 2e4, with a
 * heavy upper tail that follows the sample's kurtosis); KS distance below the 1%
 * critical value 1.63/sqrt(n) with p > 0.01.  A uniform sample of the same variance: a2 =
 * 1.8/3 - 1 = -0.4 exactly in the limit, and a KS distance (limit 0.0577 from the normal) with
 * p < 1e-6. */
static void gaussian_and_uniform(void **state) {
  (void)state;
  size_t n = getenv("HAFF_SANITIZE") && getenv("HAFF_SANITIZE")[0] == '1' ? 20000 : 200000;
  double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 7);
  for (size_t i = 0; i < n; i++)
    x[i] = 3 + gsl_ran_gaussian(r, 2.0), y[i] = gsl_ran_gaussian(r, 2.0);
  hd_velstats s, v;
  hd_error e;
  assert_int_equal(hd_velstats_1d(x, n, 1, &s, &e), HD_OK);
  printf("# gauss 1D: a2 %.4g +- %.3g, kurt %.4g, KS %.4g p %.3g, scale %.4f\n", s.a2, s.a2_err,
         s.kurt, s.ks_d, s.ks_p, s.scale);
  assert_true(fabs(s.a2) < 3.3 * s.a2_err);
  assert_true(fabs(s.kurt) < 3.3 * 3 * s.a2_err);
  assert_true(fabs(s.a2_err / sqrt(8.0 / (3.0 * (double)n)) - 1) < 0.2);
  assert_true(fabs(s.scale / 2.0 - 1) <
              5 / sqrt(2.0 * (double)n)); /* sd of a sample sd: 1/sqrt(2n) */
  assert_true(fabs(s.mean - 3) < 5 * 2 / sqrt((double)n));
  assert_true(s.ks_d < 1.63 / sqrt((double)n) && s.ks_p > 0.01);
  assert_int_equal(hd_velstats_2d(x, y, n, &v, &e), HD_OK);
  printf("# gauss 2D: a2 %.4g +- %.3g\n", v.a2, v.a2_err);
  assert_true(fabs(v.a2) < 3.3 * v.a2_err);
  assert_true(fabs(v.a2_err * sqrt((double)n) - 1) < 0.2);
  assert_true(isnan(v.ks_d));
  /* uncentred: omega keeps its mean, so a shifted sample is not Gaussian about 0 */
  assert_int_equal(hd_velstats_1d(x, n, 0, &s, &e), HD_OK);
  assert_true(s.ks_p < 1e-6);

  for (size_t i = 0; i < n; i++) x[i] = gsl_ran_flat(r, -1, 1);
  assert_int_equal(hd_velstats_1d(x, n, 1, &s, &e), HD_OK);
  printf("# uniform: a2 %.4g +- %.3g, KS %.4g p %.3g\n", s.a2, s.a2_err, s.ks_d, s.ks_p);
  assert_true(fabs(s.a2 + 0.4) < 5 * s.a2_err);
  assert_true(fabs(s.ks_d - 0.0577) < 0.01);
  assert_true(s.ks_p < 1e-6);
  double c[2] = {1, 1};
  assert_int_equal(hd_velstats_1d(c, 2, 1, &s, &e), HD_EINPUT);
  free(x), free(y);
  gsl_rng_free(r);
}

/* The Gaussian KS p-value is uniform on [0, 1] under the null when the parameters are known:
 * over 400 samples of 500 standard normals (not rescaled), the fraction with p < 0.05 is
 * Binomial(400, 0.05): mean 20, sd 4.4; accept 8..34 (3 sd). */
static void ks_pvalue_calibration(void **state) {
  (void)state;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 99);
  double z[500];
  int low = 0;
  for (int k = 0; k < 400; k++) {
    for (int i = 0; i < 500; i++) z[i] = gsl_ran_ugaussian(r);
    low += hd_ks_pvalue(hd_ks_gauss(z, 500), 500) < 0.05;
  }
  printf("# KS p < 0.05 in %d/400\n", low);
  assert_true(low >= 8 && low <= 34);
  gsl_rng_free(r);
}

/* Synthetic samples following Haff's law exactly (D_e = 3, nu0 = 1, alpha = 0.9, N = 1000,
 * samples every 0.5 cpd up to cpd 200) with the time of each sample jittered by Poisson-like
 * noise: no end is detected.  The same with the collision rate per sqrt(E) rising by 50% over
 * cpd 100..120 (clustering): the end is found at cpd 100..115 (the deviation crosses 10% at
 * cpd ~104; windows are 2000 collisions = 4 cpd). */
static void homogeneity_detector(void **state) {
  (void)state;
  enum { N = 401 };
  const double nbody = 1000, al = 0.9, g = (1 - al * al) / 6.0;
  double t[N], coll[N], e[N];
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 5);
  for (int pass = 0; pass < 2; pass++) {
    double tt = 0;
    for (int i = 0; i < N; i++) {
      double cpd = 0.5 * i;
      coll[i] = cpd * nbody / 2;
      double boost = 1;
      if (pass == 1 && cpd > 100) boost = 1 + 0.5 * fmin(1, (cpd - 100) / 20);
      e[i] = exp(-2 * g * cpd); /* E = E0 (1+g nu0 t)^-2 = E0 exp(-2 g tau) */
      if (i > 0) {
        /* d tau/dt = nu0 sqrt(E/E0) * boost; the 250 collisions of a step take a time with
         * relative Poisson noise 1/sqrt(250) */
        double rate = sqrt(e[i - 1] * e[i]) == 0 ? 1 : sqrt(sqrt(e[i - 1] * e[i])) * boost;
        tt += 0.5 / rate * (1 + gsl_ran_gaussian(r, 1 / sqrt(250.0)));
      }
      t[i] = tt;
    }
    hd_homog_opts o = hd_homog_defaults();
    hd_homog h;
    hd_error err;
    assert_int_equal(hd_homog_detect(t, coll, e, N, &o, &h, &err), HD_OK);
    printf("# homogeneity pass %d: detected %d at cpd %.1f (t %.2f), r0 %.4g, %zu windows, max dev "
           "%.3f\n",
           pass, h.detected, 0.5 * (double)(h.n_end - 1), h.t_end, h.r0, h.n_windows, h.max_dev);
    /* r = pair collisions per unit time / sqrt(E) = (nbody/2) nu0 / sqrt(E0) = 500; the
     * Poisson jitter (4% per window) allows 5% */
    assert_true(fabs(h.r0 / 500.0 - 1) < 0.05);
    if (pass == 0) {
      assert_int_equal(h.detected, 0);
      assert_int_equal(h.n_end, N);
      assert_true(h.max_dev < 0.1);
    } else {
      assert_int_equal(h.detected, 1);
      double cpd_end = 0.5 * (double)(h.n_end - 1);
      assert_true(cpd_end >= 100 && cpd_end <= 115);
    }
  }
  hd_homog_opts bad = hd_homog_defaults();
  bad.thr = 0;
  hd_homog h;
  hd_error err;
  assert_int_equal(hd_homog_detect(t, coll, e, N, &bad, &h, &err), HD_EINPUT);
  gsl_rng_free(r);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(kolmogorov_values),
      cmocka_unit_test(gaussian_and_uniform),
      cmocka_unit_test(ks_pvalue_calibration),
      cmocka_unit_test(homogeneity_detector),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
