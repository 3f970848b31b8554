/* Tests of the ring of rods (engine/rods/rods.h): conservation laws to round-off, the collision
 * rule with the true masses, exact checkpoints, collapse detection against McNamara and Young, the
 * stationary kinetic energy and collision rate against the ideal-gas theory (docs/rods.md). */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
// clang-format on

#include <gsl/gsl_fit.h>
#include <gsl/gsl_sort.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_scene.h"
#include "hd_sim.h"
#include "rods.h"
#include "test_util.h"

/* The default parameters with n rods, nmod modes per rod and a seed. */
static hd_rods_params params(long n, long nmod, unsigned long long seed) {
  hd_rods_params p;
  hd_rods_params_default(&p);
  p.n = n;
  p.nmod = nmod;
  p.seed = seed;
  return p;
}

/* A ring of parameters p (the allocation must succeed). */
static hd_rods *alloc_ok(const hd_rods_params *p) {
  hd_rods *r;
  hd_error e;
  assert_int_equal(hd_rods_alloc(&r, p, &e), HD_OK);
  return r;
}

static hd_rods *make(long n, long nmod, hd_rods_model model, double eps, unsigned long long seed) {
  hd_rods_params p = params(n, nmod, seed);
  p.model = model;
  p.eps = eps;
  return alloc_ok(&p);
}

static double momentum(const hd_rods *r) {
  double P = 0;
  for (long i = 0; i < r->p.n; i++) P += r->m[i] * r->v[i];
  return P;
}

/* Units: masses 1 + gamma and 1 + 1/gamma give mu = 1; E_kin(0) = N T0/2 exactly; P = 0. */
static void initial_state(void **state) {
  (void)state;
  hd_rods *r = make(100, 10, HD_RODS_STOCHASTIC, 0.8, 5);
  double mu = r->m[0] * r->m[1] / (r->m[0] + r->m[1]);
  assert_true(fabs(mu - 1) < 1e-15);
  assert_true(fabs(r->m[0] / r->m[1] - 0.8) < 1e-15);
  double ek, eb;
  hd_rods_energy(r, &ek, &eb, NULL);
  assert_true(fabs(ek - 50) < 1e-12 && eb == 0);
  assert_true(fabs(momentum(r)) < 1e-12);
  double x[100], gsum = 0;
  hd_rods_positions(r, x);
  for (long k = 0; k < 100; k++) {
    assert_true(x[k] >= 0 && x[k] < 100);
    gsum += r->g[k];
  }
  assert_true(fabs(gsum - 100) < 1e-10); /* the gaps fill the ring */
  hd_rods_free(r);
}

/* One collision: u -> -eps u and momentum conserved with the true masses; the paper's
 * eq. (30-32) (each velocity changes by (1+eps)/2 u) would change the momentum by
 * (1+eps) u (m_i - m_j)/2, which is not zero for gamma != 1. */
static void collision_rule(void **state) {
  (void)state;
  hd_rods *r = make(2, 10, HD_RODS_CONSTANT, 0.5, 1);
  double v0 = r->v[0], v1 = r->v[1], P0 = momentum(r);
  hd_rods_event ev;
  hd_error e;
  assert_int_equal(hd_rods_next(r, INFINITY, &ev, &e), HD_OK);
  long a = ev.i, b = ev.j;
  double u = (a == 0 ? v1 - v0 : v0 - v1);
  assert_true(fabs(ev.u - u) < 1e-15);
  assert_true(fabs((r->v[b] - r->v[a]) - (-0.5 * u)) < 1e-14);
  assert_true(fabs(momentum(r) - P0) < 1e-14);
  /* the energy lost, (1 - eps^2) u^2/2, is in the two baths: eq. (29) */
  double ek, eb;
  hd_rods_energy(r, &ek, &eb, NULL);
  assert_true(fabs(eb - 0.75 * 0.5 * u * u) < 1e-14);
  assert_true(fabs(ev.tb_i - 0.75 * 0.5 * u * u / 20) < 1e-15);
  /* the printed eq. (30-32) with these masses */
  double dP_paper = (1 + 0.5) * u * 0.5 * (r->m[a] - r->m[b]);
  assert_true(fabs(dP_paper) > 0.01 * fabs(u));
  hd_rods_free(r);
}

/* Translational + bath energy and the momentum are conserved to round-off over 10^6
 * collisions (10^5 sanitized).  Tolerance 1e-9 relative: each collision adds O(1e-16) errors. */
static void conservation(void **state) {
  (void)state;
  hd_rods_params p;
  hd_rods_params_default(&p);
  p.n = 100;
  p.nmod = 10;
  p.seed = 11;
  p.table = 1; /* the tabulated sampler: fast, and the bookkeeping is the same */
  hd_rods *r;
  hd_error e0;
  assert_int_equal(hd_rods_alloc(&r, &p, &e0), HD_OK);
  long nc = test_size(1000000, 10);
  hd_rods_event ev;
  hd_error e;
  double emin_eps = 10, emax_eps = 0;
  for (long c = 0; c < nc; c++) {
    assert_int_equal(hd_rods_next(r, INFINITY, &ev, &e), HD_OK);
    if (ev.eps < emin_eps) emin_eps = ev.eps;
    if (ev.eps > emax_eps) emax_eps = ev.eps;
  }
  double ek, eb, el;
  hd_rods_energy(r, &ek, &eb, &el);
  assert_true(el == 0);
  assert_true(fabs(ek + eb - 50) < 1e-9 * 50);
  assert_true(fabs(momentum(r)) < 1e-9);
  assert_true(emin_eps < 0.8 && emax_eps > 1); /* eps really is random, both ways */
  /* every gap is still >= 0 (up to round-off) and they fill the ring */
  double gs = 0;
  for (long k = 0; k < 100; k++) {
    double gk = r->g[k] + (r->v[(k + 1) % 100] - r->v[k]) * (r->t - r->gt[k]);
    assert_true(gk > -1e-9);
    gs += gk;
  }
  assert_true(fabs(gs - 100) < 1e-8);
  hd_rods_free(r);
}

