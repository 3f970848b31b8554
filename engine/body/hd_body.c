/* hd_body.c: shapes, exact free flight and contact prediction for hard disks and dimers.
 * (The collision rules are in hd_body_collide.c, the generic impulse rule in hd_body_impulse.c.)
 *
 * Contact prediction
 * ------------------
 * For a disk pair p (disk i of A, disk j of B) the separation vector is
 *   r(t) = R_B - R_A + (V_B - V_A) t + rho_Bj(phi_B + w_B t) - rho_Ai(phi_A + w_A t),
 * rho = -+(a/2)(cos, sin) for disk 0 / 1, and the gap is h(t) = |r(t)| - D with D = (dA + dB)/2.
 *
 * No rotation (disk bodies, or dimers with omega == 0 exactly): r is linear in t and the first
 * root of |r|^2 = D^2 is the closed form t = c / (-b + sqrt(b^2 - v^2 c)), c = r^2 - D^2,
 * b = r.v (hd_predict_disks; the engine's disk fast path, hd_disk_contact_time in hd_disk.h,
 * shares its VTOL rule for a pair in contact).
 *
 * With rotation: conservative advancement (CA) over all disk pairs at once, from the time the
 * enclosing circles (radius (a + d)/2 each) first meet to the time they part for good (or tmax).
 * At a time t with gap h and gap rate h' = r.r'/|r| for a pair, two rigorous lower bounds hold
 * for every tau >= 0:
 *   (i)  h(t + tau) >= h - L tau,               L = |V_B - V_A| + |w_A| a_A/2 + |w_B| a_B/2
 *        (L bounds |r'|, hence |d|r|/dt|);
 *   (ii) h(t + tau) >= h + h' tau - K tau^2/2,  K = w_A^2 a_A/2 + w_B^2 a_B/2 >= |r''|
 *        (Taylor with |r''| <= K, then |x + y| >= |x| + x.y/|x| by convexity of the norm).
 * The step is the larger of the first positive roots of the two bounds, minimised over pairs:
 * every pair keeps h > 0 over the step, so no root is ever skipped.  (Bound (ii) is
 * computed from g = r.r' and |r| without forming h' = g / |r|.)  Far from contact (ii) takes
 * long steps (a near-miss is passed in a few steps: (ii) is exact in h and h'); near a transversal
 * root (ii) converges quadratically, near a tangential one linearly.  sin and cos are computed
 * once per body per step (ca_sincos: an inline Cody-Waite reduction and the fdlibm polynomials,
 * absolute error < 1.2e-16, as accurate as the argument phi + omega t itself; libm beyond
 * |phi + omega t| >= 1e5).  Fast spinners take steps of order sqrt(h/K) ~ 1/omega: exact but
 * slower.  A CA that starts at t = 0 reuses the state of the t = 0 contact check as its first
 * step.  The CA is resumable (hd_ca_begin, hd_ca_step: one evaluation per step): its current
 * time t is at every step a lower bound on the contact time, which lets the engine interleave
 * the searches of one body's neighbours, always advancing the one furthest behind and stopping
 * all once it passes the earliest contact found (hd_predict.c).  Stepping a search with a
 * smaller tmax only ends it sooner: the steps do not depend on tmax (only the Newton polish
 * below stays <= tmax), so the contact found is the one hd_predict_pair finds alone.  A dimer's
 * sin and cos at t = 0 may be given (hd_ca_sincos, the same function): shared by the searches of
 * all its neighbours.  The safe steps of the pairs go two per SSE2 instruction (safe_steps: the
 * same operations on each lane, the same steps).
 *
 * Single steps (clusters only, ca_single): when one disk pair p alone limits a step at t, every
 * other pair's bounds, taken at t, keep its gap positive up to t + its own step (the bounds hold
 * for any tau), so the search goes on evaluating pair p alone (ca_eval_one_general: the same
 * values as the full evaluation) up to the smallest of the other steps; a contact of p before
 * that is the earliest.  A search of two linear trimers that finds a contact then takes ~2.4
 * calls of hd_ca_step instead of ~7.4 (test predict_single_steps); the times of the steps, and
 * so the contact times, differ from the full steps' in the last bits.  Dimers (4 pairs, whose
 * evaluation costs little more than one pair's) keep the full steps: single steps made them 5 %
 * slower (bench/issue27-ab.md).
 *
 * Tolerances (all relative to D; velocities relative to L) and their effect:
 *   TOL_C = 1e-12  a pair is "in contact" when CA brings its gap to h <= TOL_C D.  One or two
 *                  Newton steps then polish t to the root (accepted only if they stay inside
 *                  the safe step of the other pairs and improve |h| while still approaching), so
 *                  t is exact to round-off for transversal contacts.  Consequence for grazing
 *                  contacts: a trajectory whose minimum gap lies in (0, TOL_C D] is treated as a
 *                  touching contact (its |vn| is then tiny, and so is the impulse); one whose
 *                  minimum gap exceeds TOL_C D is a miss.
 *   VTOL  = 1e-12  "approaching" means the normal relative velocity of the two contact points
 *                  (rotation included), h' = r.r'/|r|, is < -vtol, vtol = VTOL L + 8 eps vs
 *                  (HD_DISK_VROUND: the round-off of the disks' own velocities, of size vs;
 *                  two bodies moving together at 1000 keep ~1e-13 of h' after an alpha = 0
 *                  collision, above VTOL L).  A touching pair with |h'| <= vtol is sliding, not
 *                  colliding: it is skipped (this also keeps an alpha = 0 collision, after which
 *                  h' = 0 up to round-off, from re-colliding) until rotation drives it into
 *                  contact again (h' < -vtol while h <= TOL_C D): then it collides at once.
 *                  At alpha = 0 a sustained sliding contact is thus a train of ever smaller
 *                  collisions, which the engine reports as inelastic collapse (the rigid-body
 *                  limit of a lasting contact).
 *   TOL_0 = 1e-10  at t = 0 a pair with h <= TOL_0 D (a gap or an overlap left by round-off) is
 *                  in contact: approaching from h <= TOL_C D, t = 0 is returned (from a larger
 *                  gap the search goes on, as for any pair: a review found pairs at gaps of
 *                  5e-11 D collided at t = 0 that never touch, a graze or a fast spinner's twin
 *                  disk); not approaching (the pair has just collided), it is ignored until it
 *                  has separated to h > TOL_SEP = 2 TOL_0 or approaches again from h > TOL_C;
 *                  after that it is an ordinary pair, so its next real contact (a fast spinner
 *                  swinging its other disk round, or the same disk pair coming back) is found.
 *                  While a pair is ignored the step is bounded by the time its gap could reach
 *                  TOL_SEP D (h'' <= 2 L^2/D + K), so CA cannot jump over its separation and
 *                  return; or, when it recedes (h' > 0), by the larger root tau_hi of bound
 *                  (ii), h + h' tau - K tau^2/2, if that is longer: the gap is > 0 on
 *                  (tau_lo, tau_hi) with tau_lo < 0, or ~ -h/h' ~ 1e-16 for a round-off overlap
 *                  that is receding (the collision just done), so no contact of that pair, nor
 *                  a separation and return, fits before tau_hi (ign_step).  This saves the
 *                  evaluation at the separation of every just-collided pair.
 * Linear (closed-form) pairs use the same TOL_C, TOL_0 and vtol rules and report a contact whose
 * normal velocity at contact is below -vtol.
 *
 * Termination: each step is >= min(h)/L > TOL_C D / L or, for ignored pairs, bounded below by the
 * time to reach TOL_SEP; the loop stops at min(tmax, parting time).  As a guard against a
 * misuse (tmax = INFINITY for two dimers spinning in place that never touch) the loop gives up
 * after HD_CA_MAXIT steps and reports no contact.
 *
 * Stop requests: the loops that run a whole search (hd_predict_pair, hd_predict_wall) look at
 * hd_stop_requested every HD_CA_POLL + 1 steps (a few ms) and, when a stop was asked for,
 * return HD_CA_CUT with the time the search reached, a lower bound on the contact: a stiff body
 * (a fast spinner) could keep one search going for minutes, deaf to SIGTERM (issue 24).
 */
