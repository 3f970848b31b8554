/* The event-driven engine with hard disks: exact two-body cases, conservation over long elastic
 * runs, no overlap, time order, the Enskog collision rate, the Maxwellian, Haff's law. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_fit.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_sort.h>

#include "hd_disk.h"
#include "hd_sim_internal.h"
#include "test_sim.h"
#include "test_util.h"

/* Two disks set up by hand in a box of edge L: positions, velocities. */
static hd_sim *two_disks(double L, double x0, double y0, double vx0, double vy0, double x1,
                         double y1, double vx1, double vy1, double alpha) {
  hd_scene sc;
  test_disk_scene(&sc, 2, 0.01, alpha, 1);
  sc.box_x = sc.box_y = L;
  sc.placement = HD_PLACE_LATTICE;
  hd_sim *s = NULL;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  double st[2][4] = {{x0, y0, vx0, vy0}, {x1, y1, vx1, vy1}};
  for (int i = 0; i < 2; i++) {
    hd_body *b = &s->b[i];
    b->k.x = st[i][0], b->k.y = st[i][1], b->k.vx = st[i][2], b->k.vy = st[i][3];
    b->t = 0;
  }
  /* re-file the moved bodies and predict again */
  for (int i = 0; i < 2; i++) {
    hd_cells_remove(s, i);
    hd_cells_insert(s, i, hd_cells_of(s, s->b[i].k.x, s->b[i].k.y));
  }
  for (int i = 0; i < 2; i++) hd_predict(s, i);
  s->c.e_kin = 0.5 * (vx0 * vx0 + vy0 * vy0 + vx1 * vx1 + vy1 * vy1);
  return s;
}

/* Head-on: equal masses exchange velocities (alpha = 1); alpha = 0 leaves them moving together;
 * the collision time is exact. */
static void head_on(void **state) {
  (void)state;
  double alphas[3] = {1.0, 0.5, 0.0};
  for (int a = 0; a < 3; a++) {
    double al = alphas[a];
    hd_sim *s = two_disks(20.0, 5.0, 10.0, 1.0, 0.0, 9.0, 10.0, -1.0, 0.0, al);
    hd_event_out ev;
    hd_error err;
    assert_int_equal(hd_sim_next(s, INFINITY, &ev, &err), HD_OK);
    assert_true(fabs(ev.t - 1.5) < 1e-14); /* gap 4 - 1 = 3 closed at speed 2 */
    assert_int_equal(ev.kind, hd_coll_kind_of(HD_KIND_DISK, HD_KIND_DISK));
    /* post velocities: v0' = -al, v1' = al (centre of mass at rest) */
    assert_true(fabs(s->b[0].k.vx + al) < 1e-14 && fabs(s->b[1].k.vx - al) < 1e-14);
    assert_true(fabs(ev.info.vn + 2.0) < 1e-14);
    assert_true(fabs(ev.info.de + 0.25 * (1 - al * al) * 4.0) < 1e-13); /* -(1-a^2) mu vn^2/2 */
    hd_sim_free(s);
  }
}

/* Oblique: impact parameter b = 0.5 sigma; the normal component is reversed, the tangential one
 * kept; a grazing miss (b = sigma + 1e-9) never collides; periodic images collide across the
 * boundary. */
static void oblique_grazing_periodic(void **state) {
  (void)state;
  hd_event_out ev;
  hd_error err;
  hd_sim *s = two_disks(20.0, 5.0, 10.0, 1.0, 0.0, 9.0, 10.5, 0.0, 0.0, 1.0);
  assert_int_equal(hd_sim_next(s, INFINITY, &ev, &err), HD_OK);
  double tc = 4.0 - sqrt(1.0 - 0.25); /* x-distance at contact: sqrt(1 - b^2) */
  assert_true(fabs(ev.t - tc) < 1e-13);
  double nx = sqrt(0.75), ny = 0.5; /* normal at contact from 0 to 1 */
  /* elastic, equal masses: v0' = v0 - (v0.n) n, v1' = (v0.n) n */
  double vn = nx;
  assert_true(fabs(s->b[0].k.vx - (1 - vn * nx)) < 1e-12 && fabs(s->b[0].k.vy + vn * ny) < 1e-12);
  assert_true(fabs(s->b[1].k.vx - vn * nx) < 1e-12 && fabs(s->b[1].k.vy - vn * ny) < 1e-12);
  hd_sim_free(s);

  s = two_disks(20.0, 5.0, 10.0, 1.0, 0.0, 9.0, 11.0 + 1e-9, 0.0, 0.0, 1.0);
  int rc = hd_sim_next(s, 30.0, &ev, &err); /* by t = 30 disk 0 has wrapped past disk 1 */
  assert_int_equal(rc, HD_SIM_STOPTIME);
  hd_sim_free(s);

  /* across the periodic boundary: disk 0 at x = 19.5 moving right meets disk 1 at x = 1.5 */
  s = two_disks(20.0, 19.5, 10.0, 1.0, 0.0, 1.5, 10.0, 0.0, 0.0, 1.0);
  assert_int_equal(hd_sim_next(s, INFINITY, &ev, &err), HD_OK);
  assert_true(fabs(ev.t - 1.0) < 1e-13);
  assert_true(fabs(s->b[1].k.vx - 1.0) < 1e-14 && fabs(s->b[0].k.vx) < 1e-14);
  hd_sim_free(s);
}

/* A pending collision survives the partner's wrap through the box: disk 1 wraps (x: 9.7 ->
 * 10 = 0) at t = 0.3 and meets disk 0 at t = 0.8 + ... with the right periodic image.  Before
 * the wrap-invariant image offsets this collision was computed with a stale image. */
