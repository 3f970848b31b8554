/* Tests of mc/rate.c (`haff mc rate`, docs/mc-rate.md): the molecular-chaos collision frequency
 * of hard dimers and any shape over eq. (29)'s nu0.  Random quantities use fixed seeds and are
 * compared within 4 standard errors (two-sided false alarm 6e-5 per check) plus the rounding of
 * the reference values. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "haff.h"
#include "hd_body.h"
#include "hd_enskog.h"
#include "hd_sim.h"
#include "rate.h"
#include "test_util.h"

static hd_rate_result run(const hd_shape *sh, unsigned long n, unsigned long seed) {
  hd_rate_opts o = {sh, n, 0, seed};
  hd_rate_result r;
  hd_error err;
  assert_int_equal(hd_rate_run(&o, &r, &err), HD_OK);
  printf("# ratio %.6f +- %.2g (%lu samples, %lu accepted, %.2f s)\n", r.ratio, r.ratio_err,
         r.samples, r.accepted, r.seconds);
  return r;
}

/* Disks: the integral is eq. (29) itself, ratio 1 with no variance, whatever d and m. */
static void disks_exact(void **state) {
  (void)state;
  hd_shape s;
  hd_shape_disk(&s, 1.7, 3.0);
  hd_rate_result r = run(&s, 1000, 1);
  assert_true(fabs(r.ratio - 1) < 1e-12 && r.ratio_err < 1e-12 && r.accepted == 1000);
}

/* Dimers at a/d = 0.5, 1, 1.5 against an independent kinetic-theory calculation (issue 25:
 * 1.645, 2.090, 2.607, given to 3 decimals: +-0.0005) and a = d against elastic runs at area
 * fraction 5.7e-4 (2.105 +- 0.008, recollisions included): within the 1.5 % of the acceptance.
 * Before this program haff had no such number (Table I's ratio had no theory). */
static void dimers_known(void **state) {
  (void)state;
  const double ad[3] = {0.5, 1, 1.5}, ref[3] = {1.645, 2.090, 2.607};
  for (int k = 0; k < 3; k++) {
    hd_shape s;
    hd_shape_dimer(&s, 1, ad[k], 1);
    hd_rate_result r = run(&s, 2000000, 11 + (unsigned long)k);
    assert_true(fabs(r.ratio - ref[k]) < 4 * r.ratio_err + 0.0005);
    if (k == 1) assert_true(fabs(r.ratio / 2.105 - 1) < 0.015);
  }
}

/* The dimer given as a cluster of two disks takes the engine's general code (hd_side_of of a
 * cluster): with the same seed, the same draws and the same number to 1e-9.  Units: a dimer of
 * d = 2, a = 2, m = 5 gives the same ratio as d = 1, a = 1 (the ratio has no units). */
static void cluster_equals_dimer(void **state) {
  (void)state;
  hd_shape a, b, c;
  hd_shape_dimer(&a, 1, 1, 1);
  double x[2] = {-0.5, 0.5}, y[2] = {0, 0}, d[2] = {1, 1}, m[2] = {1, 1};
  assert_int_equal(hd_shape_cluster(&b, 2, x, y, d, m, 0), 0);
  hd_rate_result ra = run(&a, 200000, 5), rb = run(&b, 200000, 5);
  assert_true(fabs(ra.ratio - rb.ratio) < 1e-9);
  hd_shape_dimer(&c, 2, 2, 5);
  hd_rate_result rc = run(&c, 200000, 5);
  assert_true(fabs(ra.ratio - rc.ratio) < 1e-9);
}

/* a -> 0+: the excluded region tends to a disk of radius d, the contact angles to independent
 * uniform ones, and rotation keeps adding (a/2) omega sin(theta) (variance T sin^2(theta) / 2m)
 * to each contact point: ratio -> <sqrt((2 + sin^2 th1 + sin^2 th2) / 2)>, by a 2-D midpoint
 * rule here (1200^2 nodes: error < 1e-7), about 1.22, not 1: the a -> 0 argument that Table I's
 * ratio tends to 1 is wrong (issue 25).  At a/d = 1e-4 the MC is within 4 standard errors +
 * 2e-4 (the O(a) approach) of it. */
