/* Tests of engine/rods/eps (and its store, db/hd_epsdb): the rods' stochastic coefficient of
 * restitution (docs/mc-eps.md). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <gsl/gsl_randist.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "eps.h"
#include "hd_epsdb.h"
#include "haff.h" /* hd_cmd_mc_eps */

static int sanitize(void) {
  const char *s = getenv("HAFF_SANITIZE");
  return s && *s == '1';
}

static hd_eps_sampler *make(double gamma, double step) {
  hd_eps_opts o;
  hd_eps_opts_default(&o);
  if (step > 0) o.step = step;
  hd_eps_sampler *s = NULL;
  hd_error err;
  assert_int_equal(hd_eps_sampler_alloc(&s, gamma, &o, &err), HD_OK);
  return s;
}

static gsl_rng *rng_seeded(unsigned long seed) {
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, seed);
  return r;
}

/* Cold baths (q = 0): eps = l_short/l_long = min(gamma, 1/gamma) (paper Sec. II B, wave theory);
 * the solver runs (q = 0 is not special-cased), so this checks the echo bookkeeping. The
 * tolerance 1e-9 is round-off on ~1e3 grid sums. */
/* HD_EIO "eps table: what: SQLite's message" into err. */
static int load_fail(sqlite3 *db, hd_error *err, const char *what) {
  return hd_error_set(err, HD_EIO, "eps table: %s: %s", what, sqlite3_errmsg(db));
}

/* Loads table id from db; id <= 0 loads the newest table whose gamma equals gamma (within
 * 1e-12).  Returns HD_OK, HD_EINPUT (no such table) or HD_EIO.  What hd_eps_table_save wrote,
 * read back (was hd_eps_table_load of the store, which nothing but this test called). */
static int eps_table_load(hd_eps_table **out, sqlite3 *db, int64_t id, double gamma,
                          hd_error *err) {
  *out = NULL;
  sqlite3_stmt *st = NULL;
  const char *sql =
      id > 0 ? "SELECT id, gamma, gamma_eff, nbeta, nu, beta_min, beta_max, samples, step, adapt,"
               " richardson, seconds FROM eps_tables WHERE id = ?"
             : "SELECT id, gamma, gamma_eff, nbeta, nu, beta_min, beta_max, samples, step, adapt,"
               " richardson, seconds FROM eps_tables WHERE abs(gamma - ?) < 1e-12"
               " ORDER BY id DESC LIMIT 1";
  if (sqlite3_prepare_v2(db, sql, -1, &st, NULL) != SQLITE_OK)
    return load_fail(db, err, "no eps_tables in this database");
  if (id > 0)
    sqlite3_bind_int64(st, 1, id);
  else
    sqlite3_bind_double(st, 1, gamma);
  int rc = sqlite3_step(st);
  if (rc != SQLITE_ROW) {
    sqlite3_finalize(st);
    if (rc != SQLITE_DONE) return load_fail(db, err, "select");
    if (id > 0)
      return hd_error_set(err, HD_EINPUT, "eps table: no table with id %lld", (long long)id);
    return hd_error_set(err, HD_EINPUT, "eps table: no table for gamma %g", gamma);
  }
  int64_t tab = sqlite3_column_int64(st, 0);
  int nbeta = sqlite3_column_int(st, 3), nu = sqlite3_column_int(st, 4);
  hd_eps_table *t = nbeta >= 2 && nu >= 2 ? hd_eps_table_alloc(nbeta, nu) : NULL;
  if (!t) {
    sqlite3_finalize(st);
    return hd_error_set(err, HD_EIO, "eps table %lld: bad sizes or out of memory", (long long)tab);
  }
  t->gamma = sqlite3_column_double(st, 1);
  t->gamma_eff = sqlite3_column_double(st, 2);
  t->beta_min = sqlite3_column_double(st, 5);
  t->beta_max = sqlite3_column_double(st, 6);
  t->samples = sqlite3_column_int64(st, 7);
  t->step = sqlite3_column_double(st, 8);
  t->adapt = sqlite3_column_int(st, 9);
  t->richardson = sqlite3_column_int(st, 10);
  t->seconds = sqlite3_column_double(st, 11);
  sqlite3_finalize(st);
  for (size_t i = 0; i < (size_t)nbeta * (size_t)nu; i++) t->q[i] = NAN;
  if (sqlite3_prepare_v2(db, "SELECT k, j, eps FROM eps_table_points WHERE tab = ?", -1, &st,
                         NULL) != SQLITE_OK) {
    hd_eps_table_free(t);
    return load_fail(db, err, "select points");
  }
  sqlite3_bind_int64(st, 1, tab);
  long n = 0;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    int k = sqlite3_column_int(st, 0), j = sqlite3_column_int(st, 1);
    if (k >= 0 && k < nbeta && j >= 0 && j < nu) {
      t->q[k * nu + j] = sqlite3_column_double(st, 2);
      n++;
    }
  }
  sqlite3_finalize(st);
  if (rc != SQLITE_DONE || n != (long)nbeta * nu) {
    hd_eps_table_free(t);
    return hd_error_set(err, HD_EIO, "eps table %lld: %ld of %d points present", (long long)tab, n,
                        nbeta * nu);
  }
  *out = t;
  return HD_OK;
}