/* With damping, E_kin + E_bath + E_lost = E(0) to round-off and energy is really lost. */
static void damping_balance(void **state) {
  (void)state;
  hd_rods_params p;
  hd_rods_params_default(&p);
  p.n = 50;
  p.nmod = 10;
  p.damping = 0.05;
  p.seed = 3;
  hd_rods *r;
  hd_error e;
  assert_int_equal(hd_rods_alloc(&r, &p, &e), HD_OK);
  hd_rods_event ev;
  long nc = test_size(20000, 10);
  /* the decay law itself, by hand (the balance below uses the engine's own decay): rod i's bath
   * after its collision at time tc[i] is T_i, and at any later time T_i exp(-nu (t - tc)) */
  double tc[50], tb0[50];
  for (long i = 0; i < 50; i++) tc[i] = NAN, tb0[i] = 0;
  long checked = 0;
  for (long c = 0; c < nc; c++) {
    int rc = hd_rods_next(r, INFINITY, &ev, &e);
    if (rc) print_error("%s\n", e.msg);
    assert_int_equal(rc, HD_OK);
    long k = (c * 7) % 50; /* some rod that may not have collided now */
    if (!isnan(tc[k]) && k != ev.i && k != ev.j) {
      double want = tb0[k] * exp(-0.05 * (ev.t - tc[k]));
      assert_true(fabs(hd_rods_tb(r, k) - want) <= 1e-12 * want);
      checked++;
    }
    tc[ev.i] = tc[ev.j] = ev.t, tb0[ev.i] = ev.tb_i, tb0[ev.j] = ev.tb_j;
  }
  assert_true(checked > nc / 2);
  double ek, eb, el;
  hd_rods_energy(r, &ek, &eb, &el);
  assert_true(fabs(ek + eb + el - 25) < 1e-9 * 25);
  assert_true(el > 1); /* at least 4% of the energy has gone */
  hd_rods_free(r);
}

/* gamma = 1 gives eps = 1 for every collision (paper Sec. II B): an elastic gas. */
static void gamma_one_elastic(void **state) {
  (void)state;
  hd_rods_params p;
  hd_rods_params_default(&p);
  p.n = 20;
  p.gamma = 1;
  hd_rods *r;
  hd_error e;
  assert_int_equal(hd_rods_alloc(&r, &p, &e), HD_OK);
  hd_rods_event ev;
  for (int c = 0; c < 10000; c++) {
    assert_int_equal(hd_rods_next(r, INFINITY, &ev, &e), HD_OK);
    assert_true(ev.eps == 1.0);
  }
  double ek, eb;
  hd_rods_energy(r, &ek, &eb, NULL);
  assert_true(fabs(ek - 10) < 1e-11 && eb == 0);
  hd_rods_free(r);
}

/* Runs a ring from params for nc collisions, checkpointing after nc/2 and restoring into a new
 * ring: the restored ring's collisions equal the uninterrupted ones bit for bit. */
static void checkpoint_case(const hd_rods_params *p, long nc) {
  hd_rods *a, *b;
  hd_error e;
  assert_int_equal(hd_rods_alloc(&a, p, &e), HD_OK);
  assert_int_equal(hd_rods_alloc(&b, p, &e), HD_OK);
  hd_rods_event ea, eb;
  for (long c = 0; c < nc / 2; c++) {
    assert_int_equal(hd_rods_next(a, INFINITY, &ea, &e), HD_OK);
    assert_int_equal(hd_rods_next(b, INFINITY, &eb, &e), HD_OK);
  }
  void *blob;
  size_t n;
  assert_int_equal(hd_rods_checkpoint(b, &blob, &n, &e), HD_OK);
  hd_rods_free(b);
  assert_int_equal(hd_rods_alloc_restore(&b, p, blob, n, &e), HD_OK);
  /* a blob of another ring is refused */
  hd_rods_params q = *p;
  q.n = p->n + 2;
  hd_rods *c2;
  assert_int_equal(hd_rods_alloc_restore(&c2, &q, blob, n, &e), HD_EINPUT);
  assert_int_equal(hd_rods_alloc_restore(&c2, p, blob, n - 1, &e), HD_EINPUT);
  free(blob);
  for (long c = nc / 2; c < nc; c++) {
    assert_int_equal(hd_rods_next(a, INFINITY, &ea, &e), HD_OK);
    assert_int_equal(hd_rods_next(b, INFINITY, &eb, &e), HD_OK);
    assert_true(memcmp(&ea, &eb, sizeof ea) == 0);
  }
  hd_rods_free(a);
  hd_rods_free(b);
}

static void checkpoint_exact(void **state) {
  (void)state;
  hd_rods_params p;
  hd_rods_params_default(&p);
  p.n = 64;
  p.nmod = 5;
  p.seed = 9;
  checkpoint_case(&p, test_size(40000, 4));
  p.damping = 0.02;
  p.tc = 0.01;
  p.unequal = 1;
  checkpoint_case(&p, test_size(40000, 4));
}

/* The damped ring of scenes/rods-damped50.ini (50 rods, N_mod = 1000, nu = 0.01, eps table) at
 * seed 5 was stopped as collapsed at t = 404360 (60545 collisions): 64 collisions less than
 * 1e-12 t = 4e-7 apart, at spacings going up and down between 1e-8 and 5e-7, which is two slow
 * clusters meeting, not a collapse (the paper: the damped model does not collapse).  The
 * detector also wants the spacing to fall by 1e6 over the run of tiny collisions; the ring now
 * runs to t = 1e6.  Deterministic (fixed seed); the test failed with the old criterion on the
 * unbalanced table of that time.  Since the table is balanced (issue 16, hd_eps_table_balance)
 * the trajectory differs: 56744 collisions to t = 1e6, so the count is checked against that. */