#include "hd_body.h"

#include <math.h>
#include <stddef.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "hd_disk.h"
#include "hd_stop.h"

#define TOL_C 1e-12
#define TOL_0 1e-10
#define TOL_SEP 2e-10
#define VTOL HD_DISK_VTOL
#define HD_CA_MAXIT 100000000L

const char *hd_kind_name(int kind) {
  static const char *const name[] = {[HD_KIND_DISK] = "disk",
                                     [HD_KIND_DIMER] = "dimer",
                                     [HD_KIND_BODY] = "body",
                                     [HD_KIND_ROD] = "rod",
                                     [HD_KIND_WALL] = "wall"};
  return kind >= 0 && kind < (int)(sizeof name / sizeof *name) ? name[kind] : NULL;
}

const char *hd_coll_kind_name(hd_coll_kind k) {
  /* the texts of the pairs hd_coll_kind_of makes: hd_kind_name(A) "-" hd_kind_name(B)
   * (tests/test_body.c, coll_kind_of_kinds, checks them) */
  static const char *const name[HD_NKINDS][HD_NKINDS] = {
      [HD_KIND_DIMER][HD_KIND_DIMER] = "dimer-dimer", [HD_KIND_DIMER][HD_KIND_DISK] = "dimer-disk",
      [HD_KIND_DISK][HD_KIND_DISK] = "disk-disk",     [HD_KIND_DIMER][HD_KIND_WALL] = "dimer-wall",
      [HD_KIND_DISK][HD_KIND_WALL] = "disk-wall",     [HD_KIND_ROD][HD_KIND_ROD] = "rod-rod",
      [HD_KIND_BODY][HD_KIND_BODY] = "body-body",     [HD_KIND_BODY][HD_KIND_WALL] = "body-wall"};
  const char *s = k >= 0 && k < HD_NKINDS * HD_NKINDS ? name[k / HD_NKINDS][k % HD_NKINDS] : NULL;
  return s ? s : "?";
}

void hd_shape_disk(hd_shape *s, double d, double m) {
  *s = (hd_shape){0};
  s->tag = HD_KIND_DISK;
  s->n = 1;
  s->d = s->dk[0] = d;
  s->m = s->mk[0] = m;
  s->mass = m;
  s->inertia = 0.0;
  s->radius = 0.5 * d;
  s->rmax = 0.0;
}

void hd_shape_dimer(hd_shape *s, double d, double a, double m) {
  *s = (hd_shape){0};
  s->tag = HD_KIND_DIMER;
  s->n = 2;
  s->d = s->dk[0] = s->dk[1] = d;
  s->a = a;
  s->m = s->mk[0] = s->mk[1] = m;
  s->ox[0] = -0.5 * a;
  s->ox[1] = 0.5 * a;
  s->mass = 2.0 * m;
  s->inertia = 0.5 * m * a * a;
  s->radius = 0.5 * (a + d);
  s->rmax = 0.5 * a;
}

int hd_shape_cluster(hd_shape *s, int n, const double *x, const double *y, const double *d,
                     const double *m, int fast) {
  if (n < 1 || n > HD_MAX_BODY_DISKS) return -1;
  double M = 0.0, cx = 0.0, cy = 0.0;
  for (int k = 0; k < n; k++) {
    if (!(d[k] > 0.0 && d[k] < INFINITY && m[k] > 0.0 && m[k] < INFINITY) || !isfinite(x[k]) ||
        !isfinite(y[k]))
      return -1;
    M += m[k];
    cx += m[k] * x[k];
    cy += m[k] * y[k];
  }
  cx /= M;
  cy /= M;
  hd_shape c = {0};
  c.tag = HD_KIND_BODY;
  c.n = n;
  c.mass = M;
  c.m = m[0];
  for (int k = 0; k < n; k++) {
    c.ox[k] = x[k] - cx;
    c.oy[k] = y[k] - cy;
    c.dk[k] = d[k];
    c.mk[k] = m[k];
    double r = hypot(c.ox[k], c.oy[k]);
    c.inertia += m[k] * r * r;
    c.rmax = fmax(c.rmax, r);
    c.radius = fmax(c.radius, r + 0.5 * d[k]);
    c.d = fmax(c.d, d[k]);
  }
  if (n == 1 && fast) {
    hd_shape_disk(s, d[0], m[0]);
    return 0;
  }
  if (n == 2 && fast && d[0] == d[1] && m[0] == m[1] && c.oy[0] == 0.0 && c.oy[1] == 0.0 &&
      c.ox[0] == -c.ox[1] && c.ox[0] <= 0.0) {
    hd_shape_dimer(s, d[0], c.ox[1] - c.ox[0], m[0]);
    return 0;
  }
  *s = c;
  return 0;
}

double hd_shape_mass(const hd_shape *s) {
  return s->mass;
}

double hd_shape_inertia(const hd_shape *s) {
  return s->inertia;
}

double hd_shape_radius(const hd_shape *s) {
  return s->radius;
}

void hd_kin_advance(hd_kin *k, double dt) {
  k->x += k->vx * dt;
  k->y += k->vy * dt;
  if (k->omega != 0.0) {
    double p = k->phi + k->omega * dt;
    /* remainder() leaves p in (-pi, pi] unchanged: call it only when p is out of range */
    if (!(p <= M_PI && p > -M_PI)) {
      p = remainder(p, 2.0 * M_PI); /* in [-pi, pi] */
      if (p <= -M_PI) p = M_PI;
    }
    k->phi = p;
  }
}

/* Half bond length of a shape (0 for a disk body). */
static double half_a(const hd_shape *s) {
  return s->tag == HD_KIND_DIMER ? 0.5 * s->a : 0.0;
}

/* Sign of disk `which` along the axis: -1 for disk 0, +1 for disk 1. */
static double disk_sign(int which) {
  return which ? 1.0 : -1.0;
}

void hd_kin_disk_pos(const hd_kin *k, const hd_shape *s, int which, double *px, double *py) {
  if (s->tag == HD_KIND_BODY) {
    double sn, cs, ox = s->ox[which], oy = s->oy[which];
    sincos(k->phi, &sn, &cs);
    *px = k->x + (ox * cs - oy * sn);
    *py = k->y + (ox * sn + oy * cs);
    return;
  }
  double h = half_a(s) * disk_sign(which);
  if (h == 0.0) {
    *px = k->x;
    *py = k->y;
    return;
  }
  double sn, cs;
  sincos(k->phi, &sn, &cs);
  *px = k->x + h * cs;
  *py = k->y + h * sn;
}