static void cold_baths_give_gamma(void **state) {
  (void)state;
  const double g[] = {0.8, 1.25, 0.5, 0.3};
  const double want[] = {0.8, 0.8, 0.5, 0.3};
  gsl_rng *r = rng_seeded(1);
  for (int i = 0; i < 4; i++) {
    hd_eps_sampler *s = make(g[i], 0);
    for (int k = 0; k < 5; k++) assert_true(fabs(hd_eps_sample(s, INFINITY, r) - want[i]) < 1e-9);
    /* nearly cold: sigma = 7e-7 moves eps by O(sigma) at most */
    assert_true(fabs(hd_eps_sample(s, 1e12, r) - want[i]) < 1e-4);
    hd_eps_sampler_free(s);
  }
  gsl_rng_free(r);
}

/* gamma = 1: eps = 1 for every realisation (paper Sec. II B; the grid scheme keeps this exactly
 * because the contact is snapped to a grid point, docs/mc-eps.md). Tolerance: round-off. */
static void equal_rods_are_elastic(void **state) {
  (void)state;
  hd_eps_sampler *s = make(1.0, 0);
  gsl_rng *r = rng_seeded(2);
  const double betas[] = {0.05, 1, 30};
  int n = sanitize() ? 50 : 300;
  for (int b = 0; b < 3; b++)
    for (int i = 0; i < n; i++) assert_true(fabs(hd_eps_sample(s, betas[b], r) - 1.0) < 1e-9);
  gsl_rng_free(r);
  hd_eps_sampler_free(s);
}

/* The paper's footnote: a cold LONGER rod makes the collision deterministic (eps = gamma) however
 * hot the shorter one is; a cold shorter rod does not.  Checks the assignment of the bridges to
 * the rods (period 1+gamma belongs to rod 1 of length l1), also for gamma > 1. */
static void cold_longer_rod_is_deterministic(void **state) {
  (void)state;
  gsl_rng *r = rng_seeded(3);
  hd_eps_sampler *s = make(0.8, 0);
  double sum = 0, sum2 = 0;
  int n = sanitize() ? 50 : 400;
  for (int i = 0; i < n; i++) {
    assert_true(fabs(hd_eps_sample2(s, 0.5, INFINITY, r) - 0.8) < 1e-9);
    double e = hd_eps_sample2(s, INFINITY, 0.5, r); /* shorter rod cold, longer hot */
    sum += e;
    sum2 += e * e;
  }
  double sd = sqrt(sum2 / n - (sum / n) * (sum / n));
  assert_true(sd > 0.05); /* at beta = 0.5 the spread is O(0.3) */
  hd_eps_sampler_free(s);
  s = make(1.25, 0); /* now rod 1 is the longer one */
  for (int i = 0; i < n / 4; i++)
    assert_true(fabs(hd_eps_sample2(s, INFINITY, 0.5, r) - 0.8) < 1e-9);
  hd_eps_sampler_free(s);
  gsl_rng_free(r);
}