static void small_a_limit(void **state) {
  (void)state;
  const int K = 1200;
  double sum = 0;
  for (int i = 0; i < K; i++)
    for (int j = 0; j < K; j++) {
      double s1 = sin(M_PI * (i + 0.5) / K), s2 = sin(M_PI * (j + 0.5) / K);
      sum += sqrt((2 + s1 * s1 + s2 * s2) / 2);
    }
  double lim = sum / ((double)K * K);
  printf("# a -> 0+ limit: %.7f\n", lim);
  hd_shape s;
  hd_shape_dimer(&s, 1, 1e-4, 1);
  hd_rate_result r = run(&s, 2000000, 3);
  assert_true(fabs(r.ratio - lim) < 4 * r.ratio_err + 2e-4);
  assert_true(lim > 1.2);
}

/* The collision frequency per dimer of an elastic engine run (N dimers d = m = 1, bond a, covered
 * area fraction phi, seed), over eq. (29)'s nu0 in haff's convention (sigma = d, M = 2m, T = the
 * time average of E_tr / N): the run's rate nu = 2 C / (N t) and T are measured in nb blocks of
 * equal time after a warm-up of 2 cpd; *err is the standard error of the block mean (the blocks
 * are long against the correlation time of recollisions and of T's fluctuation). */
static double engine_ratio(long N, double a, double phi, int nb, double blk,
                           unsigned long long seed, double *err) {
  hd_scene sc;
  test_disk_scene(&sc, 0, 0.1, 1.0, seed);
  sc.n_dimers = N;
  sc.dimer_a = a;
  double ad = a < 1 ? 2 * M_PI / 4 - (2 * 0.25 * acos(a) - 0.5 * a * sqrt(1 - a * a)) : M_PI / 2;
  double area = (double)N * ad / phi;
  sc.box_x = sc.box_y = sqrt(area);
  hd_sim *s;
  hd_error e;
  assert_int_equal(hd_sim_alloc(&s, &sc, &e), HD_OK);
  hd_event_out ev;
  int rc;
  while (hd_sim_cpd(s) < 2)
    if ((rc = hd_sim_next(s, INFINITY, &ev, &e)) != HD_OK && rc != HD_SIM_BUSY)
      fail_msg("%s", e.msg);
  double n = (double)N / area, sum = 0, sum2 = 0;
  double t = hd_sim_time(s), et, er;
  hd_sim_energy(s, -1, &et, &er);
  for (int b = 0; b < nb; b++) {
    double t0 = t, t1 = t0 + blk, acc = 0;
    int64_t c0 = s->c.collisions;
    for (;;) {
      rc = hd_sim_next(s, t1, &ev, &e);
      double tn = rc == HD_OK ? ev.t : hd_sim_time(s);
      acc += et * (tn - t);
      t = tn;
      if (rc == HD_SIM_STOPTIME) break;
      if (rc != HD_OK && rc != HD_SIM_BUSY) fail_msg("%s", e.msg);
      if (rc == HD_OK) hd_sim_energy(s, -1, &et, &er);
    }
    double nu = 2.0 * (double)(s->c.collisions - c0) / ((double)N * blk);
    double T = acc / blk / (double)N; /* 2 translational degrees of freedom */
    double r = nu / (2 * n * sqrt(M_PI * T / 2.0));
    sum += r;
    sum2 += r * r;
  }
  hd_sim_free(s);
  double m = sum / nb;
  *err = sqrt((sum2 / nb - m * m) / (nb - 1));
  return m;
}

