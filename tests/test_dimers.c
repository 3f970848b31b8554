/* The engine with dimers (and dimer-disk mixtures, walls): conservation over long elastic runs
 * in verification mode, equipartition and Maxwellian velocities, the singular and elongated
 * limits, alpha = 0 and 1, walls that keep every body inside, and inelastic cooling. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_sort.h>

#include "hd_model.h"
#include "hd_sim_internal.h"
#include "test_sim.h"
#include "test_util.h"

/* A scene of n dimers (d = 1, bond a) at area fraction eta, plus nd disks. */
static void dimer_scene(hd_scene *sc, long n, long nd, double a, double eta, double alpha,
                        unsigned long long seed) {
  test_disk_scene(sc, nd, 0.1, alpha, seed);
  sc->n_dimers = n;
  sc->dimer_a = a;
  sc->dimer_alpha = alpha;
  double ad = a < 1 ? 2 * M_PI / 4 - (2 * 0.25 * acos(a) - 0.5 * a * sqrt(1 - a * a)) : M_PI / 2;
  double area = (double)n * ad + (double)nd * M_PI / 4;
  sc->box_x = sc->box_y = sqrt(area / eta);
  sc->placement = HD_PLACE_RANDOM;
}

/* Two dimers (d = 1, a = 1, alpha = 1) in a box of edge 20, placed and set by hand: centres,
 * orientations, velocities and spins; predicted again. */
static hd_sim *two_dimers(const double st[2][6]) {
  hd_scene sc;
  dimer_scene(&sc, 2, 0, 1.0, 0.01, 1.0, 1);
  sc.box_x = sc.box_y = 20;
  hd_sim *s = NULL;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  for (int i = 0; i < 2; i++) {
    hd_body *b = &s->b[i];
    b->k = (hd_kin){st[i][0], st[i][1], st[i][2], st[i][3], st[i][4], st[i][5]};
    b->t = 0;
    hd_cells_remove(s, i);
    hd_cells_insert(s, i, hd_cells_of(s, b->k.x, b->k.y));
  }
  for (int i = 0; i < 2; i++) hd_predict(s, i);
  return s;
}

/* Dimers exactly at rest that spin never leave their cells, and their contact searches had no
 * horizon: at nearly one rate a search ran 10^8 steps (~7 s) and then reported no contact
 * (review).  Now such a body wakes up every HD_WAKE_TURNS turns and is predicted again.
 * (1) Spinning at one rate 1.9 apart (phase-locked, never touching): to t = 1e4 only wake-ups
 * happen, about 1e4 / (100 turns of 2 pi / 3) = 48 per body, and no collision.  (2) Rates 3 and
 * 3 + 1e-4 (their relative phase drifts into contact near t ~ 7e3): the engine, searching 100
 * turns at a time, finds the very contact that one unbounded search finds (to 1e-9). */
static void resting_spinners(void **state) {
  (void)state;
  const double lock[2][6] = {{5, 5, 0, 0, 0, 3.0}, {6.9, 5, 0, 0, M_PI / 2, 3.0}};
  hd_sim *s = two_dimers(lock);
  hd_event_out ev;
  hd_error e;
  assert_int_equal(hd_sim_next(s, 1e4, &ev, &e), HD_SIM_STOPTIME);
  printf("# phase-locked spinners at rest: %lld events, %lld collisions to t = 1e4\n",
         (long long)s->c.events, (long long)s->c.collisions);
  assert_int_equal(s->c.collisions, 0);
  assert_true(s->c.events >= 2 * 45 && s->c.events <= 2 * 50);
  hd_sim_free(s);
  const double drift[2][6] = {{5, 5, 0, 0, 0, 3.0}, {6.9, 5, 0, 0, M_PI / 2, 3.0 + 1e-4}};
  hd_shape sh;
  hd_shape_dimer(&sh, 1, 1, 1);
  hd_kin A = {5, 5, 0, 0, 0, 3.0}, B = {6.9, 5, 0, 0, M_PI / 2, 3.0 + 1e-4};
  hd_contact c;
  assert_int_equal(hd_predict_pair(&A, &sh, &B, &sh, INFINITY, &c), 1);
  s = two_dimers(drift);
  int rc = hd_sim_next(s, 1e6, &ev, &e);
  printf("# drifting spinners: contact at %.12g (one search: %.12g) after %lld events\n", ev.t, c.t,
         (long long)s->c.events);
  assert_int_equal(rc, HD_OK);
  assert_true(fabs(ev.t - c.t) <= 1e-9 * c.t);
  assert_true(s->c.events > 2); /* found through wake-ups, not by the first search */
  hd_sim_free(s);
  /* (3) two resting spinners out of each other's reach: nothing can happen, and hd_sim_next
   * says so (HD_SIM_IDLE) instead of waking them up for ever (review) */
  const double apart[2][6] = {{5, 5, 0, 0, 0, 1.0}, {15, 15, 0, 0, 0, 1.1}};
  s = two_dimers(apart);
  assert_int_equal(hd_sim_next(s, INFINITY, &ev, &e), HD_SIM_IDLE);
  hd_sim_free(s);
}