void hd_kin_disk_vel(const hd_kin *k, const hd_shape *s, int which, double *vx, double *vy) {
  if (s->tag == HD_KIND_BODY) {
    double sn, cs, ox = s->ox[which], oy = s->oy[which];
    sincos(k->phi, &sn, &cs);
    *vx = k->vx - k->omega * (ox * sn + oy * cs);
    *vy = k->vy + k->omega * (ox * cs - oy * sn);
    return;
  }
  double h = half_a(s) * disk_sign(which) * k->omega;
  if (h == 0.0) {
    *vx = k->vx;
    *vy = k->vy;
    return;
  }
  double sn, cs;
  sincos(k->phi, &sn, &cs);
  *vx = k->vx - h * sn;
  *vy = k->vy + h * cs;
}

/* ---- linear motion: closed form ----------------------------------------------------------- */

int hd_predict_disks(double dx, double dy, double dvx, double dvy, double D, double vs, double tmax,
                     double *t) {
  double r2 = dx * dx + dy * dy, b = dx * dvx + dy * dvy, v2 = dvx * dvx + dvy * dvy;
  double r = sqrt(r2), vtol = VTOL * sqrt(v2) + HD_DISK_VROUND * vs;
  if (r - D <= TOL_0 * D && !(b < -vtol * r)) {
    return 0; /* in contact and not approaching (just collided): |r(t)| (convex) only grows */
  }
  if (r - D <= TOL_C * D) { /* in contact now and approaching */
    *t = 0.0;
    return 1;
  }
  /* an approaching pair at a gap above TOL_C D, even below TOL_0 D, takes the closed form: it
   * may miss (a graze), and used to be collided at t = 0 all the same */
  if (b >= 0.0) return 0;
  double c = r2 - D * D, disc = b * b - v2 * c;
  if (!(disc >= 0.0)) return 0;
  double s = sqrt(disc);
  if (s <= vtol * D) return 0; /* grazing: normal velocity at contact is -s/D ~ 0 */
  double tc = c / (s - b);
  if (!(tc <= tmax)) return 0;
  *t = tc;
  return 1;
}

/* ---- conservative advancement ------------------------------------------------------------- */

/* sin and cos of x for the CA loop: Cody-Waite reduction by pi/2 (33 + 53 bits of pi/2, exact
 * for |x| < 1e5) and the fdlibm kernels on [-pi/4, pi/4] (polynomials in Estrin form for a short
 * latency: the CA loop is a chain of dependent steps).  Absolute error < 1.2e-16 (measured
 * against long double over |x| < 100 and near multiples of pi/2: libm's sincos has 5.6e-17);
 * larger |x| and NaN go to libm.  Deterministic: only +, -, * in a fixed order. */
static inline void ca_sincos(double x, double *sp, double *cp) {
  if (!(fabs(x) < 1e5)) {
    sincos(x, sp, cp);
    return;
  }
  const double invpio2 = 6.36619772367581382433e-01, pio2_1 = 1.57079632673412561417e+00,
               pio2_1t = 6.07710050650619224932e-11, shift = 0x1.8p52;
  double fn = (x * invpio2 + shift) - shift; /* nearest integer, round-to-nearest mode */
  long q = (long)fn;
  double r = (x - fn * pio2_1) - fn * pio2_1t, z = r * r, z2 = z * z, z4 = z2 * z2;
  double ps = (-1.66666666666666324348e-01 + z * 8.33333333332248946124e-03) +
              z2 * (-1.98412698298579493134e-04 + z * 2.75573137070700676789e-06) +
              z4 * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10);
  double pc = (4.16666666666666019037e-02 + z * -1.38888888888741095749e-03) +
              z2 * (2.48015872894767294178e-05 + z * -2.75573143513906633035e-07) +
              z4 * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11);
  double s = r + (z * r) * ps, hz = 0.5 * z, w = 1.0 - hz;
  double c = w + (((1.0 - w) - hz) + z * (z * pc));
  /* quadrant q mod 4 without branches (exact: one product of each sum is 0) */
  double odd = (double)(q & 1), even = 1.0 - odd;
  double sg = 1.0 - (double)(q & 2), cg = 1.0 - (double)((q + 1) & 2);
  *sp = sg * (s * even + c * odd);
  *cp = cg * (c * even + s * odd);
}

/* Gap, r.r' and |r| of disk i of cluster A and disk j of cluster B (general code, a body pair):
 * (rx0, ry0) = R_B - R_A at t, (ax, ay) and (bx, by) the two disks' turned offsets.  Shared by
 * ca_eval_general and ca_eval_one_general, so that a pair evaluated alone has the same values
 * bit for bit. */
static inline void cluster_pair(const hd_ca_geom *c, int i, int j, double rx0, double ry0,
                                double ax, double ay, double bx, double by, double *h, double *g,
                                double *r) {
  double rx = rx0 + bx - ax, ry = ry0 + by - ay;
  double vx = c->dvx - c->wb * by + c->wa * ay, vy = c->dvy + c->wb * bx - c->wa * ax;
  double rr = sqrt(rx * rx + ry * ry);
  *h = rr - 0.5 * (c->sha->dk[i] + c->shb->dk[j]);
  *g = rx * vx + ry * vy;
  *r = rr;
}

/* ca_eval_sc for general clusters: disk k of a body is at R + Rot(phi) o_k and moves at
 * V + omega x (Rot(phi) o_k); each pair has its own contact distance (d_i + d_j) / 2.  A wall:
 * the gap of disk k is the centre's gap (c->dx + c->dvx t) plus the disk's offset along the
 * inward normal, minus its radius. */
static void ca_eval_general(const hd_ca_geom *c, double t, double sa, double ca, double *h,
                            double *g, double *r) {
  const hd_shape *A = c->sha, *B = c->shb;
  if (c->wall) {
    double gc = c->dx + c->dvx * t;
    for (int i = 0; i < c->na; i++) {
      double ox = A->ox[i], oy = A->oy[i];
      double px = ox * ca - oy * sa, py = ox * sa + oy * ca; /* turned offset */
      double along = c->wsin != 0.0 ? py : px, rate = c->wsin != 0.0 ? px : -py;
      h[i] = gc + c->wn * along - 0.5 * A->dk[i];
      g[i] = c->dvx + c->wn * c->wa * rate;
      r[i] = 1.0;
    }
    return;
  }
  double sb, cb;
  ca_sincos(c->pb + c->wb * t, &sb, &cb);
  double rx0 = c->dx + c->dvx * t, ry0 = c->dy + c->dvy * t;
  double bx[HD_MAX_BODY_DISKS], by[HD_MAX_BODY_DISKS];
  for (int j = 0; j < c->nb; j++) {
    bx[j] = B->ox[j] * cb - B->oy[j] * sb;
    by[j] = B->ox[j] * sb + B->oy[j] * cb;
  }
  for (int i = 0; i < c->na; i++) {
    double ax = A->ox[i] * ca - A->oy[i] * sa, ay = A->ox[i] * sa + A->oy[i] * ca;
    for (int j = 0; j < c->nb; j++) {
      int p = i * c->nb + j;
      cluster_pair(c, i, j, rx0, ry0, ax, ay, bx[j], by[j], &h[p], &g[p], &r[p]);
    }
  }
}