/* eps >= 0 and finite over a wide range of temperatures; eps <= a + b - 1 = 8 for gamma = a/b =
 * 4/5 (q is periodic with period a + b, docs/mc-eps.md; approached at small beta); and
 * gamma <-> 1/gamma gives the same law (the equation depends on {Gamma_1, Gamma_2} only): same
 * seed, same samples. */
static void nonnegative_and_symmetric(void **state) {
  (void)state;
  hd_eps_sampler *a = make(0.8, 0), *b = make(1.25, 0);
  gsl_rng *ra = rng_seeded(4), *rb = rng_seeded(4);
  const double betas[] = {0.003, 0.1, 1, 10, 100};
  int n = sanitize() ? 40 : 400;
  for (int k = 0; k < 5; k++)
    for (int i = 0; i < n; i++) {
      double x = hd_eps_sample(a, betas[k], ra), y = hd_eps_sample(b, betas[k], rb);
      assert_true(isfinite(x) && x >= 0 && x <= 8 + 1e-9);
      assert_true(x == y);
    }
  hd_eps_stats st;
  hd_eps_sampler_stats(a, &st);
  assert_int_equal(st.truncated, 0);
  gsl_rng_free(ra);
  gsl_rng_free(rb);
  hd_eps_sampler_free(a);
  hd_eps_sampler_free(b);
}

/* Detailed balance, eq. (19): with E ~ Exp(1) (the collision-weighted Boltzmann law, eq. 18,
 * T_B = 1) and E' = eps^2 E, eps ~ p_E, the pair (E, E') is exchangeable.  Three consequences:
 * <E' - E> = 0, <ln(E'/E)> = 2 <ln eps> = 0, and P(E < 1/2, E' > 3/2) = P(E' < 1/2, E > 3/2).
 * Each is tested at 4.5 standard errors (false alarm 1e-5 each); the grid bias (~0.2% in eps at
 * step 0.01) is far below the resolution of n = 20000 samples.  Power: the same statistics must
 * reject a wrong temperature scale (sigma^2 = 1/beta instead of 1/(2 beta), eq. 12). */
static void detailed_balance(void **state) {
  (void)state;
  hd_eps_sampler *s = make(0.8, 0);
  gsl_rng *r = rng_seeded(5);
  int n = sanitize() ? 3000 : 20000;
  for (int wrong = 0; wrong < 2; wrong++) {
    double m[3] = {0}, m2[3] = {0};
    for (long i = 0; i < n; i++) {
      double E = gsl_ran_exponential(r, 1.0);
      double e = hd_eps_sample(s, wrong ? E / 2 : E, r);
      double E2 = e * e * E;
      double v[3] = {E2 - E, log(e), (double)(E < 0.5 && E2 > 1.5) - (double)(E2 < 0.5 && E > 1.5)};
      for (int k = 0; k < 3; k++) {
        m[k] += v[k];
        m2[k] += v[k] * v[k];
      }
    }
    double z[3];
    for (int k = 0; k < 3; k++) {
      double mean = m[k] / n, se = sqrt((m2[k] / n - mean * mean) / n);
      z[k] = mean / se;
    }
    if (!wrong) {
      for (int k = 0; k < 3; k++) {
        if (fabs(z[k]) >= 4.5) fprintf(stderr, "detailed balance statistic %d: z = %g\n", k, z[k]);
        assert_true(fabs(z[k]) < 4.5);
      }
    } else {
      assert_true(z[0] > 4.5); /* a twice hotter bath heats the rods on average */
    }
  }
  gsl_rng_free(r);
  hd_eps_sampler_free(s);
}