/* Runs ncoll collisions (verification on when verify), returning the relative energy drift and
 * |total momentum|; fails on any engine error (an overlap, time going backwards). */
static void run_checked(hd_sim *s, long ncoll, double *drift, double *pabs) {
  double e0t, e0r, px, py;
  hd_sim_energy(s, -1, &e0t, &e0r);
  hd_error err;
  double tlast = 0;
  for (long k = 0; k < ncoll; k++) {
    hd_event_out ev;
    int rc = hd_sim_next(s, INFINITY, &ev, &err);
    if (rc) fail_msg("collision %ld: %s", k, err.msg);
    assert_true(ev.t >= tlast);
    tlast = ev.t;
    assert_false(isnan(ev.info.de) || isnan(ev.info.f));
  }
  double e1t, e1r;
  hd_sim_energy(s, -1, &e1t, &e1r);
  test_sim_momentum(s, &px, &py);
  *drift = fabs(e1t + e1r - e0t - e0r) / (e0t + e0r);
  *pabs = hypot(px, py);
}

/* KS p-value of x[0..n) against the unit Gaussian (asymptotic Kolmogorov distribution). */
static double ks_p(double *x, size_t n) {
  gsl_sort(x, 1, n);
  double d = 0;
  for (size_t i = 0; i < n; i++) {
    double F = gsl_cdf_ugaussian_P(x[i]);
    d = fmax(d, fmax((double)(i + 1) / (double)n - F, F - (double)i / (double)n));
  }
  double lam = (sqrt((double)n) + 0.12 + 0.11 / sqrt((double)n)) * d, p = 0;
  for (int k = 1; k < 100; k++) p += 2 * ((k & 1) ? 1 : -1) * exp(-2.0 * k * k * lam * lam);
  return fmin(fmax(p, 0), 1);
}

/* Elastic dimers, N = 400, a = d, eta = 0.2, 10^6 collisions (10^5 sanitized), verification
 * on (contact distance at every collision, overlap of both colliders with every neighbour,
 * time order): relative energy drift < 1e-9, |momentum| < 1e-12 sqrt(N).  At equilibrium
 * E_tr/E_rot = 2 (2 translational, 1 rotational degree of freedom): the time average over the
 * second half, 2e3 samples of a quantity with relative fluctuation ~sqrt(2/N) ~ 7 %, correlated
 * over ~N collisions, has an error ~1 %; tolerance 3 %.  V and omega scaled by their
 * temperatures pass KS at the 1 % level. */
