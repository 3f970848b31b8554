/* Tests of the analysis fits on synthetic data with known parameters (analysis/hd_fit.h).
 * Coverage tolerance used throughout: 200 replicas of a 99% interval; the number of hits is
 * Binomial(200, 0.99) (mean 198, sd 1.4) if the interval is right, so fewer than 190 hits (95%)
 * is a failure (probability < 1e-4 for a correct interval).  Standard errors are compared with
 * the scatter of the 200 estimates, whose own relative sampling error is 1/sqrt(2*199) = 5%:
 * agreement within 20% (4 sigma).  Every random test has a fixed seed. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <string.h>
#include <stdio.h>
#include <stdlib.h>

#include "hd_fit.h"

#define REPL 200

/* eq. (31) with D_e = 3, nu0 = 1.25, alpha = 0.9, 100 points on t in [0.5, 50], iid Gaussian
 * noise of sd 0.3 collisions per particle. */
static void haff_fit_coverage(void **state) {
  (void)state;
  const double De = 3.0, nu = 1.25, alpha = 0.9, sd = 0.3;
  enum { N = 100 };
  double t[N], tau[N], est[2][REPL], se[2][REPL];
  int hit[2] = {0, 0};
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 20050101);
  for (int k = 0; k < REPL; k++) {
    for (int i = 0; i < N; i++) {
      t[i] = 0.5 * (i + 1);
      tau[i] = hd_haff_tau(t[i], alpha, De, nu) + gsl_ran_gaussian(r, sd);
    }
    hd_haff_fit f;
    hd_error e;
    assert_int_equal(hd_fit_haff_log(t, tau, N, alpha, &f, &e), HD_OK);
    est[0][k] = f.D_e, se[0][k] = f.D_e_err, est[1][k] = f.nu0, se[1][k] = f.nu0_err;
    hit[0] += fabs(f.D_e - De) <= f.tq * f.D_e_err;
    hit[1] += fabs(f.nu0 - nu) <= f.tq * f.nu0_err;
  }
  for (int p = 0; p < 2; p++) {
    double scatter = gsl_stats_sd(est[p], 1, REPL), mse = gsl_stats_mean(se[p], 1, REPL);
    printf("# haff fit param %d: coverage %d/200, mean se %.4g, scatter %.4g, mean %.5g\n", p,
           hit[p], mse, scatter, gsl_stats_mean(est[p], 1, REPL));
    assert_true(hit[p] >= 190);
    assert_true(fabs(mse / scatter - 1) < 0.2);
  }
  /* no bias beyond 4 standard errors of the mean of 200 estimates */
  assert_true(fabs(gsl_stats_mean(est[0], 1, REPL) - De) <
              4 * gsl_stats_sd(est[0], 1, REPL) / sqrt(REPL));
  gsl_rng_free(r);
}

/* Why haff-fit calls its per-run errors formal (D_e_fit_err) and Table I never uses them.  In a
 * run, cpd(t) is a cumulative count: here each of 200 steps of 0.5 cpd takes a time with 1/15
 * relative noise, as in test_analysis_cli's synthetic runs, so the noise of tau at a given t is
 * a random walk.  The least-squares error, which takes the residuals as independent, is then far
 * below the scatter of D_e over 200 replicas: we check it is less than half of it (it is about
 * a tenth here; 200 replicas measure the scatter to 5 %), and that the 99 % interval covers D_e
 * in fewer than 150 of 200 replicas (it would in 198 if the error were right). */
static void haff_fit_cumulative_noise(void **state) {
  (void)state;
  const double De = 3.0, nu = 1.25, alpha = 0.9, g = (1 - alpha * alpha) / (2 * De);
  enum { N = 200 };
  double t[N], tau[N], est[REPL], se[REPL];
  int hit = 0;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 1998);
  for (int k = 0; k < REPL; k++) {
    double tt = 0;
    for (int i = 0; i < N; i++) {
      /* the exact time of cpd = 0.5 (i + 1) by eq. (31) inverted, step by step, with noise */
      double c0 = 0.5 * i, c1 = 0.5 * (i + 1);
      double dt = (exp(g * c1) - exp(g * c0)) / (g * nu);
      tt += dt * (1 + gsl_ran_gaussian(r, 1 / 15.0));
      t[i] = tt, tau[i] = c1;
    }
    hd_haff_fit f;
    hd_error e;
    assert_int_equal(hd_fit_haff_log(t, tau, N, alpha, &f, &e), HD_OK);
    est[k] = f.D_e, se[k] = f.D_e_err;
    hit += fabs(f.D_e - De) <= f.tq * f.D_e_err;
  }
  double scatter = gsl_stats_sd(est, 1, REPL), mse = gsl_stats_mean(se, 1, REPL);
  printf("# cumulative noise: formal se %.4g, scatter %.4g (ratio %.3g), coverage %d/200\n", mse,
         scatter, mse / scatter, hit);
  assert_true(mse < 0.5 * scatter);
  assert_true(hit < 150);
  gsl_rng_free(r);
}