static void collision_across_wrap(void **state) {
  (void)state;
  hd_event_out ev;
  hd_error err;
  hd_sim *s = two_disks(10.0, 1.5, 5.0, 0.0, 0.0, 9.7, 5.5, 1.0, 0.0, 1.0);
  assert_int_equal(hd_sim_next(s, INFINITY, &ev, &err), HD_OK);
  double dx = sqrt(1.0 - 0.25); /* x-distance at contact */
  double tc = (1.5 - dx) - (9.7 - 10.0);
  assert_true(fabs(ev.t - tc) < 1e-13);
  double nx = dx, ny = 0.5; /* unit normal from disk 1 to disk 0 */
  /* elastic, equal masses, disk 0 at rest: it leaves along the normal with speed v.n = nx */
  assert_true(fabs(s->b[0].k.vx - nx * nx) < 1e-12 && fabs(s->b[0].k.vy + nx * ny) < 1e-12);
  assert_true(fabs(s->b[1].k.vx - (1 - nx * nx)) < 1e-12 && fabs(s->b[1].k.vy - nx * ny) < 1e-12);
  hd_sim_free(s);
}

/* Wrap counts are labels: the collision of collision_across_wrap comes out the same when the
 * two disks have lapped the box 40000 and -30000 times before (a 16-bit image offset
 * overflowed once they differed by more than 32767: one disk lapping a 10x10
 * box 40000 times met its partner through an image 65536 boxes away).  hd_image_code itself is
 * exact modulo 2^16 for any counts, wrapping through 2^32 included. */
static void image_code_long_runs(void **state) {
  (void)state;
  hd_event_out ev;
  hd_error err;
  hd_sim *s = two_disks(10.0, 1.5, 5.0, 0.0, 0.0, 9.7, 5.5, 1.0, 0.0, 1.0);
  s->b[0].wx = 40000u, s->b[0].wy = 7u;
  s->b[1].wx = (uint32_t)-30000, s->b[1].wy = 0xfffffff0u;
  for (int i = 0; i < 2; i++) hd_predict(s, i);
  assert_int_equal(hd_sim_next(s, INFINITY, &ev, &err), HD_OK);
  double dx = sqrt(1.0 - 0.25), tc = (1.5 - dx) - (9.7 - 10.0);
  assert_true(fabs(ev.t - tc) < 1e-13);
  assert_true(fabs(s->b[0].k.vx - dx * dx) < 1e-12 && fabs(s->b[0].k.vy + dx * 0.5) < 1e-12);
  hd_sim_free(s);
  uint32_t w[5] = {0u, 1u, 40000u, 0x7fffffffu, 0xffffffffu};
  for (int a = 0; a < 5; a++)
    for (int b = 0; b < 5; b++)
      for (int ix = -1; ix <= 1; ix++) {
        int im = hd_image_code(ix, w[b], w[a]); /* stored: ix - w[a] + w[b] */
        assert_true(im >= INT16_MIN && im <= INT16_MAX);
        assert_int_equal(hd_image_code(im, w[a], w[b]), ix);
      }
}

/* The disk fast path's contact rule (hd_disk.h): a round-off overlap collides now only while
 * approaching faster than HD_DISK_VTOL |v| + HD_DISK_VROUND vs.  Before the rule
 * an alpha = 0 pair (normal velocity 0 up to round-off after its collision) collided again at
 * t = 0 for ever: the impulse, below an ulp of the velocities, changed nothing. */
static void disk_contact_rule(void **state) {
  (void)state;
  double D = 1.0, ov = 1.0 - 1e-15; /* |r| = ov: overlap by round-off */
  assert_true(hd_disk_contact_time(ov, 0.0, -1e-17, 1.0, D, 2.0) == INFINITY); /* ~1e-17 |v| */
  assert_true(hd_disk_contact_time(ov, 0.0, -1e-6, 1.0, D, 2.0) == 0.0);       /* approaching */
  assert_true(hd_disk_contact_time(ov, 0.0, 1e-6, 1.0, D, 2.0) == INFINITY);   /* receding */
  /* 3e-12 with |v| = 1 approaches for bodies of speed ~1; for bodies moving together at ~1000
   * (vs = 4000) it is round-off of their velocities (8 eps vs = 7e-12) */
  assert_true(hd_disk_contact_time(ov, 0.0, -3e-12, 1.0, D, 2.0) == 0.0);
  assert_true(hd_disk_contact_time(ov, 0.0, -3e-12, 1.0, D, 4000.0) == INFINITY);
  /* head-on from a gap of 2 at closing speed 1, and a transversal oblique contact */
  assert_true(fabs(hd_disk_contact_time(3.0, 0.0, -1.0, 0.0, D, 2.0) - 2.0) < 1e-15);
  double t = hd_disk_contact_time(3.0, 0.5, -1.0, 0.0, D, 2.0);
  assert_true(fabs(t - (3.0 - sqrt(0.75))) < 1e-14);
}

/* Two disks moving together fast (speed 1000 in a random direction) meet at a relative speed of
 * 1 at alpha = 0, 1000 times with random geometry (seed 17): none collides again at t = 0.
 * After the collision their normal relative velocity is round-off of velocities of size 1000,
 * ~1e-13, above 1e-12 of the relative speed; with that as the only margin 12 pairs in 1000 piled
 * up (a false collapse after 1000 collisions at one instant). */