static void elastic_dimers(void **state) {
  (void)state;
  hd_scene sc;
  long N = 400;
  dimer_scene(&sc, N, 0, 1.0, 0.2, 1.0, 17);
  sc.verify = 1;
  hd_sim *s;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  long n = test_size(1000000, 10);
  double e0t, e0r;
  hd_sim_energy(s, -1, &e0t, &e0r);
  double drift, p, p2;
  run_checked(s, n / 2, &drift, &p); /* first half: checked event by event */
  double ksum = 0;
  int nk = 0;
  for (long k = 0; k < n / 2; k++) {
    hd_event_out ev;
    if (hd_sim_next(s, INFINITY, &ev, &err)) fail_msg("%s", err.msg);
    if (k % 200 == 0) {
      double et, er;
      hd_sim_energy(s, -1, &et, &er);
      ksum += et / er;
      nk++;
    }
  }
  double et, er;
  hd_sim_energy(s, -1, &et, &er);
  drift = fabs(et + er - e0t - e0r) / (e0t + e0r); /* over all n collisions */
  test_sim_momentum(s, &p, &p2);
  double K = ksum / nk;
  printf("# elastic dimers: %ld collisions, drift %.3g, |p| %.3g, max overlap %.3g, <K> %.4f\n", n,
         drift, hypot(p, p2), s->max_overlap, K);
  assert_true(drift < 1e-9);
  assert_true(hypot(p, p2) < 1e-12 * sqrt((double)N));
  assert_true(s->max_overlap < 1e-9);
  int32_t i, j;
  assert_true(hd_sim_max_overlap(s, &i, &j) < 1e-9);
  if (!test_sanitized()) assert_true(fabs(K / 2 - 1) < 0.03);
  /* Maxwellian: V components scaled by sqrt(T_tr/M), omega by sqrt(T_rot/I) */
  double Ttr = et / (double)N, Trot = 2 * er / (double)N, M = 2.0, I = 0.5;
  double v[800], w[400];
  for (long b = 0; b < N; b++) {
    v[2 * b] = s->b[b].k.vx / sqrt(Ttr / M);
    v[2 * b + 1] = s->b[b].k.vy / sqrt(Ttr / M);
    w[b] = s->b[b].k.omega / sqrt(Trot / I);
  }
  double pv = ks_p(v, 800), pw = ks_p(w, 400);
  printf("# KS p: V %.3f, omega %.3f\n", pv, pw);
  assert_true(pv > 0.01 && pw > 0.01);
  hd_sim_free(s);
}

/* Limits and extremes, each elastic for 2e5 collisions in verification mode (2e4 sanitized):
 * a = 1e-3 d (singular: rotation keeps exchanging energy, omega ~ 1/a after collisions), a = 2d
 * and a = 3d (the disks no longer shadow each other), a dense gas near jamming (eta = 0.55, a
 * melted lattice: random addition cannot get there).  Energy drift < 1e-9, no NaN, no overlap. */
static void limits(void **state) {
  (void)state;
  struct {
    double a, eta;
  } cases[] = {{1e-3, 0.2}, {2.0, 0.2}, {3.0, 0.15}, {1.0, 0.55}};
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
    hd_scene sc;
    dimer_scene(&sc, 300, 0, cases[c].a, cases[c].eta, 1.0, 23 + c);
    sc.verify = 1;
    hd_sim *s;
    hd_error err;
    int rc = hd_sim_alloc(&s, &sc, &err);
    if (rc) fail_msg("a = %g: %s", cases[c].a, err.msg);
    double drift, p;
    run_checked(s, test_size(200000, 10), &drift, &p);
    printf("# a = %g, eta = %g: drift %.3g, |p| %.3g, max overlap %.3g\n", cases[c].a, cases[c].eta,
           drift, p, s->max_overlap);
    assert_true(drift < 1e-9);
    assert_true(s->max_overlap < 1e-9);
    hd_sim_free(s);
  }
}

/* Double contacts: with a = 2d the gap between a dimer's disks is exactly one disk wide, so a
 * disk of another dimer can sit in it touching both at once (the paper assumes double contacts
 * never happen).  In an inelastic gas (900 dimers, alpha = 0.9, eta = 0.05, fixed seed) the
 * collisions then pile up at one instant; the engine must stop and report it as a collapse
 * naming the bodies, within a bounded number of events (not hang, not count the pile-up as
 * cooling).  Without the pile-up check this run reached 84 cpd by t < 10 as if cooling. */
static void double_contact(void **state) {
  (void)state;
  if (test_sanitized()) skip();
  hd_scene sc;
  dimer_scene(&sc, 900, 0, 2.0, 0.05, 0.9, 2005);
  hd_sim *s;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  int rc = HD_OK;
  long k;
  hd_event_out ev;
  for (k = 0; k < 2000000 && rc == HD_OK && hd_sim_cpd(s) < 150; k++)
    rc = hd_sim_next(s, INFINITY, &ev, &err);
  printf("# a = 2d: %s (t = %.4g, cpd %.1f)\n", rc == HD_ECOLLAPSE ? err.msg : "no pile-up",
         hd_sim_time(s), hd_sim_cpd(s));
  assert_int_equal(rc, HD_ECOLLAPSE);
  assert_non_null(strstr(err.msg, "bodies"));
  hd_sim_free(s);
}