static void damped_no_false_collapse(void **state) {
  (void)state;
  hd_rods_params p = params(50, 1000, 5);
  p.damping = 0.01;
  p.table = 1;
  hd_rods *r = alloc_ok(&p);
  hd_error e;
  hd_rods_event ev;
  int rc;
  while ((rc = hd_rods_next(r, 1e6, &ev, &e)) == HD_OK) {
  }
  if (rc != HD_SIM_STOPTIME) print_error("%s\n", e.msg);
  printf("# damped 50 rods, seed 5: %lld collisions to t = %g\n", (long long)r->collisions, r->t);
  assert_int_equal(rc, HD_SIM_STOPTIME);
  assert_true(r->collisions >= 56744);
  hd_rods_free(r);
}

/* The paper's Fig. 11: 50 damped rods (N_mod = 1000, nu = 0.01, gamma = 0.8, table) cool on
 * average as E ~ t^-2, with steps where clusters meet.  Measured: the log of the mean over 12
 * seeds of E_kin at 41 times 10^(1 + k/10) up to 10^5 (E is constant between collisions) has
 * slope -1.95 (seeds 1-12), -1.90 (9-20), -1.92 (1-20); bootstrap s.e. of 12 seeds 0.016-0.026.
 * Tolerance 0.25 (5x the spread of two seed sets): the same ring undamped levels off at
 * equipartition (slope ~ -0.6 over that window), a bath that never gives energy back collapses.
 * Fixed seeds 1-12.  (Up to 10^6 the mean steepens: -2.10 +- 0.03 from 10, -2.4 +- 0.09 from 10^3;
 * docs/rods.md.) */
static void damped_energy_t_minus_2(void **state) {
  (void)state;
  if (test_sanitized()) return; /* 12 rings to t = 1e5: slow under ASan */
  enum { NT = 41, NS = 12 };
  double tg[NT], em[NT] = {0}, lx[NT], ly[NT];
  for (int k = 0; k < NT; k++) tg[k] = pow(10.0, 1.0 + 0.1 * k);
  for (int s = 1; s <= NS; s++) {
    hd_rods_params p = params(50, 1000, (unsigned long long)s);
    p.damping = 0.01;
    p.table = 1;
    hd_rods *r = alloc_ok(&p);
    hd_error e;
    hd_rods_event ev;
    for (int k = 0; k < NT; k++) {
      int rc;
      while ((rc = hd_rods_next(r, tg[k], &ev, &e)) == HD_OK) {
      }
      if (rc != HD_SIM_STOPTIME) fail_msg("seed %d, t = %g: %s", s, tg[k], e.msg);
      double ek;
      hd_rods_energy(r, &ek, NULL, NULL);
      em[k] += ek / NS;
    }
    hd_rods_free(r);
  }
  for (int k = 0; k < NT; k++) lx[k] = log10(tg[k]), ly[k] = log10(em[k]);
  double c0, c1, v00, v01, v11, ss;
  gsl_fit_linear(lx, 1, ly, 1, NT, &c0, &c1, &v00, &v01, &v11, &ss);
  printf("# damped 50 rods, 12 seeds: log10 <E_kin> slope %.3f over t = 10..1e5 (E(1e5) = %.3g)\n",
         c1, em[NT - 1]);
  assert_true(fabs(c1 + 2.0) < 0.25);
}

/* A damped ring of 1000 rods (nu = 0.01, N_mod = 1000, eps table, seed 2) forms dense clusters
 * whose collisions come ~1e-10 apart, some rounded to the same double.  The former detector (a
 * fall of the spacing by 1e6 over 64 tiny collisions, which below 1e-12 t only a spacing of 0
 * passes) stopped it as collapsed at t = 4360 (4.48e6 collisions); in the cluster the pairs draw
 * eps > 1 from their warm baths and their relative energies do not fall (docs/rods.md), and the
 * ring runs on.  Deterministic (fixed seed); it must now reach t = 5000. */
static void damped_cluster_not_collapse(void **state) {
  (void)state;
  if (test_sanitized()) return; /* 6.5e6 collisions: too slow under ASan */
  hd_rods_params p = params(1000, 1000, 2);
  p.damping = 0.01;
  p.table = 1;
  hd_rods *r = alloc_ok(&p);
  hd_error e;
  hd_rods_event ev;
  int rc;
  while ((rc = hd_rods_next(r, 5000, &ev, &e)) == HD_OK) {
  }
  if (rc != HD_SIM_STOPTIME) print_error("%s\n", e.msg);
  printf("# damped 1000 rods, seed 2: %lld collisions to t = %g\n", (long long)r->collisions, r->t);
  assert_int_equal(rc, HD_SIM_STOPTIME);
  assert_true(r->collisions > 4476270);
  hd_rods_free(r);
}

/* The criterion separates the models as the paper says (Sec. IV): 20 rods at gamma = 0.3 with
 * constant eps = 0.3 collapse within 1000 collisions (the relative energies of the tiny
 * collisions fall by more than 1e9), while the stochastic ring of the same size, seed and
 * nearly cold baths (N_mod = 1e9: eps starts at gamma) does not within 2e5: by the time its
 * collisions crowd, E_tr has fallen to the baths' temperature, beta ~ 1 and eps > 1 gives the
 * energy back. */