static void alpha_zero_fast_pair(void **state) {
  (void)state;
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(r, 17);
  int again = 0;
  for (int k = 0; k < 1000; k++) {
    double th = 2 * M_PI * gsl_rng_uniform(r), ang = 2 * M_PI * gsl_rng_uniform(r);
    double ux = 1000 * cos(th), uy = 1000 * sin(th), ex = cos(ang), ey = sin(ang);
    double b = 0.9 * gsl_rng_uniform(r); /* impact parameter */
    hd_sim *s = two_disks(10.0, 5.0, 5.0, ux, uy, 5.0 + 1.2 * ex - b * ey, 5.0 + 1.2 * ey + b * ex,
                          ux - ex, uy - ey, 0.0);
    hd_event_out ev;
    hd_error err;
    assert_int_equal(hd_sim_next(s, INFINITY, &ev, &err), HD_OK);
    double t1 = ev.t; /* the next collision, if any, must come later (a lap of the box) */
    int rc = hd_sim_next(s, t1 + 1e-3, &ev, &err);
    again += rc == HD_OK && ev.t == t1;
    hd_sim_free(s);
  }
  gsl_rng_free(r);
  assert_int_equal(again, 0);
}

/* A gas of 500 disks at alpha = 0 (area fraction 0.1, seed 1) runs 5000 collisions without a
 * pile-up, and every collision leaves its pair with no normal relative velocity (to 1e-13, the
 * round-off of velocities of order 1, plus 1e-12 of the approach speed).  With the round-off
 * re-collision above, `haff run` of such a gas piled up after 29 distinct collision times at
 * seed 1 (7 and 13 at seeds 2 and 3), ending in 1000 identical rows of one pair; with the rule
 * the same runs reach a genuine inelastic collapse (a disk squeezed between two others, |vn|
 * halving at each collision) after 10096, 11421 and 25507 collisions.  Many collisions share
 * their time: a hit passes at once along chains of disks left touching by earlier ones. */
static void alpha_zero_gas(void **state) {
  (void)state;
  hd_scene sc;
  test_disk_scene(&sc, 500, 0.1, 0.0, 1);
  hd_sim *s;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  hd_event_out ev;
  double tprev = -1.0;
  int distinct = 0;
  for (int k = 0; k < 5000; k++) {
    int rc = hd_sim_next(s, INFINITY, &ev, &err);
    if (rc != HD_OK) fprintf(stderr, "alpha_zero_gas: collision %d: %s\n", k, err.msg);
    assert_int_equal(rc, HD_OK);
    assert_true(ev.info.vn < 0.0);
    const hd_kin *a = &s->b[ev.i].k, *b = &s->b[ev.j].k; /* both at the current time */
    double dx = b->x - a->x, dy = b->y - a->y;
    dx -= s->lx * round(dx / s->lx);
    dy -= s->ly * round(dy / s->ly);
    double r = hypot(dx, dy), vn = ((b->vx - a->vx) * dx + (b->vy - a->vy) * dy) / r;
    assert_true(fabs(vn) <= 1e-13 + 1e-12 * fabs(ev.info.vn));
    distinct += ev.t != tprev;
    tprev = ev.t;
  }
  printf("# alpha = 0 gas: 5000 collisions at %d distinct times\n", distinct);
  assert_true(distinct > 300); /* 664; the pile-up came after at most 29 */
  hd_sim_free(s);
}

/* hd_sim_state on the initial gas (random positions, independent Maxwellian velocities: no
 * correlation).  Over 60 seeds of 400 disks at area fraction 0.05: the mean s_perp, s_par and
 * flow_frac/flow_chaos are 1 (each sample's s averages 4 exponential |p_k|^2 of mean 1, sd 0.5;
 * 60 samples: se 0.065; tolerance 0.3, 4.6 se), count_var and s_rho near S(0) (0.82 for
 * disks at 0.05; se ~0.07 for the 4 modes, ~0.05 for 16 cells; tolerance 0.35).  Then an
 * imposed shear v_x = U sin(2 pi y/Ly) on bodies at rest (exact numbers, no noise but the random
 * positions): s_perp = N/6 (only k = (0, 1) carries it, N/2, averaged over the 3 modes where the
 * transverse velocity is not 0 everywhere: k = (1, 0) has none), s_par ~ 1, and
 * flow_frac = 8/pi^2 (the 4 x 4 grid's rows average sin to +-2/pi, against <sin^2> = 1/2). */
static void state_measures(void **state) {
  (void)state;
  double sp = 0, sl = 0, fr = 0, cv = 0, sr = 0;
  int n = 60;
  for (int seed = 1; seed <= n; seed++) {
    hd_scene sc;
    test_disk_scene(&sc, 400, 0.05, 0.9, (unsigned long)seed);
    hd_sim *s;
    hd_error err;
    assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
    hd_state_measures q;
    hd_sim_state(s, &q);
    assert_true(q.flow_frac >= 0 && q.flow_frac <= 1 && q.flow_chaos > 0 && q.flow_chaos <= 1);
    sp += q.s_perp, sl += q.s_par, fr += q.flow_frac / q.flow_chaos, cv += q.count_var;
    sr += q.s_rho;
    hd_sim_free(s);
  }
  sp /= n, sl /= n, fr /= n, cv /= n, sr /= n;
  printf("# state measures, no correlation: s_perp %.3f s_par %.3f flow/chaos %.3f count_var "
         "%.3f s_rho %.3f\n",
         sp, sl, fr, cv, sr);
  assert_true(fabs(sp - 1) < 0.3 && fabs(sl - 1) < 0.3 && fabs(fr - 1) < 0.3);
  assert_true(fabs(cv - 0.82) < 0.35 && fabs(sr - 0.82) < 0.35);
  hd_scene sc;
  test_disk_scene(&sc, 4000, 0.05, 0.9, 7);
  hd_sim *s;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  for (int32_t i = 0; i < s->n; i++) {
    hd_body *b = &s->b[i];
    b->k.vx = 0.3 * sin(2 * M_PI * b->k.y / s->ly), b->k.vy = 0, b->k.omega = 0;
  }
  hd_state_measures q;
  hd_sim_state(s, &q);
  printf("# shear flow: s_perp %.1f (N/6 = 667) s_par %.3g flow_frac %.4f (8/pi^2 = %.4f)\n",
         q.s_perp, q.s_par, q.flow_frac, 8 / (M_PI * M_PI));
  assert_true(fabs(q.s_perp / (4000.0 / 6) - 1) < 0.05);
  assert_true(q.s_par < 2);
  assert_true(fabs(q.flow_frac - 8 / (M_PI * M_PI)) < 0.02);
  hd_sim_free(s);
}