/* alpha = 0: every collision ends with zero normal relative velocity, energy only decreases,
 * no overlaps or NaN.  A sliding contact (rotation drives the touching disks together again)
 * becomes a train of ever smaller collisions that the engine reports as a collapse, after a
 * number of collisions that any change of round-off reshuffles: for 200 dimers at 0.1 and seeds
 * 31 to 36 it came after 2013, 1010, 4433, 2048, 32840 and 5139 collisions, and after 2487,
 * 1010, 1005, 2048, 1025 and 3821 once the conservative advancement's margin grew by 0.4 %.  So
 * the test takes all six seeds (at most n/6 collisions each), demands that each stops only
 * with a reported collapse, and that together they give at least 0.3 n collisions to check. */
static void alpha_zero(void **state) {
  (void)state;
  long n = test_size(20000, 4), checked = 0;
  for (unsigned long long seed = 31; seed <= 36; seed++) {
    hd_scene sc;
    dimer_scene(&sc, 200, 0, 1.0, 0.1, 0.0, seed);
    sc.verify = 1;
    hd_sim *s;
    hd_error err;
    assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
    double eprev = s->c.e_kin;
    int rc = HD_OK;
    for (long k = 0; k < n / 6; k++) {
      hd_event_out ev;
      rc = hd_sim_next(s, INFINITY, &ev, &err);
      if (rc) break;
      checked++;
      assert_true(ev.info.de <= 1e-15 * eprev);
      eprev = s->c.e_kin;
      /* the touching disks leave with no normal relative velocity: 1e-13 (round-off of
       * velocities of order 1, rotation included) plus 1e-12 of the approach speed */
      const hd_body *bi = &s->b[ev.i], *bj = &s->b[ev.j]; /* both at the current time */
      double xa, ya, xb, yb, ua, wa, ub, wb;
      hd_kin_disk_pos(&bi->k, &s->shape[bi->species], ev.ka, &xa, &ya);
      hd_kin_disk_pos(&bj->k, &s->shape[bj->species], ev.kb, &xb, &yb);
      hd_kin_disk_vel(&bi->k, &s->shape[bi->species], ev.ka, &ua, &wa);
      hd_kin_disk_vel(&bj->k, &s->shape[bj->species], ev.kb, &ub, &wb);
      double dx = xb - xa, dy = yb - ya;
      dx -= s->lx * round(dx / s->lx), dy -= s->ly * round(dy / s->ly);
      double vn = ((ub - ua) * dx + (wb - wa) * dy) / hypot(dx, dy);
      if (!(fabs(vn) <= 1e-13 + 1e-12 * fabs(ev.info.vn)))
        fail_msg("seed %llu: normal velocity %g after, %g before", seed, vn, ev.info.vn);
    }
    if (rc && rc != HD_ECOLLAPSE) fail_msg("seed %llu: %s", seed, err.msg);
    assert_true(s->max_overlap < 1e-9);
    hd_sim_free(s);
  }
  printf("# alpha = 0: %ld collisions checked over 6 seeds\n", checked);
  assert_true(checked >= 3 * n / 10);
}

/* The temperature of the progress line (the model's `temperature`) is 2 E / degrees of freedom:
 * 2 per body, 1 more per dimer with a lever arm.  The initial velocities give exactly T = 1.5
 * per degree of freedom (hd_init_velocities rescales them), so the value is 1.5 to round-off;
 * dimers of a = 0 have no rotation, and counting it gave 1.5 * 300/400 = 1.125 here. */
static void model_temperature(void **state) {
  (void)state;
  const double as[2] = {0.0, 1.0};
  for (int k = 0; k < 2; k++) {
    hd_scene sc;
    dimer_scene(&sc, 100, 50, as[k], 0.1, 1.0, 3);
    sc.temperature = 1.5;
    hd_sim *s;
    hd_error err;
    assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
    double T = hd_model_bodies2d.temperature(s);
    printf("# a = %g: T %.15g\n", as[k], T);
    assert_true(fabs(T - 1.5) < 1e-12);
    hd_sim_free(s);
  }
}