/* Gaps h[p] of every pair at time t (sa, ca: sin and cos of A's orientation then), and their rates
 * h'[p] = g[p] / r[p] (ca_rate): for a body pair r is the distance of the disk centres and g =
 * r.r', for a wall r = 1 and g = h'.  The division is left to the few pairs that need h' itself
 * (safe_step does without). */
static inline void ca_eval_sc(const hd_ca_geom *c, double t, double sa, double ca, double *h,
                              double *g, double *r) {
  if (c->sha) {
    ca_eval_general(c, t, sa, ca, h, g, r);
    return;
  }
  if (c->wall) {
    double gc = c->dx + c->dvx * t;
    for (int i = 0; i < c->na; i++) {
      double s = disk_sign(i) * c->ha * c->wn;
      if (c->na == 1) s = 0.0;
      h[i] = gc + s * (c->wsin != 0.0 ? sa : ca);
      g[i] = c->dvx + s * c->wa * (c->wsin != 0.0 ? ca : -sa);
      r[i] = 1.0;
    }
    return;
  }
  double sb, cb;
  ca_sincos(c->pb + c->wb * t, &sb, &cb);
  double rx0 = c->dx + c->dvx * t, ry0 = c->dy + c->dvy * t;
  for (int i = 0; i < c->na; i++) {
    double ka = c->na == 1 ? 0.0 : disk_sign(i) * c->ha;
    double oax = ka * ca, oay = ka * sa, wax = -ka * c->wa * sa, way = ka * c->wa * ca;
    for (int j = 0; j < c->nb; j++) {
      double kb = c->nb == 1 ? 0.0 : disk_sign(j) * c->hb;
      double rx = rx0 + kb * cb - oax, ry = ry0 + kb * sb - oay;
      double vx = c->dvx - kb * c->wb * sb - wax, vy = c->dvy + kb * c->wb * cb - way;
      double rr = sqrt(rx * rx + ry * ry);
      int p = i * c->nb + j;
      h[p] = rr - c->D;
      g[p] = rx * vx + ry * vy;
      r[p] = rr;
    }
  }
}

/* ca_eval_sc with sin and cos of A's orientation at t computed here. */
static void ca_eval(const hd_ca_geom *c, double t, double *h, double *g, double *r) {
  double sa, ca;
  ca_sincos(c->pa + c->wa * t, &sa, &ca);
  ca_eval_sc(c, t, sa, ca, h, g, r);
}

/* Pair p alone of ca_eval for two clusters (general code, not a wall): the same values as
 * ca_eval_general's for that pair, bit for bit (the same turned offsets and cluster_pair). */
static void ca_eval_one_general(const hd_ca_geom *c, double t, int p, double *h, double *g,
                                double *r) {
  const hd_shape *A = c->sha, *B = c->shb;
  const int i = p / c->nb, j = p % c->nb;
  double sa, ca, sb, cb;
  ca_sincos(c->pa + c->wa * t, &sa, &ca);
  ca_sincos(c->pb + c->wb * t, &sb, &cb);
  double rx0 = c->dx + c->dvx * t, ry0 = c->dy + c->dvy * t;
  double bx = B->ox[j] * cb - B->oy[j] * sb, by = B->ox[j] * sb + B->oy[j] * cb;
  double ax = A->ox[i] * ca - A->oy[i] * sa, ay = A->ox[i] * sa + A->oy[i] * ca;
  cluster_pair(c, i, j, rx0, ry0, ax, ay, bx, by, h, g, r);
}

/* The gap rate h' = g / r of a pair evaluated by ca_eval (-inf for coincident centres). */
static inline double ca_rate(double g, double r) {
  return r > 0.0 ? g / r : -HUGE_VAL;
}

/* A step over which the gap stays positive: the larger first root of bounds (i) and (ii), for a
 * pair with gap h > 0 and rate h' = g / r (r > 0), written without computing h' (one division
 * fewer): with s = sqrt(g^2 + 2 K h r^2) = r sqrt(h'^2 + 2 K h), the first positive root of
 * h + h' tau - K tau^2 / 2 is 2 h r / (s - g) if g < 0, (g + s) / (r K) otherwise. */
static inline double safe_step(double h, double g, double r, double L, double K) {
  double tl = h / L, tq;
  if (K > 0.0) {
    /* the two forms are equal ((s - g)(s + g) = 2 K h r^2), each free of cancellation on its
     * side; numerator and denominator (finite) are selected by arithmetic with m = 0 or 1, which
     * is exact, so that no branch waits on the sign of g (it varies from pair to pair) */
    double s = sqrt(g * g + 2.0 * K * h * r * r), m = (double)(g < 0.0);
    tq = (m * (2.0 * h * r) + (1.0 - m) * (g + s)) / (m * (s - g) + (1.0 - m) * (r * K));
  } else {
    tq = g < 0.0 ? h * r / (-g) : HUGE_VAL;
  }
  return tl > tq ? tl : tq;
}

/* min(step, safe_step of every pair p in the mask far), pairs 0 .. np - 1.  With SSE2 two
 * pairs go through each instruction: the same operations in the same order on each lane, so the
 * same steps bit for bit as safe_step (a pair's sqrt and two divisions are what a step of a
 * cluster waits on: 9 pairs of linear trimers, 4 of dimers).  h, g, r have room for np + 1. */
static inline double safe_steps(double *h, double *g, double *r, int np, uint64_t far, double L,
                                double K, double step, int *pmin, double *sother_out) {
#if defined(__SSE2__)
  if (np & 1) h[np] = 1.0, g[np] = 0.0, r[np] = 1.0; /* a pad lane, never selected */
  double st[HD_CA_MAXP + 1];
  const __m128d vL = _mm_set1_pd(L), vK = _mm_set1_pd(K), two = _mm_set1_pd(2.0),
                one = _mm_set1_pd(1.0), zero = _mm_setzero_pd();
  for (int p = 0; p < np; p += 2) {
    __m128d vh = _mm_loadu_pd(h + p), vg = _mm_loadu_pd(g + p), vr = _mm_loadu_pd(r + p);
    __m128d tl = _mm_div_pd(vh, vL), tq;
    __m128d neg = _mm_cmplt_pd(vg, zero); /* g < 0 */
    if (K > 0.0) {
      /* s = sqrt(g * g + 2.0 * K * h * r * r), m = (double)(g < 0.0) */
      __m128d sq = _mm_sqrt_pd(_mm_add_pd(
          _mm_mul_pd(vg, vg), _mm_mul_pd(_mm_mul_pd(_mm_mul_pd(_mm_mul_pd(two, vK), vh), vr), vr)));
      __m128d m = _mm_and_pd(neg, one), m1 = _mm_sub_pd(one, m);
      __m128d num = _mm_add_pd(_mm_mul_pd(m, _mm_mul_pd(_mm_mul_pd(two, vh), vr)),
                               _mm_mul_pd(m1, _mm_add_pd(vg, sq)));
      __m128d den =
          _mm_add_pd(_mm_mul_pd(m, _mm_sub_pd(sq, vg)), _mm_mul_pd(m1, _mm_mul_pd(vr, vK)));
      tq = _mm_div_pd(num, den);
    } else {
      /* g < 0 ? h * r / (-g) : HUGE_VAL */
      __m128d q = _mm_div_pd(_mm_mul_pd(vh, vr), _mm_sub_pd(zero, vg));
      tq = _mm_or_pd(_mm_and_pd(neg, q), _mm_andnot_pd(neg, _mm_set1_pd(HUGE_VAL)));
    }
    /* tl > tq ? tl : tq */
    __m128d gt = _mm_cmpgt_pd(tl, tq);
    _mm_storeu_pd(st + p, _mm_or_pd(_mm_and_pd(gt, tl), _mm_andnot_pd(gt, tq)));
  }
#else
  double st[HD_CA_MAXP + 1];
  for (int p = 0; p < np; p++) st[p] = safe_step(h[p], g[p], r[p], L, K);
#endif
  if (pmin) { /* the smallest far step (pair *pmin) and the smallest of the others */
    double sfar = HUGE_VAL, sother = step;
    *pmin = -1;
    for (int p = 0; p < np; p++) {
      if (!((far >> p) & 1u)) continue;
      if (st[p] < sfar) {
        if (sfar < sother) sother = sfar;
        sfar = st[p];
        *pmin = p;
      } else if (st[p] < sother) {
        sother = st[p];
      }
    }
    *sother_out = sother;
    return sfar < step ? sfar : step;
  }
  for (int p = 0; p < np; p++)
    if ((far >> p) & 1u) step = st[p] < step ? st[p] : step;
  return step;
}