/* placement = lattice fills every box the scene check lets through (a grid of floor(L / range)
 * sites per edge), with no two bodies closer than the range: before, the engine chose its own
 * grid and refused 35 disks in 6.5 x 6 (7 x 5 sites of 0.93) and 100 disks in 10 x 10. */
static void lattice_fits_scene_check(void **state) {
  (void)state;
  const char *scenes[] = {
      "[system]\nbox = 6.5 6\n[disks]\ncount = 35\n",          /* 6 x 6 sites for 35 */
      "[system]\nbox = 10 10\n[disks]\ncount = 100\n",         /* 10 x 10, touching */
      "[system]\nbox = 40 2.5\n[disks]\ncount = 80\n",         /* a strip: 40 x 2 */
      "[system]\nbox = 12 6.1\n[dimers]\ncount = 18\na = 1\n", /* 6 x 3 sites of 2 */
  };
  for (int k = 0; k < 4; k++) {
    char text[256];
    snprintf(text, sizeof text, "%s[init]\nplacement = lattice\n[run]\nstop_events = 1\n",
             scenes[k]);
    hd_scene sc;
    hd_error err;
    assert_int_equal(hd_scene_load_string(&sc, text, "lattice.ini", NULL, 0, &err), HD_OK);
    hd_sim *s;
    int rc = hd_sim_alloc(&s, &sc, &err);
    if (rc) fprintf(stderr, "lattice_fits_scene_check %d: %s\n", k, err.msg);
    assert_int_equal(rc, HD_OK);
    double range = sc.n_dimers ? sc.dimer_a + sc.dimer_d : sc.disk_sigma, dmin = INFINITY;
    for (int32_t i = 0; i < s->n; i++)
      for (int32_t j = i + 1; j < s->n; j++) {
        double dx = s->b[j].k.x - s->b[i].k.x, dy = s->b[j].k.y - s->b[i].k.y;
        dx -= s->lx * round(dx / s->lx), dy -= s->ly * round(dy / s->ly);
        dmin = fmin(dmin, hypot(dx, dy));
      }
    assert_true(dmin >= range * (1 - 1e-12));
    hd_sim_free(s);
    hd_scene_free(&sc);
  }
}

/* A box of more than ~1e308 diameters: the cell grid (floor(box / diameter) = inf, which the
 * halving down to 4 cells per body never reduced) hung the set-up at 100 % CPU, deaf to
 * SIGINT.  Now that grid starts at the cap (<= 4 cells per body); the alarm turns a hang back
 * into a failure.  A finite grid halves as it always did (it is part of a checkpoint, which a
 * resume must match): 1000 x 10 cells for 100 disks, halved along x to 31 x 10 <= 400
 * (clamping first to 400 x 10 gave 25 x 10, and old checkpoints were refused). */
static void huge_box_in_diameters(void **state) {
  (void)state;
  const struct {
    const char *system_disks;
    int32_t ncx, ncy; /* the grid expected, 0 0: any within the cap */
  } cases[] = {
      {"[system]\nbox = 10 10\n[disks]\ncount = 2\nsigma = 1e-308\n", 0, 0},
      {"[system]\nbox = 1e300 1e300\n[disks]\ncount = 2\nsigma = 1e-10\n", 0, 0},
      {"[system]\nbox = 1000 10\n[disks]\ncount = 100\n", 31, 10},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    char text[256];
    snprintf(text, sizeof text, "%s[run]\nstop_time = 1\n", cases[k].system_disks);
    hd_scene sc;
    hd_error err;
    assert_int_equal(hd_scene_load_string(&sc, text, "grid.ini", NULL, 0, &err), HD_OK);
    hd_sim *s;
    alarm(60);
    int rc = hd_sim_alloc(&s, &sc, &err);
    alarm(0);
    assert_int_equal(rc, HD_OK);
    assert_true((int64_t)s->ncx * s->ncy <= 4 * s->n);
    if (cases[k].ncx) {
      assert_int_equal(s->ncx, cases[k].ncx);
      assert_int_equal(s->ncy, cases[k].ncy);
    }
    hd_sim_free(s);
    hd_scene_free(&sc);
  }
}

/* Elastic N = 1000 at eta = 0.2 for 10^6 collisions (10^5 sanitized), verification on:
 * relative energy drift < 1e-10, momentum < 1e-12 (absolute, per unit total |p| scale
 * sqrt(N m T)), no overlap beyond 1e-9 of a diameter at any event (checked by the engine
 * against every neighbour of both colliding bodies, and over all pairs at the end), event
 * times never decrease (asserted by the engine and checked here on the collision stream). */