/* Walls on all four sides: no disk centre ever closer than d/2 to a wall (checked at every
 * collision through verification and over all bodies at the end), energy conserved at
 * alpha = 1, and wall collisions happen. */
static void walls_keep_inside(void **state) {
  (void)state;
  hd_scene sc;
  dimer_scene(&sc, 200, 100, 1.0, 0.2, 1.0, 37);
  sc.walls = HD_WALL_LEFT | HD_WALL_RIGHT | HD_WALL_BOTTOM | HD_WALL_TOP;
  sc.verify = 1;
  hd_sim *s;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  double e0t, e0r;
  hd_sim_energy(s, -1, &e0t, &e0r);
  long n = test_size(300000, 10);
  for (long k = 0; k < n; k++) {
    hd_event_out ev;
    if (hd_sim_next(s, INFINITY, &ev, &err)) fail_msg("%s", err.msg);
    if (k % 97 == 0 || ev.j < 0) { /* the bodies of this event stay inside */
      int32_t ids[2] = {ev.i, ev.j};
      for (int q = 0; q < 2; q++) {
        if (ids[q] < 0) continue;
        hd_kin kk;
        hd_sim_body_now(s, ids[q], &kk);
        const hd_shape *sh = &s->shape[s->b[ids[q]].species];
        for (int dsk = 0; dsk < (sh->tag == HD_KIND_DIMER ? 2 : 1); dsk++) {
          double x, y;
          hd_kin_disk_pos(&kk, sh, dsk, &x, &y);
          double r = 0.5 * sh->d * (1 - 1e-9);
          assert_true(x >= r && x <= s->lx - r && y >= r && y <= s->ly - r);
        }
      }
    }
  }
  double e1t, e1r;
  hd_sim_energy(s, -1, &e1t, &e1r);
  printf("# walls: %lld wall hits, drift %.3g\n", (long long)s->c.wall_hits,
         fabs(e1t + e1r - e0t - e0r) / (e0t + e0r));
  assert_true(s->c.wall_hits > 100);
  assert_true(fabs(e1t + e1r - e0t - e0r) / (e0t + e0r) < 1e-9);
  for (int32_t i = 0; i < s->n; i++) {
    hd_kin kk;
    hd_sim_body_now(s, i, &kk);
    const hd_shape *sh = &s->shape[s->b[i].species];
    for (int dsk = 0; dsk < (sh->tag == HD_KIND_DIMER ? 2 : 1); dsk++) {
      double x, y;
      hd_kin_disk_pos(&kk, sh, dsk, &x, &y);
      double r = 0.5 * sh->d * (1 - 1e-9);
      assert_true(x >= r && x <= s->lx - r && y >= r && y <= s->ly - r);
    }
  }
  hd_sim_free(s);
}

/* Elastic dimer-disk mixture: every degree of freedom gets T (equipartition): dimer
 * translation, dimer rotation, disk translation, time-averaged over the second half of 4e5
 * collisions (300 dimers, 300 disks); tolerance 4 % (as for K above, with fewer bodies per
 * species). */
static void mixture_equipartition(void **state) {
  (void)state;
  hd_scene sc;
  dimer_scene(&sc, 300, 300, 1.0, 0.2, 1.0, 41);
  hd_sim *s;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  long n = test_size(400000, 10);
  double sum_dt = 0, sum_dr = 0, sum_st = 0;
  int m = 0;
  for (long k = 0; k < n; k++) {
    hd_event_out ev;
    if (hd_sim_next(s, INFINITY, &ev, &err)) fail_msg("%s", err.msg);
    if (k >= n / 2 && k % 200 == 0) {
      double dt, dr, st, sr;
      hd_sim_energy(s, 0, &dt, &dr); /* species 0: [dimers], 1: [disks] */
      hd_sim_energy(s, 1, &st, &sr);
      sum_dt += dt / 300.0, sum_dr += 2 * dr / 300.0, sum_st += st / 300.0; /* each in units of T */
      m++;
    }
  }
  double Tdt = sum_dt / m, Tdr = sum_dr / m, Tst = sum_st / m;
  printf("# mixture: T dimer tr %.4f, dimer rot %.4f, disk tr %.4f\n", Tdt, Tdr, Tst);
  if (!test_sanitized()) {
    assert_true(fabs(Tdr / Tdt - 1) < 0.04);
    assert_true(fabs(Tst / Tdt - 1) < 0.04);
  }
  hd_sim_free(s);
}