/* The earliest time at which the gap of an ignored pair could reach hsep (h'' <= K2u). */
static double sep_step(double h, double hd, double hsep, double hc, double K2u) {
  double d = hsep - h;
  if (d < hc) d = hc;
  double s = sqrt(hd * hd + 2.0 * K2u * d);
  if (hd + s <= 0.0) return HUGE_VAL;
  return 2.0 * d / (hd + s);
}

/* For a touching pair (h <= hc) that is not approaching: a step short enough that rotation
 * (|h''| <= K2u) cannot make it approach faster than 2 vtol before the next look, so that a
 * sliding contact is caught at once instead of sinking in (alpha = 0). */
static double slide_step(double h, double hd, double hc, double vtol, double K2u) {
  if (h > hc || !(K2u > 0.0)) return HUGE_VAL;
  return (hd + 2.0 * vtol) / K2u;
}

/* The step for an ignored pair (h <= hsep, not approaching): the sep_step and slide_step
 * guards, or, if it recedes (h' > 0), the second root tau_hi of bound (ii), if larger: the gap
 * h + h' tau - K tau^2 / 2 > 0 on (tau_lo, tau_hi), tau_lo < 0 or, for an overlap of round-off
 * size, tau_lo ~ -h/h' tiny (the receding just-collided overlap, ignored by design).  This skips
 * the separation to hsep in one step instead of two evaluations. */
static double ign_step(double h, double hd, double hsep, double hc, double vtol, double K,
                       double K2u) {
  double s = sep_step(h, hd, hsep, hc, K2u), sl = slide_step(h, hd, hc, vtol, K2u);
  if (sl < s) s = sl;
  if (hd > 0.0) {
    double disc = hd * hd + 2.0 * K * h, th = HUGE_VAL;
    if (K > 0.0) th = disc > 0.0 ? (hd + sqrt(disc)) / K : 0.0;
    if (th > s) s = th;
  }
  return s;
}

/* Starts a CA at t0 (0, or when the enclosing circles first meet) that ends after tend. */
static void ca_init(hd_ca *s, double t0, double tend) {
  s->t = t0;
  s->tend = tend;
  s->ign = 0;
  s->fresh = 1;
  s->it = 0;
  s->sc0 = 0;
}

/* Newton steps for the gap of candidate pair p (gap hp <= TOL_C D at tp, rate hdp < 0) towards
 * its root, each kept only inside [tp, tlim) and at most tmax, and only while it lowers |h| and
 * the pair still approaches.  Returns the polished time.  one: evaluate pair p alone (clusters:
 * ca_eval_one_general, the same values), else all pairs. */
static double ca_polish(const hd_ca_geom *c, int p, double tp, double hp, double hdp, double tlim,
                        double tmax, int one) {
  for (int k = 0; k < 3 && hp > 0.0; k++) {
    double t1 = tp + hp / (-hdp);
    if (!(t1 < tlim) || !(t1 <= tmax)) break;
    double h1[HD_CA_MAXP + 1], g1[HD_CA_MAXP + 1], r1[HD_CA_MAXP + 1], hd1;
    if (one) {
      ca_eval_one_general(c, t1, p, &h1[p], &g1[p], &r1[p]);
    } else {
      ca_eval(c, t1, h1, g1, r1);
    }
    hd1 = ca_rate(g1[p], r1[p]);
    if (!(fabs(h1[p]) < hp) || !(hd1 < 0.0)) break;
    tp = t1;
    hp = h1[p];
    hdp = hd1;
  }
  return tp;
}

/* Single steps of two clusters: pair p alone limits the step of a search at t, and every other
 * pair (and every ignored one) keeps its gap positive up to tsafe > t + its own step (their
 * bounds (i) and (ii) hold from t on, for any tau).  Then the search goes on with pair p alone,
 * evaluating only it (ca_eval_one_general), up to tsafe: a contact of p before tsafe is the
 * earliest of the bodies.  It stops at a contact of p (polished as in ca_advance, inside
 * [t, tsafe)), at min(tend, tmax) (no contact: 0), when p touches without approaching (sliding:
 * the full step takes it, 2), at tsafe (2), or after HD_CA_SINGLE steps (2; s->t is a lower
 * bound on the contact).  Each single step counts as a step (HD_CA_MAXIT), and the callers'
 * look at a stop request every HD_CA_POLL + 1 steps is kept: it returns under way when the
 * count reaches one. */
#define HD_CA_SINGLE 64
static int ca_single(hd_ca *s, int p, double t, double hp, double gp, double rp, double tsafe,
                     double tmax, double *tout, int *pout) {
  const hd_ca_geom *c = &s->g;
  const double hc = TOL_C * c->D, vtol = VTOL * c->L + HD_DISK_VROUND * c->vs;
  for (int k = 0; k < HD_CA_SINGLE; k++) {
    if (k > 0 && (++s->it > HD_CA_MAXIT || (s->it & HD_CA_POLL) == 0))
      return s->it > HD_CA_MAXIT ? 0 : 2;
    double tn = t + safe_step(hp, gp, rp, c->L, c->K);
    if (!(tn > t)) tn = nextafter(t, HUGE_VAL);
    if (!(tn < tsafe)) {
      tn = tsafe; /* the others' bound: the full step from there */
      s->t = tn;
      return tn <= s->tend && tn <= tmax ? 2 : 0;
    }
    s->t = tn;
    if (!(tn <= s->tend && tn <= tmax)) return 0;
    ca_eval_one_general(c, tn, p, &hp, &gp, &rp);
    t = tn;
    if (hp != hp || gp != gp) return 0; /* NaN state */
    if (hp <= hc) {
      double hd = ca_rate(gp, rp);
      if (!(hd < -vtol)) return 2; /* touching, not approaching: the full step decides */
      *tout = ca_polish(c, p, t, hp, hd, tsafe, tmax, 1);
      *pout = p;
      return 1;
    }
  }
  return 2;
}