static void elastic_conservation(void **state) {
  (void)state;
  hd_scene sc;
  test_disk_scene(&sc, 1000, 0.2, 1.0, 42);
  sc.verify = 1;
  hd_sim *s;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  double e0t, e0r, px, py;
  hd_sim_energy(s, -1, &e0t, &e0r);
  long n = test_size(1000000, 10);
  double tlast = 0;
  for (long k = 0; k < n; k++) {
    hd_event_out ev;
    int rc = hd_sim_next(s, INFINITY, &ev, &err);
    if (rc) fail_msg("event %ld: %s", k, err.msg);
    assert_true(ev.t >= tlast);
    tlast = ev.t;
    /* the pair leaves with its normal velocity reversed, seen on the bodies themselves (the
     * logged de is -(1 - alpha^2) mu vn^2 / 2, exactly 0 here, and could not show it) */
    const hd_kin *a = &s->b[ev.i].k, *b = &s->b[ev.j].k;
    double dx = b->x - a->x, dy = b->y - a->y;
    dx -= s->lx * round(dx / s->lx), dy -= s->ly * round(dy / s->ly);
    double vn = ((b->vx - a->vx) * dx + (b->vy - a->vy) * dy) / hypot(dx, dy);
    if (!(fabs(vn + ev.info.vn) <= 1e-13 + 1e-12 * fabs(ev.info.vn)))
      fail_msg("collision %ld: vn %g before, %g after", k, ev.info.vn, vn);
  }
  double e1t, e1r;
  hd_sim_energy(s, -1, &e1t, &e1r);
  test_sim_momentum(s, &px, &py);
  double drift = fabs(e1t + e1r - e0t - e0r) / (e0t + e0r);
  printf("# elastic N=1000: %ld collisions, energy drift %.3g, |p| %.3g, max overlap %.3g\n", n,
         drift, hypot(px, py), s->max_overlap);
  assert_true(drift < 1e-10);
  assert_true(hypot(px, py) < 1e-12 * sqrt(1000.0));
  int32_t i, j;
  double o = hd_sim_max_overlap(s, &i, &j);
  assert_true(o < 1e-9);
  assert_true(s->max_overlap < 1e-9);
  hd_sim_free(s);
}

/* The event queue's prefetch hints (on by themselves only for bodies past a core's L2 cache)
 * change nothing: a disk gas and a dimer-disk mixture run with none, the near (2-stage) and the
 * far (3-stage) hint forced on end in the same state bit for bit.  Under the sanitizer build
 * this also checks that the hints read only inside the cell and body arrays. */
static void prefetch_hints_change_nothing(void **state) {
  (void)state;
  for (int mix = 0; mix < 2; mix++) {
    hd_body *end[3] = {NULL, NULL, NULL};
    int32_t n = 0;
    for (int h = 0; h < 3; h++) {
      hd_scene sc;
      test_disk_scene(&sc, 3000, 0.3, 0.9, 7);
      if (mix) sc.n_disks = 600, sc.n_dimers = 600, sc.dimer_alpha = 0.95;
      hd_sim *s;
      hd_error err;
      assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
      if (h == 1) hd_queue_set_prefetch(s->q, hd_predict_prefetch_near, s, 2);
      if (h == 2) hd_queue_set_prefetch(s->q, hd_predict_prefetch_far, s, 3);
      long steps = test_size(200000, 10);
      for (long k = 0; k < steps; k++) {
        hd_event_out ev;
        if (hd_sim_next(s, INFINITY, &ev, &err)) fail_msg("event %ld: %s", k, err.msg);
      }
      n = s->n;
      end[h] = malloc(sizeof(hd_body) * (size_t)n);
      memcpy(end[h], s->b, sizeof(hd_body) * (size_t)n);
      hd_sim_free(s);
    }
    for (int h = 1; h < 3; h++)
      for (int32_t i = 0; i < n; i++) {
        assert_memory_equal(&end[0][i].k, &end[h][i].k, sizeof(hd_kin));
        assert_true(end[0][i].t == end[h][i].t && end[0][i].ev_t == end[h][i].ev_t);
      }
    for (int h = 0; h < 3; h++) free(end[h]);
  }
}

/* The contact angles are left out (NaN) when the scene logs no collision ([log] collisions =
 * none, hd_sim.angles = 0: two atan2 per collision of bodies of several disks saved), and
 * nothing else changes: a dimer-disk mixture and a trimer-disk mixture (the general rule), each
 * run with and without them, have the same events with the same times, bodies, disks, vn, de and
 * f bit for bit, and the same final state; with them the angle of a body of several disks is a
 * number in (-pi, pi] (NaN for a disk at its centre), without them NaN. */
