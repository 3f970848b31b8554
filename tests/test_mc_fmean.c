/* Tests of mc/fmean: the allowed contact angle, the heuristic <f> by quadrature and Monte
 * Carlo, the exclusion and collision models, and the convergence study.
 *
 * Statistical checks use fixed seeds and a tolerance of 4 standard errors: for a Gaussian
 * estimator the two-sided false-alarm rate is 2 (1 - Phi(4)) = 6.3e-5 per check, so the ~30
 * such checks below together fail by chance with probability ~2e-3 for a new seed, while a real
 * bias of a few standard errors is still caught.  (With the fixed seeds they are deterministic.) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fmean.h"
#include "fmean_stats.h"

/* Sample sizes shrink under the sanitizers (HAFF_SANITIZE=1); the checks stay the same. */
static unsigned long scaled(unsigned long n) {
  const char *s = getenv("HAFF_SANITIZE");
  return (s && s[0] == '1') ? n / 10 : n;
}

/* ---- independent reference geometry and integrals (not using the library) ------------------ */

/* Does a disk of diameter 1 at (x, y) overlap one at (px, py)?  (distance < 1) */
static int overlaps(double x, double y, double px, double py) {
  return hypot(x - px, y - py) < 1.0 - 1e-12;
}

/* Nested 2-D GSL quadrature of g(t1, t2) over [0, L]^2, divided by L^2. */
typedef double (*fn2)(double, double);
typedef struct nest {
  fn2 g;
  double L, t1;
  gsl_integration_workspace *w_in;
} nest;

static double nest_inner(double t2, void *p) {
  nest *n = p;
  return n->g(n->t1, t2);
}

static double nest_outer(double t1, void *p) {
  nest *n = p;
  n->t1 = t1;
  gsl_function F = {nest_inner, n};
  double v, e;
  gsl_integration_qag(&F, 0.0, n->L, 1e-14, 1e-12, 1000, GSL_INTEG_GAUSS61, n->w_in, &v, &e);
  return v;
}

static double mean2d(fn2 g, double L) {
  nest n = {g, L, 0.0, gsl_integration_workspace_alloc(1000)};
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
  gsl_function F = {nest_outer, &n};
  double v, e;
  gsl_integration_qag(&F, 0.0, L, 1e-14, 1e-12, 1000, GSL_INTEG_GAUSS61, w, &v, &e);
  gsl_integration_workspace_free(w);
  gsl_integration_workspace_free(n.w_in);
  return v / (L * L);
}

/* f of eq. 36 written directly from the paper, in the a -> 0 form 2 / (2 + sin^2 + sin^2). */
static double f_paper(double t1, double t2) {
  double s1 = sin(t1), s2 = sin(t2);
  return 2.0 / (2.0 + s1 * s1 + s2 * s2);
}

/* ---- the allowed angle --------------------------------------------------------------------- */

/* Brute force: A's contacting disk at the origin with outward axis +x, partner at (-a, 0); the
 * other dimer's contacting disk at distance d = 1 in direction theta.  On a grid of 200001
 * angles in (-pi, pi], "no overlap with the partner" must hold exactly for |theta| <= theta_max,
 * up to one grid step at the boundary. */
static void theta_max_brute_force(void **state) {
  (void)state;
  const double as[] = {0.1, 0.5, 1.0, 1.5, 1.99, 2.5};
  const int ng = 200000;
  const double h = 2.0 * M_PI / ng;
  for (size_t i = 0; i < sizeof as / sizeof as[0]; i++) {
    double a = as[i], tm = hd_fmean_theta_max(a), last_ok = 0.0;
    for (int g = 1; g <= ng; g++) {
      double th = -M_PI + g * h;
      int ok = !overlaps(cos(th), sin(th), -a, 0.0);
      if (fabs(fabs(th) - tm) > h) assert_int_equal(ok, fabs(th) <= tm);
      if (ok && fabs(th) > last_ok) last_ok = fabs(th);
    }
    /* the largest allowed grid angle is within one step of theta_max */
    assert_true(fabs(last_ok - tm) <= h);
  }
  assert_true(fabs(hd_fmean_theta_max(1.0) - 2.0 * M_PI / 3.0) < 1e-14); /* Fig. 4 */
  assert_true(hd_fmean_theta_max(2.0) == M_PI);
  assert_true(hd_fmean_theta_max(3.0) == M_PI);
  assert_true(isnan(hd_fmean_theta_max(0.0)));
  assert_true(isnan(hd_fmean_theta_max(-1.0)));
}

