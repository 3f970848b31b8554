/* Tests of hd_body: shapes, free flight, the collision rules (against conservation laws, the
 * paper's energy formulas eq. 19/20/23/26, eq. 36 and the generic rigid-body impulse rule), and
 * contact prediction against an independent brute force (dense sampling of the gap, Brent
 * refinement of every small sampled minimum, bisection of the first sign change).
 * All random cases use gsl_rng_mt19937 with fixed seeds.  Sizes shrink under HAFF_SANITIZE=1. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "hd_body.h"
#include "hd_body_impulse.h"
#include "test_rng.h"
#include "test_sim.h"

static int sanitize(void) {
  const char *s = getenv("HAFF_SANITIZE");
  return s && s[0] == '1';
}

static hd_shape dimer(double d, double a, double m) {
  hd_shape s;
  hd_shape_dimer(&s, d, a, m);
  return s;
}

static hd_shape disk(double d, double m) {
  hd_shape s;
  hd_shape_disk(&s, d, m);
  return s;
}

static int ndisks(const hd_shape *s) {
  return s->n;
}

/* The same shape for the general code (HD_KIND_BODY): its disks as given. */
static hd_shape general(const hd_shape *s) {
  hd_shape g;
  double x[HD_MAX_BODY_DISKS], y[HD_MAX_BODY_DISKS];
  for (int k = 0; k < s->n; k++) x[k] = s->ox[k], y[k] = s->oy[k];
  assert_int_equal(hd_shape_cluster(&g, s->n, x, y, s->dk, s->mk, 0), 0);
  assert_int_equal(g.tag, HD_KIND_BODY);
  return g;
}

/* A cluster of n disks at (x, y) with diameters d, masses m, tagged by hd_shape_cluster. */
static hd_shape cluster(int n, const double *x, const double *y, const double *d, const double *m) {
  hd_shape g;
  assert_int_equal(hd_shape_cluster(&g, n, x, y, d, m, 1), 0);
  return g;
}

static hd_shape trimer_linear(void);
static hd_shape trimer_bent(void);
static hd_shape trimer_triangle(void);
static hd_shape dimer_asym(void);

/* ---- independent kinematics (not using hd_body) ------------------------------------------ */

/* Centre of disk k of a body at time t of free flight from state b. */
static void ref_pos(const hd_kin *b, const hd_shape *s, int k, double t, double *x, double *y) {
  *x = b->x + b->vx * t;
  *y = b->y + b->vy * t;
  if (s->tag == HD_KIND_DIMER) {
    double g = (k ? 0.5 : -0.5) * s->a, ang = b->phi + b->omega * t;
    *x += g * cos(ang);
    *y += g * sin(ang);
  } else if (s->tag == HD_KIND_BODY) { /* the offset turned by the angle */
    double ang = b->phi + b->omega * t;
    *x += s->ox[k] * cos(ang) - s->oy[k] * sin(ang);
    *y += s->ox[k] * sin(ang) + s->oy[k] * cos(ang);
  }
}

static void ref_vel(const hd_kin *b, const hd_shape *s, int k, double *vx, double *vy) {
  *vx = b->vx;
  *vy = b->vy;
  if (s->tag == HD_KIND_DIMER) {
    double g = (k ? 0.5 : -0.5) * s->a * b->omega;
    *vx -= g * sin(b->phi);
    *vy += g * cos(b->phi);
  } else if (s->tag == HD_KIND_BODY) { /* omega x the turned offset */
    double c = cos(b->phi), sn = sin(b->phi);
    *vx -= b->omega * (s->ox[k] * sn + s->oy[k] * c);
    *vy += b->omega * (s->ox[k] * c - s->oy[k] * sn);
  }
}

/* Kinetic energy as the sum over disks (for a dimer: m v1^2/2 + m v2^2/2). */
static double ref_ke(const hd_kin *b, const hd_shape *s) {
  double e = 0.0;
  for (int k = 0; k < ndisks(s); k++) {
    double vx, vy;
    ref_vel(b, s, k, &vx, &vy);
    e += 0.5 * s->mk[k] * (vx * vx + vy * vy);
  }
  return e;
}

/* Gap of disk pair (i, j) at time t. */
static double ref_gap_pair(const hd_kin *A, const hd_shape *sa, const hd_kin *B, const hd_shape *sb,
                           int i, int j, double t) {
  double xa, ya, xb, yb;
  ref_pos(A, sa, i, t, &xa, &ya);
  ref_pos(B, sb, j, t, &xb, &yb);
  return hypot(xb - xa, yb - ya) - 0.5 * (sa->dk[i] + sb->dk[j]);
}

/* The brute-force gap function: pairs or a wall, with an optional ignored pair. */
typedef struct bf {
  const hd_kin *A, *B;
  const hd_shape *sa, *sb;
  const hd_wall *w; /* not NULL: gap of A to the wall */
  int skip;         /* pair index ignored (-1: none) */
} bf;

static double bf_gap(double t, void *par) {
  const bf *f = par;
  double g = HUGE_VAL;
  if (f->w) {
    for (int i = 0; i < ndisks(f->sa); i++) {
      double x, y;
      ref_pos(f->A, f->sa, i, t, &x, &y);
      double v = f->w->normal * ((f->w->axis ? y : x) - f->w->pos) - 0.5 * f->sa->dk[i];
      if (v < g) g = v;
    }
    return g;
  }
  for (int i = 0; i < ndisks(f->sa); i++)
    for (int j = 0; j < ndisks(f->sb); j++) {
      if (i * ndisks(f->sb) + j == f->skip) continue;
      double v = ref_gap_pair(f->A, f->sa, f->B, f->sb, i, j, t);
      if (v < g) g = v;
    }
  return g;
}

/* Minimum of the gap on [lo, hi] around a sampled minimum at mid (GSL Brent). */
static double bf_refine_min(bf *f, double lo, double mid, double hi, double *tm) {
  gsl_function F = {bf_gap, f};
  gsl_min_fminimizer *m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
  if (gsl_min_fminimizer_set(m, &F, mid, lo, hi) != GSL_SUCCESS) {
    gsl_min_fminimizer_free(m);
    *tm = mid;
    return bf_gap(mid, f);
  }
  for (int it = 0; it < 200; it++) {
    gsl_min_fminimizer_iterate(m);
    double a = gsl_min_fminimizer_x_lower(m), b = gsl_min_fminimizer_x_upper(m);
    if (gsl_min_test_interval(a, b, 1e-15, 0.0) == GSL_SUCCESS) break;
  }
  *tm = gsl_min_fminimizer_x_minimum(m);
  double v = gsl_min_fminimizer_f_minimum(m);
  gsl_min_fminimizer_free(m);
  return v;
}