static void angles_only_when_logged(void **state) {
  (void)state;
  for (int tri = 0; tri < 2; tri++) {
    hd_sim *s[2];
    hd_error err;
    for (int k = 0; k < 2; k++) {
      hd_scene sc;
      test_disk_scene(&sc, 400, 0.08, 0.9, 19); /* 0.24 with the dimers, 0.20 with trimers */
      if (tri) {
        hd_scene_species *sp = &sc.named[sc.n_named++];
        snprintf(sp->name, sizeof sp->name, "trimer");
        sp->count = 200;
        sp->ndisk = 3;
        for (int d = 0; d < 3; d++) sp->x[d] = d, sp->y[d] = 0, sp->d[d] = sp->m[d] = 1;
        sp->alpha = 0.95;
        for (int j = 0; j < 2; j++) sc.alpha_pair[2][j] = sc.alpha_pair[j][2] = 0.85;
      } else {
        sc.n_dimers = 400, sc.dimer_alpha = 0.95, sc.disk_alpha_dimer = 0.8;
      }
      sc.log_collisions = k ? HD_LOG_NONE : HD_LOG_ALL;
      assert_int_equal(hd_sim_alloc(&s[k], &sc, &err), HD_OK);
    }
    assert_int_equal(s[0]->angles, 1);
    assert_int_equal(s[1]->angles, 0);
    long steps = test_size(20000, 10), with_angle = 0;
    for (long n = 0; n < steps; n++) {
      hd_event_out e[2];
      for (int k = 0; k < 2; k++)
        if (hd_sim_next(s[k], INFINITY, &e[k], &err)) fail_msg("event %ld: %s", n, err.msg);
      assert_memory_equal(&e[0].t, &e[1].t, sizeof(double));
      assert_true(e[0].i == e[1].i && e[0].j == e[1].j && e[0].ka == e[1].ka && e[0].kb == e[1].kb);
      assert_memory_equal(&e[0].info.vn, &e[1].info.vn, sizeof(double));
      assert_memory_equal(&e[0].info.de, &e[1].info.de, sizeof(double));
      assert_memory_equal(&e[0].info.f, &e[1].info.f, sizeof(double));
      /* a number for the disks of a body off its centre (a trimer's middle disk has no axis) */
      for (int side = 0; side < 2; side++) {
        double th = side ? e[0].info.theta_j : e[0].info.theta_i;
        int32_t b = side ? e[0].j : e[0].i;
        if (isnan(th)) continue;
        assert_true(b >= 0 && s[0]->shape[s[0]->b[b].species].n > 1);
        assert_true(th > -M_PI && th <= M_PI);
        with_angle++;
      }
      assert_true(isnan(e[1].info.theta_i) && isnan(e[1].info.theta_j));
    }
    assert_true(with_angle > steps / 4); /* the check saw dimers or trimers, not only disks */
    for (int32_t i = 0; i < s[0]->n; i++)
      assert_memory_equal(&s[0]->b[i].k, &s[1]->b[i].k, sizeof(hd_kin));
    hd_sim_free(s[0]);
    hd_sim_free(s[1]);
  }
}

/* Near jamming: 1000 elastic disks at area fraction 0.72 (a melted lattice; hard disks freeze
 * near 0.70), 2e5 collisions in verification mode: energy drift < 1e-10, no overlap, and the
 * melt left no overlap and a Maxwellian start (exact T). */
static void near_jamming(void **state) {
  (void)state;
  hd_scene sc;
  test_disk_scene(&sc, 1000, 0.72, 1.0, 3);
  sc.verify = 1;
  hd_sim *s;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  int32_t i, j;
  assert_true(hd_sim_max_overlap(s, &i, &j) < 1e-12);
  double e0t, e0r;
  hd_sim_energy(s, -1, &e0t, &e0r);
  assert_true(fabs(e0t / 1000.0 - 1.0) < 1e-12);
  hd_event_out ev;
  long n = test_size(200000, 10);
  for (long k = 0; k < n; k++)
    if (hd_sim_next(s, INFINITY, &ev, &err)) fail_msg("%s", err.msg);
  double e1t, e1r;
  hd_sim_energy(s, -1, &e1t, &e1r);
  printf("# near jamming (eta 0.72): drift %.3g, max overlap %.3g\n", fabs(e1t - e0t) / e0t,
         s->max_overlap);
  assert_true(fabs(e1t - e0t) / e0t < 1e-10);
  assert_true(s->max_overlap < 1e-9);
  hd_sim_free(s);
}

/* Enskog: elastic disks collide at nu0 = 2 sqrt(pi) n sigma g(sigma) sqrt(T/m) per particle
 * (cpd per unit time), Henderson g = (1 - 7 eta/16)/(1 - eta)^2.  Measured over 2e5 collisions
 * (N = 2000) after 5e4 of equilibration; the statistical error of the rate is ~0.5 %, and
 * Henderson's g is itself good to ~0.5 % below eta = 0.3, so the tolerance is 1.5 %. */
static void enskog_rate(void **state) {
  (void)state;
  double etas[3] = {0.05, 0.15, 0.3};
  for (int e = 0; e < 3; e++) {
    double eta = etas[e];
    hd_scene sc;
    long N = test_size(2000, 4);
    test_disk_scene(&sc, N, eta, 1.0, 7 + (unsigned)e);
    hd_sim *s;
    hd_error err;
    assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
    hd_event_out ev;
    long warm = test_size(50000, 20), meas = test_size(200000, 20);
    for (long k = 0; k < warm; k++) assert_int_equal(hd_sim_next(s, INFINITY, &ev, &err), HD_OK);
    double t0 = hd_sim_time(s), c0 = hd_sim_cpd(s);
    for (long k = 0; k < meas; k++) assert_int_equal(hd_sim_next(s, INFINITY, &ev, &err), HD_OK);
    double rate = (hd_sim_cpd(s) - c0) / (hd_sim_time(s) - t0);
    double et, er;
    hd_sim_energy(s, -1, &et, &er);
    double T = et / (double)N, n = (double)N / (sc.box_x * sc.box_y);
    double g = (1 - 7 * eta / 16) / ((1 - eta) * (1 - eta));
    double nu0 = 2 * sqrt(M_PI) * n * g * sqrt(T);
    printf("# eta %.2f: rate %.5f, Enskog %.5f, ratio %.4f\n", eta, rate, nu0, rate / nu0);
    if (!test_sanitized()) assert_true(fabs(rate / nu0 - 1) < 0.015);
    hd_sim_free(s);
  }
}