/* hd_fmean_sample_contact: the angles it reports follow DESIGN.md's convention (recomputed
 * here from the configuration), its accept flag is exactly "no disk pair overlaps but the
 * touching one", and accepted contacts respect |theta| <= theta_max for both dimers. */
static void sample_contact_geometry(void **state) {
  (void)state;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 7);
  const double as[] = {0.3, 1.0, 1.7, 2.5};
  for (size_t i = 0; i < sizeof as / sizeof as[0]; i++) {
    double a = as[i], tm = hd_fmean_theta_max(a);
    for (int pp = 0; pp <= 1; pp++)
      for (int k = 0; k < 20000; k++) {
        double ta, tb, cfg[2];
        int acc = hd_fmean_sample_contact(r, a, pp, &ta, &tb, cfg);
        double nx = cos(cfg[0]), ny = sin(cfg[0]); /* normal A1 -> B1 */
        double ux = cos(cfg[1]), uy = sin(cfg[1]); /* B's outward axis (B2 -> B1) */
        double b1x = nx, b1y = ny, b2x = nx - a * ux, b2y = ny - a * uy;
        /* theta_A: from +x to n; theta_B: from u_B to -n (signed, counter-clockwise) */
        double ta_ref = atan2(ny, nx);
        double tb_ref = atan2(ux * (-ny) - uy * (-nx), ux * (-nx) + uy * (-ny));
        assert_true(fabs(ta - ta_ref) < 1e-12);
        assert_true(fabs(tb - tb_ref) < 1e-12 || fabs(fabs(tb - tb_ref) - 2 * M_PI) < 1e-12);
        assert_true(ta > -M_PI && ta <= M_PI && tb > -M_PI && tb <= M_PI);
        int bad = overlaps(b1x, b1y, -a, 0.0) || overlaps(b2x, b2y, 0.0, 0.0) ||
                  (!pp && overlaps(b2x, b2y, -a, 0.0));
        assert_int_equal(acc, !bad);
        if (acc) assert_true(fabs(ta) <= tm + 1e-12 && fabs(tb) <= tm + 1e-12);
      }
  }
  gsl_rng_free(r);
}

/* ---- heuristic: quadrature, Monte Carlo, the paper's numbers, limits ------------------------ */

/* The library's 1-D quadrature (inner integral analytic) against a nested 2-D GSL quadrature
 * of eq. 36 done here: both are deterministic, so they must agree to ~1e-10. */
static void quadrature_vs_nested(void **state) {
  (void)state;
  const double as[] = {0.1, 0.5, 1.0, 1.5, 1.99, 2.5};
  for (size_t i = 0; i < sizeof as / sizeof as[0]; i++) {
    double f, e;
    assert_int_equal(hd_fmean_quadrature(as[i], &f, &e), HD_OK);
    double ref = mean2d(hd_fmean_f, hd_fmean_theta_max(as[i]));
    assert_true(fabs(f - ref) < 1e-10);
    assert_true(e < 1e-10);
  }
  double f, e;
  assert_int_equal(hd_fmean_quadrature(0.0, &f, &e), HD_EINPUT);
  assert_int_equal(hd_fmean_quadrature(-1.0, &f, &e), HD_EINPUT);
}

/* Monte Carlo against quadrature within 4 standard errors (see the top of the file). */
static void heuristic_mc_vs_quadrature(void **state) {
  (void)state;
  const double as[] = {0.1, 0.5, 1.0, 1.5, 2.5};
  for (size_t i = 0; i < sizeof as / sizeof as[0]; i++) {
    hd_fmean_opts o;
    hd_fmean_result r;
    hd_error err;
    hd_fmean_opts_default(&o);
    o.a_over_d = as[i];
    o.samples = scaled(1000000);
    o.seed = 11 + i;
    assert_int_equal(hd_fmean_run(&o, &r, &err), HD_OK);
    assert_int_equal(r.samples, o.samples);
    assert_true(r.f_stderr > 0.0 && r.f_stderr < 1e-3);
    assert_true(fabs(r.f_mean - r.f_quad) < 4.0 * r.f_stderr);
    assert_true(fabs(r.d_e - 2.0 / r.f_mean) < 1e-12);
    assert_true(fabs(r.d_e_stderr - 2.0 * r.f_stderr / (r.f_mean * r.f_mean)) < 1e-12);
  }
}