static void stochastic_baths_prevent_collapse(void **state) {
  (void)state;
  hd_rods_params p = params(20, 1, 3);
  p.gamma = 0.3;
  p.model = HD_RODS_CONSTANT;
  p.eps = 0.3;
  hd_rods *r = alloc_ok(&p);
  hd_error e;
  hd_rods_event ev;
  int rc = HD_OK;
  long c;
  for (c = 0; c < 1000 && rc == HD_OK; c++) rc = hd_rods_next(r, INFINITY, &ev, &e);
  printf("# constant eps = 0.3, 20 rods: %s\n", rc ? e.msg : "no collapse");
  assert_int_equal(rc, HD_ECOLLAPSE);
  assert_non_null(strstr(e.msg, "down from"));
  hd_rods_free(r);
  p.model = HD_RODS_STOCHASTIC;
  p.nmod = 1000000000L;
  r = alloc_ok(&p);
  long nc = test_size(200000, 10);
  for (c = 0; c < nc; c++) {
    rc = hd_rods_next(r, INFINITY, &ev, &e);
    if (rc) print_error("%s\n", e.msg);
    assert_int_equal(rc, HD_OK);
  }
  hd_rods_free(r);
}

/* Three rods in contact at t = 1 (a light one between two heavy ones, gamma = 0.1), the fourth
 * far away: the ring's fields are set by hand and every gap predicted again. */
static hd_rods *three_in_contact(hd_rods_model model, long nmod) {
  hd_rods_params p = params(4, nmod, 1);
  p.gamma = 0.1;
  p.model = model;
  p.eps = 0.1;
  hd_rods *r = alloc_ok(&p);
  const double g[4] = {2, 0, 0, 2}, v[4] = {0, 1, 0, -1};
  double P = 0, M = 0;
  for (int i = 0; i < 4; i++) P += r->m[i] * v[i], M += r->m[i];
  r->t = r->x0t = 1;
  r->x0 = 0;
  for (int i = 0; i < 4; i++) {
    r->g[i] = g[i], r->gt[i] = 1, r->v[i] = v[i] - P / M;
  }
  for (int k = 0; k < 4; k++) {
    double dv = r->v[(k + 1) % 4] - r->v[k];
    r->key[k] = dv < 0 ? 1 + r->g[k] / -dv : INFINITY;
  }
  hd_queue_build(r->q, 4, r->key, 1);
  return r;
}

/* A pile-up at one instant is stopped, the stochastic model's is not one (issue 16 item 2).
 * The same three rods in contact: at constant eps = gamma = 0.1 the light rod bounces between
 * the heavy ones for ever in zero time (E_tr falls geometrically): stopped as collapsed within
 * 1000 collisions, all at t = 1.  The stochastic model with nearly cold baths (N_mod = 1e15:
 * eps starts at gamma) piles up at t = 1 too (> 128 collisions at that one instant, so the
 * energy test ran), until E_tr has fallen to what the first collisions put into the baths;
 * then eps > 1 gives energy back and the rods separate (145 collisions): no collapse, and the
 * ring runs on to t = 10.  With warm baths (N_mod = 10) it ends sooner (28). */
static void pileup_one_instant(void **state) {
  (void)state;
  hd_rods *r = three_in_contact(HD_RODS_CONSTANT, 10);
  hd_rods_event ev;
  hd_error e;
  int rc = HD_OK;
  long c;
  for (c = 0; c < 1000 && (rc = hd_rods_next(r, 10, &ev, &e)) == HD_OK; c++) assert_true(ev.t == 1);
  printf("# three rods in contact, constant eps: %s\n", rc ? e.msg : "no collapse");
  assert_int_equal(rc, HD_ECOLLAPSE);
  assert_non_null(strstr(e.msg, "at t = 1 after"));
  assert_non_null(strstr(e.msg, "cluster of rods 1..3 (3 rods)"));
  hd_rods_free(r);
  const long nmods[2] = {1000000000000000L, 10};
  for (int k = 0; k < 2; k++) {
    r = three_in_contact(HD_RODS_STOCHASTIC, nmods[k]);
    long at_one = 0;
    while ((rc = hd_rods_next(r, 10, &ev, &e)) == HD_OK) at_one += ev.t == 1;
    if (rc != HD_SIM_STOPTIME) print_error("%s\n", e.msg);
    printf("# three rods in contact, stochastic, N_mod = %ld: %ld collisions at t = 1\n", nmods[k],
           at_one);
    assert_int_equal(rc, HD_SIM_STOPTIME);
    if (k == 0) assert_true(at_one > 2 * HD_RODS_TINY_RUN);
    hd_rods_free(r);
  }
}

/* A cluster resolved at one instant is not a collapse (issue 16 item 2).  500 equal rods
 * (gamma = 1: eps = 1, warm) all in contact at t = 1 with velocities in falling order
 * (multiples of 1/256, so that every elastic collision swaps two velocities exactly): the ring
 * sorts them at that one instant in exactly K(K-1)/2 = 124750 collisions (each undoes one
 * inversion), then the cluster flies apart.  The former rule (1e5 collisions at one time) stopped
 * it as collapsed, as it stopped the paper's damped ring of 10^4 rods at t = 43929.6 in a
 * cluster colliding ~1e-13 apart, below the clock's 7e-12 (docs/rods.md). */
static void cluster_at_one_instant(void **state) {
  (void)state;
  enum { K = 500 };
  hd_rods_params p = params(K, 10, 1);
  p.gamma = 1;
  hd_rods *r = alloc_ok(&p);
  r->t = r->x0t = 1;
  r->x0 = 0;
  for (long i = 0; i < K; i++) {
    r->g[i] = i + 1 < K ? 0 : K, r->gt[i] = 1, r->v[i] = ((double)K / 2 - 0.5 - (double)i) / 256;
  }
  for (long k = 0; k < K; k++) {
    double dv = r->v[(k + 1) % K] - r->v[k];
    r->key[k] = dv < 0 ? 1 + r->g[k] / -dv : INFINITY;
  }
  hd_queue_build(r->q, K, r->key, 1);
  hd_rods_event ev;
  hd_error e;
  int rc;
  long at_one = 0;
  while ((rc = hd_rods_next(r, 2, &ev, &e)) == HD_OK) {
    at_one += ev.t == 1;
    assert_true(ev.eps == 1);
  }
  if (rc != HD_SIM_STOPTIME) print_error("%s\n", e.msg);
  printf("# %d rods in contact, reversed: %ld collisions at t = 1\n", K, at_one);
  assert_int_equal(rc, HD_SIM_STOPTIME);
  assert_int_equal(at_one, K * (K - 1) / 2);
  assert_int_equal(r->collisions, at_one);
  for (long i = 0; i + 1 < K; i++) assert_true(r->v[i] < r->v[i + 1]);
  hd_rods_free(r);
}