/* Velocities after equilibration: each component of every disk's velocity, scaled by sqrt(T),
 * passes a Kolmogorov-Smirnov test against the unit Gaussian at the 1 % level (N = 2000: 4000
 * values; fixed seed, so the outcome is reproducible; the asymptotic Kolmogorov distribution
 * gives the p-value). */
static void maxwellian(void **state) {
  (void)state;
  hd_scene sc;
  long N = 2000;
  test_disk_scene(&sc, N, 0.1, 1.0, 11);
  hd_sim *s;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  hd_event_out ev;
  long steps = test_size(100000, 10);
  for (long k = 0; k < steps; k++) assert_int_equal(hd_sim_next(s, INFINITY, &ev, &err), HD_OK);
  double et, er;
  hd_sim_energy(s, -1, &et, &er);
  double T = et / (double)N;
  double *v = malloc(sizeof(double) * 2 * (size_t)N);
  for (long i = 0; i < N; i++)
    v[2 * i] = s->b[i].k.vx / sqrt(T), v[2 * i + 1] = s->b[i].k.vy / sqrt(T);
  size_t m = 2 * (size_t)N;
  gsl_sort(v, 1, m);
  double d = 0;
  for (size_t i = 0; i < m; i++) {
    double F = gsl_cdf_ugaussian_P(v[i]);
    d = fmax(d, fmax((double)(i + 1) / (double)m - F, F - (double)i / (double)m));
  }
  double lam = (sqrt((double)m) + 0.12 + 0.11 / sqrt((double)m)) * d, p = 0;
  for (int k = 1; k < 100; k++) p += 2 * ((k & 1) ? 1 : -1) * exp(-2.0 * k * k * lam * lam);
  printf("# KS distance %.4f, p = %.3f\n", d, p);
  assert_true(p > 0.01);
  free(v);
  hd_sim_free(s);
}

/* Haff's law: dilute inelastic disks (eta = 0.02, alpha = 0.95, N = 2000) over 20 cpd:
 * ln T against cpd is a line of slope -(1 - alpha^2)/D_e, D_e = 2 for disks.  The slope is fitted
 * by least squares; the tolerance 3 % covers the finite-density and velocity-distribution
 * (Sonine) corrections, ~1 %, and the sampling noise of 2e4 collisions, ~1 %. */
static void haff_law(void **state) {
  (void)state;
  hd_scene sc;
  long N = test_size(2000, 4);
  double alpha = 0.95;
  test_disk_scene(&sc, N, 0.02, alpha, 5);
  hd_sim *s;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  enum { NP = 40 };
  double x[NP], y[NP];
  int np = 0;
  hd_event_out ev;
  double next = 1.0; /* skip the first cpd: the initial Maxwellian relaxes to the HCS */
  while (np < NP) {
    assert_int_equal(hd_sim_next(s, INFINITY, &ev, &err), HD_OK);
    if (hd_sim_cpd(s) >= next) {
      double et, er;
      hd_sim_energy(s, -1, &et, &er);
      x[np] = hd_sim_cpd(s);
      y[np++] = log(et / (double)N);
      next += 0.5;
    }
  }
  double c0, c1, c00, c01, c11, ss;
  gsl_fit_linear(x, 1, y, 1, NP, &c0, &c1, &c00, &c01, &c11, &ss);
  double De = -(1 - alpha * alpha) / c1;
  printf("# Haff: slope %.5f +- %.5f, D_e = %.4f (expected 2)\n", c1, sqrt(c11), De);
  if (!test_sanitized()) assert_true(fabs(De / 2 - 1) < 0.03);
  hd_sim_free(s);
}

/* Energies falling over many decades: 64 dilute disks at alpha = 0.95 cool until their energy
 * is 1e-60 of the start, every event verified (no overlap, time order).  Two failures of long
 * cooling are held here.  (1) They were stopped as "collapsed" near E/E0 = 1e-16 while colliding
 * at the thermal speed: the booked energy (the running sum of de, whose round-off is ~1e-16 of
 * the starting energy) had gone to <= 0, so every collision looked slow (rebook_energy).  (2)
 * Near E/E0 = 1e-33 the thermal speed reaches the round-off drift of the zero total momentum
 * and the gas moved as a whole: 1.4e5 cell crossings per collision, a run that no longer
 * advanced (remove_drift: the centre-of-mass frame is restored at a rebase).  Here the events
 * stay below 20 per collision, the frame was restored at least once, and the time keeps growing
 * like Haff's t ~ E^(-1/2): the last decade of E takes longer than the first. */