/* Noise-free data: the fit recovers the parameters to 1e-6 relative (convergence, Jacobian),
 * from a start (D_e = 3) far from D_e = 2 (hard disks). */
static void haff_fit_exact(void **state) {
  (void)state;
  enum { N = 50 };
  double t[N], tau[N];
  for (int i = 0; i < N; i++) t[i] = 0.1 * i * i, tau[i] = hd_haff_tau(t[i], 0.8, 2.0, 0.7);
  hd_haff_fit f;
  hd_error e;
  assert_int_equal(hd_fit_haff_log(t, tau, N, 0.8, &f, &e), HD_OK);
  assert_true(fabs(f.D_e / 2.0 - 1) < 1e-6);
  assert_true(fabs(f.nu0 / 0.7 - 1) < 1e-6);
  /* alpha = 1: tau = nu0 t, D_e not identifiable */
  for (int i = 0; i < N; i++) tau[i] = 1.3 * t[i];
  assert_int_equal(hd_fit_haff_log(t, tau, N, 1.0, &f, &e), HD_OK);
  assert_true(isnan(f.D_e));
  assert_true(fabs(f.nu0 - 1.3) < 1e-12);
  /* bad input */
  assert_int_equal(hd_fit_haff_log(t, tau, 2, 0.9, &f, &e), HD_EINPUT);
  tau[3] = NAN;
  assert_int_equal(hd_fit_haff_log(t, tau, N, 0.9, &f, &e), HD_EINPUT);
}

/* Bug found on real runs (a = 2d dimers, plots/plots.mk): a run whose collisions pile up at one
 * instant (a disk clamped in the gap of a dimer) has tau(t) with no cooling curvature; the fit
 * used to return D_e ~ 1e64 with D_e_err = 0 as a success and Table I printed it.  Such fits
 * must fail.  Data shaped like that run: 7 samples of normal cooling, then 160 more samples of
 * 0.5 cpd each within 0.016 time units. */
static void haff_fit_diverged(void **state) {
  (void)state;
  enum { N = 169 };
  double t[N], tau[N];
  for (int i = 0; i < N; i++) {
    t[i] = i < 8 ? 0.85 * i : 6.8 + 1e-4 * (i - 7);
    tau[i] = 0.5 * i;
  }
  hd_haff_fit f;
  hd_error e;
  assert_int_equal(hd_fit_haff_log(t, tau, N, 0.9, &f, &e), HD_EINPUT);
  assert_non_null(strstr(e.msg, "diverged"));
  /* a straight line tau = nu0 t at alpha < 1 (no cooling at all) also has no finite D_e */
  for (int i = 0; i < N; i++) t[i] = 0.1 * i, tau[i] = 0.4 * t[i];
  assert_int_equal(hd_fit_haff_log(t, tau, N, 0.9, &f, &e), HD_EINPUT);
}

/* OLS with iid noise: a0 = 2.01, a1 = -3e-4 on x in [0, 200), 400 points, sd 0.02. */
static void linear_ols_coverage(void **state) {
  (void)state;
  enum { N = 400 };
  double x[N], y[N], est[2][REPL], se[2][REPL];
  int hit[2] = {0, 0};
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 31);
  for (int k = 0; k < REPL; k++) {
    for (int i = 0; i < N; i++)
      x[i] = 0.5 * i, y[i] = 2.01 - 3e-4 * x[i] + gsl_ran_gaussian(r, 0.02);
    hd_linfit f;
    hd_error e;
    assert_int_equal(hd_fit_linear_t(x, y, N, 0.99, &f, &e), HD_OK);
    hit[0] += f.a0_lo <= 2.01 && 2.01 <= f.a0_hi;
    hit[1] += f.a1_lo <= -3e-4 && -3e-4 <= f.a1_hi;
    est[0][k] = f.a0, est[1][k] = f.a1, se[0][k] = f.a0_err, se[1][k] = f.a1_err;
    /* iid residuals: tau_int near 1/2, so the corrected interval is about the OLS one */
    assert_true(f.tau_int < 1.0);
  }
  for (int p = 0; p < 2; p++) {
    double scatter = gsl_stats_sd(est[p], 1, REPL), mse = gsl_stats_mean(se[p], 1, REPL);
    printf("# OLS param %d: coverage %d/200, mean se %.4g, scatter %.4g\n", p, hit[p], mse,
           scatter);
    assert_true(hit[p] >= 190);
    assert_true(fabs(mse / scatter - 1) < 0.2);
  }
  gsl_rng_free(r);
}