/* The paper (a = d): <f> = 0.64 and D_e = D/<f> = 3.12, rounded to the 2 decimals printed. */
static void paper_values_at_a_equal_d(void **state) {
  (void)state;
  double f, e;
  char buf[32];
  assert_int_equal(hd_fmean_quadrature(1.0, &f, &e), HD_OK);
  snprintf(buf, sizeof buf, "%.2f", f);
  assert_string_equal(buf, "0.64");
  snprintf(buf, sizeof buf, "%.2f", 2.0 / f);
  assert_string_equal(buf, "3.12");
  /* and the Monte Carlo run rounds the same way */
  hd_fmean_opts o;
  hd_fmean_result r;
  hd_error err;
  hd_fmean_opts_default(&o);
  o.samples = scaled(1000000);
  assert_int_equal(hd_fmean_run(&o, &r, &err), HD_OK);
  snprintf(buf, sizeof buf, "%.2f %.2f", r.f_mean, r.d_e);
  assert_string_equal(buf, "0.64 3.12");
}

/* a -> 0: theta_max -> pi/2 (+a/2d to first order) and <f> -> the mean of 2/(2 + sin^2 th1 +
 * sin^2 th2) over [0, pi/2]^2.  At a/d = 1e-3, theta_max = pi/2 + 5e-4; moving the edge of the
 * square by dL changes its mean by (2/L)(edge mean - square mean) dL, and f is in [1/2, 1], so
 * |<f>(1e-3) - limit| <= (2/(pi/2)) (1/2) 5e-4 = 3.2e-4: tolerance 3.5e-4.  a >= 2d: no
 * restriction, and f has period pi and is even, so <f> equals that same limit exactly. */
static void limits(void **state) {
  (void)state;
  double lim = mean2d(f_paper, M_PI / 2.0);
  double tm = hd_fmean_theta_max(1e-3);
  assert_true(fabs(tm - M_PI / 2.0 - 5e-4) < 1e-9);
  double f, e;
  assert_int_equal(hd_fmean_quadrature(1e-3, &f, &e), HD_OK);
  assert_true(fabs(f - lim) < 3.5e-4);
  assert_int_equal(hd_fmean_quadrature(1e-7, &f, &e), HD_OK);
  assert_true(fabs(f - lim) < 1e-7); /* same bound, scaled to dL = 5e-8 */
  const double big[] = {2.0, 2.5, 3.0, 10.0};
  for (size_t i = 0; i < sizeof big / sizeof big[0]; i++) {
    assert_int_equal(hd_fmean_quadrature(big[i], &f, &e), HD_OK);
    assert_true(fabs(f - lim) < 1e-10);
  }
  /* a >= 2d: a contacting disk can never hit the partner, so without the partner-partner
   * check every configuration is accepted. */
  hd_fmean_opts o;
  hd_fmean_result r;
  hd_error err;
  hd_fmean_opts_default(&o);
  o.model = HD_FMEAN_EXCLUSION;
  o.a_over_d = 2.5;
  o.no_partner_partner = 1;
  o.samples = scaled(100000);
  assert_int_equal(hd_fmean_run(&o, &r, &err), HD_OK);
  assert_int_equal(r.tried, r.samples);
  assert_true(fabs(r.f_mean - lim) < 4.0 * r.f_stderr);
  /* MC at a/d = 1e-3 against the a -> 0 limit: 4 standard errors plus the 3.5e-4 bound */
  o.model = HD_FMEAN_HEURISTIC;
  o.a_over_d = 1e-3;
  o.no_partner_partner = 0;
  o.samples = scaled(1000000);
  assert_int_equal(hd_fmean_run(&o, &r, &err), HD_OK);
  assert_true(fabs(r.f_mean - lim) < 4.0 * r.f_stderr + 3.5e-4);
}

/* ---- exclusion ----------------------------------------------------------------------------- */

/* Without the partner-partner check, the two remaining constraints each involve one angle, and
 * the normal and B's axis are uniform: the accepted angles are independent and uniform on
 * [-theta_max, theta_max], i.e. the heuristic model.  So <f> must match the quadrature within
 * 4 standard errors, and the acceptance rate (theta_max/pi)^2 within 4 binomial errors. */