/* One CA step: evaluates the pairs at s->t (the pair state at t = 0 is first checked for
 * contacts and just-collided pairs) and advances s->t by the safe step.  Returns 1 and (t, pair
 * index) on a contact, 0 if there is none up to min(tend, tmax), 2 if under way. */
static int ca_advance(hd_ca *s, double tmax, double *tout, int *pout) {
  const hd_ca_geom *c = &s->g;
  const int np = c->na * c->nb;
  const double D = c->D, hc = TOL_C * D, h0 = TOL_0 * D, hsep = TOL_SEP * D;
  const double vtol = VTOL * c->L + HD_DISK_VROUND * c->vs;
  double h[HD_CA_MAXP + 1], g[HD_CA_MAXP + 1], r[HD_CA_MAXP + 1], t = s->t;
  int have = 0; /* h, g, r hold the state at t (from the t = 0 check) */
  uint64_t ign = s->ign;
  if (s->fresh) {
    s->fresh = 0;
    if (t == 0.0) {
      if (s->sc0)
        ca_eval_sc(c, 0.0, s->sa0, s->ca0, h, g, r);
      else
        ca_eval(c, 0.0, h, g, r);
      int best = -1;
      for (int p = 0; p < np; p++) {
        if (!(h[p] <= h0)) continue;
        if (!(ca_rate(g[p], r[p]) < -vtol)) {
          ign |= (uint64_t)1 << p; /* in contact, not approaching: just collided */
        } else if (h[p] <= hc) {
          if (best < 0 || h[p] < h[best]) best = p; /* in contact and approaching: now */
        } /* approaching from a gap above TOL_C D: an ordinary pair for the search, which finds
           * its contact or its miss (rotation may curve it away: it was collided at t = 0) */
      }
      if (best >= 0) {
        *tout = 0.0;
        *pout = best;
        return 1;
      }
      have = 1;
    }
  }
  if (++s->it > HD_CA_MAXIT) return 0;
  if (!have) ca_eval(c, t, h, g, r);
  double step = HUGE_VAL;
  uint64_t cand = 0, far = 0; /* far: pairs with h > hc, not ignored: the safe step */
  for (int p = 0; p < np; p++) {
    uint64_t bit = (uint64_t)1 << p;
    if (h[p] != h[p] || g[p] != g[p]) return 0; /* NaN state */
    if (!(ign & bit) && h[p] > hc) {
      far |= bit;
      continue;
    }
    double hd = ca_rate(g[p], r[p]);
    if (ign & bit) {
      if (hd < -vtol && h[p] <= hc) {
        /* a touching pair that was sliding (|h'| tiny after an alpha = 0 collision) and that
         * rotation now drives into each other: it collides now, before any overlap grows */
        cand |= bit;
        ign &= ~bit;
        continue;
      }
      if (h[p] > hsep || (hd < -vtol && h[p] > hc)) {
        ign &= ~bit;
        far |= bit;
        continue;
      } else if (hd >= -vtol) {
        double st = ign_step(h[p], hd, hsep, hc, vtol, c->K, c->K2u);
        if (st < step) step = st;
        continue;
      }
    }
    /* h <= hc here */
    if (hd < -vtol) {
      cand |= bit;
    } else {
      ign |= bit;
      double st = ign_step(h[p], hd, hsep, hc, vtol, c->K, c->K2u);
      if (st < step) step = st;
    }
  }
  s->ign = ign;
  const int single = c->sha != NULL && !c->wall; /* clusters: single steps */
  int pmin = -1;
  double sother = HUGE_VAL;
  step = safe_steps(h, g, r, np, far, c->L, c->K, step, single ? &pmin : NULL, &sother);
  if (cand) {
    /* polish each candidate by Newton steps inside [t, t + step) and keep the earliest */
    double tbest = HUGE_VAL;
    int pbest = -1;
    for (int p = 0; p < np; p++) {
      if (!((cand >> p) & 1u)) continue;
      double tp = ca_polish(c, p, t, h[p], ca_rate(g[p], r[p]), t + step, tmax, single);
      if (tp < tbest) {
        tbest = tp;
        pbest = p;
      }
    }
    *tout = tbest;
    *pout = pbest;
    return 1;
  }
  /* single steps only when the others' bound lies beyond the full step in floating point too
   * (else a first single step could not move t: review), and not on a step whose count the
   * callers look at for a stop request (ca_single counts on from there) */
  if (pmin >= 0 && t + sother > t + step && (s->it & HD_CA_POLL) != 0)
    return ca_single(s, pmin, t, h[pmin], g[pmin], r[pmin], t + sother, tmax, tout, pout);
  double tn = t + step;
  if (!(tn > t)) tn = nextafter(t, HUGE_VAL);
  s->t = tn;
  return tn <= s->tend && tn <= tmax ? 2 : 0;
}

/* CA from s->t to the end: returns 1 and (t, pair index) on a contact, 0 if none, HD_CA_CUT
 * with *tout = s->t (no contact before it) when a stop was requested during a long search. */
static int ca_solve(hd_ca *s, double tmax, double *tout, int *pout) {
  int r;
  while ((r = ca_advance(s, tmax, tout, pout)) == 2)
    if ((s->it & HD_CA_POLL) == 0 && hd_stop_requested) {
      *tout = s->t;
      return HD_CA_CUT;
    }
  return r;
}

double hd_circle_exit(double c, double b, double v2, double disc) {
  double s = sqrt(disc);
  if (c > 0.0) return (s - b) / v2;
  if (v2 == 0.0) return HUGE_VAL;
  return b <= 0.0 ? (s - b) / v2 : -c / (b + s); /* the positive root, without cancellation */
}

/* The interval [t_in, t_out] in which |d + v t| <= R, intersected with t >= 0. Returns 0 if empty.
 */
static int circle_window(double dx, double dy, double vx, double vy, double R, double *t_in,
                         double *t_out) {
  double c = dx * dx + dy * dy - R * R, b = dx * vx + dy * vy, v2 = vx * vx + vy * vy;
  double disc = b * b - v2 * c;
  if (c <= 0.0) {
    *t_in = 0.0;
    *t_out = hd_circle_exit(c, b, v2, disc);
    return 1;
  }
  if (b >= 0.0) return 0;
  if (!(disc >= 0.0)) return 0;
  *t_in = c / (sqrt(disc) - b);
  *t_out = hd_circle_exit(c, b, v2, disc);
  return 1;
}

void hd_ca_sincos(double x, double *s, double *c) {
  ca_sincos(x, s, c);
}