/* AR(1) noise e_i = phi e_{i-1} + w_i, phi = 0.9 (tau_int = (1+phi)/(2(1-phi)) = 9.5), 2000
 * points: the plain OLS interval is far too narrow (coverage well below 95%), the corrected
 * one covers at the stated rate and its error matches the scatter within 20%. */
static void linear_autocorr_coverage(void **state) {
  (void)state;
  enum { N = 2000 };
  const double phi = 0.9;
  double *x = malloc(N * sizeof *x), *y = malloc(N * sizeof *y), est[REPL], se[REPL], tau[REPL];
  int hit_ols = 0, hit_ac = 0;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 4242);
  for (int k = 0; k < REPL; k++) {
    double eps = gsl_ran_gaussian(r, 0.01 / sqrt(1 - phi * phi));
    for (int i = 0; i < N; i++) {
      eps = phi * eps + gsl_ran_gaussian(r, 0.01);
      x[i] = 0.1 * i, y[i] = 2.0 + 1e-4 * x[i] + eps;
    }
    hd_linfit f;
    hd_error e;
    assert_int_equal(hd_fit_linear_t(x, y, N, 0.99, &f, &e), HD_OK);
    hit_ols += f.a1_lo <= 1e-4 && 1e-4 <= f.a1_hi;
    hit_ac += f.a1_lo_ac <= 1e-4 && 1e-4 <= f.a1_hi_ac;
    est[k] = f.a1, se[k] = f.a1_err_ac, tau[k] = f.tau_int;
  }
  double scatter = gsl_stats_sd(est, 1, REPL), mse = gsl_stats_mean(se, 1, REPL);
  printf("# AR(1): OLS coverage %d/200, corrected %d/200, mean tau_int %.3g (exact 9.5), "
         "se %.4g scatter %.4g\n",
         hit_ols, hit_ac, gsl_stats_mean(tau, 1, REPL), mse, scatter);
  assert_true(hit_ols < 190);
  assert_true(hit_ac >= 190);
  assert_true(fabs(mse / scatter - 1) < 0.2);
  /* tau_int within 20% of the exact 9.5 on average (the window estimator is biased low a bit) */
  assert_true(fabs(gsl_stats_mean(tau, 1, REPL) / 9.5 - 1) < 0.2);
  free(x), free(y);
  gsl_rng_free(r);
}

static void linear_bad_input(void **state) {
  (void)state;
  double x[3] = {1, 1, 1}, y[3] = {1, 2, 3};
  hd_linfit f;
  hd_error e;
  assert_int_equal(hd_fit_linear_t(x, y, 3, 0.99, &f, &e), HD_EINPUT);
  assert_int_equal(hd_fit_linear_t(x, y, 2, 0.99, &f, &e), HD_EINPUT);
  double x2[3] = {0, 1, 2};
  assert_int_equal(hd_fit_linear_t(x2, y, 3, 1.5, &f, &e), HD_EINPUT);
  /* exact line: zero errors, the interval is the point */
  assert_int_equal(hd_fit_linear_t(x2, y, 3, 0.99, &f, &e), HD_OK);
  assert_true(fabs(f.a0 - 1) < 1e-12 && fabs(f.a1 - 1) < 1e-12);
}

/* Alternating residuals (+e, -e, ...) have a lag-1 autocorrelation near -1, so the window
 * estimator gives tau_int < 0.5, here about -0.5.  n_eff used to be n / (2 tau) = -400 and the
 * corrected interval took t with 1 dof (63.7 instead of 2.6: 24 times the OLS one).  Anti-
 * correlation is taken as independence: n_eff = n, the corrected interval is the OLS one. */
static void linear_anticorrelated(void **state) {
  (void)state;
  enum { N = 400 };
  double x[N], y[N];
  for (int i = 0; i < N; i++) x[i] = i, y[i] = 1.0 + 0.01 * i + (i % 2 ? 0.1 : -0.1);
  hd_linfit f;
  hd_error e;
  assert_int_equal(hd_fit_linear_t(x, y, N, 0.99, &f, &e), HD_OK);
  printf("# alternating residuals: tau_int %.3g, n_eff %.4g, tq %.4g, tq_ac %.4g\n", f.tau_int,
         f.n_eff, f.tq, f.tq_ac);
  assert_true(f.tau_int < 0.0);
  assert_true(f.n_eff == (double)N);
  assert_true(f.tq_ac == f.tq && f.a1_err_ac == f.a1_err);
  assert_true(f.a1_lo_ac == f.a1_lo && f.a1_hi_ac == f.a1_hi);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(haff_fit_coverage),        cmocka_unit_test(haff_fit_exact),
      cmocka_unit_test(haff_fit_diverged),        cmocka_unit_test(linear_ols_coverage),
      cmocka_unit_test(linear_autocorr_coverage), cmocka_unit_test(linear_bad_input),
      cmocka_unit_test(linear_anticorrelated),    cmocka_unit_test(haff_fit_cumulative_noise),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