static void exclusion_without_pp_is_heuristic(void **state) {
  (void)state;
  const double as[] = {0.5, 1.0, 1.5, 1.99};
  for (size_t i = 0; i < sizeof as / sizeof as[0]; i++) {
    hd_fmean_opts o;
    hd_fmean_result r;
    hd_error err;
    hd_fmean_opts_default(&o);
    o.model = HD_FMEAN_EXCLUSION;
    o.no_partner_partner = 1;
    o.a_over_d = as[i];
    o.samples = scaled(400000);
    o.seed = 100 + i;
    assert_int_equal(hd_fmean_run(&o, &r, &err), HD_OK);
    double fq, fe;
    assert_int_equal(hd_fmean_quadrature(as[i], &fq, &fe), HD_OK);
    assert_true(fabs(r.f_mean - fq) < 4.0 * r.f_stderr);
    double p = pow(hd_fmean_theta_max(as[i]) / M_PI, 2.0);
    double acc = (double)r.samples / (double)r.tried;
    assert_true(fabs(acc - p) < 4.0 * sqrt(p * (1.0 - p) / (double)r.tried));
  }
}

/* With the partner-partner check the model is not the heuristic one: at a = d, <f> differs
 * from the quadrature by many standard errors (the constraint removes configurations with both
 * dimers side by side, where cos^2 is small). */
static void exclusion_differs_from_heuristic(void **state) {
  (void)state;
  hd_fmean_opts o;
  hd_fmean_result r;
  hd_error err;
  hd_fmean_opts_default(&o);
  o.model = HD_FMEAN_EXCLUSION;
  o.samples = scaled(400000);
  assert_int_equal(hd_fmean_run(&o, &r, &err), HD_OK);
  double fq, fe;
  hd_fmean_quadrature(1.0, &fq, &fe);
  assert_true(r.f_mean - fq > 10.0 * r.f_stderr);
  assert_true(r.samples < r.tried);
}

/* ---- collision ----------------------------------------------------------------------------- */

/* At a fixed configuration the normal approach speed is Gaussian with variance
 * (T/2m)(2 + sin^2 th_A + sin^2 th_B) = T/(m f), so E[max(0, -v_n)] is proportional to
 * f^(-1/2) and the collision-weighted <f> is <f^(1/2)>_excl / <f^(-1/2)>_excl.  That estimate
 * is computed here from independent exclusion samples (other seed) and the two must agree
 * within 4 combined standard errors. */
static void collision_vs_rao_blackwell(void **state) {
  (void)state;
  const double as[] = {0.5, 1.0, 2.5};
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 999);
  for (size_t i = 0; i < sizeof as / sizeof as[0]; i++) {
    hd_fmean_opts o;
    hd_fmean_result r;
    hd_error err;
    hd_fmean_opts_default(&o);
    o.model = HD_FMEAN_COLLISION;
    o.a_over_d = as[i];
    o.samples = scaled(600000);
    o.seed = 200 + i;
    assert_int_equal(hd_fmean_run(&o, &r, &err), HD_OK);
    hd_fmean_moments m;
    hd_fmean_moments_init(&m, 2);
    double num[1024], den[1024];
    unsigned long got = 0;
    while (got < scaled(600000)) {
      size_t k = 0;
      while (k < 1024) {
        double ta, tb;
        if (!hd_fmean_sample_contact(rng, as[i], 0, &ta, &tb, NULL)) continue;
        double f = hd_fmean_f(ta, tb);
        num[k] = sqrt(f);
        den[k] = 1.0 / sqrt(f);
        k++;
      }
      const double *cols[2] = {num, den};
      hd_fmean_moments_add_batch(&m, cols, k);
      got += k;
    }
    double rb, rb_se;
    hd_fmean_moments_ratio(&m, 0, 1, &rb, &rb_se);
    assert_true(fabs(r.f_mean - rb) < 4.0 * hypot(r.f_stderr, rb_se));
  }
  gsl_rng_free(rng);
}

/* The energy balance (docs/mc-fmean.md): per collision <f v_n^2>_coll = 2T/m exactly, for any
 * a/d, so the consistent effective dimension 4E/(m <f v_n^2>) with E = 3T/2 is 3, within 4
 * standard errors.  The paper's D/<f> with the same collision-weighted <f> is not: at a = d
 * it is ~3.12, over 10 of its standard errors from 3. */