/* Discretisation bias: on coupled paths, eps at step 0.01 and at step 0.01/16 differ on average by
 * c (sqrt(0.01) - sqrt(0.01/16)) with c ~ 0.02 at beta = 1 (docs/mc-eps.md); we require < 0.006,
 * and that the strides API rejects a stride that is not a divisor. */
static void step_bias_is_small(void **state) {
  (void)state;
  hd_eps_opts o;
  hd_eps_opts_default(&o);
  o.adapt = 16;
  hd_eps_sampler *s;
  assert_int_equal(hd_eps_sampler_alloc(&s, 0.8, &o, NULL), HD_OK);
  gsl_rng *r = rng_seeded(6);
  const int strides[2] = {16, 1};
  double out[2], d = 0, d2 = 0;
  int n = sanitize() ? 300 : 3000;
  for (long i = 0; i < n; i++) {
    assert_int_equal(hd_eps_sample_strides(s, 1, 1, strides, 2, out, r), HD_OK);
    d += out[0] - out[1];
    d2 += (out[0] - out[1]) * (out[0] - out[1]);
  }
  double mean = d / n, se = sqrt((d2 / n - mean * mean) / n);
  assert_true(fabs(mean) < 0.006 + 3 * se);
  const int bad[1] = {3};
  assert_int_equal(hd_eps_sample_strides(s, 1, 1, bad, 1, out, r), HD_EINPUT);
  gsl_rng_free(r);
  hd_eps_sampler_free(s);
}

/* The energy moment D = <E (eps^2 - eps_ref^2)> over E ~ Exp(1), beta = E, that sets the ring's
 * stationary E_kin (E_kin shifts by about 6.6 D, docs/mc-eps.md 4b): the default sampler
 * (refined to step 0.01/128) against a reference refined to 0.01/1024 on the same paths and
 * strides (the refined noise is shared), with the default's step adaptation, at gamma = 0.8 and
 * 0.6 (the rings of issue 25).  Measured (seeds fixed, 2000 paths each): gamma = 0.8:
 * D = -0.00021 +- 0.00026 (default), -0.0057 +- 0.0033 for the plain grid on the same paths;
 * gamma = 0.6: +0.00011 +- 0.00026 and -0.0071 +- 0.0034 (20000 paths, docs/mc-eps.md 4f:
 * D(0.01/128) - D(0.01/2048) = -0.00011 +- 0.00009).  Bound: |D| < 0.00075 (0.5 % of E_kin), with
 * its s.e. < 0.0003.  The plain grid's row is printed, not held: 2000 paths resolve its bias to
 * only 1.7-2 s.e. (-0.0057 +- 0.0033, -0.0071 +- 0.0034), so a bound on it would pass by the seed
 * alone; what shows that the bound sees a biased sampler is that the grid's |D| is 8-9 times it,
 * and the ring tests of test_rods (equilibrium_table fails with the grid at step >= 0.0025). */