/* Kinetic energy in the centre-of-mass frame. */
static double ekin_com(const hd_rods *r) {
  double P = 0, M = 0, e = 0;
  for (long i = 0; i < r->p.n; i++) P += r->m[i] * r->v[i], M += r->m[i];
  for (long i = 0; i < r->p.n; i++) e += 0.5 * r->m[i] * (r->v[i] - P / M) * (r->v[i] - P / M);
  return e;
}

/* A ring of 4 equal rods at constant eps = 0.3 cools for ever without collapsing.  The round-off
 * left of its zero momentum (a drift ~1e-19) used to stop it: once the speeds fell to that
 * drift's last digits (relative speeds ~6e-36 at 5e-20) collisions no longer changed them, while
 * the log still booked de.  Now every collision changes the centre-of-mass energy by its de, to
 * 1e-6 relative, however far it cools (here by more than 1e-100), and the ring was taken to its
 * centre-of-mass frame at least once. */
static void constant_cooling_below_drift(void **state) {
  (void)state;
  hd_rods_params p = params(4, 1, 2);
  p.gamma = 1;
  p.model = HD_RODS_CONSTANT;
  p.eps = 0.3;
  hd_rods *r = alloc_ok(&p);
  hd_error e;
  hd_rods_event ev;
  double e0 = ekin_com(r), ek = e0;
  long bad = 0, c;
  for (c = 0; c < 200000 && ek > 1e-100 * e0; c++) {
    int rc = hd_rods_next(r, INFINITY, &ev, &e);
    if (rc) print_error("%s\n", e.msg);
    assert_int_equal(rc, HD_OK);
    double en = ekin_com(r);
    if (!(fabs(en - ek - ev.de) <= 1e-6 * fabs(ev.de) + 1e-12 * ek)) bad++;
    ek = en;
  }
  printf("# 4 rods at eps 0.3: E_com/E0 = %.3g after %ld collisions, t = %.3g, %lld frame "
         "changes, %ld collisions whose energy change was not de\n",
         ek / e0, c, r->t, (long long)r->frames, bad);
  assert_true(ek <= 1e-100 * e0);
  assert_int_equal(bad, 0);
  assert_true(r->frames >= 1);
  hd_rods_free(r);
}

/* Draws at beta = E_tr / T_B below the eps table's grid (1e-3: slow pairs among hot baths, ~1e-3
 * of the collisions) come from the direct sampler: the table only repeated its end node there
 * (mean eps 3.39 against 5.71 at beta = 1e-5, review).  A ring of 50 rods with the table, 1e6
 * collisions; each draw's beta is read back from the event (the baths before are the mean the
 * event's bath after minus the loss share).  The ~100 draws at beta < 1e-4 must agree in mean
 * with one direct draw at each of the same betas within 4 standard errors of the difference
 * (fixed seeds; with the table's end node instead the test fails). */
static void table_below_grid(void **state) {
  (void)state;
  hd_rods_params p = params(50, 1000, 9);
  p.table = 1;
  hd_rods *r = alloc_ok(&p);
  hd_error e;
  gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(g, 99);
  hd_rods_event ev;
  double s1 = 0, s2 = 0, d1 = 0, d2 = 0;
  long m = 0, nc = test_size(1000000, 10);
  for (long c = 0; c < nc; c++) {
    assert_int_equal(hd_rods_next(r, INFINITY, &ev, &e), HD_OK);
    double tbm = ev.tb_i - (1 - ev.eps * ev.eps) * ev.e_tr / (2.0 * (double)p.nmod);
    double beta = ev.e_tr / tbm;
    if (!(tbm > 0) || !(beta < 1e-4)) continue;
    double x = hd_eps_sample(r->sampler, beta, g);
    s1 += ev.eps, s2 += ev.eps * ev.eps, d1 += x, d2 += x * x, m++;
  }
  double mr = s1 / (double)m, md = d1 / (double)m;
  double se = sqrt((s2 / (double)m - mr * mr + d2 / (double)m - md * md) / (double)m);
  printf("# %ld draws below beta = 1e-4: mean eps %.4f, direct %.4f (se of the difference %.3g)\n",
         m, mr, md, se);
  gsl_rng_free(g);
  hd_rods_free(r);
  if (test_sanitized()) return; /* a tenth of the collisions: too few draws for the statistics */
  assert_true(m >= 30);
  assert_true(fabs(mr - md) < 4 * se);
}

/* Two-sample Kolmogorov-Smirnov distance of x[0..n) and y[0..m) (both sorted here). */
static double ks2(double *x, size_t n, double *y, size_t m) {
  gsl_sort(x, 1, n);
  gsl_sort(y, 1, m);
  size_t i = 0, j = 0;
  double d = 0;
  while (i < n && j < m) {
    double v = fmin(x[i], y[j]);
    while (i < n && x[i] <= v) i++;
    while (j < m && y[j] <= v) j++;
    d = fmax(d, fabs((double)i / (double)n - (double)j / (double)m));
  }
  return d;
}