/* hd_ca_begin for a pair with a general cluster: the same steps over na x nb disk pairs. */
static int ca_begin_general(hd_ca *ca, const hd_kin *A, const hd_shape *sa, const hd_kin *B,
                            const hd_shape *sb, double tmax, const double *sca, const double *win,
                            hd_contact *c) {
  hd_ca_geom *x = &ca->g;
  x->wall = 0;
  x->sha = sa;
  x->shb = sb;
  x->na = sa->n;
  x->nb = sb->n;
  x->dx = B->x - A->x;
  x->dy = B->y - A->y;
  x->dvx = B->vx - A->vx;
  x->dvy = B->vy - A->vy;
  x->ha = sa->rmax;
  x->hb = sb->rmax;
  x->pa = sa->rmax > 0.0 ? A->phi : 0.0;
  x->wa = sa->rmax > 0.0 ? A->omega : 0.0;
  x->pb = sb->rmax > 0.0 ? B->phi : 0.0;
  x->wb = sb->rmax > 0.0 ? B->omega : 0.0;
  x->wsin = 0.0;
  x->wn = 0.0;
  double dmin = HUGE_VAL;
  for (int i = 0; i < x->na; i++)
    for (int j = 0; j < x->nb; j++) {
      double D = 0.5 * (sa->dk[i] + sb->dk[j]);
      dmin = D < dmin ? D : dmin;
    }
  x->D = dmin;
  x->vs = fabs(A->vx) + fabs(A->vy) + fabs(B->vx) + fabs(B->vy) + fabs(x->wa) * x->ha +
          fabs(x->wb) * x->hb;
  if (!(tmax >= 0.0)) return 0;

  if (x->wa * x->ha == 0.0 && x->wb * x->hb == 0.0) {
    /* no rotation: closed form for every disk pair, earliest wins */
    double sa_, ca_, sb_, cb_;
    sincos(x->pa, &sa_, &ca_);
    sincos(x->pb, &sb_, &cb_);
    double best = HUGE_VAL;
    int found = 0;
    for (int i = 0; i < x->na; i++) {
      double ax = sa->ox[i] * ca_ - sa->oy[i] * sa_, ay = sa->ox[i] * sa_ + sa->oy[i] * ca_;
      for (int j = 0; j < x->nb; j++) {
        double bx = sb->ox[j] * cb_ - sb->oy[j] * sb_, by = sb->ox[j] * sb_ + sb->oy[j] * cb_, tc;
        double rx = x->dx + bx - ax, ry = x->dy + by - ay;
        if (hd_predict_disks(rx, ry, x->dvx, x->dvy, 0.5 * (sa->dk[i] + sb->dk[j]), x->vs, tmax,
                             &tc) &&
            tc < best) {
          best = tc;
          c->ka = i;
          c->kb = j;
          found = 1;
        }
      }
    }
    if (found) c->t = best;
    return found;
  }

  /* pre-filter: the enclosing circles must meet */
  double t_in, t_out;
  if (win) {
    t_in = win[0], t_out = win[1];
  } else if (!circle_window(x->dx, x->dy, x->dvx, x->dvy, hd_ca_reach(sa, sb), &t_in, &t_out)) {
    return 0;
  }
  if (t_in > tmax) return 0;
  x->L = sqrt(x->dvx * x->dvx + x->dvy * x->dvy) + fabs(x->wa) * x->ha + fabs(x->wb) * x->hb;
  x->K = x->wa * x->wa * x->ha + x->wb * x->wb * x->hb;
  x->K2u = 2.0 * x->L * x->L / x->D + x->K;
  ca_init(ca, t_in, t_out);
  if (sca && sa->rmax > 0.0) {
    ca->sc0 = 1;
    ca->sa0 = sca[0];
    ca->ca0 = sca[1];
  }
  return 2;
}

double hd_ca_reach(const hd_shape *sa, const hd_shape *sb) {
  if (sa->tag == HD_KIND_BODY || sb->tag == HD_KIND_BODY) {
    double dmax = 0.0;
    for (int i = 0; i < sa->n; i++)
      for (int j = 0; j < sb->n; j++) {
        double D = 0.5 * (sa->dk[i] + sb->dk[j]);
        dmax = D > dmax ? D : dmax;
      }
    return sa->radius + sb->radius + 2.0 * TOL_SEP * dmax;
  }
  return half_a(sa) + half_a(sb) + 0.5 * (sa->d + sb->d) * (1.0 + 2.0 * TOL_SEP);
}

/* hd_ca_begin and hd_ca_begin_in: win is NULL or {t_in, t_out}. */
static int ca_begin(hd_ca *ca, const hd_kin *A, const hd_shape *sa, const hd_kin *B,
                    const hd_shape *sb, double tmax, const double *sca, const double *win,
                    hd_contact *c) {
  if (sa->tag == HD_KIND_BODY || sb->tag == HD_KIND_BODY)
    return ca_begin_general(ca, A, sa, B, sb, tmax, sca, win, c);
  hd_ca_geom *x = &ca->g;
  x->wall = 0;
  x->sha = x->shb = NULL;
  x->na = sa->n;
  x->nb = sb->n;
  x->dx = B->x - A->x;
  x->dy = B->y - A->y;
  x->dvx = B->vx - A->vx;
  x->dvy = B->vy - A->vy;
  x->ha = half_a(sa);
  x->hb = half_a(sb);
  x->pa = x->na == 2 ? A->phi : 0.0;
  x->wa = x->na == 2 ? A->omega : 0.0;
  x->pb = x->nb == 2 ? B->phi : 0.0;
  x->wb = x->nb == 2 ? B->omega : 0.0;
  x->wsin = 0.0;
  x->wn = 0.0;
  x->D = 0.5 * (sa->d + sb->d);
  x->vs = fabs(A->vx) + fabs(A->vy) + fabs(B->vx) + fabs(B->vy) + fabs(x->wa) * x->ha +
          fabs(x->wb) * x->hb;
  if (!(tmax >= 0.0)) return 0;

  if (x->wa * x->ha == 0.0 && x->wb * x->hb == 0.0) {
    /* no rotation: closed form for every disk pair, earliest wins */
    double sa_, ca_, sb_, cb_;
    sincos(x->pa, &sa_, &ca_);
    sincos(x->pb, &sb_, &cb_);
    double best = HUGE_VAL;
    int found = 0;
    for (int i = 0; i < x->na; i++) {
      double ka = x->na == 1 ? 0.0 : disk_sign(i) * x->ha;
      for (int j = 0; j < x->nb; j++) {
        double kb = x->nb == 1 ? 0.0 : disk_sign(j) * x->hb, tc;
        double rx = x->dx + kb * cb_ - ka * ca_, ry = x->dy + kb * sb_ - ka * sa_;
        if (hd_predict_disks(rx, ry, x->dvx, x->dvy, x->D, x->vs, tmax, &tc) && tc < best) {
          best = tc;
          c->ka = i;
          c->kb = j;
          found = 1;
        }
      }
    }
    if (found) c->t = best;
    return found;
  }

  /* pre-filter: the enclosing circles must meet */
  double t_in, t_out;
  if (win) {
    t_in = win[0], t_out = win[1];
  } else if (!circle_window(x->dx, x->dy, x->dvx, x->dvy, hd_ca_reach(sa, sb), &t_in, &t_out)) {
    return 0;
  }
  if (t_in > tmax) return 0;
  x->L = sqrt(x->dvx * x->dvx + x->dvy * x->dvy) + fabs(x->wa) * x->ha + fabs(x->wb) * x->hb;
  x->K = x->wa * x->wa * x->ha + x->wb * x->wb * x->hb;
  x->K2u = 2.0 * x->L * x->L / x->D + x->K;
  ca_init(ca, t_in, t_out);
  if (sca && x->na == 2) {
    ca->sc0 = 1;
    ca->sa0 = sca[0];
    ca->ca0 = sca[1];
  }
  return 2;
}