static void energy_moment_at(double gamma, unsigned long seed) {
  hd_eps_opts o;
  hd_eps_opts_default(&o);
  hd_eps_sampler *s;
  assert_int_equal(hd_eps_sampler_alloc(&s, gamma, &o, NULL), HD_OK);
  int ldef = hd_eps_sampler_levels(s);
  assert_int_equal(ldef, 7); /* 0.01 / 2^7 */
  hd_eps_sampler_free(s);
  o.refine = o.step / 1024;
  assert_int_equal(hd_eps_sampler_alloc(&s, gamma, &o, NULL), HD_OK);
  assert_int_equal(hd_eps_sampler_levels(s), 10);
  gsl_rng *re = rng_seeded(seed), *r = rng_seeded(1);
  int n = sanitize() ? 100 : 2000;
  double m[2] = {0}, m2[2] = {0};
  for (long i = 0; i < n; i++) {
    double E = gsl_ran_exponential(re, 1.0);
    int st = o.adapt;
    for (double b = E; st > 1 && b < 1; b *= 2) st /= 2; /* the working stride at beta = E */
    const int strides[3] = {st, st, st}, levels[3] = {0, ldef, 10};
    double out[3];
    assert_int_equal(hd_eps_sample_levels(s, E, E, strides, levels, 3, out, r), HD_OK);
    for (int k = 0; k < 2; k++) {
      double x = E * (out[k] * out[k] - out[2] * out[2]);
      m[k] += x;
      m2[k] += x * x;
    }
  }
  double d[2], se[2];
  for (int k = 0; k < 2; k++) {
    d[k] = m[k] / n;
    se[k] = sqrt((m2[k] / n - d[k] * d[k]) / n);
  }
  fprintf(stderr,
          "gamma %g: energy moment D: grid %+.5f +- %.5f, default (refined) %+.5f +- %.5f\n", gamma,
          d[0], se[0], d[1], se[1]);
  if (!sanitize()) {
    assert_true(se[1] < 0.0003);
    assert_true(fabs(d[1]) < 0.00075);
  }
  const int bad[1] = {16}, badl[1] = {11};
  double out[1];
  assert_int_equal(hd_eps_sample_levels(s, 1, 1, bad, badl, 1, out, r), HD_EINPUT);
  gsl_rng_free(r);
  gsl_rng_free(re);
  hd_eps_sampler_free(s);
}

static void refined_energy_moment(void **state) {
  (void)state;
  energy_moment_at(0.8, 12345);
  energy_moment_at(0.6, 12346);
}

/* hd_eps_sample_pair is the same path solved at the working step and at a quarter of it: with
 * richardson (r = 4 adapt = 64) the working stride at beta = 2 is 64, so the pair must equal
 * hd_eps_sample_strides at strides {64, 16} drawn from the same seed, exactly (same normals, same
 * phase).  Without richardson the pair is refused. */
static void pair_is_paired(void **state) {
  (void)state;
  hd_eps_opts o;
  hd_eps_opts_default(&o);
  o.richardson = 1;
  hd_eps_sampler *s;
  assert_int_equal(hd_eps_sampler_alloc(&s, 0.8, &o, NULL), HD_OK);
  gsl_rng *ra = rng_seeded(9), *rb = rng_seeded(9);
  const int strides[2] = {64, 16};
  for (int i = 0; i < 20; i++) {
    double c, f, out[2];
    assert_int_equal(hd_eps_sample_pair(s, 2, 2, &c, &f, ra), HD_OK);
    assert_int_equal(hd_eps_sample_strides(s, 2, 2, strides, 2, out, rb), HD_OK);
    assert_true(c == out[0] && f == out[1]);
  }
  hd_eps_sampler_free(s);
  double c, f;
  s = make(0.8, 0);
  assert_int_equal(hd_eps_sample_pair(s, 1, 1, &c, &f, ra), HD_EINPUT);
  hd_eps_sampler_free(s);
  gsl_rng_free(ra);
  gsl_rng_free(rb);
}

static void bad_input(void **state) {
  (void)state;
  hd_eps_sampler *s = NULL;
  hd_error err;
  hd_error_clear(&err);
  assert_int_equal(hd_eps_sampler_alloc(&s, 0, NULL, &err), HD_EINPUT);
  assert_null(s);
  assert_true(strlen(err.msg) > 0);
  hd_eps_opts o;
  hd_eps_opts_default(&o);
  o.adapt = 3;
  assert_int_equal(hd_eps_sampler_alloc(&s, 0.8, &o, &err), HD_EINPUT);
  s = make(0.8, 0);
  gsl_rng *r = rng_seeded(7);
  assert_true(isnan(hd_eps_sample(s, 0, r)));
  assert_true(isnan(hd_eps_sample(s, NAN, r)));
  assert_true(isnan(hd_eps_sample2(s, 1, -1, r)));
  gsl_rng_free(r);
  hd_eps_sampler_free(s);
}