/* Crowded neighbourhoods: 40 long dimers (a = 3d) among 2000 small disks (sigma = 0.2 d), so
 * the cells (>= 4d wide) hold ~80 disks each and a prediction sees far more neighbours than it
 * sorts (HD_MAX_CAND in engine/sim/hd_predict.c): the unsorted remainder must stay exact.  Elastic,
 * verification on, 1e4 collisions: energy drift < 1e-9 relative, |momentum| < 1e-12 sqrt(N),
 * the same bounds as the elastic dimer test. */
static void crowded_neighbours(void **state) {
  (void)state;
  hd_scene sc;
  dimer_scene(&sc, 40, 2000, 3.0, 0.25, 1.0, 17);
  sc.disk_sigma = 0.2;
  double area = 40 * M_PI / 2 + 2000 * M_PI / 4 * 0.04;
  sc.box_x = sc.box_y = sqrt(area / 0.25);
  sc.verify = 1;
  hd_sim *s;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  assert_true(s->cwx >= 4.0 && s->ncx >= 3);
  double drift, p;
  run_checked(s, test_size(10000, 1000), &drift, &p);
  printf("# crowded: drift %.3g, |p| %.3g, %d x %d cells\n", drift, p, s->ncx, s->ncy);
  assert_true(drift < 1e-9);
  assert_true(p < 1e-12 * sqrt(2040.0));
  hd_sim_free(s);
}

/* Inelastic dimers (alpha = 0.9, a = d, dilute): the energy decays (by > 5x over 40 cpd), and
 * K = E_tr/E_rot settles to a constant near 2: its mean over cpd 20-40 is within 10 % of 2 and
 * its drift between cpd 20-30 and 30-40 below 5 %.  K is averaged over 6 runs (seeds 43-48) of
 * 1000 dimers: over 100 seeds one run's drift has a standard deviation of 4 % (so a 5 % bound
 * on a single run failed for about one seed in five, and flipped with any change of round-off
 * that moves the trajectory), the 6-run mean 1.7 %, which puts the 5 % bound at 3 sigma. */
static void inelastic_cooling(void **state) {
  (void)state;
  long N = test_size(1000, 4);
  int nrun = test_sanitized() ? 1 : 6;
  double k1 = 0, k2 = 0;
  int n1 = 0, n2 = 0;
  for (int run = 0; run < nrun; run++) {
    hd_scene sc;
    dimer_scene(&sc, N, 0, 1.0, 0.05, 0.9, 43 + (unsigned long long)run);
    hd_sim *s;
    hd_error err;
    assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
    double e0 = s->c.e_kin;
    double next = 20;
    while (hd_sim_cpd(s) < 40) {
      hd_event_out ev;
      if (hd_sim_next(s, INFINITY, &ev, &err)) fail_msg("%s", err.msg);
      if (hd_sim_cpd(s) >= next) {
        double et, er;
        hd_sim_energy(s, -1, &et, &er);
        if (next < 30)
          k1 += et / er, n1++;
        else
          k2 += et / er, n2++;
        next += 0.25;
      }
    }
    printf("# inelastic (seed %d): E(40 cpd)/E(0) = %.4g\n", 43 + run, s->c.e_kin / e0);
    assert_true(s->c.e_kin < e0 / 5);
    hd_sim_free(s);
  }
  double K1 = k1 / n1, K2 = k2 / n2;
  printf("# inelastic: K over cpd 20-30 %.4f, 30-40 %.4f (%d runs)\n", K1, K2, nrun);
  if (!test_sanitized()) {
    assert_true(fabs((K1 + K2) / 4 - 1) < 0.10);
    assert_true(fabs(K2 / K1 - 1) < 0.05);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(elastic_dimers),
      cmocka_unit_test(resting_spinners),
      cmocka_unit_test(limits),
      cmocka_unit_test(alpha_zero),
      cmocka_unit_test(double_contact),
      cmocka_unit_test(model_temperature),
      cmocka_unit_test(walls_keep_inside),
      cmocka_unit_test(mixture_equipartition),
      cmocka_unit_test(inelastic_cooling),
      cmocka_unit_test(crowded_neighbours),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