static void collision_energy_balance(void **state) {
  (void)state;
  const double as[] = {0.01, 0.5, 1.0, 1.5, 3.0};
  for (size_t i = 0; i < sizeof as / sizeof as[0]; i++) {
    hd_fmean_opts o;
    hd_fmean_result r;
    hd_error err;
    hd_fmean_opts_default(&o);
    o.model = HD_FMEAN_COLLISION;
    o.a_over_d = as[i];
    o.samples = scaled(600000);
    o.seed = 300 + i;
    assert_int_equal(hd_fmean_run(&o, &r, &err), HD_OK);
    assert_true(fabs(r.fvn2 - 2.0) < 4.0 * r.fvn2_stderr);
    assert_true(fabs(r.d_e_energy - 3.0) < 4.0 * r.d_e_energy_stderr);
    if (as[i] == 1.0) assert_true(r.d_e - 3.0 > 10.0 * r.d_e_stderr);
  }
}

/* ---- any shape ------------------------------------------------------------------------------ */

/* The shapes of the tests: the dimer of a = d as a general cluster, and trimers. */
static hd_shape shape_of(int which) {
  hd_shape sh;
  double x[3] = {0, 1, 2}, y[3] = {0, 0, 0}, d[3] = {1, 1, 1}, m[3] = {1, 1, 1};
  if (which == 1) x[2] = 0.5, y[2] = sqrt(3) / 2; /* triangle */
  if (which == 2) x[0] = 1, x[1] = 0, x[2] = cos(2 * M_PI / 3), y[2] = sin(2 * M_PI / 3); /* bent */
  assert_int_equal(hd_shape_cluster(&sh, which == 3 ? 2 : 3, x, y, d, m, 0), 0);
  return sh;
}

/* The shape path (contacts drawn by hd_fmean_sample_shape, f, mu and vn from the engine's rule)
 * for the dimer of a = d reproduces the dimer path of each model (eq. 36, its own geometry)
 * within 4 combined standard errors (independent streams); its heuristic <f> is the
 * quadrature's.  For trimers (linear, triangle, bent) the collision model's <mu vn^2> is 2T
 * and D_e = 4E/<mu vn^2> = 3 within 4 standard errors (equipartition, any shape), and the
 * exclusion model rejects some configurations that the heuristic one keeps. */
static void shape_models(void **state) {
  (void)state;
  hd_shape dimer = shape_of(3);
  for (int m = HD_FMEAN_HEURISTIC; m <= HD_FMEAN_COLLISION; m++) {
    hd_fmean_opts o;
    hd_fmean_result r1, r2;
    hd_error err;
    hd_fmean_opts_default(&o);
    o.model = (hd_fmean_model)m;
    o.samples = scaled(400000);
    o.seed = 400 + (unsigned long)m;
    assert_int_equal(hd_fmean_run(&o, &r1, &err), HD_OK);
    o.shape = &dimer;
    o.seed = 500 + (unsigned long)m;
    assert_int_equal(hd_fmean_run(&o, &r2, &err), HD_OK);
    printf("# %s: dimer path <f> %.5f +- %.5f, shape path %.5f +- %.5f\n",
           hd_fmean_model_name(o.model), r1.f_mean, r1.f_stderr, r2.f_mean, r2.f_stderr);
    assert_true(fabs(r1.f_mean - r2.f_mean) < 4.0 * hypot(r1.f_stderr, r2.f_stderr));
    if (m == HD_FMEAN_HEURISTIC) assert_true(fabs(r2.f_mean - r1.f_quad) < 4.0 * r2.f_stderr);
  }
  for (int w = 0; w < 3; w++) {
    hd_shape sh = shape_of(w);
    hd_fmean_opts o;
    hd_fmean_result r, h;
    hd_error err;
    hd_fmean_opts_default(&o);
    o.shape = &sh;
    o.model = HD_FMEAN_COLLISION;
    o.samples = scaled(400000);
    o.seed = 600 + (unsigned long)w;
    assert_int_equal(hd_fmean_run(&o, &r, &err), HD_OK);
    o.model = HD_FMEAN_HEURISTIC;
    assert_int_equal(hd_fmean_run(&o, &h, &err), HD_OK);
    printf("# trimer %d: collision <f> %.5f, <mu vn^2> %.4f +- %.4f, D_e %.4f +- %.4f; "
           "heuristic <f> %.5f, acceptance %.3f vs %.3f\n",
           w, r.f_mean, r.fvn2, r.fvn2_stderr, r.d_e_energy, r.d_e_energy_stderr, h.f_mean,
           (double)r.samples / (double)r.tried, (double)h.samples / (double)h.tried);
    assert_true(fabs(r.fvn2 - 2.0) < 4.0 * r.fvn2_stderr);
    assert_true(fabs(r.d_e_energy - 3.0) < 4.0 * r.d_e_energy_stderr);
    assert_true((double)r.samples / (double)r.tried < (double)h.samples / (double)h.tried);
    assert_true(isnan(h.f_quad));
  }
}