/* The nodes built below the table's grid (rods.h, HD_RODS_LOW_NODES) against direct draws at
 * betas between nodes, where the interpolation in ln beta is worst, and the table's own error on
 * its grid (beta = 3e-3, between its nodes) for scale.  2000 draws each, fixed seeds; the
 * balance factor divided out.  A node is 1000 direct draws, so its two-sample KS distance from
 * 2000 direct draws is ~0.03-0.06 by noise alone (95 % points: 0.043 for the node, 0.043 for
 * the comparison), more where p_beta's atom at eps = a + b - 1 = 8 (docs/mc-eps.md; ~25 % of the
 * draws at beta ~ 1e-5) meets an interpolation.  Measured D: 0.056 on the grid; 0.035, 0.031, 0.079
 * at 3.2e-4, 5.6e-5, 4.2e-6; means within 1.2 s.e.  The end node repeated (the table before the
 * extension): 0.050, 0.19, 0.62.  Tolerance 0.1 on D (the end node fails it below 1e-4) and 4
 * standard errors on the mean. */
static void table_extension_below_grid(void **state) {
  (void)state;
  if (test_sanitized()) return; /* 24000 direct draws */
  enum { N = 2000 };
  static const double betas[] = {3e-3, 3.2e-4, 5.6e-5, 4.2e-6};
  hd_rods_params p = params(50, 1000, 11);
  p.table = 1;
  hd_rods *r = alloc_ok(&p);
  gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(g, 123);
  static double x[N], y[N], z[N];
  for (size_t k = 0; k < sizeof betas / sizeof betas[0]; k++) {
    double sx = 0, sx2 = 0, sy = 0, sy2 = 0;
    for (int i = 0; i < N; i++) {
      /* the table's balance factor (a deliberate correction of every node) divided out */
      x[i] = hd_rods_table_eps(r, betas[k]) / r->table_scale;
      y[i] = hd_eps_sample(r->sampler, betas[k], g);
      z[i] = hd_eps_table_sample(r->table, betas[k], g) / r->table_scale; /* the end node */
      sx += x[i], sx2 += x[i] * x[i], sy += y[i], sy2 += y[i] * y[i];
    }
    double mx = sx / N, my = sy / N;
    double se = sqrt((sx2 / N - mx * mx + sy2 / N - my * my) / N);
    double d = ks2(x, N, y, N), dz = ks2(z, N, y, N);
    printf("# beta %.2g: table %.4f, direct %.4f (se %.3f), KS %.4f; end node KS %.4f\n", betas[k],
           mx, my, se, d, dz);
    assert_true(d < 0.1);
    assert_true(fabs(mx - my) < 4 * se);
    if (betas[k] < 1e-4) assert_true(dz > 0.1); /* the test sees what the extension mends */
  }
  gsl_rng_free(g);
  hd_rods_free(r);
}

/* Constant eps: a ring of 20 rods at eps = 0.5 (McNamara-Young: collapse needs only
 * N > -ln(0.5)/0.5 = 1.4) collapses, reported with time, collisions and a cluster; the same
 * ring at eps = 0.99 (N_c ~ 460 > 20) runs 10^5 collisions without collapse. */
static void collapse(void **state) {
  (void)state;
  hd_rods *r = make(20, 10, HD_RODS_CONSTANT, 0.5, 3);
  hd_rods_event ev;
  hd_error e;
  int rc = HD_OK;
  long c;
  for (c = 0; c < 1000000 && rc == HD_OK; c++) rc = hd_rods_next(r, INFINITY, &ev, &e);
  assert_int_equal(rc, HD_ECOLLAPSE);
  assert_true(c < 1000000);
  assert_non_null(strstr(e.msg, "inelastic collapse at t = "));
  assert_non_null(strstr(e.msg, "collisions"));
  assert_non_null(strstr(e.msg, "cluster of rods"));
  hd_rods_free(r);
  r = make(20, 10, HD_RODS_CONSTANT, 0.99, 3);
  for (c = 0; c < 100000; c++) assert_int_equal(hd_rods_next(r, INFINITY, &ev, &e), HD_OK);
  hd_rods_free(r);
  /* the TC model (tc = 1e-3) keeps the eps = 0.5 ring from collapsing (for 2e4 collisions, by
   * then t ~ 1e4 times the collapse time above; docs/rods.md: the detector's limits) */
  hd_rods_params p;
  hd_rods_params_default(&p);
  p.n = 20;
  p.nmod = 10;
  p.model = HD_RODS_CONSTANT;
  p.eps = 0.5;
  p.tc = 1e-3;
  p.seed = 3;
  assert_int_equal(hd_rods_alloc(&r, &p, &e), HD_OK);
  long elastic = 0, mixed = 0;
  double tb[20];
  for (c = 0; c < 20000; c++) {
    for (long i = 0; i < 20; i++) tb[i] = hd_rods_tb(r, i);
    int rc2 = hd_rods_next(r, INFINITY, &ev, &e);
    if (rc2) print_error("%s\n", e.msg);
    assert_int_equal(rc2, HD_OK);
    elastic += ev.eps == 1.0;
    /* a TC-elastic collision leaves both baths as they were (docs/rods.md); they used to be
     * set to their mean.  Exact: no damping, nothing computed on the TC branch */
    if (ev.eps == 1.0) {
      assert_true(ev.tb_i == tb[ev.i] && ev.tb_j == tb[ev.j]);
      assert_true(hd_rods_tb(r, ev.i) == tb[ev.i] && hd_rods_tb(r, ev.j) == tb[ev.j]);
      mixed += tb[ev.i] != tb[ev.j];
    }
  }
  printf("# TC ring: %ld elastic collisions, %ld of them between unequal baths\n", elastic, mixed);
  assert_true(elastic > 0 && mixed > 0);
  hd_rods_free(r);
}