static void cooling_many_decades(void **state) {
  (void)state;
  hd_scene sc;
  test_disk_scene(&sc, 64, 0.05, 0.95, 11);
  sc.verify = 1;
  hd_sim *s;
  hd_error err;
  assert_int_equal(hd_sim_alloc(&s, &sc, &err), HD_OK);
  hd_event_out ev;
  double et, er, e0;
  hd_sim_energy(s, -1, &e0, &er);
  double t_decade1 = NAN, t_last = 0, t_prev = 0, target = 0.1;
  long coll = 0;
  void *blob = NULL; /* a checkpoint at 1e-20, before the frame is restored */
  size_t nblob = 0;
  for (et = e0; coll < 1000000;) { /* ~90000 collisions are needed: a run that stalls fails */
    int rc = hd_sim_next(s, INFINITY, &ev, &err);
    if (rc) print_error("%s\n", err.msg);
    assert_int_equal(rc, HD_OK);
    if (++coll % 100) continue;
    hd_sim_energy(s, -1, &et, &er);
    if (!blob && et <= 1e-20 * e0) {
      assert_int_equal(s->drift_removed, 0);
      assert_int_equal(hd_sim_checkpoint(s, &blob, &nblob, &err), HD_OK);
    }
    if (et <= target * e0) {
      double t = hd_sim_time(s);
      if (isnan(t_decade1)) t_decade1 = t;
      t_last = t - t_prev, t_prev = t;
      target *= 0.1;
    }
    if (et <= 1e-60 * e0) break;
  }
  printf("# 64 disks, alpha 0.95: E/E0 = %.3g after %ld collisions (%.4g cpd), %lld events, "
         "frame restored %lld times, t = %.4g; first decade t = %.3g, last %.3g\n",
         et / e0, coll, hd_sim_cpd(s), (long long)s->c.events, (long long)s->drift_removed,
         hd_sim_time(s), t_decade1, t_last);
  assert_true(et <= 1e-60 * e0);
  assert_true(t_last > t_decade1);
  assert_true(s->c.events < 20 * s->c.collisions);
  assert_true(s->drift_removed >= 1);
  /* resumed from the checkpoint, the run restores its frame at the same events and ends in the
   * very same state (bit for bit) */
  hd_sim *r;
  assert_non_null(blob);
  assert_int_equal(hd_sim_alloc_restore(&r, &sc, blob, nblob, &err), HD_OK);
  while (r->c.collisions < s->c.collisions)
    assert_int_equal(hd_sim_next(r, INFINITY, &ev, &err), HD_OK);
  assert_int_equal(r->drift_removed, s->drift_removed);
  assert_true(r->c.events == s->c.events && r->c.t == s->c.t);
  for (int32_t i = 0; i < s->n; i++) {
    hd_kin a, b;
    hd_sim_body_now(s, i, &a);
    hd_sim_body_now(r, i, &b);
    assert_true(a.x == b.x && a.y == b.y && a.vx == b.vx && a.vy == b.vy);
  }
  free(blob);
  hd_sim_free(r);
  hd_sim_free(s);
}

/* Issue 24 item 11: 5 disks at area fraction 1e-9 (a box of 6.3e4 diameters) failed
 * verification at t = 4.9e7, colliding 6.3e-9 of a diameter from contact: the time origin was
 * rebased every 1e5 events only, so the clock grew to ~1e8 before (its round-off ~1e-8), and
 * the discriminant of the contact time of a pair 1e4 diameters apart cancelled (~1e-16 r^2 / D).
 * Now the origin is also rebased after a flight of 1e4 diameters and far pairs take the
 * discriminant without cancellation: the run goes to t = 1e9 (10 collisions, the first at
 * t ~ 4e7, and ~4e5 cell crossings: the mean free time is ~1e8) verified at every collision
 * (contact distance and overlaps within 1e-9 of a diameter), its energy conserved to 1e-9
 * (elastic). */
static void dilute_precision(void **state) {
  (void)state;
  hd_scene sc;
  hd_error err;
  if (hd_scene_load_string(&sc,
                           "[system]\narea_fraction = 1e-9\nseed = 1\n[disks]\ncount = 5\n[run]\n"
                           "stop_time = 1e9\nverify = 1\n",
                           "dilute.ini", NULL, 0, &err))
    fail_msg("%s", err.msg);
  hd_sim *s;
  if (hd_sim_alloc(&s, &sc, &err)) fail_msg("%s", err.msg);
  double e0t, e0r, et, er;
  hd_sim_energy(s, -1, &e0t, &e0r);
  long n = 0;
  for (;;) {
    hd_event_out ev;
    int rc = hd_sim_next(s, 1e9, &ev, &err);
    if (rc == HD_SIM_STOPTIME) break;
    if (rc == HD_SIM_BUSY) continue;
    if (rc) fail_msg("after %ld collisions: %s", n, err.msg);
    n++;
  }
  hd_sim_energy(s, -1, &et, &er);
  printf("# dilute: %ld collisions to t = 1e9, max overlap %.3g, energy drift %.3g\n", n,
         s->max_overlap, fabs(et - e0t) / e0t);
  assert_true(n >= 5);
  assert_true(s->max_overlap < 1e-9);
  assert_true(fabs(et - e0t) < 1e-9 * e0t);
  hd_sim_free(s);
  hd_scene_free(&sc);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(head_on),
      cmocka_unit_test(angles_only_when_logged),
      cmocka_unit_test(huge_box_in_diameters),
      cmocka_unit_test(oblique_grazing_periodic),
      cmocka_unit_test(collision_across_wrap),
      cmocka_unit_test(image_code_long_runs),
      cmocka_unit_test(disk_contact_rule),
      cmocka_unit_test(alpha_zero_gas),
      cmocka_unit_test(alpha_zero_fast_pair),
      cmocka_unit_test(lattice_fits_scene_check),
      cmocka_unit_test(near_jamming),
      cmocka_unit_test(prefetch_hints_change_nothing),
      cmocka_unit_test(elastic_conservation),
      cmocka_unit_test(enskog_rate),
      cmocka_unit_test(maxwellian),
      cmocka_unit_test(haff_law),
      cmocka_unit_test(state_measures),
      cmocka_unit_test(cooling_many_decades),
      cmocka_unit_test(dilute_precision),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