/* `haff mc rate` against the engine (issue 25: "agrees with elastic runs at area fraction <= 1e-3
 * within 1.5 %, and so do other a/d checked independently"): elastic dimers, N = 2000 at covered
 * area fraction 1e-3, seed 5, 40 blocks of 2000 time units (~6.5 cpd each, 2.6e5 collisions in
 * all; recollisions, 18-22 % of all contacts, and T's fluctuation are correlated over ~1 cpd, so
 * the blocks are independent), at a/d = 1 and 1.5, over hd_rate_run's ratio times Enskog's
 * g(phi) = 1.0016 (docs/mc-rate.md: g of the covered area fraction).  Measured (seeds 5-7, and
 * a/d = 0.5): ratios 0.995-1.003, block standard error 0.25 %.  Tolerance: 4 combined standard
 * errors (engine blocks and Monte Carlo; two-sided false alarm 6e-5) and the acceptance's
 * 1.5 %.  A theory without rotation (w = sqrt(2/M) in rate.c) is 25 % off at a = d (checked: this
 * test fails with it), a wrong mass convention (m for 2m) sqrt(2).  ~10 s. */
static void engine_agrees(void **state) {
  (void)state;
  if (test_sanitized()) return; /* statistics need the full length: skip under ASan */
  const long N = 2000;
  const double phi = 1e-3, ads[2] = {1.0, 1.5};
  for (int k = 0; k < 2; k++) {
    double err, r = engine_ratio(N, ads[k], phi, 40, 2000, 5, &err);
    hd_shape sh;
    hd_shape_dimer(&sh, 1, ads[k], 1);
    hd_rate_result mc = run(&sh, 1000000, 21);
    double ref = mc.ratio * hd_enskog_g2d(phi), q = r / ref;
    double se = q * hypot(err / r, mc.ratio_err / mc.ratio);
    printf("# a/d %g: engine %.4f +- %.4f (40 blocks), mc %.4f +- %.4f, g %.5f: engine / theory "
           "%.4f +- %.4f\n",
           ads[k], r, err, mc.ratio, mc.ratio_err, hd_enskog_g2d(phi), q, se);
    assert_true(fabs(q - 1) < 4 * se);
    assert_true(fabs(q - 1) < 0.015);
  }
}

/* The command: one TSV row; bad input refused with exit 2. */
static void command(void **state) {
  (void)state;
  char *ok[] = {"rate", "--a", "0", "--samples", "100"};
  assert_int_equal(hd_cmd_mc_rate(5, ok), 0);
  char *neg[] = {"rate", "--a", "-1"};
  assert_int_equal(hd_cmd_mc_rate(3, neg), 2);
  char *both[] = {"rate", "--a", "1", "--disks", "0 0 1 1"};
  assert_int_equal(hd_cmd_mc_rate(5, both), 2);
  char *none[] = {"rate", "--samples", "100"};
  assert_int_equal(hd_cmd_mc_rate(3, none), 2);
  char *bad[] = {"rate", "--disks", "0 0 1"};
  assert_int_equal(hd_cmd_mc_rate(3, bad), 2);
  char *two[] = {"rate", "--a", "1", "--samples", "10", "--seconds", "1"};
  assert_int_equal(hd_cmd_mc_rate(7, two), 2);
  /* review 14: disks that are not one body (a scene's [species] refuses them) are refused by
   * mc rate and mc fmean too (before: accepted, exit 0); touching ones are a body */
  char *apart[] = {"rate", "--disks", "0 0 1 1; 5 0 1 1", "--samples", "100"};
  assert_int_equal(hd_cmd_mc_rate(5, apart), 2);
  char *touch[] = {"rate", "--disks", "0 0 1 1; 1 0 1 1", "--samples", "100"};
  assert_int_equal(hd_cmd_mc_rate(5, touch), 0);
  hd_shape sh;
  assert_int_equal(hd_mc_parse_disks("mc fmean", "0 0 1 1; 1 0 1 1; 3 0 1 1", &sh), 2);
  assert_int_equal(hd_mc_parse_disks("mc fmean", "0 0 1 1; 1 0 1 1; 2 0 1 1", &sh), 0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(disks_exact),
      cmocka_unit_test(dimers_known),
      cmocka_unit_test(cluster_equals_dimer),
      cmocka_unit_test(small_a_limit),
      cmocka_unit_test(command),
      cmocka_unit_test(engine_agrees),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