/* The conservative ring at equilibrium (N = 50, N_mod = 5, after 300 collisions per rod), eps
 * from the direct sampler at step 0.0025 (on the plain grid its sqrt(h) bias made E_kin ~1 % low
 * at 0.0025 and ~4 % at 0.01; refined since issue 25, docs/mc-eps.md 4f): time averages of E_kin
 * and of the collision rate over 8 blocks.  Held to
 *   E_kin = E(0)(N-1)/(N-1+2 N N_mod)   (equipartition, zero momentum), and
 *   rate  = (N-1) sqrt(T/(2 pi)), T = 2 <E_kin>/(N-1)   (1D ideal gas, docs/rods.md),
 * within 4 standard errors of the block means (the blocks are 400 collisions per rod long,
 * >> the ~80 collisions of a velocity relaxation, so they are close to independent).  The
 * paper's eq. (35) is smaller by sqrt(2): it is checked to be rejected by the same data. */
static void equilibrium(void **state) {
  (void)state;
  if (test_sanitized()) return; /* statistics need the full length: skip under ASan */
  long N = 50, nmod = 5;
  hd_rods_params p;
  hd_rods_params_default(&p);
  p.n = N;
  p.nmod = nmod;
  p.seed = 17;
  p.eps_step = 0.0025;
  hd_rods *r;
  hd_error e0;
  assert_int_equal(hd_rods_alloc(&r, &p, &e0), HD_OK);
  hd_rods_event ev;
  hd_error e;
  for (long c = 0; c < 300 * N / 2; c++)
    assert_int_equal(hd_rods_next(r, INFINITY, &ev, &e), HD_OK);
  enum { NB = 8 };
  long per = 400 * N / 2;
  double ekb[NB], rateb[NB];
  for (int b = 0; b < NB; b++) {
    double t0 = r->t, acc = 0, ek;
    hd_rods_energy(r, &ek, NULL, NULL);
    for (long c = 0; c < per; c++) {
      double tprev = r->t;
      assert_int_equal(hd_rods_next(r, INFINITY, &ev, &e), HD_OK);
      acc += ek * (ev.t - tprev);
      ek -= (1 - ev.eps * ev.eps) * ev.e_tr; /* E_kin changes by de at each collision */
    }
    ekb[b] = acc / (r->t - t0);
    rateb[b] = (double)per / (r->t - t0);
  }
  double m1 = 0, m2 = 0, r1 = 0, r2 = 0;
  for (int b = 0; b < NB; b++)
    m1 += ekb[b], m2 += ekb[b] * ekb[b], r1 += rateb[b], r2 += rateb[b] * rateb[b];
  m1 /= NB, r1 /= NB;
  double se_e = sqrt((m2 / NB - m1 * m1) / (NB - 1)), se_r = sqrt((r2 / NB - r1 * r1) / (NB - 1));
  double e_th = hd_rods_ekin_stat(N, nmod, 0.5 * (double)N);
  double T = 2 * m1 / (double)(N - 1), rate_th = hd_rods_rate_ideal(N, T);
  print_message("E_kin %.5f +- %.5f (theory %.5f); rate %.4f +- %.4f (ideal gas %.4f, eq. 35 "
                "%.4f); resampled %lld\n",
                m1, se_e, e_th, r1, se_r, rate_th, hd_rods_rate_eq35(N, nmod),
                (long long)r->resampled);
  assert_true(fabs(m1 - e_th) < 4 * se_e + 1e-3 * e_th);
  assert_true(fabs(r1 - rate_th) < 4 * se_r + 1e-3 * rate_th);
  /* eq. (35) at the measured T = 1/(2 N_mod + 1) level is off by far more than the noise */
  assert_true(fabs(r1 - hd_rods_rate_eq35(N, nmod)) > 10 * se_r);
  hd_rods_free(r);
}

/* E_kin / E_th - 1 of the conservative ring with the balanced table (gamma, N rods, nmod), time
 * averaged over nb blocks of per collisions after 300 per rod; *se its standard error. */
static double table_ring_shift(double gamma, long N, long nmod, unsigned long long seed, int nb,
                               long per, double *se) {
  hd_rods_params p;
  hd_rods_params_default(&p);
  p.n = N;
  p.nmod = nmod;
  p.gamma = gamma;
  p.seed = seed;
  p.table = 1;
  hd_rods *r;
  hd_error e;
  assert_int_equal(hd_rods_alloc(&r, &p, &e), HD_OK);
  hd_rods_event ev;
  for (long c = 0; c < 300 * N / 2; c++)
    assert_int_equal(hd_rods_next(r, INFINITY, &ev, &e), HD_OK);
  double m1 = 0, m2 = 0;
  for (int b = 0; b < nb; b++) {
    double t0 = r->t, acc = 0, ek;
    hd_rods_energy(r, &ek, NULL, NULL);
    for (long c = 0; c < per; c++) {
      double tprev = r->t;
      assert_int_equal(hd_rods_next(r, INFINITY, &ev, &e), HD_OK);
      acc += ek * (ev.t - tprev);
      ek -= (1 - ev.eps * ev.eps) * ev.e_tr;
    }
    double x = acc / (r->t - t0);
    m1 += x, m2 += x * x;
  }
  m1 /= nb;
  double e_th = hd_rods_ekin_stat(N, nmod, 0.5 * (double)N);
  *se = sqrt((m2 / nb - m1 * m1) / (nb - 1)) / e_th;
  print_message(
      "gamma %g, N %ld, N_mod %ld: E_kin/E_th - 1 = %+.3f %% +- %.3f %% (%d blocks of %ld; "
      "%lld redrawn)\n",
      gamma, N, nmod, 100 * (m1 / e_th - 1), 100 * *se, nb, per, (long long)r->resampled);
  assert_int_equal(r->resampled, 0); /* the cap on eps^2 plays no part (comment below) */
  hd_rods_free(r);
  return m1 / e_th - 1;
}

/* The ring with `table = yes` (issue 16): the same conservative ring (N = 50, N_mod = 5, seed
 * 17) after 300 collisions per rod, E_kin time-averaged over 20 blocks of 5e5 collisions (2e4
 * per rod, >> the ~80 of a velocity relaxation).  Held to the target, |E_kin/E_th - 1| <
 * 0.5 % with E_th = E(0)(N-1)/(N-1+2 N N_mod), and the standard error of the block mean must be
 * below 0.15 % so that the test can see it (measured 0.1 %).  Fails with the table unbalanced
 * (-6 %, its Monte Carlo noise) and with the direct sampler at steps >= 0.0025 (-1.2 % and
 * more; docs/mc-eps.md section 4b); measured with the balanced table: -0.3 +- 0.1 %. */