int hd_ca_begin(hd_ca *ca, const hd_kin *A, const hd_shape *sa, const hd_kin *B, const hd_shape *sb,
                double tmax, const double *sca, hd_contact *c) {
  return ca_begin(ca, A, sa, B, sb, tmax, sca, NULL, c);
}

int hd_ca_begin_in(hd_ca *ca, const hd_kin *A, const hd_shape *sa, const hd_kin *B,
                   const hd_shape *sb, double tmax, const double *sca, double t_in, double t_out,
                   hd_contact *c) {
  const double win[2] = {t_in, t_out};
  return ca_begin(ca, A, sa, B, sb, tmax, sca, win, c);
}

int hd_ca_step(hd_ca *ca, double tmax, hd_contact *c) {
  double tc;
  int p, r = ca_advance(ca, tmax, &tc, &p);
  if (r == 1) {
    c->t = tc;
    c->ka = p / ca->g.nb;
    c->kb = p % ca->g.nb;
  }
  return r;
}

int hd_predict_pair(const hd_kin *A, const hd_shape *sa, const hd_kin *B, const hd_shape *sb,
                    double tmax, hd_contact *c) {
  hd_ca ca;
  int r = hd_ca_begin(&ca, A, sa, B, sb, tmax, NULL, c);
  while (r == 2) {
    r = hd_ca_step(&ca, tmax, c);
    if (r == 2 && (ca.it & HD_CA_POLL) == 0 && hd_stop_requested) {
      c->t = ca.t;
      return HD_CA_CUT;
    }
  }
  return r;
}

/* The rotating part of a wall search (hd_predict_wall): the window where
 * G(t) = x->dx - reach - hsep + x->dvx t <= 0 (the body, reach from its centre at most, can touch
 * the wall only there), then the conservative advancement over x's disks in it.  Returns 1 with
 * *c filled (kb = 0) at the earliest contact in [0, tmax], else 0. */
static int wall_search(const hd_ca_geom *x, double reach, double tmax, hd_contact *c) {
  double hsep = TOL_SEP * x->D, G0 = x->dx - reach - hsep, t_in = 0.0, t_out = HUGE_VAL;
  if (G0 > 0.0) {
    if (!(x->dvx < 0.0)) return 0;
    t_in = G0 / (-x->dvx);
  } else if (x->dvx > 0.0) {
    t_out = -G0 / x->dvx;
  }
  if (t_in > tmax) return 0;
  hd_ca ca;
  double tc;
  int p;
  ca.g = *x;
  ca_init(&ca, t_in, t_out);
  int r = ca_solve(&ca, tmax, &tc, &p);
  if (r == HD_CA_CUT) {
    c->t = tc;
    return r;
  }
  if (!r) return 0;
  c->t = tc;
  c->ka = p;
  c->kb = 0;
  return 1;
}

/* hd_predict_wall for a general cluster. */
static int predict_wall_general(const hd_kin *A, const hd_shape *sa, const hd_wall *w, double tmax,
                                hd_contact *c) {
  hd_ca_geom x = {0};
  x.wall = 1;
  x.sha = sa;
  x.na = sa->n;
  x.nb = 1;
  double yc = w->axis ? A->y : A->x, vy = w->axis ? A->vy : A->vx;
  x.dx = w->normal * (yc - w->pos); /* gap of the centre of mass */
  x.dvx = w->normal * vy;
  x.ha = sa->rmax;
  x.pa = sa->rmax > 0.0 ? A->phi : 0.0;
  x.wa = sa->rmax > 0.0 ? A->omega : 0.0;
  x.wsin = w->axis ? 1.0 : 0.0;
  x.wn = w->normal;
  double dmin = HUGE_VAL;
  for (int i = 0; i < sa->n; i++) dmin = sa->dk[i] < dmin ? sa->dk[i] : dmin;
  x.D = dmin;
  if (!(tmax >= 0.0)) return 0;
  x.L = fabs(x.dvx) + fabs(x.wa) * x.ha;
  x.K = x.wa * x.wa * x.ha;
  x.K2u = x.K;
  x.vs = fabs(A->vx) + fabs(A->vy) + fabs(x.wa) * x.ha;
  const double vtol = VTOL * x.L + HD_DISK_VROUND * x.vs;

  if (x.wa * x.ha == 0.0) {
    double h[HD_MAX_BODY_DISKS], hd[HD_MAX_BODY_DISKS], r[HD_MAX_BODY_DISKS], best = HUGE_VAL;
    int found = 0;
    ca_eval(&x, 0.0, h, hd, r);
    for (int i = 0; i < x.na; i++) {
      double tc;
      if (!(hd[i] < -vtol)) continue;
      tc = h[i] <= TOL_C * x.D ? 0.0 : h[i] / (-hd[i]);
      if (tc <= tmax && tc < best) {
        best = tc;
        c->ka = i;
        found = 1;
      }
    }
    if (found) {
      c->t = best;
      c->kb = 0;
    }
    return found;
  }

  /* pre-filter: the enclosing circle must reach the wall */
  return wall_search(&x, sa->radius, tmax, c);
}

int hd_predict_wall(const hd_kin *A, const hd_shape *sa, const hd_wall *w, double tmax,
                    hd_contact *c) {
  if (sa->tag == HD_KIND_BODY) return predict_wall_general(A, sa, w, tmax, c);
  hd_ca_geom x;
  x.wall = 1;
  x.sha = x.shb = NULL;
  x.na = sa->n;
  x.nb = 1;
  double yc = w->axis ? A->y : A->x, vy = w->axis ? A->vy : A->vx;
  x.dx = w->normal * (yc - w->pos) - 0.5 * sa->d; /* gap of a disk at the centre */
  x.dvx = w->normal * vy;
  x.dy = x.dvy = 0.0;
  x.ha = half_a(sa);
  x.hb = 0.0;
  x.pa = x.na == 2 ? A->phi : 0.0;
  x.wa = x.na == 2 ? A->omega : 0.0;
  x.pb = x.wb = 0.0;
  x.wsin = w->axis ? 1.0 : 0.0;
  x.wn = w->normal;
  x.D = sa->d;
  if (!(tmax >= 0.0)) return 0;
  x.L = fabs(x.dvx) + fabs(x.wa) * x.ha;
  x.K = x.wa * x.wa * x.ha;
  x.K2u = x.K;
  x.vs = fabs(A->vx) + fabs(A->vy) + fabs(x.wa) * x.ha;
  const double vtol = VTOL * x.L + HD_DISK_VROUND * x.vs;

  if (x.wa * x.ha == 0.0) {
    double h[2], hd[2], r[2], best = HUGE_VAL;
    int found = 0;
    ca_eval(&x, 0.0, h, hd, r);
    for (int i = 0; i < x.na; i++) {
      double tc;
      if (h[i] <= TOL_C * x.D) {
        if (!(hd[i] < -vtol)) continue;
        tc = 0.0;
      } else {
        if (!(hd[i] < -vtol)) continue;
        tc = h[i] / (-hd[i]);
      }
      if (tc <= tmax && tc < best) {
        best = tc;
        c->ka = i;
        found = 1;
      }
    }
    if (found) {
      c->t = best;
      c->kb = 0;
    }
    return found;
  }

  /* pre-filter: the body's extreme point (a/2 from the centre) must reach the wall */
  return wall_search(&x, x.ha, tmax, c);
}