/* Tables: monotone quantiles, the cold limit, agreement with direct sampling at an off-node beta
 * (mean within 4.5 standard errors of the difference plus 0.01 for interpolation in ln beta),
 * and a lossless round trip through SQLite. */
static void table_build_sample_store(void **state) {
  (void)state;
  hd_eps_sampler *s = make(0.8, 0);
  gsl_rng *r = rng_seeded(8);
  int n = sanitize() ? 200 : 1500;
  hd_eps_table *t;
  hd_error err;
  assert_int_equal(hd_eps_table_build(&t, s, 0.1, 100, 7, 65, n, r, &err), HD_OK);
  for (int k = 0; k < t->nbeta; k++)
    for (int j = 1; j < t->nu; j++) assert_true(t->q[k * t->nu + j] >= t->q[k * t->nu + j - 1]);
  assert_true(fabs(hd_eps_table_sample(t, INFINITY, r) - 0.8) < 1e-12);
  assert_true(isnan(hd_eps_table_sample(t, -1, r)));
  double b = 0.1 * pow(1000.0, 2.5 / 6); /* between nodes 2 and 3 */
  double md = 0, mt = 0, vd = 0;
  for (long i = 0; i < n; i++) {
    double x = hd_eps_sample(s, b, r), y = hd_eps_table_sample(t, b, r);
    md += x;
    mt += y;
    vd += x * x;
  }
  md /= n;
  mt /= n;
  vd = vd / n - md * md;
  assert_true(fabs(md - mt) < 4.5 * sqrt(2 * vd / n) + 0.01);

  char path[] = "/tmp/haff_test_eps_XXXXXX";
  int fd = mkstemp(path);
  assert_true(fd >= 0);
  close(fd);
  sqlite3 *db;
  assert_int_equal(sqlite3_open(path, &db), SQLITE_OK);
  int64_t id = 0;
  assert_int_equal(hd_eps_table_save(t, db, 8, &id, &err), HD_OK);
  assert_true(id > 0);
  hd_eps_table *u = NULL;
  assert_int_equal(eps_table_load(&u, db, id, 0, &err), HD_OK);
  assert_int_equal(u->nbeta, t->nbeta);
  assert_int_equal(u->nu, t->nu);
  assert_memory_equal(u->q, t->q, sizeof(double) * (size_t)(t->nbeta * t->nu));
  hd_eps_table_free(u);
  assert_int_equal(eps_table_load(&u, db, 0, 0.8, &err), HD_OK); /* newest for gamma */
  assert_true(u->beta_max == 100);
  hd_eps_table_free(u);
  sqlite3_close(db);
  unlink(path);
  char wal[64];
  snprintf(wal, sizeof wal, "%s-wal", path);
  unlink(wal);
  snprintf(wal, sizeof wal, "%s-shm", path);
  unlink(wal);
  hd_eps_table_free(t);
  gsl_rng_free(r);
  hd_eps_sampler_free(s);
}

/* Mean of E (1 - eps^2) over E ~ Exp(1) and eps drawn from the table at beta = E (T_B = 1): the
 * table's detailed-balance moment F(1) = 1 - M by plain Monte Carlo, independent of the
 * quadrature of hd_eps_table_moment.  *se gets its standard error. */
static double table_d_mc(const hd_eps_table *t, long n, gsl_rng *g, double *se) {
  double a = 0, a2 = 0;
  for (long i = 0; i < n; i++) {
    double E = gsl_ran_exponential(g, 1.0), x = hd_eps_table_sample(t, E, g), y = E * (1 - x * x);
    a += y, a2 += y * y;
  }
  a /= (double)n;
  *se = sqrt((a2 / (double)n - a * a) / (double)n);
  return a;
}