static void equilibrium_table(void **state) {
  (void)state;
  if (test_sanitized()) return; /* statistics need the full length: skip under ASan */
  double se, d = table_ring_shift(HD_RODS_GAMMA_DEFAULT, 50, 5, 17, 20, 500000, &se);
  assert_true(se < 1.5e-3);
  assert_true(fabs(d) < 5e-3);
}

/* What equipartition E_th = E(0)(N-1)/(N-1+2 N N_mod) is a reference for (issue 25 item 5): the
 * ring whose eps law is in detailed balance (the balanced table, D = 0 by construction) sits
 * below it by an amount that falls like 1/N_mod, because eps's law is that of a bath of
 * infinitely many modes at a fixed T_B (eq. 9), while the ring's baths hold 2 N_mod T_B and move
 * with every collision (eq. 28-29); the cap on eps^2 plays no part (never hit).  gamma = 0.6,
 * N = 40, seed 17, 200 blocks of 4e4 collisions (1e3 per rod, >> a velocity relaxation):
 * measured -1.44 +- 0.08 % at N_mod = 3 (seeds 17-20: -1.40 to -1.45 %), -0.58 % at 6, -0.27 % at
 * 12, -0.16 % at 24, -0.07 % at 48, +0.06 % at 96 (each +- 0.1 %; docs/mc-eps.md 4g).  So
 * at N_mod = 3 the sampler is to be held to the table's ring (-1.4 %), not to E_th: the direct
 * sampler's -1.27 and -1.31 % there are within 0.2 % of it.  Held here: N_mod = 3 below -0.9 %
 * (> 6 s.e. from 0), N_mod = 24 within 0.5 % of E_th, each with s.e. < 0.15 %.  ~10 s. */
static void equilibrium_finite_nmod(void **state) {
  (void)state;
  if (test_sanitized()) return; /* statistics need the full length: skip under ASan */
  double se3, se24;
  double d3 = table_ring_shift(0.6, 40, 3, 17, 200, 40000, &se3);
  double d24 = table_ring_shift(0.6, 40, 24, 17, 200, 40000, &se24);
  assert_true(se3 < 1.5e-3 && se24 < 1.5e-3);
  assert_true(d3 < -0.009);
  assert_true(fabs(d24) < 0.005);
}

/* What a new user gets (issue 16): a scene that does not set `table` draws eps from the balanced
 * table (stationary E_kin within 0.25 % of equipartition, equilibrium_table) wherever it applies,
 * the stochastic model with mean baths and gamma < 1; the direct sampler (2-3 % low at its
 * default step) only where the table cannot be used, or when asked for. */
static void scene_table_default(void **state) {
  (void)state;
  static const struct {
    const char *extra;
    int table;
  } cases[] = {{"", 1},
               {"eps_step = 0.005\n", 1},
               {"table = no\n", 0},
               {"baths = unequal\n", 0},
               {"model = constant\n", 0},
               {"gamma = 1\n", 0}};
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    char text[200];
    snprintf(text, sizeof text, "[rods]\ncount = 50\nnmod = 5\n%s[run]\nstop_time = 1\n",
             cases[i].extra);
    hd_scene sc;
    hd_error e;
    int rc = hd_scene_load_string(&sc, text, "default.ini", NULL, 0, &e);
    if (rc) print_error("%s\n", e.msg);
    assert_int_equal(rc, HD_OK);
    assert_int_equal(sc.rod_table, cases[i].table);
    /* the stored scene says which it was, so that resume builds the same ring */
    assert_non_null(strstr(sc.text, cases[i].table ? "table = yes" : "table = no"));
    hd_scene_free(&sc);
  }
}

/* The theory helpers against hand values. */
static void theory(void **state) {
  (void)state;
  /* N -> infinity: E_kin(0)/(2 N_mod + 1) */
  assert_true(fabs(hd_rods_ekin_stat(1000000, 1000, 1.0) * 2001 - 1) < 1e-5);
  /* ideal rate over eq. (35) at T = 1/(2 N_mod + 1), large N: sqrt(2) */
  double T = 1.0 / 2001;
  assert_true(fabs(hd_rods_rate_ideal(1000001, T) / hd_rods_rate_eq35(1000000, 1000) - sqrt(2)) <
              1e-6);
  assert_true(fabs(hd_rods_my_ncrit(0.95) - log(20) / 0.05) < 1e-12);
  assert_true(isinf(hd_rods_my_ncrit(1)));
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(initial_state),
      cmocka_unit_test(collision_rule),
      cmocka_unit_test(conservation),
      cmocka_unit_test(damping_balance),
      cmocka_unit_test(gamma_one_elastic),
      cmocka_unit_test(checkpoint_exact),
      cmocka_unit_test(collapse),
      cmocka_unit_test(damped_no_false_collapse),
      cmocka_unit_test(damped_energy_t_minus_2),
      cmocka_unit_test(damped_cluster_not_collapse),
      cmocka_unit_test(stochastic_baths_prevent_collapse),
      cmocka_unit_test(pileup_one_instant),
      cmocka_unit_test(cluster_at_one_instant),
      cmocka_unit_test(constant_cooling_below_drift),
      cmocka_unit_test(table_below_grid),
      cmocka_unit_test(table_extension_below_grid),
      cmocka_unit_test(equilibrium),
      cmocka_unit_test(equilibrium_table),
      cmocka_unit_test(equilibrium_finite_nmod),
      cmocka_unit_test(scene_table_default),
      cmocka_unit_test(theory),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