/* First root of the gap in [lo, hi] with gap(lo) > 0 > gap(hi), by bisection to round-off. */
static double bf_bisect(bf *f, double lo, double hi) {
  for (int it = 0; it < 200 && hi - lo > 1e-16 * (1.0 + hi); it++) {
    double mid = 0.5 * (lo + hi);
    if (bf_gap(mid, f) > 0.0)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

/* Brute force: first time in (t0, tmax] the gap turns negative, sampled on n points; every
 * sampled local minimum below 0.05 is refined.  Returns 1 and *t if found; *gmin is the smallest
 * gap seen (refined). */
static int bf_first(bf *f, double t0, double tmax, int n, double *t, double *gmin) {
  double dt = (tmax - t0) / n, gpp = HUGE_VAL, gp = bf_gap(t0, f);
  *gmin = gp;
  for (int k = 1; k <= n; k++) {
    double tk = t0 + k * dt, g = bf_gap(tk, f);
    if (g < *gmin) *gmin = g;
    if (g < 0.0) {
      *t = bf_bisect(f, tk - dt, tk);
      return 1;
    }
    if (k >= 2 && gp < gpp && gp < g && gp < 0.05) {
      double tm, gm = bf_refine_min(f, tk - 2 * dt, tk - dt, tk, &tm);
      if (gm < *gmin) *gmin = gm;
      if (gm < 0.0) {
        *t = bf_bisect(f, tk - 2 * dt, tm);
        return 1;
      }
    }
    gpp = gp;
    gp = g;
  }
  return 0;
}

/* Smallest gap over [0, tmax]: n samples, every sampled local minimum refined (GSL Brent). */
static double bf_min(bf *f, double tmax, int n) {
  double dt = tmax / n, gpp = HUGE_VAL, gp = bf_gap(0.0, f), gmin = gp;
  for (int k = 1; k <= n; k++) {
    double tk = k * dt, g = bf_gap(tk, f), tm;
    if (g < gmin) gmin = g;
    if (k >= 2 && gp < gpp && gp < g) {
      double gm = bf_refine_min(f, tk - 2 * dt, tk - dt, tk, &tm);
      if (gm < gmin) gmin = gm;
    }
    gpp = gp;
    gp = g;
  }
  return gmin;
}

/* ---- shapes and free flight --------------------------------------------------------------- */

static void shapes(void **state) {
  (void)state;
  hd_shape s = dimer(1.0, 1.0, 1.0), t = dimer(0.5, 3.0, 2.0), u = disk(1.3, 4.0);
  /* by definition: 2m, m a^2/2, (a + d)/2 */
  assert_true(hd_shape_mass(&s) == 2.0 && hd_shape_inertia(&s) == 0.5);
  assert_true(hd_shape_radius(&s) == 1.0);
  assert_true(hd_shape_mass(&t) == 4.0 && hd_shape_inertia(&t) == 9.0);
  assert_true(hd_shape_radius(&t) == 1.75);
  assert_true(hd_shape_mass(&u) == 4.0 && hd_shape_inertia(&u) == 0.0);
  assert_true(hd_shape_radius(&u) == 0.65);
}

/* Angle difference modulo 2 pi, in [0, pi]. */
static double angdiff(double a, double b) {
  return fabs(remainder(a - b, 2.0 * M_PI));
}

static void free_flight(void **state) {
  (void)state;
  gsl_rng *r = rng_new(11);
  hd_shape s = dimer(1.0, 1.0, 1.0);
  for (int n = 0; n < 2000; n++) {
    hd_kin k0 = {unif(r, -50, 50),       unif(r, -50, 50),
                 gsl_ran_gaussian(r, 1), gsl_ran_gaussian(r, 1),
                 unif(r, -M_PI, M_PI),   gsl_ran_gaussian(r, n % 3 == 0 ? 1e3 : 2.0)};
    double dt = unif(r, -3, 3);
    hd_kin k = k0;
    hd_kin_advance(&k, dt);
    assert_true(k.phi > -M_PI && k.phi <= M_PI);
    hd_kin_advance(&k, -dt);
    /* round-off of x + v dt - v dt and of phi + w dt - w dt: 1e-14 relative to the sizes involved
     */
    assert_true(fabs(k.x - k0.x) <= 1e-14 * (fabs(k0.x) + fabs(k0.vx * dt)));
    assert_true(fabs(k.y - k0.y) <= 1e-14 * (fabs(k0.y) + fabs(k0.vy * dt)));
    assert_true(angdiff(k.phi, k0.phi) <= 1e-14 * (M_PI + fabs(k0.omega * dt)));
    assert_true(k.vx == k0.vx && k.vy == k0.vy && k.omega == k0.omega);
    /* composition: dt1 then dt2 equals dt1 + dt2 (same round-off bound) */
    double d1 = unif(r, 0, 2), d2 = unif(r, 0, 2);
    hd_kin a = k0, b = k0;
    hd_kin_advance(&a, d1);
    hd_kin_advance(&a, d2);
    hd_kin_advance(&b, d1 + d2);
    assert_true(angdiff(a.phi, b.phi) <= 1e-14 * (M_PI + fabs(k0.omega) * (d1 + d2)));
    /* omega = 0 exactly keeps phi bit for bit */
    hd_kin c = k0;
    c.omega = 0.0;
    hd_kin_advance(&c, dt * 1e3);
    assert_true(c.phi == k0.phi);
    /* disk velocity = derivative of the disk position (central difference, h = 1e-6:
     * truncation ~ w^2 a h^2 ~ 1e-6 at w = 1e3, round-off ~ 50 * 1e-16 / 1e-6) */
    for (int w = 0; w < 2; w++) {
      double h = 1e-6 / (1.0 + fabs(k0.omega) * 1e-3), xp, yp, xm, ym, vx, vy;
      hd_kin p = k0, m = k0;
      hd_kin_advance(&p, h);
      hd_kin_advance(&m, -h);
      hd_kin_disk_pos(&p, &s, w, &xp, &yp);
      hd_kin_disk_pos(&m, &s, w, &xm, &ym);
      hd_kin_disk_vel(&k0, &s, w, &vx, &vy);
      double sc = 1.0 + fabs(k0.omega);
      assert_true(fabs((xp - xm) / (2 * h) - vx) <= 1e-5 * sc);
      assert_true(fabs((yp - ym) / (2 * h) - vy) <= 1e-5 * sc);
      double rx, ry;
      ref_pos(&k0, &s, w, 0.0, &rx, &ry);
      hd_kin_disk_pos(&k0, &s, w, &xp, &yp);
      assert_true(fabs(rx - xp) <= 1e-14 * 50 && fabs(ry - yp) <= 1e-14 * 50);
    }
    /* (2m) V^2/2 + I w^2/2 equals the sum over disks (Koenig), to round-off */
    double e1 = test_kin_energy(&k0, &s), e2 = ref_ke(&k0, &s);
    assert_true(fabs(e1 - e2) <= 1e-13 * e2);
  }
  gsl_rng_free(r);
}

/* ---- collision rules ---------------------------------------------------------------------- */

/* A random state of two bodies in contact at disks (ka, kb), no other pair overlapping, with
 * approaching contact points.  wsc: scale of the angular velocities. */
static void random_contact(gsl_rng *r, const hd_shape *sa, const hd_shape *sb, double wsc,
                           hd_kin *A, hd_kin *B, int *ka, int *kb) {
  for (;;) {
    hd_kin a = {unif(r, -5, 5),         unif(r, -5, 5),       gsl_ran_gaussian(r, 1),
                gsl_ran_gaussian(r, 1), unif(r, -M_PI, M_PI), gsl_ran_gaussian(r, wsc)};
    hd_kin b = {0,
                0,
                gsl_ran_gaussian(r, 1),
                gsl_ran_gaussian(r, 1),
                unif(r, -M_PI, M_PI),
                gsl_ran_gaussian(r, wsc)};
    if (sa->tag == HD_KIND_DISK) a.phi = a.omega = 0.0;
    if (sb->tag == HD_KIND_DISK) b.phi = b.omega = 0.0;
    int i = (int)gsl_rng_uniform_int(r, (unsigned long)ndisks(sa));
    int j = (int)gsl_rng_uniform_int(r, (unsigned long)ndisks(sb));
    double D = 0.5 * (sa->dk[i] + sb->dk[j]);
    double ang = unif(r, -M_PI, M_PI), pax, pay, obx, oby;
    ref_pos(&a, sa, i, 0.0, &pax, &pay);
    ref_pos(&b, sb, j, 0.0, &obx, &oby); /* offset of B's disk from B's centre (b at 0) */
    b.x = pax + D * cos(ang) - obx;
    b.y = pay + D * sin(ang) - oby;
    int ok = 1;
    for (int p = 0; p < ndisks(sa); p++)
      for (int q = 0; q < ndisks(sb); q++)
        if ((p != i || q != j) && ref_gap_pair(&a, sa, &b, sb, p, q, 0.0) < 1e-9) ok = 0;
    if (!ok) continue;
    double v1x, v1y, v3x, v3y;
    ref_vel(&a, sa, i, &v1x, &v1y);
    ref_vel(&b, sb, j, &v3x, &v3y);
    double vn = (v3x - v1x) * cos(ang) + (v3y - v1y) * sin(ang);
    if (fabs(vn) < 1e-3) continue;
    if (vn > 0) { /* reverse time: both bodies' velocities */
      a.vx = -a.vx, a.vy = -a.vy, a.omega = -a.omega;
      b.vx = -b.vx, b.vy = -b.vy, b.omega = -b.omega;
    }
    *A = a;
    *B = b;
    *ka = i;
    *kb = j;
    return;
  }
}

/* Largest disk-centre speed of a body (the velocity scale of the tolerances). */
static double vscale(const hd_kin *k, const hd_shape *s) {
  double m = 0.0;
  for (int i = 0; i < ndisks(s); i++) {
    double vx, vy;
    ref_vel(k, s, i, &vx, &vy);
    m = fmax(m, hypot(vx, vy));
  }
  return m;
}

/* Angular momentum about (px, py): the sum over the disks (point masses at their centres). */
static double ang_mom(const hd_kin *k, const hd_shape *s, double px, double py) {
  double L = 0.0;
  for (int i = 0; i < ndisks(s); i++) {
    double x, y, vx, vy;
    ref_pos(k, s, i, 0.0, &x, &y);
    ref_vel(k, s, i, &vx, &vy);
    L += s->mk[i] * ((x - px) * vy - (y - py) * vx);
  }
  return L;
}

/* The paper's energy change of a pair collision (eq. 19, 20, 23), from its own vectors. */
static double paper_de(const hd_kin *A, const hd_shape *sa, const hd_kin *B, const hd_shape *sb,
                       int ka, int kb, double alpha) {
  double r1x, r1y, r2x, r2y, r3x, r3y, r4x, r4y, v1x, v1y, v3x, v3y;
  ref_pos(A, sa, ka, 0, &r1x, &r1y);
  ref_pos(A, sa, 1 - ka, 0, &r2x, &r2y);
  ref_pos(B, sb, kb, 0, &r3x, &r3y);
  ref_pos(B, sb, 1 - kb, 0, &r4x, &r4y);
  ref_vel(A, sa, ka, &v1x, &v1y);
  ref_vel(B, sb, kb, &v3x, &v3y);
  double r13x = r1x - r3x, r13y = r1y - r3y, r12x = r1x - r2x, r12y = r1y - r2y;
  double r34x = r3x - r4x, r34y = r3y - r4y, d2 = r13x * r13x + r13y * r13y;
  double g = (v3x - v1x) * r13x + (v3y - v1y) * r13y, l = 1.0 - alpha * alpha;
  if (sa->tag == HD_KIND_DIMER && sb->tag == HD_KIND_DIMER) { /* eq. 19 (equal m, a) */
    if (sa->a != sb->a || sa->m != sb->m) return NAN;         /* not in the paper */
    double a2 = sa->a * sa->a, x = r13x * r12x + r13y * r12y, y = r13x * r34x + r13y * r34y;
    return -sa->m * l / (4 * d2) * g * g / (1 - (x * x + y * y) / (4 * a2 * d2));
  }
  if (sa->tag == HD_KIND_DIMER || sb->tag == HD_KIND_DIMER) { /* eq. 23, C^2 = d2 */
    const hd_shape *sd = sa->tag == HD_KIND_DIMER ? sa : sb, *sk = sd == sa ? sb : sa;
    double x = sd == sa ? -(r13x * r12x + r13y * r12y) : (r13x * r34x + r13y * r34y);
    return -sd->m * l / (2 * d2) * g * g / (1 + sd->m / sk->m - x * x / (2 * sd->a * sd->a * d2));
  }
  double mu = sa->m * sb->m / (sa->m + sb->m); /* eq. 20 with masses */
  return -0.5 * mu * l * g * g / d2;
}

/* Normal velocity (B - A).n of the contact points, n = unit vector between the disk centres. */
static double ref_vn(const hd_kin *A, const hd_shape *sa, const hd_kin *B, const hd_shape *sb,
                     int ka, int kb) {
  double ax, ay, bx, by, avx, avy, bvx, bvy;
  ref_pos(A, sa, ka, 0, &ax, &ay);
  ref_pos(B, sb, kb, 0, &bx, &by);
  ref_vel(A, sa, ka, &avx, &avy);
  ref_vel(B, sb, kb, &bvx, &bvy);
  double n = hypot(bx - ax, by - ay);
  return ((bvx - avx) * (bx - ax) + (bvy - avy) * (by - ay)) / n;
}

/* Outward axis angle test: cos and sin of theta against e.n, e x n from the disk positions. */
static void check_theta(const hd_kin *k, const hd_shape *s, int kk, double nx, double ny, double th,
                        double D) {
  if (s->tag != HD_KIND_DIMER) {
    assert_true(isnan(th));
    return;
  }
  double c1x, c1y, c2x, c2y;
  ref_pos(k, s, kk, 0, &c1x, &c1y);
  ref_pos(k, s, 1 - kk, 0, &c2x, &c2y);
  /* e from the disk positions: accurate to ~1e-16 |x| / a; a >= 1e-3 here */
  double ex = (c1x - c2x) / s->a, ey = (c1y - c2y) / s->a, tol = 1e-11;
  assert_true(th > -M_PI && th <= M_PI);
  assert_true(fabs(cos(th) - (ex * nx + ey * ny)) <= tol);
  assert_true(fabs(sin(th) - (ex * ny - ey * nx)) <= tol);
  /* non-overlap of the partner disk: |theta| <= pi - acos(a / 2D) (Fig. 4) */
  if (s->a < 2 * D) assert_true(fabs(th) <= M_PI - acos(s->a / (2 * D)) + 1e-6);
}

/* One random pair collision checked in every way; returns nothing, asserts. */
static void check_pair_collision(gsl_rng *r, const hd_shape *sa, const hd_shape *sb, double alpha,
                                 double wsc) {
  hd_kin A, B;
  int ka, kb;
  random_contact(r, sa, sb, wsc, &A, &B, &ka, &kb);
  hd_kin A1 = A, B1 = B, A2 = A, B2 = B;
  hd_collision_info in, ig;
  hd_collide_pair(&A1, sa, &B1, sb, ka, kb, alpha, &in);
  hd_impulse_pair(&A2, sa, &B2, sb, ka, kb, alpha, &ig);
  double Ma = hd_shape_mass(sa), Mb = hd_shape_mass(sb);
  double vs = fmax(fmax(vscale(&A, sa), vscale(&B, sb)), fmax(vscale(&A1, sa), vscale(&B1, sb)));
  /* momentum: round-off of a few operations on momenta of size M vs (1e-13 relative) */
  double ps = (Ma + Mb) * vs;
  assert_true(fabs(Ma * (A1.vx - A.vx) + Mb * (B1.vx - B.vx)) <= 1e-13 * ps);
  assert_true(fabs(Ma * (A1.vy - A.vy) + Mb * (B1.vy - B.vy)) <= 1e-13 * ps);
  /* angular momentum about a random point up to 20 away: lever arms ~ 25 (1e-13 relative) */
  double px = unif(r, -20, 20), py = unif(r, -20, 20);
  double L0 = ang_mom(&A, sa, px, py) + ang_mom(&B, sb, px, py);
  double L1 = ang_mom(&A1, sa, px, py) + ang_mom(&B1, sb, px, py);
  assert_true(fabs(L1 - L0) <= 1e-13 * ps * 40);
  /* restitution of the normal velocity of the contact points (1e-12 of the speed scale) */
  double vn0 = ref_vn(&A, sa, &B, sb, ka, kb), vn1 = ref_vn(&A1, sa, &B1, sb, ka, kb);
  assert_true(vn0 < 0);
  assert_true(fabs(in.vn - vn0) <= 1e-12 * vs);
  assert_true(fabs(vn1 + alpha * vn0) <= 1e-12 * vs);
  /* energy: KE difference = info.de = paper eq. 19/20/23 (1e-12 of KE: round-off of sums) */
  double E0 = ref_ke(&A, sa) + ref_ke(&B, sb), E1 = ref_ke(&A1, sa) + ref_ke(&B1, sb);
  double dep = paper_de(&A, sa, &B, sb, ka, kb, alpha);
  assert_true(fabs((E1 - E0) - in.de) <= 1e-12 * E0);
  if (!isnan(dep)) assert_true(fabs(dep - in.de) <= 1e-12 * (E0 + fabs(dep)));
  assert_true(in.de <= 0.0 && E1 - E0 <= 1e-13 * E0);
  if (alpha == 1.0) assert_true(fabs(E1 - E0) <= 1e-13 * E0);
  /* paper formula == generic impulse rule (1e-12 of the speed scale; omega as a/2 omega) */
  double ha = 0.5 * sa->a, hb = 0.5 * sb->a;
  assert_true(fabs(A1.vx - A2.vx) <= 1e-12 * vs && fabs(A1.vy - A2.vy) <= 1e-12 * vs);
  assert_true(fabs(B1.vx - B2.vx) <= 1e-12 * vs && fabs(B1.vy - B2.vy) <= 1e-12 * vs);
  assert_true(ha * fabs(A1.omega - A2.omega) <= 1e-12 * vs);
  assert_true(hb * fabs(B1.omega - B2.omega) <= 1e-12 * vs);
  assert_true(A1.x == A.x && B1.y == B.y && A1.phi == A.phi);
  assert_true(in.f == ig.f && in.de == ig.de && in.vn == ig.vn);
  /* theta by the DESIGN convention, and f */
  double ax, ay, bx, by;
  ref_pos(&A, sa, ka, 0, &ax, &ay);
  ref_pos(&B, sb, kb, 0, &bx, &by);
  double D = hypot(bx - ax, by - ay), nx = (bx - ax) / D, ny = (by - ay) / D;
  check_theta(&A, sa, ka, nx, ny, in.theta_i, D);
  check_theta(&B, sb, kb, -nx, -ny, in.theta_j, D);
  double f;
  if (sa->tag == HD_KIND_DIMER && sb->tag == HD_KIND_DIMER) {
    /* eq. 36 for equal disk masses; in general mu/m_A = 1/((1 + s_i^2)/2 + (1 + s_j^2) m_A/(2 m_B))
     */
    double ci = cos(in.theta_i), cj = cos(in.theta_j), si = sin(in.theta_i), sj = sin(in.theta_j);
    f = 1.0 / (2.0 - (ci * ci + cj * cj) / 2.0); /* eq. 36 */
    assert_true(fabs(2.0 / (2.0 + si * si + sj * sj) - f) <= 1e-14);
    if (sa->m != sb->m) f = 1.0 / ((1 + si * si) / 2 + (1 + sj * sj) * sa->m / (2 * sb->m));
  } else if (sa->tag == HD_KIND_DIMER) {
    double c = cos(in.theta_i);
    f = 1.0 / (1.0 + sa->m / Mb - c * c / 2);
  } else if (sb->tag == HD_KIND_DIMER) {
    double c = cos(in.theta_j);
    f = 1.0 / (1.0 + sb->m / Ma - c * c / 2);
  } else {
    f = Mb / (Ma + Mb);
  }
  assert_true(fabs(in.f - f) <= 1e-12 * f);
  if (alpha == 0.0) assert_true(fabs(vn1) <= 1e-12 * vs);
  /* a pair that is not approaching is left alone */
  hd_kin A3 = A1, B3 = B1;
  if (alpha > 0.0) {
    hd_collide_pair(&A3, sa, &B3, sb, ka, kb, alpha, NULL);
    assert_true(A3.vx == A1.vx && B3.omega == B1.omega);
  }
}

static void collide_pairs(void **state) {
  (void)state;
  gsl_rng *r = rng_new(21);
  const double alphas[] = {0.0, 0.5, 0.9, 1.0}, as[] = {1e-3, 0.5, 1.0, 2.0, 3.0};
  int n = sanitize() ? 40 : 300;
  for (int ia = 0; ia < 5; ia++)
    for (int il = 0; il < 4; il++) {
      double a = as[ia], al = alphas[il], wsc = a < 0.01 ? 1.0 / a : 2.0;
      hd_shape dm = dimer(1.0, a, 1.0), dk = disk(1.4, 2.5), dk2 = disk(0.7, 0.8);
      for (int k = 0; k < n; k++) {
        check_pair_collision(r, &dm, &dm, al, wsc);
        check_pair_collision(r, &dm, &dk, al, wsc);
        check_pair_collision(r, &dk, &dm, al, wsc);
        if (ia == 0) check_pair_collision(r, &dk, &dk2, al, wsc);
        /* dimers of two species: other bond length (eq. 18 branch), other disk mass (general) */
        hd_shape o1 = dimer(1.0, as[(ia + 2) % 5], 1.0), o2 = dimer(0.6, 1.5, 0.3);
        check_pair_collision(r, &dm, &o1, al, wsc);
        check_pair_collision(r, &o2, &dm, al, wsc);
      }
    }
  gsl_rng_free(r);
}

/* Bond lengths far below 1e-154 (a^2 underflows): the rules give finite velocities that
 * conserve momentum and agree with the generic impulse rule (1e-12 of the speed scale).  The
 * paper's formulas divide (r13.r12)^2 by a^2; written that way they gave 0/0 = NaN at
 * a = 1e-170.  (Scenes refuse 0 < a < 1e-9 d, see hd_scene.h; the rules must still hold.) */
static void collide_tiny_bond(void **state) {
  (void)state;
  gsl_rng *r = rng_new(23);
  hd_shape dm = dimer(1.0, 1e-170, 1.0), dk = disk(1.4, 2.5);
  for (int k = 0; k < 200; k++) {
    const hd_shape *sa = &dm, *sb = k % 2 ? &dk : &dm;
    /* a contact of disk ka of A with disk kb of B along a random direction (random_contact
     * would refuse it: the other disk of a tiny dimer touches too) */
    int ka = k % 4 < 2, kb = sb->tag == HD_KIND_DIMER && k % 3 == 0;
    hd_kin A = {0,
                0,
                gsl_ran_gaussian(r, 1),
                gsl_ran_gaussian(r, 1),
                unif(r, -M_PI, M_PI),
                gsl_ran_gaussian(r, 1)};
    hd_kin B = {0,
                0,
                gsl_ran_gaussian(r, 1),
                gsl_ran_gaussian(r, 1),
                unif(r, -M_PI, M_PI),
                gsl_ran_gaussian(r, 1)};
    if (sb->tag == HD_KIND_DISK) B.phi = B.omega = 0.0;
    double ang = unif(r, -M_PI, M_PI), D = 0.5 * (sa->d + sb->d), pax, pay, obx, oby;
    ref_pos(&A, sa, ka, 0.0, &pax, &pay);
    ref_pos(&B, sb, kb, 0.0, &obx, &oby);
    B.x = pax + D * cos(ang) - obx, B.y = pay + D * sin(ang) - oby;
    if ((B.vx - A.vx) * cos(ang) + (B.vy - A.vy) * sin(ang) > 0) /* make it approach */
      A.vx = -A.vx, A.vy = -A.vy, B.vx = -B.vx, B.vy = -B.vy;
    hd_kin A1 = A, B1 = B, A2 = A, B2 = B;
    hd_collide_pair(&A1, sa, &B1, sb, ka, kb, 0.7, NULL);
    hd_impulse_pair(&A2, sa, &B2, sb, ka, kb, 0.7, NULL);
    double vs = fmax(fabs(A.vx) + fabs(A.vy), fabs(B.vx) + fabs(B.vy)) + 1.0;
    assert_true(isfinite(A1.vx) && isfinite(A1.vy) && isfinite(B1.vx) && isfinite(B1.vy));
    double Ma = hd_shape_mass(sa), Mb = hd_shape_mass(sb);
    assert_true(fabs(Ma * (A1.vx - A.vx) + Mb * (B1.vx - B.vx)) <= 1e-13 * (Ma + Mb) * vs);
    assert_true(fabs(A1.vx - A2.vx) <= 1e-12 * vs && fabs(A1.vy - A2.vy) <= 1e-12 * vs);
    assert_true(fabs(B1.vx - B2.vx) <= 1e-12 * vs && fabs(B1.vy - B2.vy) <= 1e-12 * vs);
    /* a wall: the normal velocity of the touching disk is reversed times alpha */
    hd_wall w = {0, A.x + 1.0, -1.0}; /* x = A.x + 1, bodies on its left */
    hd_kin W = {A.x + 0.5, 0, 1.0 + gsl_rng_uniform(r), 0.3, unif(r, -M_PI, M_PI), 0.5};
    hd_kin W1 = W, W2 = W;
    hd_collide_wall(&W1, &dm, 0, &w, 0.7, NULL);
    hd_impulse_wall(&W2, &dm, 0, &w, 0.7, NULL);
    assert_true(isfinite(W1.vx) && fabs(W1.vx - W2.vx) <= 1e-12 * (1 + fabs(W.vx)));
  }
  gsl_rng_free(r);
}

/* Hand-derived cases of the theta convention and of a head-on collision. */
static void collide_by_hand(void **state) {
  (void)state;
  hd_shape s = dimer(1.0, 1.0, 1.0);
  double c = cos(M_PI / 6), sn = sin(M_PI / 6);
  /* A along +x, disk 1 at (0.5, 0); B's disk 0 at (0.5, 0) + (c, sn), B along +x, so B's outward
   * axis at disk 0 is -x: theta_i = +30 deg, theta_j = +30 deg (counter-clockwise). */
  hd_kin A = {0, 0, 1, 0, 0, 0}, B = {0.5 + c + 0.5, sn, -1, 0, 0, 0};
  hd_collision_info in;
  hd_collide_pair(&A, &s, &B, &s, 1, 0, 0.5, &in);
  assert_true(fabs(in.theta_i - M_PI / 6) <= 1e-15 && fabs(in.theta_j - M_PI / 6) <= 1e-15);
  assert_true(fabs(in.f - 1.0 / (2.0 - 0.75)) <= 1e-15); /* cos^2 30 = 3/4 */
  /* head-on collinear dimers (theta = 0): mu = m, like two masses 2m: V' = -alpha V */
  hd_kin P = {0, 0, 1, 0, 0, 0}, Q = {2, 0, -1, 0, 0, 0};
  hd_collide_pair(&P, &s, &Q, &s, 1, 0, 0.7, &in);
  assert_true(fabs(P.vx + 0.7) <= 1e-15 && fabs(Q.vx - 0.7) <= 1e-15);
  assert_true(P.omega == 0.0 && Q.omega == 0.0 && in.theta_i == 0.0 && in.f == 1.0 / 1.0);
  assert_true(fabs(in.de - (-(1 - 0.49) * 1.0 * 4.0 / 2.0)) <= 1e-15); /* -(1-a^2) mu vn^2 / 2 */
}

static void collide_walls(void **state) {
  (void)state;
  gsl_rng *r = rng_new(31);
  const double alphas[] = {0.0, 0.5, 0.9, 1.0}, as[] = {1e-3, 0.5, 1.0, 2.0, 3.0};
  int n = sanitize() ? 100 : 1000;
  for (int ia = 0; ia < 5; ia++)
    for (int il = 0; il < 4; il++)
      for (int k = 0; k < n; k++) {
        double a = as[ia], al = alphas[il];
        hd_shape s = k % 4 == 3 ? disk(1.3, 2.0) : dimer(1.0, a, 1.0);
        hd_wall w = {(int)gsl_rng_uniform_int(r, 2), unif(r, -10, 10), k % 2 ? 1.0 : -1.0};
        hd_kin A = {0,
                    0,
                    gsl_ran_gaussian(r, 1),
                    gsl_ran_gaussian(r, 1),
                    unif(r, -M_PI, M_PI),
                    gsl_ran_gaussian(r, a < 0.01 ? 1e3 : 2.0)};
        if (s.tag == HD_KIND_DISK) A.phi = A.omega = 0;
        int ka = (int)gsl_rng_uniform_int(r, (unsigned long)ndisks(&s));
        /* put disk ka on the wall and keep the other one inside */
        double x, y, o = unif(r, -10, 10);
        ref_pos(&A, &s, ka, 0, &x, &y);
        double want = w.pos + w.normal * 0.5 * s.d;
        if (w.axis)
          A.y += want - y, A.x += o;
        else
          A.x += want - x, A.y += o;
        if (s.tag == HD_KIND_DIMER) {
          ref_pos(&A, &s, 1 - ka, 0, &x, &y);
          if (w.normal * ((w.axis ? y : x) - want) < 0) continue;
        }
        double vx, vy;
        ref_vel(&A, &s, ka, &vx, &vy);
        double v1n = w.axis ? vy * w.normal : vx * w.normal;
        if (fabs(v1n) < 1e-3) continue;
        if (v1n > 0) A.vx = -A.vx, A.vy = -A.vy, A.omega = -A.omega, v1n = -v1n;
        hd_kin A1 = A, A2 = A;
        hd_collision_info in, ig;
        hd_collide_wall(&A1, &s, ka, &w, al, &in);
        hd_impulse_wall(&A2, &s, ka, &w, al, &ig);
        double M = hd_shape_mass(&s), vs = fmax(vscale(&A, &s), vscale(&A1, &s));
        /* momentum along the wall conserved (1e-13 of M vs) */
        double dpx = M * (A1.vx - A.vx), dpy = M * (A1.vy - A.vy);
        assert_true(fabs(w.axis ? dpx : dpy) <= 1e-13 * M * vs);
        /* angular momentum about any point changes by (contact point - P) x impulse */
        double cx, cy, px = unif(r, -20, 20), py = unif(r, -20, 20);
        ref_pos(&A, &s, ka, 0, &cx, &cy);
        if (w.axis)
          cy = w.pos;
        else
          cx = w.pos;
        double dL = ang_mom(&A1, &s, px, py) - ang_mom(&A, &s, px, py);
        assert_true(fabs(dL - ((cx - px) * dpy - (cy - py) * dpx)) <= 1e-13 * M * vs * 40);
        /* restitution, energy eq. 26 (and -M (1-a^2) vn^2/2 for a disk), paper == generic */
        double ux, uy;
        ref_vel(&A1, &s, ka, &ux, &uy);
        double v1n1 = w.axis ? uy * w.normal : ux * w.normal;
        assert_true(fabs(v1n1 + al * v1n) <= 1e-12 * vs);
        assert_true(fabs(in.vn - v1n) <= 1e-12 * vs);
        double E0 = ref_ke(&A, &s), E1 = ref_ke(&A1, &s), de;
        if (s.tag == HD_KIND_DIMER) {
          /* r12 from the disk positions of A moved to the origin (no round-off of |x| ~ 20
           * against a = 1e-3) */
          double c1x, c1y, c2x, c2y, c;
          hd_kin A0 = A;
          A0.x = A0.y = 0.0;
          ref_pos(&A0, &s, ka, 0, &c1x, &c1y);
          ref_pos(&A0, &s, 1 - ka, 0, &c2x, &c2y);
          c = w.axis ? c1y - c2y : c1x - c2x;                                        /* n . r12 */
          de = -s.m * (1 - al * al) / 2 * v1n * v1n / (1 - c * c / (2 * s.a * s.a)); /* eq. 26 */
          double ct = cos(in.theta_i);
          assert_true(fabs(in.f - 1.0 / (1.0 - ct * ct / 2)) <= 1e-12 * in.f);
        } else {
          de = -M * (1 - al * al) / 2 * v1n * v1n;
          assert_true(fabs(in.f - 1.0) <= 1e-15 && isnan(in.theta_i));
        }
        assert_true(isnan(in.theta_j));
        assert_true(fabs((E1 - E0) - in.de) <= 1e-12 * E0);
        assert_true(fabs(de - in.de) <= 1e-12 * (E0 + fabs(de)));
        assert_true(in.de <= 0 && E1 - E0 <= 1e-13 * E0);
        if (al == 1.0) assert_true(fabs(E1 - E0) <= 1e-13 * E0);
        double ha = 0.5 * s.a;
        assert_true(fabs(A1.vx - A2.vx) <= 1e-12 * vs && fabs(A1.vy - A2.vy) <= 1e-12 * vs);
        assert_true(ha * fabs(A1.omega - A2.omega) <= 1e-12 * vs);
        if (s.tag == HD_KIND_DIMER) {
          double nx = w.axis ? 0 : -w.normal, ny = w.axis ? -w.normal : 0;
          check_theta(&A, &s, ka, nx, ny, in.theta_i, 1e300);
        }
      }
  gsl_rng_free(r);
}

/* ---- contact prediction against brute force ----------------------------------------------- */

/* Compares hd_predict_pair with the brute force on one case; returns 1 if both found a contact.
 * skip: the pair the brute force ignores until it has separated (just-collided), -1: none. */
static int compare_pair(const hd_kin *A, const hd_shape *sa, const hd_kin *B, const hd_shape *sb,
                        double tmax, int nsamp, int skip) {
  hd_contact c;
  int got = hd_predict_pair(A, sa, B, sb, tmax, &c);
  bf f = {A, B, sa, sb, NULL, -1};
  double tb = 0, gmin, t0 = 0.0;
  int found;
  if (skip >= 0) {
    /* the just-collided pair: the other pairs from 0, that one from its separation (> 1e-9) */
    int i = skip / ndisks(sb), j = skip % ndisks(sb);
    double dt = tmax / nsamp;
    while (t0 < tmax && ref_gap_pair(A, sa, B, sb, i, j, t0) <= 1e-9) t0 += dt;
    bf g = {A, B, sa, sb, NULL, skip};
    double t1, g1;
    int f1 = bf_first(&g, 0.0, t0, nsamp / 100 + 10, &t1, &g1);
    int f2 = t0 < tmax ? bf_first(&f, t0, tmax, nsamp, &tb, &gmin) : 0;
    found = f1 || f2;
    if (f1) tb = t1;
    if (got) assert_true(c.t > 1e-9); /* never a t = 0 re-collision */
  } else {
    found = bf_first(&f, 0.0, tmax, nsamp, &tb, &gmin);
  }
  if (got != found) {
    fprintf(stderr, "predict %d (t=%.17g) brute %d (t=%.17g, gmin=%g)\n", got, got ? c.t : 0, found,
            tb, gmin);
  }
  assert_int_equal(got, found);
  if (!got) return 0;
  /* contact time to 1e-9; the predicted disk pair touches at the brute-force time */
  if (fabs(c.t - tb) > 1e-9) fprintf(stderr, "t %.17g vs %.17g\n", c.t, tb);
  assert_true(fabs(c.t - tb) <= 1e-9);
  assert_true(fabs(ref_gap_pair(A, sa, B, sb, c.ka, c.kb, tb)) <= 1e-8);
  /* post-collision state to 1e-8 (collision at the predicted vs the brute-force time) */
  hd_kin a1 = *A, b1 = *B, a2 = *A, b2 = *B;
  hd_kin_advance(&a1, c.t);
  hd_kin_advance(&b1, c.t);
  hd_kin_advance(&a2, tb);
  hd_kin_advance(&b2, tb);
  hd_collide_pair(&a1, sa, &b1, sb, c.ka, c.kb, 0.9, NULL);
  hd_collide_pair(&a2, sa, &b2, sb, c.ka, c.kb, 0.9, NULL);
  double vs = 1.0 + vscale(A, sa) + vscale(B, sb);
  assert_true(fabs(a1.vx - a2.vx) <= 1e-8 * vs && fabs(a1.vy - a2.vy) <= 1e-8 * vs);
  assert_true(fabs(b1.vx - b2.vx) <= 1e-8 * vs && fabs(b1.vy - b2.vy) <= 1e-8 * vs);
  assert_true(0.5 * sa->a * fabs(a1.omega - a2.omega) <= 1e-8 * vs);
  assert_true(0.5 * sb->a * fabs(b1.omega - b2.omega) <= 1e-8 * vs);
  return 1;
}

/* A random approach of B towards A: B starts outside A's enclosing circle, with a gap in
 * [gmin, gmax] between the circles, its velocity roughly towards A. */
static void random_approach(gsl_rng *r, const hd_shape *sa, const hd_shape *sb, double wa,
                            double wb, double gmin, double gmax, hd_kin *A, hd_kin *B) {
  double R = hd_shape_radius(sa) + hd_shape_radius(sb) + unif(r, gmin, gmax);
  double ang = unif(r, -M_PI, M_PI);
  *A = (hd_kin){0,
                0,
                0.3 * gsl_ran_gaussian(r, 1),
                0.3 * gsl_ran_gaussian(r, 1),
                unif(r, -M_PI, M_PI),
                wa * gsl_ran_gaussian(r, 1)};
  *B = (hd_kin){R * cos(ang),
                R * sin(ang),
                -cos(ang) + 0.5 * gsl_ran_gaussian(r, 1),
                -sin(ang) + 0.5 * gsl_ran_gaussian(r, 1),
                unif(r, -M_PI, M_PI),
                wb * gsl_ran_gaussian(r, 1)};
  if (sa->tag == HD_KIND_DISK) A->phi = A->omega = 0;
  if (sb->tag == HD_KIND_DISK) B->phi = B->omega = 0;
}

typedef struct pclass {
  const char *name;
  hd_shape sa, sb;
  double wa, wb; /* angular velocity scales */
  double gmax;   /* largest initial gap between the enclosing circles */
  double tmax;
  int nsamp;
} pclass;

static void predict_pairs(void **state) {
  (void)state;
  const pclass cl[] = {
      {"omega=0", dimer(1, 1, 1), dimer(1, 1, 1), 0, 0, 1.5, 3, 30000},
      {"spin", dimer(1, 1, 1), dimer(1, 1, 1), 2, 2, 1.5, 3, 100000},
      {"fast", dimer(1, 1, 1), dimer(1, 1, 1), 1e3, 1, 0.2, 0.3, 300000},
      {"a=1e-3", dimer(1, 1e-3, 1), dimer(1, 1e-3, 1), 1e3, 1e3, 0.3, 0.5, 200000},
      {"a=2", dimer(1, 2, 1), dimer(1, 2, 1), 2, 2, 1.5, 3, 100000},
      {"a=3", dimer(1, 3, 1), dimer(1, 3, 1), 2, 2, 1.5, 3, 100000},
      {"disk-dimer", disk(1.3, 2), dimer(1, 1, 1), 0, 3, 1.5, 3, 100000},
      {"dimer-disk", dimer(1, 1, 1), disk(0.6, 0.5), 3, 0, 1.5, 3, 100000},
      {"disk-disk", disk(1.3, 2), disk(0.6, 0.5), 0, 0, 1.5, 3, 30000},
  };
  gsl_rng *r = rng_new(41);
  int ncase = sanitize() ? 4 : 30;
  for (size_t k = 0; k < sizeof cl / sizeof cl[0]; k++) {
    int hits = 0;
    for (int n = 0; n < ncase; n++) {
      hd_kin A, B;
      random_approach(r, &cl[k].sa, &cl[k].sb, cl[k].wa, cl[k].wb, 0.01, cl[k].gmax, &A, &B);
      int ns = sanitize() ? cl[k].nsamp / 10 : cl[k].nsamp;
      hd_contact c;
      if (!compare_pair(&A, &cl[k].sa, &B, &cl[k].sb, cl[k].tmax, ns, -1)) continue;
      hits++;
      assert_true(hd_predict_pair(&A, &cl[k].sa, &B, &cl[k].sb, cl[k].tmax, &c));
      /* the just-collided pair: collide at contact, then predict again from there */
      for (int ia = 0; ia < 2; ia++) {
        hd_kin a = A, b = B;
        hd_kin_advance(&a, c.t);
        hd_kin_advance(&b, c.t);
        hd_collide_pair(&a, &cl[k].sa, &b, &cl[k].sb, c.ka, c.kb, ia ? 0.0 : 0.9, NULL);
        if (ia == 0) {
          compare_pair(&a, &cl[k].sa, &b, &cl[k].sb, cl[k].tmax, ns,
                       c.ka * ndisks(&cl[k].sb) + c.kb);
        } else {
          hd_contact c2; /* alpha = 0: vn = 0 after; no re-collision at t = 0 */
          if (hd_predict_pair(&a, &cl[k].sa, &b, &cl[k].sb, cl[k].tmax, &c2))
            assert_true(c2.t > 0.0);
        }
      }
    }
    /* each class must exercise contacts (and the fast spinners a second contact) */
    if (!sanitize()) {
      assert_true(hits >= ncase / 5);
    }
  }
  gsl_rng_free(r);
}

/* The resumable search (hd_ca_begin, hd_ca_step) as the engine uses it (hd_predict.c): one
 * spinning dimer A and several dimers B_k around it, most within reach, the search furthest behind
 * stepped first, tmax shrinking to the earliest contact found, A's sin and cos shared.  Checks
 * against the brute force of every pair that (1) each search's time is a lower bound: no pair
 * touches before it (to 1e-9, the brute force's time resolution), and (2) the earliest contact and
 * its partner are those of the brute force, to 1e-9 in time.  Fixed seed; tolerances as in
 * compare_pair. */
static void predict_interleaved(void **state) {
  (void)state;
  const hd_shape s = dimer(1, 1, 1);
  enum { NB = 5 };
  gsl_rng *r = rng_new(47);
  int ncase = sanitize() ? 3 : 25, ns = sanitize() ? 10000 : 60000, hits = 0;
  for (int n = 0; n < ncase; n++) {
    hd_kin A, B[NB], tmp;
    double tb[NB], tmax = 2.0;
    int fb[NB];
    random_approach(r, &s, &s, 2.0, 2.0, 0.01, 1.0, &A, &tmp); /* A's own state */
    for (int k = 0; k < NB; k++) {
      /* most B_k inside A's reach (enclosing circles overlapping: the search starts at t = 0
       * with A's shared sin and cos), not touching A yet */
      double g0 = -1.0;
      while (g0 < 0.01) {
        random_approach(r, &s, &s, 2.0, 2.0, -1.0, 0.5, &tmp, &B[k]);
        bf f0 = {&A, &B[k], &s, &s, NULL, -1};
        g0 = bf_gap(0.0, &f0);
      }
    }
    int kbest = -1;
    for (int k = 0; k < NB; k++) {
      bf f = {&A, &B[k], &s, &s, NULL, -1};
      double gmin;
      fb[k] = bf_first(&f, 0.0, tmax, ns, &tb[k], &gmin);
      if (fb[k] && (kbest < 0 || tb[k] < tb[kbest])) kbest = k;
    }
    double sca[2], best = tmax;
    hd_ca_sincos(A.phi, &sca[0], &sca[1]);
    hd_ca ca[NB];
    int live[NB], got = -1;
    hd_contact cbest = {0, 0, 0}, c;
    for (int k = 0; k < NB; k++) {
      live[k] = hd_ca_begin(&ca[k], &A, &s, &B[k], &s, tmax, sca, &c);
      assert_int_not_equal(live[k], 1); /* rotating: never closed form */
    }
    for (;;) {
      int k = -1;
      for (int q = 0; q < NB; q++)
        if (live[q] == 2 && (k < 0 || ca[q].t < ca[k].t)) k = q;
      if (k < 0 || !(ca[k].t < best)) break;
      int rc = hd_ca_step(&ca[k], best, &c);
      if (rc == 2) {
        if (fb[k]) assert_true(ca[k].t <= tb[k] + 1e-9); /* (1) a lower bound */
        continue;
      }
      live[k] = 0;
      if (rc == 1 && c.t < best) {
        best = c.t;
        cbest = c;
        got = k;
      }
    }
    assert_int_equal(got, kbest); /* (2) */
    if (got < 0) continue;
    hits++;
    if (fabs(cbest.t - tb[got]) > 1e-9) fprintf(stderr, "t %.17g vs %.17g\n", cbest.t, tb[got]);
    assert_true(fabs(cbest.t - tb[got]) <= 1e-9);
    hd_contact c1; /* the same contact as the search of that pair alone */
    assert_true(hd_predict_pair(&A, &s, &B[got], &s, tmax, &c1));
    assert_true(fabs(c1.t - cbest.t) <= 1e-12 && c1.ka == cbest.ka && c1.kb == cbest.kb);
  }
  if (!sanitize()) assert_true(hits >= ncase / 2); /* most cases have a contact */
  gsl_rng_free(r);
}

/* A spinner whose other disk (or the same one) swings round and hits again after a collision:
 * random spinners hitting a disk or a dimer; every case with a second contact, and some without,
 * is checked against the brute force started after the first collision. */
static void predict_second_contact(void **state) {
  (void)state;
  gsl_rng *r = rng_new(45);
  int want = sanitize() ? 1 : 4, found = 0, nocont = 0, ns = sanitize() ? 20000 : 100000;
  for (int n = 0; n < 20000 && found < want; n++) {
    hd_shape sa = dimer(1, 1, 1), sb = n % 2 ? disk(1, n % 4 == 1 ? 1e3 : 1.0) : dimer(1, 1, 5);
    double ang = unif(r, -M_PI, M_PI), R = hd_shape_radius(&sa) + hd_shape_radius(&sb) + 0.05;
    double v = unif(r, 1, 10), w = unif(r, 30, 1e3) * (n % 3 ? 1 : -1);
    hd_kin A = {0, 0, 0, 0, unif(r, -M_PI, M_PI), w};
    hd_kin B = {R * cos(ang),  R * sin(ang),         -v * cos(ang),
                -v * sin(ang), unif(r, -M_PI, M_PI), 0.0};
    hd_contact c, c2;
    if (!hd_predict_pair(&A, &sa, &B, &sb, 1.0, &c)) continue;
    hd_kin_advance(&A, c.t);
    hd_kin_advance(&B, c.t);
    hd_collide_pair(&A, &sa, &B, &sb, c.ka, c.kb, 0.9, NULL);
    double tmax = 40.0 / fabs(w); /* about six turns */
    int again = hd_predict_pair(&A, &sa, &B, &sb, tmax, &c2);
    if (!again && nocont++ % 200 != 0) continue;
    assert_int_equal(compare_pair(&A, &sa, &B, &sb, tmax, ns, c.ka * ndisks(&sb) + c.kb), again);
    found += again;
  }
  assert_true(found >= want);
  gsl_rng_free(r);
}

/* After an alpha = 0 collision the pair does not touch again at t = 0, also when both bodies
 * move fast (a common velocity of 1e4 added; relative speeds of order 1, rotation included):
 * the round-off of the bodies' own velocities (~1e-12 of normal speed) is not an approach.
 * Dimer pairs go through the conservative advancement, the others through the closed form.
 * With the margin VTOL L alone in the conservative advancement, 94 of these 3000 pairs
 * collided again at t = 0. */
static void alpha_zero_fast_bodies(void **state) {
  (void)state;
  gsl_rng *r = rng_new(29);
  const hd_shape shp[3][2] = {
      {dimer(1, 1, 1), dimer(1, 1, 1)}, {dimer(1, 1, 1), disk(1.2, 1.5)}, {disk(1, 1), disk(1, 1)}};
  int again = 0, n = sanitize() ? 300 : 3000;
  for (int k = 0; k < n; k++) {
    const hd_shape *sa = &shp[k % 3][0], *sb = &shp[k % 3][1];
    hd_kin A, B;
    int ka, kb;
    random_contact(r, sa, sb, 1.0, &A, &B, &ka, &kb);
    double th = unif(r, -M_PI, M_PI), ux = 1e4 * cos(th), uy = 1e4 * sin(th);
    A.vx += ux, A.vy += uy, B.vx += ux, B.vy += uy;
    hd_collide_pair(&A, sa, &B, sb, ka, kb, 0.0, NULL);
    hd_contact c;
    again += hd_predict_pair(&A, sa, &B, sb, 1e-3, &c) && c.t == 0.0;
  }
  gsl_rng_free(r);
  assert_int_equal(again, 0);
}

/* In contact now (gap -1e-11 or 0): approaching gives t = 0 and the touching pair; at a gap of
 * +1e-11 the contact is searched (it used to be t = 0 up to gaps of 1e-10, see
 * predict_near_miss) and agrees with the brute force;
 * receding (the same state with every velocity reversed) never gives t = 0, and its next
 * contact, if any, agrees with the brute force. */
static void predict_touching_now(void **state) {
  (void)state;
  gsl_rng *r = rng_new(47);
  hd_shape dm = dimer(1, 1, 1), ds = dimer(1, 1e-3, 1), dk = disk(1.4, 2.0);
  const hd_shape *pairs[][2] = {{&dm, &dm}, {&ds, &ds}, {&dm, &dk}, {&dk, &dm}, {&dk, &dk}};
  int ncase = sanitize() ? 3 : 20;
  for (int k = 0; k < 5; k++)
    for (int n = 0; n < ncase; n++) {
      const hd_shape *sa = pairs[k][0], *sb = pairs[k][1];
      hd_kin A, B;
      int ka, kb;
      random_contact(r, sa, sb, sa->a < 0.01 ? 1e3 : 2.0, &A, &B, &ka, &kb);
      double ax, ay, bx, by, dgap = (n % 3 - 1) * 1e-11;
      ref_pos(&A, sa, ka, 0, &ax, &ay);
      ref_pos(&B, sb, kb, 0, &bx, &by);
      double D = hypot(bx - ax, by - ay);
      B.x += dgap * (bx - ax) / D;
      B.y += dgap * (by - ay) / D;
      hd_contact c;
      if (dgap > 0) { /* a gap of 1e-11 D is above TOL_C: searched, against the brute force */
        assert_true(compare_pair(&A, sa, &B, sb, 1.0, sanitize() ? 10000 : 100000, -1));
      } else {
        assert_true(hd_predict_pair(&A, sa, &B, sb, 1.0, &c));
        assert_true(c.t == 0.0 && c.ka == ka && c.kb == kb);
      }
      A.vx = -A.vx, A.vy = -A.vy, A.omega = -A.omega;
      B.vx = -B.vx, B.vy = -B.vy, B.omega = -B.omega;
      compare_pair(&A, sa, &B, sb, 1.0, sanitize() ? 10000 : 100000, ka * ndisks(sb) + kb);
    }
  gsl_rng_free(r);
}

/* A just-collided pair that comes back: CA skips a receding ignored pair's separation in one
 * step, up to the larger root tau_hi of bound (ii) (ign_step in hd_body.c).  Built case: a
 * spinning dimer A (phi = 0, omega = w < 0) whose disk 1 touches a heavy disk B placed at angle
 * beta in (pi/2, 2 pi/3) from it (clear of disk 0), A's centre moving towards B so that the
 * contact recedes at speed eps only: rotation then curves the gap back, h'' = w^2 cos(beta)
 * (2 + cos(beta)) / 4 < 0 (without the centre's motion), and the same pair touches again at
 * about 2 eps / |h''|, 3 to 8 times tau_hi = 2 eps / K (K = w^2 / 2).  Gaps of 0, +1e-11 and -1e-12
 * at t = 0 (the round-off a collision leaves).  Then random soft collisions (alpha 0.01 - 0.3) of
 * spinners. Every next contact must agree with the brute force, which ignores the collided pair
 * until it has separated by 1e-9 (eps >= 1e-3 |w|/2 makes the gap open to > 1e-8 first). */
static void predict_recontact(void **state) {
  (void)state;
  hd_shape dm = dimer(1, 1, 1), dh = disk(1, 100);
  int ns = sanitize() ? 20000 : 100000;
  const double betas[] = {1.7, 1.85, 2.0}, ws[] = {-1.0, -10.0}, epss[] = {1e-3, 1e-2, 0.1};
  const double gaps[] = {0.0, 1e-11, -1e-12};
  for (int ib = 0; ib < 3; ib++)
    for (int iw = 0; iw < 2; iw++)
      for (int ie = 0; ie < 3; ie++) {
        double beta = betas[ib], w = ws[iw], nx = cos(beta), ny = sin(beta);
        double v1 = 0.5 * w * ny; /* n . (velocity of disk 1 from rotation) */
        double eps = epss[ie] * 0.5 * fabs(w), u = -v1 - eps; /* A's centre along n */
        hd_kin A = {0, 0, u * nx, u * ny, 0, w};
        double g = gaps[(ib + ie) % 3];
        hd_kin B = {0.5 + (1 + g) * nx, (1 + g) * ny, 0, 0, 0, 0};
        double tmax = 2.0 / fabs(w);
        hd_contact c;
        int got = hd_predict_pair(&A, &dm, &B, &dh, tmax, &c);
        assert_int_equal(compare_pair(&A, &dm, &B, &dh, tmax, ns, 1), got);
        assert_true(got); /* the pair comes back well inside one radian of turn */
        /* eps <= 0.01 |w|/2: the same pair, at t ~ 2 eps / |h''|; at 0.1 disk 0 comes first */
        if (ie < 2) assert_true(c.ka == 1 && c.kb == 0);
      }
  gsl_rng *r = rng_new(53);
  hd_shape dk = disk(1, 1);
  const hd_shape *pairs[][2] = {{&dm, &dm}, {&dm, &dk}, {&dk, &dm}, {&dm, &dh}};
  int ncase = sanitize() ? 3 : 25, again = 0;
  for (int k = 0; k < 4; k++)
    for (int n = 0; n < ncase; n++) {
      const hd_shape *sa = pairs[k][0], *sb = pairs[k][1];
      hd_kin A, B;
      int ka, kb;
      random_contact(r, sa, sb, n % 2 ? 2.0 : 10.0, &A, &B, &ka, &kb);
      double alpha = n % 3 == 0 ? 0.01 : n % 3 == 1 ? 0.1 : 0.3;
      hd_collide_pair(&A, sa, &B, sb, ka, kb, alpha, NULL);
      double tmax = 3.0 / (fmax(fabs(A.omega), fabs(B.omega)) + 1.0);
      again += compare_pair(&A, sa, &B, sb, tmax, ns, ka * ndisks(sb) + kb);
    }
  if (!sanitize()) assert_true(again >= 10); /* some next contacts were compared */
  gsl_rng_free(r);
}

/* Near-parallel dimers approaching side by side: two disk pairs touch almost together. */
static void predict_near_parallel(void **state) {
  (void)state;
  gsl_rng *r = rng_new(51);
  hd_shape s = dimer(1, 1, 1);
  const double eps[] = {0.0, 1e-12, 1e-9, 1e-6, 1e-3}, ws[] = {0.0, 1e-9, 1e-4};
  int ns = sanitize() ? 5000 : 50000;
  for (int ie = 0; ie < 5; ie++)
    for (int iw = 0; iw < 3; iw++)
      for (int n = 0; n < (sanitize() ? 1 : 4); n++) {
        double dx = n == 0 ? 0.0 : unif(r, -0.5, 0.5);
        hd_kin A = {0, 0, 0, 0, 0, ws[iw]},
               B = {dx, 1.0 + unif(r, 0.01, 0.5), 0, -1, eps[ie], -ws[iw]};
        assert_true(compare_pair(&A, &s, &B, &s, 2.0, ns, -1));
      }
  gsl_rng_free(r);
}

/* Grazing: shift B sideways to the edge between hit and miss (found by bisection on the
 * brute-force minimum gap), then check a hit 1e-7 inside and a miss 1e-7 outside. */
static double min_gap(bf *f, double tmax, int n) {
  double t;
  double g;
  bf_first(f, 0.0, tmax, n, &t, &g);
  /* bf_first stops at the first negative gap: g < 0 then */
  return g;
}

static void predict_grazing(void **state) {
  (void)state;
  gsl_rng *r = rng_new(61);
  const hd_shape shp[][2] = {{dimer(1, 1, 1), dimer(1, 1, 1)},
                             {disk(1.3, 2), dimer(1, 1, 1)},
                             {dimer(1, 2, 1), disk(1, 1)},
                             {disk(1, 1), disk(1, 1)}};
  int ncase = sanitize() ? 1 : 3, ns = sanitize() ? 4000 : 20000;
  for (int k = 0; k < 4; k++) {
    int done = 0;
    for (int n = 0; n < 10 && done < ncase; n++) {
      const hd_shape *sa = &shp[k][0], *sb = &shp[k][1];
      hd_kin A, B;
      random_approach(r, sa, sb, n == 0 ? 0.0 : 0.5, n == 0 ? 0.0 : 0.5, 0.2, 0.5, &A, &B);
      double vx = B.vx - A.vx, vy = B.vy - A.vy, v = hypot(vx, vy), ex = -vy / v, ey = vx / v;
      double tmax = 4.0, s_hit = 0.0, s_miss = 4.0;
      hd_kin Bs = B;
      bf f = {&A, &Bs, sa, sb, NULL, -1};
      /* s = 0 aims B's centre at A's (up to noise): find a hit first */
      Bs.x = B.x, Bs.y = B.y;
      if (min_gap(&f, tmax, ns) >= 0) continue;
      Bs.x = B.x + s_miss * ex, Bs.y = B.y + s_miss * ey;
      if (min_gap(&f, tmax, ns) < 0) continue;
      for (int it = 0; it < 45; it++) {
        double s = 0.5 * (s_hit + s_miss);
        Bs.x = B.x + s * ex, Bs.y = B.y + s * ey;
        if (min_gap(&f, tmax, ns) < 0)
          s_hit = s;
        else
          s_miss = s;
      }
      double s0 = 0.5 * (s_hit + s_miss);
      Bs.x = B.x + (s0 - 1e-7) * ex, Bs.y = B.y + (s0 - 1e-7) * ey;
      assert_true(compare_pair(&A, sa, &Bs, sb, tmax, ns, -1) == 1);
      Bs.x = B.x + (s0 + 1e-7) * ex, Bs.y = B.y + (s0 + 1e-7) * ey;
      assert_true(compare_pair(&A, sa, &Bs, sb, tmax, ns, -1) == 0);
      done++;
    }
    assert_true(done == ncase); /* every shape pair was tested at the edge */
  }
  gsl_rng_free(r);
}

/* Walls: random dimers and disks against random walls, brute force; plus grazing ones. */
static void predict_walls(void **state) {
  (void)state;
  gsl_rng *r = rng_new(71);
  const double ws[] = {0.0, 2.0, 1e3};
  int ncase = sanitize() ? 10 : 60;
  for (int iw = 0; iw < 3; iw++)
    for (int n = 0; n < ncase; n++) {
      hd_shape s = n % 5 == 4 ? disk(1.2, 1.0) : dimer(1, n % 3 == 0 ? 1e-3 : 1.0 + n % 3, 1);
      if (n % 7 >= 4) /* general clusters */
        s = n % 7 == 4 ? trimer_linear() : n % 7 == 5 ? trimer_triangle() : dimer_asym();
      hd_wall w = {n % 2, unif(r, -2, 2), (n / 2) % 2 ? 1.0 : -1.0};
      double tmax = iw == 2 ? 0.3 : 3.0;
      int ns = (iw == 2 ? 100000 : 30000) / (sanitize() ? 10 : 1);
      hd_kin A = {0,
                  0,
                  gsl_ran_gaussian(r, 1),
                  gsl_ran_gaussian(r, 1),
                  unif(r, -M_PI, M_PI),
                  ws[iw] * gsl_ran_gaussian(r, 1)};
      if (s.tag == HD_KIND_DISK) A.phi = A.omega = 0;
      double gap = unif(r, 0.01, iw == 2 ? 0.3 : 1.5) + hd_shape_radius(&s);
      if (w.axis)
        A.y = w.pos + w.normal * gap;
      else
        A.x = w.pos + w.normal * gap;
      double *vnorm = w.axis ? &A.vy : &A.vx;
      *vnorm = -w.normal * fabs(*vnorm);
      for (int graze = 0; graze < 3; graze++) {
        hd_wall ww = w;
        bf f = {&A, NULL, &s, NULL, &ww, -1};
        double tb, gmin;
        if (graze) {
          /* move the wall so that the minimum gap over [0, tmax] is -1e-7 (hit) or +1e-7 (miss):
           * the gap shifts uniformly with the wall */
          double gm = bf_min(&f, tmax, ns);
          ww.pos = w.pos - w.normal * (-gm + (graze == 1 ? -1e-7 : 1e-7));
        }
        hd_contact c;
        int got = hd_predict_wall(&A, &s, &ww, tmax, &c);
        int found = bf_first(&f, 0.0, tmax, ns, &tb, &gmin);
        if (got != found) fprintf(stderr, "wall: predict %d brute %d gmin %g\n", got, found, gmin);
        assert_int_equal(got, found);
        if (graze) assert_int_equal(found, graze == 1);
        if (!got) continue;
        assert_true(fabs(c.t - tb) <= 1e-9);
        hd_kin a1 = A, a2 = A;
        hd_kin_advance(&a1, c.t);
        hd_kin_advance(&a2, tb);
        double x, y;
        hd_kin_disk_pos(&a1, &s, c.ka, &x, &y);
        assert_true(fabs(ww.normal * ((ww.axis ? y : x) - ww.pos) - 0.5 * s.dk[c.ka]) <= 1e-8);
        hd_contact c0; /* at the contact, approaching: contact now (t = 0 up to round-off) */
        assert_true(hd_predict_wall(&a2, &s, &ww, tmax, &c0) && c0.t <= 1e-9 && c0.ka == c.ka);
        hd_collide_wall(&a1, &s, c.ka, &ww, 0.9, NULL);
        hd_collide_wall(&a2, &s, c.ka, &ww, 0.9, NULL);
        double vs = 1.0 + vscale(&A, &s);
        assert_true(fabs(a1.vx - a2.vx) <= 1e-8 * vs && fabs(a1.vy - a2.vy) <= 1e-8 * vs);
        assert_true(s.rmax * fabs(a1.omega - a2.omega) <= 1e-8 * vs);
        /* just collided: no t = 0 contact with the wall again */
        hd_contact c2;
        if (hd_predict_wall(&a1, &s, &ww, tmax, &c2)) assert_true(c2.t > 1e-9);
      }
    }
  gsl_rng_free(r);
}

/* ---- general clusters --------------------------------------------------------------------- */

/* The cluster shapes of the tests: trimers of unit disks (linear, bent at 120 degrees at the
 * middle disk, triangular) and an asymmetric dimer (d 1 and 0.5, m 1 and 0.3, 0.8 apart). */
static hd_shape trimer_linear(void) {
  const double x[] = {0, 1, 2}, y[] = {0, 0, 0}, d[] = {1, 1, 1}, m[] = {1, 1, 1};
  return cluster(3, x, y, d, m);
}
static hd_shape trimer_bent(void) {
  const double x[] = {1, 0, cos(2 * M_PI / 3)}, y[] = {0, 0, sin(2 * M_PI / 3)};
  const double d[] = {1, 1, 1}, m[] = {1, 1, 1};
  return cluster(3, x, y, d, m);
}
static hd_shape trimer_triangle(void) {
  const double x[] = {0, 1, 0.5}, y[] = {0, 0, sqrt(3) / 2}, d[] = {1, 1, 1}, m[] = {1, 1, 1};
  return cluster(3, x, y, d, m);
}
static hd_shape dimer_asym(void) {
  const double x[] = {0, 0.8}, y[] = {0, 0}, d[] = {1, 0.5}, m[] = {1, 0.3};
  return cluster(2, x, y, d, m);
}

static void cluster_shapes(void **state) {
  (void)state;
  hd_shape l = trimer_linear(), b = trimer_bent(), t = trimer_triangle(), a = dimer_asym();
  assert_int_equal(l.tag, HD_KIND_BODY);
  assert_int_equal(a.tag, HD_KIND_BODY);
  /* by definition: total mass, centre of mass at the origin, I = sum m |o|^2 */
  assert_true(l.mass == 3.0 && fabs(l.inertia - 2.0) <= 1e-15 && fabs(l.radius - 1.5) <= 1e-15);
  assert_true(fabs(t.inertia - 1.0) <= 1e-15); /* 3 (1/sqrt 3)^2 */
  assert_true(fabs(t.radius - (1 / sqrt(3) + 0.5)) <= 1e-15);
  double cx = 0, cy = 0;
  for (int k = 0; k < 3; k++) cx += b.ox[k], cy += b.oy[k];
  assert_true(fabs(cx) <= 1e-15 && fabs(cy) <= 1e-15);
  /* asymmetric dimer: centre of mass 0.8 * 0.3 / 1.3 from disk 0 */
  assert_true(fabs(a.ox[0] + 0.24 / 1.3) <= 1e-15 && fabs(a.mass - 1.3) <= 1e-15);
  assert_true(fabs(a.inertia - 0.8 * 0.8 * 0.3 / 1.3) <= 1e-15); /* reduced mass x a^2 */
  /* the fast tags: a disk, an equal dimer on the x axis (any origin) */
  const double x1[] = {3.0}, y1[] = {-2.0}, d1[] = {1.3}, m1[] = {2.0};
  hd_shape k = cluster(1, x1, y1, d1, m1);
  assert_int_equal(k.tag, HD_KIND_DISK);
  assert_true(k.d == 1.3 && k.m == 2.0 && k.mass == 2.0 && k.inertia == 0.0);
  const double x2[] = {0.0, 1.5}, y2[] = {0, 0}, d2[] = {1, 1}, m2[] = {1, 1};
  hd_shape e = cluster(2, x2, y2, d2, m2), ref = dimer(1, 1.5, 1);
  assert_int_equal(e.tag, HD_KIND_DIMER);
  assert_true(e.a == 1.5 && e.inertia == ref.inertia && e.radius == ref.radius);
  /* out of range */
  const double d0[] = {0.0}, mn[] = {-1.0};
  assert_int_equal(hd_shape_cluster(&e, 1, x1, y1, d0, m1, 1), -1);
  assert_int_equal(hd_shape_cluster(&e, 1, x1, y1, d1, mn, 1), -1);
  assert_int_equal(hd_shape_cluster(&e, 0, x1, y1, d1, m1, 1), -1);
  assert_int_equal(hd_shape_cluster(&e, HD_MAX_BODY_DISKS + 1, x1, y1, d1, m1, 1), -1);
}

/* Same double, or both NaN. */
static int same_or_nan(double a, double b, double tol) {
  return (isnan(a) && isnan(b)) || fabs(a - b) <= tol;
}

/* The general code (HD_KIND_BODY) against the paper's formulas (eq. 13-26, the fast paths)
 * for disks and equal dimers: the same collisions (velocities, angles, f, dE, vn) to 1e-12 of
 * their scale, with walls too, and the same contacts predicted (same disks, times to 1e-12
 * relative: both polish the root to round-off; a search stopped at a grazing gap <= 1e-12 d
 * could differ more, which these random approaches do not meet).  Fixed seed. */
static void general_matches_paper(void **state) {
  (void)state;
  gsl_rng *r = rng_new(91);
  const hd_shape sh[][2] = {{dimer(1, 1, 1), dimer(1, 1, 1)}, {dimer(1, 2, 1), dimer(1, 0.5, 1)},
                            {dimer(1, 1, 1), disk(1.3, 0.7)}, {disk(0.8, 2), dimer(1, 1.5, 1)},
                            {disk(1.3, 2), disk(0.6, 0.5)},   {dimer(1, 0.3, 2), dimer(1, 3, 2)}};
  const double alphas[] = {0.0, 0.6, 1.0};
  int n = sanitize() ? 50 : 400;
  double worst_v = 0, worst_t = 0;
  for (size_t c = 0; c < sizeof sh / sizeof sh[0]; c++) {
    const hd_shape *sa = &sh[c][0], *sb = &sh[c][1];
    hd_shape ga = general(sa), gb = general(sb);
    for (int k = 0; k < n; k++) {
      hd_kin A, B;
      int ka, kb;
      double alpha = alphas[k % 3];
      random_contact(r, sa, sb, 2.0, &A, &B, &ka, &kb);
      hd_kin A1 = A, B1 = B, A2 = A, B2 = B;
      hd_collision_info i1, i2;
      hd_collide_pair(&A1, sa, &B1, sb, ka, kb, alpha, &i1);
      hd_collide_pair(&A2, &ga, &B2, &gb, ka, kb, alpha, &i2);
      double vs = 1.0 + vscale(&A, sa) + vscale(&B, sb), tol = 1e-12 * vs;
      double dv = fmax(fmax(fabs(A1.vx - A2.vx), fabs(A1.vy - A2.vy)),
                       fmax(fabs(B1.vx - B2.vx), fabs(B1.vy - B2.vy)));
      dv = fmax(dv,
                fmax(sa->rmax * fabs(A1.omega - A2.omega), sb->rmax * fabs(B1.omega - B2.omega)));
      worst_v = fmax(worst_v, dv / vs);
      assert_true(dv <= tol);
      assert_true(same_or_nan(i1.theta_i, i2.theta_i, 1e-12));
      assert_true(same_or_nan(i1.theta_j, i2.theta_j, 1e-12));
      assert_true(fabs(i1.f - i2.f) <= 1e-12 * i1.f && fabs(i1.vn - i2.vn) <= tol);
      assert_true(fabs(i1.de - i2.de) <=
                  1e-12 * (test_kin_energy(&A, sa) + test_kin_energy(&B, sb)));
      /* prediction from an approach */
      random_approach(r, sa, sb, k % 2 ? 2.0 : 0.0, 2.0, 0.01, 1.5, &A, &B);
      hd_contact c1, c2;
      int g1 = hd_predict_pair(&A, sa, &B, sb, 3.0, &c1),
          g2 = hd_predict_pair(&A, &ga, &B, &gb, 3.0, &c2);
      assert_int_equal(g1, g2);
      if (g1) {
        worst_t = fmax(worst_t, fabs(c1.t - c2.t) / (1.0 + c1.t));
        assert_true(fabs(c1.t - c2.t) <= 1e-12 * (1.0 + c1.t));
        assert_true(c1.ka == c2.ka && c1.kb == c2.kb);
      }
      /* walls: A's disk ka against a wall through its contact point */
      hd_wall w = {k % 2, 0.0, (k / 2) % 2 ? 1.0 : -1.0};
      hd_kin W = {0,
                  0,
                  gsl_ran_gaussian(r, 1),
                  gsl_ran_gaussian(r, 1),
                  unif(r, -M_PI, M_PI),
                  sa->n > 1 ? gsl_ran_gaussian(r, 2.0) : 0.0};
      if (sa->n == 1) W.phi = 0;
      double gap = unif(r, 0.01, 1.5) + hd_shape_radius(sa);
      *(w.axis ? &W.y : &W.x) = w.normal * gap;
      *(w.axis ? &W.vy : &W.vx) = -w.normal * fabs(w.axis ? W.vy : W.vx);
      g1 = hd_predict_wall(&W, sa, &w, 3.0, &c1);
      g2 = hd_predict_wall(&W, &ga, &w, 3.0, &c2);
      assert_int_equal(g1, g2);
      if (!g1) continue;
      worst_t = fmax(worst_t, fabs(c1.t - c2.t) / (1.0 + c1.t));
      assert_true(fabs(c1.t - c2.t) <= 1e-12 * (1.0 + c1.t) && c1.ka == c2.ka);
      hd_kin_advance(&W, c1.t);
      hd_kin W1 = W, W2 = W;
      hd_collide_wall(&W1, sa, c1.ka, &w, alpha, &i1);
      hd_collide_wall(&W2, &ga, c1.ka, &w, alpha, &i2);
      vs = 1.0 + vscale(&W, sa);
      assert_true(fabs(W1.vx - W2.vx) <= 1e-12 * vs && fabs(W1.vy - W2.vy) <= 1e-12 * vs);
      assert_true(sa->rmax * fabs(W1.omega - W2.omega) <= 1e-12 * vs);
      assert_true(same_or_nan(i1.theta_i, i2.theta_i, 1e-12) && fabs(i1.f - i2.f) <= 1e-12);
      assert_true(fabs(i1.de - i2.de) <= 1e-12 * test_kin_energy(&W, sa));
    }
  }
  printf("# general vs paper: largest velocity difference %.3g of the speed scale, contact time "
         "%.3g\n",
         worst_v, worst_t);
  gsl_rng_free(r);
}

/* One random collision of two clusters checked against the conservation laws and the rigid-body
 * rule written independently: momentum and angular momentum (sum over the disks), restitution of
 * the contact points' normal velocity, energy change = info.de = -(1 - alpha^2) mu vn^2 / 2 with
 * 1/mu = sum 1/M + (rho x n)^2 / I (rho from the disk positions, I = sum m |o|^2 from them), the
 * contact angle from the centre of mass to the contacting disk, and f = mu / m_ref. */
static void check_cluster_collision(gsl_rng *r, const hd_shape *sa, const hd_shape *sb,
                                    double alpha) {
  hd_kin A, B;
  int ka, kb;
  random_contact(r, sa, sb, 2.0, &A, &B, &ka, &kb);
  hd_kin A1 = A, B1 = B;
  hd_collision_info in;
  hd_collide_pair(&A1, sa, &B1, sb, ka, kb, alpha, &in);
  double Ma = hd_shape_mass(sa), Mb = hd_shape_mass(sb);
  double vs = fmax(fmax(vscale(&A, sa), vscale(&B, sb)), fmax(vscale(&A1, sa), vscale(&B1, sb)));
  double ps = (Ma + Mb) * vs;
  assert_true(fabs(Ma * (A1.vx - A.vx) + Mb * (B1.vx - B.vx)) <= 1e-13 * ps);
  assert_true(fabs(Ma * (A1.vy - A.vy) + Mb * (B1.vy - B.vy)) <= 1e-13 * ps);
  double px = unif(r, -20, 20), py = unif(r, -20, 20);
  double L0 = ang_mom(&A, sa, px, py) + ang_mom(&B, sb, px, py);
  double L1 = ang_mom(&A1, sa, px, py) + ang_mom(&B1, sb, px, py);
  assert_true(fabs(L1 - L0) <= 1e-13 * ps * 40);
  double vn0 = ref_vn(&A, sa, &B, sb, ka, kb), vn1 = ref_vn(&A1, sa, &B1, sb, ka, kb);
  assert_true(vn0 < 0 && fabs(in.vn - vn0) <= 1e-12 * vs);
  assert_true(fabs(vn1 + alpha * vn0) <= 1e-12 * vs);
  /* mu from the disk positions */
  double ax, ay, bx, by, inv = 1.0 / Ma + 1.0 / Mb, rho[2][2];
  ref_pos(&A, sa, ka, 0, &ax, &ay);
  ref_pos(&B, sb, kb, 0, &bx, &by);
  double D = hypot(bx - ax, by - ay), nx = (bx - ax) / D, ny = (by - ay) / D;
  const hd_shape *sh[2] = {sa, sb};
  const hd_kin *kk[2] = {&A, &B};
  for (int s = 0; s < 2; s++) {
    double I = 0.0, cx = s ? bx : ax, cy = s ? by : ay;
    for (int q = 0; q < ndisks(sh[s]); q++) {
      double x, y;
      ref_pos(kk[s], sh[s], q, 0, &x, &y);
      I += sh[s]->mk[q] * ((x - kk[s]->x) * (x - kk[s]->x) + (y - kk[s]->y) * (y - kk[s]->y));
    }
    rho[s][0] = cx - kk[s]->x;
    rho[s][1] = cy - kk[s]->y;
    double cr = rho[s][0] * ny - rho[s][1] * nx;
    if (I > 0) inv += cr * cr / I;
  }
  double mu = 1.0 / inv, de = -0.5 * (1 - alpha * alpha) * mu * vn0 * vn0;
  double E0 = ref_ke(&A, sa) + ref_ke(&B, sb), E1 = ref_ke(&A1, sa) + ref_ke(&B1, sb);
  assert_true(fabs((E1 - E0) - in.de) <= 1e-12 * E0);
  assert_true(fabs(de - in.de) <= 1e-12 * (E0 + fabs(de)));
  if (alpha == 1.0) assert_true(fabs(E1 - E0) <= 1e-13 * E0);
  /* contact angles: from the outward axis (centre of mass -> contacting disk) to the normal */
  for (int s = 0; s < 2; s++) {
    double th = s ? in.theta_j : in.theta_i, rr = hypot(rho[s][0], rho[s][1]);
    double mx = s ? -nx : nx, my = s ? -ny : ny;
    if (rr < 1e-12) {
      assert_true(isnan(th));
      continue;
    }
    assert_true(fabs(cos(th) - (rho[s][0] * mx + rho[s][1] * my) / rr) <= 1e-11);
    assert_true(fabs(sin(th) - (rho[s][0] * my - rho[s][1] * mx) / rr) <= 1e-11);
  }
  double mref = sa->n > 1 ? sa->mk[ka] : sb->n > 1 ? sb->mk[kb] : sa->mk[ka];
  assert_true(fabs(in.f - mu / mref) <= 1e-12 * in.f);
}

static void collide_clusters(void **state) {
  (void)state;
  gsl_rng *r = rng_new(93);
  const hd_shape sh[] = {trimer_linear(), trimer_bent(),  trimer_triangle(),
                         dimer_asym(),    dimer(1, 1, 1), disk(1.3, 0.7)};
  const double alphas[] = {0.0, 0.5, 0.9, 1.0};
  int n = sanitize() ? 20 : 150;
  for (size_t a = 0; a < 4; a++)
    for (size_t b = 0; b < sizeof sh / sizeof sh[0]; b++)
      for (int k = 0; k < n; k++) {
        check_cluster_collision(r, &sh[a], &sh[b], alphas[k % 4]);
        check_cluster_collision(r, &sh[b], &sh[a], alphas[k % 4]);
      }
  gsl_rng_free(r);
}

/* Contact prediction of clusters against the brute force (compare_pair: same contact or none,
 * times to 1e-9), with the just-collided pair predicted again, as predict_pairs does for
 * dimers. */
static void predict_clusters(void **state) {
  (void)state;
  const pclass cl[] = {
      {"linear-linear", trimer_linear(), trimer_linear(), 2, 2, 1.5, 3, 100000},
      {"bent-triangle", trimer_bent(), trimer_triangle(), 2, 3, 1.5, 3, 100000},
      {"asym fast", dimer_asym(), dimer_asym(), 1e2, 1, 0.3, 0.5, 200000},
      {"triangle-disk", trimer_triangle(), disk(0.6, 0.5), 3, 0, 1.5, 3, 100000},
      {"dimer-linear", dimer(1, 1, 1), trimer_linear(), 2, 2, 1.5, 3, 100000},
      {"linear still", trimer_linear(), trimer_bent(), 0, 0, 1.5, 3, 30000},
  };
  gsl_rng *r = rng_new(95);
  int ncase = sanitize() ? 4 : 30;
  for (size_t k = 0; k < sizeof cl / sizeof cl[0]; k++) {
    int hits = 0;
    for (int n = 0; n < ncase; n++) {
      hd_kin A, B;
      random_approach(r, &cl[k].sa, &cl[k].sb, cl[k].wa, cl[k].wb, 0.01, cl[k].gmax, &A, &B);
      int ns = sanitize() ? cl[k].nsamp / 10 : cl[k].nsamp;
      hd_contact c;
      if (!compare_pair(&A, &cl[k].sa, &B, &cl[k].sb, cl[k].tmax, ns, -1)) continue;
      hits++;
      assert_true(hd_predict_pair(&A, &cl[k].sa, &B, &cl[k].sb, cl[k].tmax, &c));
      hd_kin a = A, b = B;
      hd_kin_advance(&a, c.t);
      hd_kin_advance(&b, c.t);
      hd_collide_pair(&a, &cl[k].sa, &b, &cl[k].sb, c.ka, c.kb, 0.9, NULL);
      compare_pair(&a, &cl[k].sa, &b, &cl[k].sb, cl[k].tmax, ns, c.ka * ndisks(&cl[k].sb) + c.kb);
    }
    printf("# %s: %d of %d approaches touch\n", cl[k].name, hits, ncase);
    if (!sanitize()) assert_true(hits >= ncase / 5);
  }
  gsl_rng_free(r);
}

/* Single steps of clusters (ca_single in hd_body.c): when one disk pair alone limits the step,
 * the search goes on with that pair alone up to where the other pairs' bounds end.  Random
 * approaches of linear trimers, and of a dimer (as a general cluster) with a linear trimer, fixed
 * seed, each against the brute force (compare_pair: the same contact or none, times to 1e-9, the
 * brute force's resolution); the resumable search (hd_ca_begin, hd_ca_step) gives
 * hd_predict_pair's contact bit for bit, and a search that finds a contact takes at most 3 calls
 * of hd_ca_step on average.  Without single steps (every step evaluates all 9 or 6 pairs) this
 * sample takes 7.4 calls per contact found (linear-linear); with them 2.4 and 2.1 (printed).
 * 40 contacts per class (4 in the sanitizer build). */
static void predict_single_steps(void **state) {
  (void)state;
  hd_shape dg; /* a dimer of the general code */
  double x[2] = {-0.5, 0.5}, y[2] = {0.0, 0.0}, d[2] = {1.0, 1.0}, m[2] = {1.0, 1.0};
  assert_int_equal(hd_shape_cluster(&dg, 2, x, y, d, m, 0), 0);
  assert_int_equal(dg.tag, HD_KIND_BODY);
  const pclass cl[] = {
      {"linear-linear", trimer_linear(), trimer_linear(), 2, 2, 1.0, 3, 50000},
      {"dimer-linear", dg, trimer_linear(), 2, 2, 1.0, 3, 50000},
  };
  gsl_rng *r = rng_new(2727);
  int want = sanitize() ? 4 : 40;
  for (size_t k = 0; k < sizeof cl / sizeof cl[0]; k++) {
    long calls = 0;
    int hits = 0;
    for (int n = 0; n < 20 * want && hits < want; n++) {
      hd_kin A, B;
      random_approach(r, &cl[k].sa, &cl[k].sb, cl[k].wa, cl[k].wb, 0.01, cl[k].gmax, &A, &B);
      hd_ca ca;
      hd_contact c1, c2;
      int rc = hd_ca_begin(&ca, &A, &cl[k].sa, &B, &cl[k].sb, cl[k].tmax, NULL, &c1);
      long calls_n = 0;
      while (rc == 2) rc = hd_ca_step(&ca, cl[k].tmax, &c1), calls_n++;
      int got = hd_predict_pair(&A, &cl[k].sa, &B, &cl[k].sb, cl[k].tmax, &c2);
      assert_int_equal(rc, got);
      if (got) assert_true(c1.t == c2.t && c1.ka == c2.ka && c1.kb == c2.kb);
      int ns = sanitize() ? cl[k].nsamp / 10 : cl[k].nsamp;
      assert_int_equal(compare_pair(&A, &cl[k].sa, &B, &cl[k].sb, cl[k].tmax, ns, -1), got);
      if (!got) continue;
      hits++;
      calls += calls_n;
    }
    assert_int_equal(hits, want);
    printf("# %s: %.2f calls of hd_ca_step per contact found\n", cl[k].name, (double)calls / hits);
    assert_true((double)calls / hits <= 3.0);
  }
  gsl_rng_free(r);
}

/* Closed form for disks: exact values for a head-on approach, the t = 0 rules. */
static void predict_disks_closed_form(void **state) {
  (void)state;
  double t;
  /* gap 1 closing at speed 2: t = 0.5 */
  assert_true(hd_predict_disks(2.0, 0.0, -2.0, 0.0, 1.0, 0.0, 10.0, &t) && fabs(t - 0.5) <= 1e-15);
  assert_false(hd_predict_disks(2.0, 0.0, -2.0, 0.0, 1.0, 0.0, 0.4, &t)); /* beyond tmax */
  /* impact parameter b < D: t = (sqrt(x^2) - sqrt(D^2 - b^2)) / v with x = 3, b = 0.6, D = 1 */
  assert_true(hd_predict_disks(3.0, 0.6, -1.0, 0.0, 1.0, 0.0, 10.0, &t) && fabs(t - 2.2) <= 1e-14);
  assert_false(hd_predict_disks(3.0, 1.0 + 1e-9, -1.0, 0.0, 1.0, 0.0, 10.0, &t)); /* miss */
  /* touching now: approaching -> 0 (a gap of ~1e-12 D: at once, or within its closing time),
   * receding -> none */
  assert_true(hd_predict_disks(1.0 + 1e-13, 0.0, -1.0, 0.0, 1.0, 0.0, 10.0, &t) && t == 0.0);
  assert_true(hd_predict_disks(1.0 + 1e-12, 0.0, -1.0, 0.0, 1.0, 0.0, 10.0, &t) && t <= 1.1e-12);
  /* a gap of 5e-11 D approached at 1e-6 with tangential speed 1: a miss (discriminant < 0),
   * which the t = 0 rule used to collide (review) */
  assert_false(hd_predict_disks(1.0 + 5e-11, 0.0, -1e-6, 1.0, 1.0, 2.0, 10.0, &t));
  assert_false(hd_predict_disks(1.0 - 1e-12, 0.0, 1.0, 0.0, 1.0, 0.0, 10.0, &t));
  /* in contact, approaching at 3e-12 with |v| = 1: a collision for slow bodies, round-off for
   * bodies moving at ~1000 (vs = 4000: 8 eps vs = 7e-12) */
  assert_true(hd_predict_disks(1.0, 0.0, -3e-12, 1.0, 1.0, 0.0, 10.0, &t) && t == 0.0);
  assert_false(hd_predict_disks(1.0, 0.0, -3e-12, 1.0, 1.0, 4000.0, 10.0, &t));
}

/* Near misses at a gap between TOL_C and TOL_0 (1e-12 and 1e-10 D) that approach: they used to
 * be collided at t = 0 although they never touch (review).  (1) A disk passing a dimer's disk at
 * a gap of 5e-11 with normal speed 1e-6 and tangential 1, without and with a slow rotation.
 * (2) A dimer with a = 1e-9 d spinning at -1.5e9 just after its disk 0 hit a disk: its twin disk
 * 1, at a gap of 5.2e-11, stays more than 1.36e-11 away for 1e-3 (the reviewer's long-double
 * brute force) and must not be collided now; with the old rule it got an impulse with vn = -0.13.
 * No contact at all within 1e-3. */
static void predict_near_miss(void **state) {
  (void)state;
  hd_shape dm = dimer(1, 1, 1), dk = disk(1, 1);
  hd_kin A = {0, 0, 0, 0, 0, 0}, B = {0.5 + 1 + 5e-11, 0, -1e-6, 1.0, 0, 0};
  hd_contact c;
  assert_false(hd_predict_pair(&A, &dm, &B, &dk, 10, &c));
  A.omega = 1e-3;
  assert_false(hd_predict_pair(&A, &dm, &B, &dk, 10, &c));
  hd_shape tiny = dimer(1, 1e-9, 1);
  hd_kin T = {
      0, 0, 0.28350627093425912, 1.1915629145013629, -1.5561774963877713, -1501044978.1256156};
  hd_kin K = {
      -0.99929091247064561, 0.037651989400833662, -0.35520746707631856, 0.72376337291188708, 0, 0};
  int got = hd_predict_pair(&T, &tiny, &K, &dk, 1e-3, &c);
  printf("# spinner's twin disk: %s (t = %g)\n", got ? "contact" : "no contact", got ? c.t : 0.0);
  assert_false(got); /* nor the disk that has just collided, which recedes */
}

/* A collision's kind follows from its partners' kinds (hd_coll_kind_of): every pair of body
 * kinds and a body with a wall gives the log's text, "A-B" of the kinds' names, with a body of a
 * named species (HD_KIND_BODY) making body-body or body-wall and a dimer with a disk dimer-disk
 * whichever is i; the paper's six kinds keep their texts. */
static void coll_kind_of_kinds(void **state) {
  (void)state;
  const hd_kind body[] = {HD_KIND_DISK, HD_KIND_DIMER, HD_KIND_BODY, HD_KIND_ROD};
  for (size_t x = 0; x < 4; x++)
    for (size_t y = 0; y <= 4; y++) {
      hd_kind a = body[x], b = y < 4 ? body[y] : HD_KIND_WALL;
      if ((a == HD_KIND_ROD) != (b == HD_KIND_ROD)) continue; /* rods meet rods only */
      hd_kind wa = a, wb = b;
      if (a == HD_KIND_BODY || b == HD_KIND_BODY)
        wa = HD_KIND_BODY, wb = b == HD_KIND_WALL ? HD_KIND_WALL : HD_KIND_BODY;
      else if (a == HD_KIND_DISK && b == HD_KIND_DIMER)
        wa = HD_KIND_DIMER, wb = HD_KIND_DISK;
      char want[32];
      snprintf(want, sizeof want, "%s-%s", hd_kind_name(wa), hd_kind_name(wb));
      if (a == HD_KIND_ROD && b == HD_KIND_WALL) continue;
      assert_string_equal(hd_coll_kind_name(hd_coll_kind_of(a, b)), want);
      assert_int_equal(hd_coll_kind_of(a, b), hd_coll_kind_of(wa, wb));
    }
  static const struct {
    hd_kind a, b;
    const char *name;
  } paper[] = {
      {HD_KIND_DIMER, HD_KIND_DIMER, "dimer-dimer"}, {HD_KIND_DISK, HD_KIND_DIMER, "dimer-disk"},
      {HD_KIND_DISK, HD_KIND_DISK, "disk-disk"},     {HD_KIND_DIMER, HD_KIND_WALL, "dimer-wall"},
      {HD_KIND_DISK, HD_KIND_WALL, "disk-wall"},     {HD_KIND_ROD, HD_KIND_ROD, "rod-rod"},
      {HD_KIND_DIMER, HD_KIND_BODY, "body-body"},    {HD_KIND_BODY, HD_KIND_WALL, "body-wall"}};
  for (size_t k = 0; k < sizeof paper / sizeof *paper; k++)
    assert_string_equal(hd_coll_kind_name(hd_coll_kind_of(paper[k].a, paper[k].b)), paper[k].name);
  assert_string_equal(hd_coll_kind_name(hd_coll_kind_of(HD_KIND_ROD, HD_KIND_WALL)), "?");
  assert_string_equal(hd_coll_kind_name(-1), "?");
  assert_null(hd_kind_name(HD_NKINDS));
}

int main(void) {
  gsl_set_error_handler_off();
  if (getenv("HAFF_TEST_FILTER")) cmocka_set_test_filter(getenv("HAFF_TEST_FILTER"));
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(shapes),
      cmocka_unit_test(coll_kind_of_kinds),
      cmocka_unit_test(free_flight),
      cmocka_unit_test(collide_by_hand),
      cmocka_unit_test(collide_pairs),
      cmocka_unit_test(collide_tiny_bond),
      cmocka_unit_test(alpha_zero_fast_bodies),
      cmocka_unit_test(collide_walls),
      cmocka_unit_test(predict_disks_closed_form),
      cmocka_unit_test(predict_pairs),
      cmocka_unit_test(predict_touching_now),
      cmocka_unit_test(predict_near_miss),
      cmocka_unit_test(predict_second_contact),
      cmocka_unit_test(predict_interleaved),
      cmocka_unit_test(predict_recontact),
      cmocka_unit_test(predict_near_parallel),
      cmocka_unit_test(predict_grazing),
      cmocka_unit_test(predict_walls),
      cmocka_unit_test(cluster_shapes),
      cmocka_unit_test(general_matches_paper),
      cmocka_unit_test(collide_clusters),
      cmocka_unit_test(predict_clusters),
      cmocka_unit_test(predict_single_steps),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