/* hd_eps_table_balance (issue 16): a small table (gamma = 0.8, 25 x 129 x 200, fixed seed) has
 * an F(1) = <E (1 - eps^2)> (= -D of docs/mc-eps.md 4b) far from 0 from its noise; the quadrature
 * of hd_eps_table_moment must agree with a Monte Carlo estimate of the same moment (1e7 draws, s.e.
 * ~1.7e-4) within 4 s.e., and after the balance the Monte Carlo F(1) must be 0 within 7e-4, which
 * is 4 s.e. and the precision the rods ring needs for its E_kin to 0.5 % (docs/mc-eps.md section
 * 4b: 1 % of E_kin is D ~ 0.0015).  The unbalanced table is checked to miss that tolerance. */
static void table_balance(void **state) {
  (void)state;
  hd_eps_sampler *s = make(0.8, 0.01);
  gsl_rng *g = rng_seeded(11);
  hd_eps_table *t = NULL;
  hd_error err;
  assert_int_equal(hd_eps_table_build(&t, s, 1e-3, 1e3, 25, 129, sanitize() ? 40 : 200, g, &err),
                   HD_OK);
  long n = sanitize() ? 1000000 : 10000000;
  double se0, d0 = table_d_mc(t, n, g, &se0), m0 = hd_eps_table_moment(t);
  double c;
  assert_int_equal(hd_eps_table_balance(t, &c, &err), HD_OK);
  double se1, d1 = table_d_mc(t, n, g, &se1), m1 = hd_eps_table_moment(t);
  printf("# table D: quadrature %.5f, MC %.5f +- %.5f; balanced (x %.5f): quadrature %.1e, MC "
         "%.5f +- %.5f\n",
         1 - m0, d0, se0, c, 1 - m1, d1, se1);
  assert_true(fabs((1 - m0) - d0) < 4 * se0);
  assert_true(fabs(1 - m1) < 1e-9);
  assert_true(fabs(c * c * m0 - 1) < 1e-12);
  for (int k = 0; k < t->nbeta; k++) /* still a quantile function: nondecreasing, >= 0 */
    for (int j = 0; j < t->nu; j++)
      assert_true(t->q[k * t->nu + j] >= 0 &&
                  (j == 0 || t->q[k * t->nu + j] >= t->q[k * t->nu + j - 1]));
  if (!sanitize()) {
    assert_true(se1 < 2e-4);
    assert_true(fabs(d0) > 7e-4); /* the unbalanced table fails the test below */
    assert_true(fabs(d1) < 7e-4);
  }
  hd_eps_table_free(t);
  gsl_rng_free(g);
  hd_eps_sampler_free(s);
}

/* CLI exit codes: --help 0, missing --gamma 2, bad value 2, --tabulate without --db 2. */
static void cli_usage(void **state) {
  (void)state;
  char *a1[] = {"eps", "--gamma", "0.8", "--beta", "zero", NULL};
  assert_int_equal(hd_cmd_mc_eps(5, a1), 2);
  char *a2[] = {"eps", "--beta", "1", NULL};
  assert_int_equal(hd_cmd_mc_eps(3, a2), 2);
  char *a3[] = {"eps", "--gamma", "0.8", "--tabulate", NULL};
  assert_int_equal(hd_cmd_mc_eps(4, a3), 2);
  char *a4[] = {"eps", "--gamma", "-1", "--samples", "3", NULL};
  assert_int_equal(hd_cmd_mc_eps(5, a4), 2);
}

int main(void) {
  const struct CMUnitTest tests[] = {cmocka_unit_test(cold_baths_give_gamma),
                                     cmocka_unit_test(equal_rods_are_elastic),
                                     cmocka_unit_test(cold_longer_rod_is_deterministic),
                                     cmocka_unit_test(nonnegative_and_symmetric),
                                     cmocka_unit_test(detailed_balance),
                                     cmocka_unit_test(step_bias_is_small),
                                     cmocka_unit_test(refined_energy_moment),
                                     cmocka_unit_test(pair_is_paired),
                                     cmocka_unit_test(bad_input),
                                     cmocka_unit_test(table_build_sample_store),
                                     cmocka_unit_test(table_balance),
                                     cmocka_unit_test(cli_usage)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