/* ---- statistics helper, convergence, input errors ------------------------------------------ */

/* Batch-merged moments equal gsl_stats on the whole array (deterministic: 1e-12 relative). */
static void moments_merge_exact(void **state) {
  (void)state;
  enum { N = 5003 };
  static double x[N], y[N];
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 3);
  for (int i = 0; i < N; i++) {
    x[i] = 5.0 + gsl_rng_uniform(r);
    y[i] = x[i] * x[i] + gsl_rng_uniform(r);
  }
  hd_fmean_moments m;
  hd_fmean_moments_init(&m, 2);
  for (size_t s = 0, b = 1; s < N; s += b, b = b * 2 + 1) {
    size_t k = s + b > N ? N - s : b;
    const double *cols[2] = {x + s, y + s};
    hd_fmean_moments_add_batch(&m, cols, k);
  }
  double mx = 0, my = 0;
  for (int i = 0; i < N; i++) mx += x[i], my += y[i];
  mx /= N, my /= N;
  double vx = 0, cxy = 0;
  for (int i = 0; i < N; i++) vx += (x[i] - mx) * (x[i] - mx), cxy += (x[i] - mx) * (y[i] - my);
  assert_true(m.n == N);
  assert_true(fabs(m.mean[0] - mx) < 1e-12 * mx && fabs(m.mean[1] - my) < 1e-12 * my);
  assert_true(fabs(hd_fmean_moments_var(&m, 0) - vx / (N - 1)) < 1e-10 * vx / (N - 1));
  assert_true(fabs(m.cd[0][1] - cxy) < 1e-10 * fabs(cxy));
  gsl_rng_free(r);
}

/* The error falls as n^(-1/2): the fitted slope of log rms error vs log n over n = 1e3..1e5
 * must be within 4 of its (fit) standard errors of -1/2, and that error must be small enough
 * (< 0.1) for the check to mean something. */
static void convergence_slope(void **state) {
  (void)state;
  hd_fmean_conv_row rows[8];
  size_t nr;
  double slope, se;
  hd_error err;
  unsigned long nmax = scaled(100000);
  assert_int_equal(hd_fmean_convergence(1.0, 5, 1e9, nmax, rows, 8, &nr, &slope, &se, &err), HD_OK);
  assert_int_equal(nr, nmax >= 100000 ? 3 : 2);
  assert_int_equal(rows[0].n, 1000);
  assert_int_equal(rows[0].reps, 1000);
  assert_true(se < 0.1);
  assert_true(fabs(slope + 0.5) < 4.0 * se);
}

static void bad_input(void **state) {
  (void)state;
  hd_fmean_opts o;
  hd_fmean_result r;
  hd_error err;
  hd_fmean_opts_default(&o);
  o.a_over_d = 0.0;
  assert_int_equal(hd_fmean_run(&o, &r, &err), HD_EINPUT);
  assert_true(err.msg[0] != '\0');
  o.a_over_d = NAN;
  assert_int_equal(hd_fmean_run(&o, &r, &err), HD_EINPUT);
  hd_fmean_opts_default(&o);
  o.samples = 0;
  o.seconds = 0.0;
  assert_int_equal(hd_fmean_run(&o, &r, &err), HD_EINPUT);
  /* the time-budget mode draws some samples and gives an error estimate */
  o.seconds = 0.02;
  assert_int_equal(hd_fmean_run(&o, &r, &err), HD_OK);
  assert_true(r.samples >= 2 && r.f_stderr > 0.0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(theta_max_brute_force),
      cmocka_unit_test(sample_contact_geometry),
      cmocka_unit_test(quadrature_vs_nested),
      cmocka_unit_test(heuristic_mc_vs_quadrature),
      cmocka_unit_test(paper_values_at_a_equal_d),
      cmocka_unit_test(limits),
      cmocka_unit_test(exclusion_without_pp_is_heuristic),
      cmocka_unit_test(exclusion_differs_from_heuristic),
      cmocka_unit_test(collision_vs_rao_blackwell),
      cmocka_unit_test(collision_energy_balance),
      cmocka_unit_test(shape_models),
      cmocka_unit_test(moments_merge_exact),
      cmocka_unit_test(convergence_slope),
      cmocka_unit_test(bad_input),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
