/* hd_eps sampler: one rod collision in the hard-core limit (eqs. 13-14) on a grid aligned with
 * both round-trip times.  See docs/mc-eps.md for the derivation of every step. */
#include "eps.h"

#include <gsl/gsl_randist.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The default finest step of the refined sampler (hd_eps_opts.refine; docs/mc-eps.md 2b, 4f);
 * -DHD_EPS_REFINE=... at compile time for a study of the ring at another step. */
#ifndef HD_EPS_REFINE
#define HD_EPS_REFINE (0.01 / 128)
#endif

struct hd_eps_sampler {
  double gamma_in; /* as requested */
  double gamma;    /* canonical simulated ratio N1/N2 <= 1 */
  int swap;        /* 1 when gamma_in > 1: the caller's rod 1 is our (longer) rod 2 */
  int r;           /* working grids: coarse step / r at the finest */
  int lv;          /* refinement levels below the working step (0: plain grid) */
  long f;          /* points of b per coarse step (= r) */
  int adapt;       /* largest step reduction at small beta (power of 2) */
  int richardson;  /* 1: per-path Richardson with a 4x finer grid */
  long n1, n2;     /* coarse steps per period Gamma_1, Gamma_2 */
  double h;        /* coarse step */
  long period;     /* lcm(n1, n2): q is periodic with this many coarse steps */
  double max_tau;
  hd_eps_opts opts;    /* as given */
  double *b1, *b2;     /* unit-diffusion periodic bridges at the fine step, r*n+1 points */
  double *s1, *s2;     /* ring buffers of the echo sums at working points, r*n each */
  double *e1, *e2;     /* refined solver: echo sums inside working cells, minus s1/s2, f*n */
  unsigned *t1, *t2;   /* generation stamp of each cell's row of e1/e2 (r*n each) */
  unsigned gen;        /* current refined solve */
  double *z1, *z2;     /* refined noise inside working cells, 2^lv per cell (NaN: not drawn) */
  unsigned *zt1, *zt2; /* stamp of each value of z1/z2: 16 * pgen + log2(stride) when drawn */
  unsigned pgen;       /* current path */
  long *lo1, *lo2;     /* e1/e2 rows hold values from this offset on (0 below) */
  long *jo;            /* jumps of w inside one working step: offsets and sizes */
  double *jd;
  double qmax1, qmax2; /* max of b1, b2 over the fine points */
  hd_eps_stats st;
};

void hd_eps_opts_default(hd_eps_opts *o) {
  o->step = 0.01;
  o->adapt = 16;
  o->richardson = 0;
  o->max_tau = 1e4;
  o->refine = HD_EPS_REFINE;
}

/* Refinement levels for coarse step h: the least L with h / 2^L <= refine, such that the finest
 * arrays (nmin * r * 2^L points) still fit; 0 when refine is off. */
static int refine_levels(double h, double nmin, int r, double refine) {
  int L = 0;
  if (!(refine > 0)) return 0;
  while (L < 12 && h / (double)(1L << L) > refine * (1 + 1e-9) &&
         nmin * r * (double)(2L << L) <= 5e7)
    L++;
  return L;
}

static long gcd_l(long a, long b) {
  while (b) {
    long t = a % b;
    a = b;
    b = t;
  }
  return a;
}

/* Chooses n1/n2 ~ g (g <= 1) with n2 >= nmin: the last continued-fraction convergent p/q of g
 * with q <= nmin (exact when g is such a fraction), scaled up to n2 >= nmin. */
static void choose_grid(double g, long nmin, long *n1, long *n2) {
  long p0 = 0, q0 = 1, p1 = 1, q1 = 0; /* convergents p_{-2}/q_{-2}, p_{-1}/q_{-1} */
  double x = g;
  long bp = 0, bq = 1;
  for (int it = 0; it < 60; it++) {
    double a = floor(x);
    long p2 = (long)a * p1 + p0, q2 = (long)a * q1 + q0;
    if (q2 > nmin) break;
    bp = p2;
    bq = q2;
    if (fabs((double)p2 / (double)q2 - g) < 1e-13 * g) break;
    double fr = x - a;
    if (fr < 1e-15) break;
    x = 1.0 / fr;
    p0 = p1;
    q0 = q1;
    p1 = p2;
    q1 = q2;
  }
  if (bp == 0) { /* g < 1/nmin: take the nearest p/nmin */
    bq = nmin;
    bp = lround(g * (double)nmin);
    if (bp < 1) bp = 1;
  }
  long m = (nmin + bq - 1) / bq;
  *n1 = bp * m;
  *n2 = bq * m;
}

int hd_eps_grid_fits(double gamma, const hd_eps_opts *o) {
  double g = gamma > 1 ? 1.0 / gamma : gamma;
  double nmin = (1.0 + 1.0 / g) / o->step, r = o->adapt * (o->richardson ? 4 : 1);
  /* in doubles first: 1e-300 overflowed the cast */
  return nmin * r <= 5e7 && ceil(nmin - 1e-9) * r <= 5e7;
}

int hd_eps_sampler_alloc(hd_eps_sampler **out, double gamma, const hd_eps_opts *opts,
                         hd_error *err) {
  hd_eps_opts o;
  if (opts)
    o = *opts;
  else
    hd_eps_opts_default(&o);
  *out = NULL;
  if (!(gamma > 0) || !isfinite(gamma))
    return hd_error_set(err, HD_EINPUT, "eps: gamma must be a positive number (got %g)", gamma);
  if (!(o.step > 0) || o.step > 0.5)
    return hd_error_set(err, HD_EINPUT, "eps: step must be in (0, 0.5] (got %g)", o.step);
  if (o.adapt < 1 || o.adapt > 1024 || (o.adapt & (o.adapt - 1)))
    return hd_error_set(err, HD_EINPUT, "eps: adapt must be a power of 2 in 1..1024 (got %d)",
                        o.adapt);
  if (!(o.refine >= 0) || !isfinite(o.refine))
    return hd_error_set(err, HD_EINPUT, "eps: refine must be >= 0 (got %g)", o.refine);
  if (!(o.max_tau > 10))
    return hd_error_set(err, HD_EINPUT, "eps: max_tau must exceed 10 (got %g)", o.max_tau);
  double g = gamma > 1 ? 1.0 / gamma : gamma;
  double gam2 = 1.0 + 1.0 / g;
  int r = o.adapt * (o.richardson ? 4 : 1);
  if (!hd_eps_grid_fits(gamma, &o))
    return hd_error_set(err, HD_EINPUT, "eps: step %g too small for gamma %g", o.step, gamma);
  long nmin = (long)ceil(gam2 / o.step - 1e-9);
  hd_eps_sampler *s = calloc(1, sizeof *s);
  if (!s) return hd_error_set(err, HD_ENOMEM, "eps: out of memory");
  s->gamma_in = gamma;
  s->swap = gamma > 1;
  s->r = r;
  s->adapt = o.adapt;
  s->richardson = o.richardson != 0;
  s->max_tau = o.max_tau;
  s->opts = o;
  choose_grid(g, nmin, &s->n1, &s->n2);
  s->gamma = (double)s->n1 / (double)s->n2;
  s->h = (1.0 + 1.0 / s->gamma) / (double)s->n2;
  s->period = s->n1 / gcd_l(s->n1, s->n2) * s->n2;
  /* per-path Richardson combines two plain grids: no refinement with it */
  s->lv = s->richardson ? 0 : refine_levels(s->h, (double)s->n2, r, o.refine);
  s->f = r;
  size_t r1 = (size_t)(s->n1 * s->r), r2 = (size_t)(s->n2 * s->r);
  size_t f1 = r1, f2 = r2, z1 = r1 << s->lv, z2 = r2 << s->lv;
  s->b1 = malloc((f1 + 1) * sizeof(double));
  s->b2 = malloc((f2 + 1) * sizeof(double));
  s->s1 = malloc(r1 * sizeof(double));
  s->s2 = malloc(r2 * sizeof(double));
  int bad = !s->b1 || !s->b2 || !s->s1 || !s->s2;
  if (!bad && s->lv > 0) {
    s->e1 = malloc(z1 * sizeof(double));
    s->e2 = malloc(z2 * sizeof(double));
    s->t1 = calloc(r1, sizeof(unsigned));
    s->t2 = calloc(r2, sizeof(unsigned));
    s->z1 = malloc(z1 * sizeof(double));
    s->z2 = malloc(z2 * sizeof(double));
    s->zt1 = calloc(z1, sizeof(unsigned));
    s->zt2 = calloc(z2, sizeof(unsigned));
    s->lo1 = calloc(r1, sizeof(long));
    s->lo2 = calloc(r2, sizeof(long));
    s->jo = malloc(((size_t)1 << s->lv) * sizeof(long));
    s->jd = malloc(((size_t)1 << s->lv) * sizeof(double));
    bad = !s->e1 || !s->e2 || !s->t1 || !s->t2 || !s->z1 || !s->z2 || !s->zt1 || !s->zt2 ||
          !s->lo1 || !s->lo2 || !s->jo || !s->jd;
  }
  if (bad) {
    hd_eps_sampler_free(s);
    return hd_error_set(err, HD_ENOMEM, "eps: out of memory");
  }
  *out = s;
  return HD_OK;
}

void hd_eps_sampler_free(hd_eps_sampler *s) {
  if (!s) return;
  free(s->b1);
  free(s->b2);
  free(s->s1);
  free(s->s2);
  free(s->e1);
  free(s->e2);
  free(s->t1);
  free(s->t2);
  free(s->z1);
  free(s->z2);
  free(s->zt1);
  free(s->zt2);
  free(s->lo1);
  free(s->lo2);
  free(s->jo);
  free(s->jd);
  free(s);
}

double hd_eps_sampler_gamma(const hd_eps_sampler *s) {
  return s->gamma;
}
double hd_eps_sampler_gamma_in(const hd_eps_sampler *s) {
  return s->gamma_in;
}
int hd_eps_sampler_levels(const hd_eps_sampler *s) {
  return s->lv;
}
double hd_eps_sampler_step(const hd_eps_sampler *s) {
  return s->h;
}
void hd_eps_sampler_opts(const hd_eps_sampler *s, hd_eps_opts *opts) {
  *opts = s->opts;
}
void hd_eps_sampler_stats(const hd_eps_sampler *s, hd_eps_stats *st) {
  *st = s->st;
}

/* A periodic Brownian bridge of unit diffusion at n+1 points of step dt (b[0] = b[n] = 0);
 * returns its maximum.  The zero-mean condition of the paper only shifts q by a constant, which
 * moves the first contact and cancels (docs/mc-eps.md), so it is not applied. */
static double bridge(double *b, long n, long d, double dt, gsl_rng *rng) {
  double sd = sqrt(dt), x = 0;
  b[0] = 0;
  for (long j = 1; j <= n; j++) {
    x += sd * gsl_ran_gaussian_ziggurat(rng, 1.0);
    b[j * d] = x;
  }
  double mx = 0, end = b[n * d];
  for (long j = 1; j <= n; j++) {
    b[j * d] -= end * (double)j / (double)n;
    if (b[j * d] > mx) mx = b[j * d];
  }
  return mx;
}

/* Solves one collision on the current path at stride d (grid step d*h/r), noise amplitudes
 * sig1, sig2, random phase uph in [0,1).  Returns eps = W - 1. */
static double solve(hd_eps_sampler *s, long d, double sig1, double sig2, double uph) {
  const long n1 = s->n1 * s->f / d, n2 = s->n2 * s->f / d;
  const double hd = s->h * (double)d / (double)s->f;
  const double *b1 = s->b1, *b2 = s->b2;
  const double qmax = sig1 * s->qmax1 + sig2 * s->qmax2;
  const double gam2 = (double)n2 * hd; /* the longer round trip */
  /* Random level L = Qmax + U * P (P the common period) so that the first-contact point is at
   * a uniformly random phase of the quasi-periodic noise; before k_start, Y_k < L for sure. */
  const double pst = uph * (double)s->period * (double)s->f / (double)d;
  const long kstart = (long)floor(pst);
  const double thr = qmax + (pst - (double)kstart) * hd;
  long j1 = kstart % n1, j2 = kstart % n2;
  long t = 0;
  double q;
  for (;; t++) {
    q = sig1 * b1[j1 * d] + sig2 * b2[j2 * d];
    if ((double)t * hd + q >= thr) break;
    if (++j1 == n1) j1 = 0;
    if (++j2 == n2) j2 = 0;
  }
  /* contact at this grid point: h = 0, w = 0 (the level is snapped to this discrete record) */
  const double q0 = q;
  double *S1 = s->s1, *S2 = s->s2;
  memset(S1, 0, (size_t)n1 * sizeof(double));
  memset(S2, 0, (size_t)n2 * sizeof(double));
  const long tmax = (long)(s->max_tau / hd);
  double w = 0, A = 0;
  long stop = -1;
  for (t = 0;; t++) {
    q = sig1 * b1[j1 * d] + sig2 * b2[j2 * d];
    double m1 = S1[j1], m2 = S2[j2];
    double g = (double)t * hd + q - q0 - m1 - m2;
    if (g > w) w = g;
    S1[j1] = w + m1;
    S2[j2] = w + m2;
    A += w;
    if (stop < 0) {
      /* Stopping rule (docs/mc-eps.md): for every later step k >= t + n2 the memory is at least
       * hd*A + W*(k-t)*hd - 2W, so g_k <= W for all of them once this holds. */
      if ((t & 31) == 0 && w > 1 && (double)t * hd + gam2 + qmax - q0 - hd * A - w * gam2 + w <= 0)
        stop = t + n2;
    } else if (t >= stop) {
      break;
    }
    if (t >= tmax) {
      s->st.truncated++;
      break;
    }
    if (++j1 == n1) j1 = 0;
    if (++j2 == n2) j2 = 0;
  }
  s->st.steps += (double)t;
  return w - 1.0;
}

/* Samples the bridges for noise amplitudes sig1, sig2 (canonical rods) at stride d of the
 * finest grid (only the points j*d are written). */
static void sample_path(hd_eps_sampler *s, long d, double sig1, double sig2, gsl_rng *rng) {
  const double hd = s->h * (double)d / (double)s->f;
  const long f1 = s->n1 * s->f / d, f2 = s->n2 * s->f / d;
  if (s->lv > 0 && ++s->pgen >= (1u << 27)) { /* stamps about to wrap: forget every value */
    memset(s->zt1, 0, ((size_t)(s->n1 * s->r) << s->lv) * sizeof(unsigned));
    memset(s->zt2, 0, ((size_t)(s->n2 * s->r) << s->lv) * sizeof(unsigned));
    s->pgen = 1;
  }
  if (sig1 > 0)
    s->qmax1 = bridge(s->b1, f1, d, hd, rng);
  else {
    for (long j = 0; j <= f1; j++) s->b1[j * d] = 0;
    s->qmax1 = 0;
  }
  if (sig2 > 0)
    s->qmax2 = bridge(s->b2, f2, d, hd, rng);
  else {
    for (long j = 0; j <= f2; j++) s->b2[j * d] = 0;
    s->qmax2 = 0;
  }
}

/* The stride of the working grid for noise amplitudes sig1, sig2: the step is halved for each
 * halving of beta_eff = 1/(sig1^2 + sig2^2) below 1, down to step/adapt. */
static int work_stride(const hd_eps_sampler *s, double sig1, double sig2) {
  double v = sig1 * sig1 + sig2 * sig2; /* = 1/beta for equal temperatures */
  int d = s->r;
  double b = 1.0 / v;
  for (int m = s->adapt; m > 1 && b < 1.0; m >>= 1, b *= 2.0) d >>= 1;
  return d;
}

/* sigma of one rod from its beta; -1 on a bad beta. */
static double sigma_of(double beta) {
  if (isnan(beta) || !(beta > 0)) return -1;
  if (isinf(beta)) return 0;
  return sqrt(0.5 / beta);
}

/* Canonical (shorter rod first) sigmas; returns 0 on bad input. */
static int sigmas(const hd_eps_sampler *s, double beta1, double beta2, double *sg1, double *sg2) {
  double a = sigma_of(beta1), b = sigma_of(beta2);
  if (a < 0 || b < 0) return 0;
  *sg1 = s->swap ? b : a;
  *sg2 = s->swap ? a : b;
  return 1;
}

/* ---- the refined solver (docs/mc-eps.md section 2b) ---- */

/* ln(1/p)/2 for the refinement threshold p: an interval is left unrefined when the probability
 * that the bound of g over it (a Brownian bridge) crosses the record is below p (-DHD_EPS_KE=...
 * for a study: docs/mc-eps.md 4f). */
#ifndef HD_EPS_KE
#define HD_EPS_KE 3.45 /* p = 1e-3 */
#endif

/* State of one refined solve. Offsets inside the current working step are in units u (finest
 * points) = d >> lev, nsub = 2^lev of them per step. */
typedef struct rctx {
  hd_eps_sampler *s;
  gsl_rng *rng;
  double sig1, sig2, v; /* noise amplitudes, v = sig1^2 + sig2^2 */
  long u, nsub;
  double hu;             /* tau per offset unit */
  double ke;             /* refinement threshold (HD_EPS_KE) */
  unsigned zst;          /* stamp of this path and stride */
  long j1, j2, d;        /* the current cells, and the working stride */
  int sh;                /* row index = offset << sh */
  long pabs;             /* position of the current step's left point in offset units (origin 0) */
  double t0;             /* tau of the current step's left point (loop origin 0) */
  double vc;             /* contact: g = V - vc - M with V = tau + q */
  double w, wcap;        /* record, and its exact upper bound (the period of q) */
  const double *x1, *x2; /* e1/e2 rows of the current cells, NULL when empty */
  long xl1, xl2;         /* their first nonzero offsets */
  double m0;             /* s1 + s2 of the current cells */
  long nj;               /* jumps of w inside the current step */
  long force[3];     /* finest positions that are always drawn: contact + Gamma1, + Gamma2, + P */
  long thr_o;        /* search: offset found */
  double thr, thr_v; /* search: level, and V at the point found */
} rctx;

/* The noise of component comp at index k of working cell j's row, the midpoint of neighbours
 * with values ba, bb: drawn as a Brownian bridge's on first use on this path at this stride
 * (stamp st) and kept for the rest of the path. */
static double reveal(hd_eps_sampler *s, int comp, long j, long k, unsigned st, double ba, double bb,
                     double sd, gsl_rng *rng) {
  long i = (j << s->lv) + k;
  double *z = comp == 1 ? s->z1 : s->z2;
  unsigned *t = comp == 1 ? s->zt1 : s->zt2;
  if (t[i] == st) return z[i];
  double x = 0.5 * (ba + bb) + sd * gsl_ran_gaussian_ziggurat(rng, 1.0);
  z[i] = x;
  t[i] = st;
  s->st.refined++;
  return x;
}

/* Midpoint m of the offsets (o, o + ln): both components drawn, returns V = tau + q there. */
static double mid(rctx *c, long m, long ln, double a1, double b1, double a2, double b2, double *m1,
                  double *m2) {
  double sd = 0.5 * sqrt((double)ln * c->hu); /* a bridge's midpoint: variance len / 4 */
  *m1 = c->sig1 > 0 ? reveal(c->s, 1, c->j1, m << c->sh, c->zst, a1, b1, sd, c->rng) : 0;
  *m2 = c->sig2 > 0 ? reveal(c->s, 2, c->j2, m << c->sh, c->zst, a2, b2, sd, c->rng) : 0;
  return c->t0 + (double)m * c->hu + c->sig1 * *m1 + c->sig2 * *m2;
}

static int forced_in(const rctx *c, long o, long ln) {
  long a = c->pabs + o, b = a + ln;
  for (int k = 0; k < 3; k++)
    if (c->force[k] > a && c->force[k] < b) return 1;
  return 0;
}

/* Whether the bound of g (or V) over (o, o+ln), a Brownian bridge from A to B of diffusion v,
 * may cross level x with probability above the threshold. */
static int may_cross(const rctx *c, long ln, double A, double B, double x) {
  if (B >= x) return 1;
  if (c->v <= 0) return 0;
  return (x - A) * (x - B) < c->ke * c->v * (double)ln * c->hu;
}

/* The inside of (o, o+ln) after contact, its left point done (w includes it): refines where the
 * bound V - vc - M(o) of g (M, the echo sum, is nondecreasing) may cross w. */
static void interval(rctx *c, long o, long ln, double a1, double b1, double a2, double b2,
                     double va, double vb, double ma) {
  if (ln < 2) return;
  if (!may_cross(c, ln, va - c->vc - ma, vb - c->vc - ma, c->w) && !forced_in(c, o, ln)) return;
  long h2 = ln / 2, m = o + h2;
  double m1, m2, vm = mid(c, m, ln, a1, b1, a2, b2, &m1, &m2);
  double mm = c->m0 + (c->x1 && m >= c->xl1 ? c->x1[m] : 0) + (c->x2 && m >= c->xl2 ? c->x2[m] : 0);
  interval(c, o, h2, a1, m1, a2, m2, va, vm, ma);
  double g = vm - c->vc - mm;
  if (g > c->wcap) g = c->wcap;
  if (g > c->w) {
    c->s->jo[c->nj] = m;
    c->s->jd[c->nj++] = g - c->w;
    c->w = g;
  }
  interval(c, m, h2, m1, b1, m2, b2, vm, vb, mm);
}

/* Before contact: the first offset in (o, o+ln] with V >= thr (refining where the bridge may
 * cross it), or -1; sets thr_o and thr_v. */
static long search(rctx *c, long o, long ln, double a1, double b1, double a2, double b2, double va,
                   double vb) {
  if (ln == 1 || !may_cross(c, ln, va, vb, c->thr)) {
    if (vb < c->thr) return -1;
    c->thr_o = o + ln;
    c->thr_v = vb;
    return c->thr_o;
  }
  long h2 = ln / 2, m = o + h2;
  double m1, m2, vm = mid(c, m, ln, a1, b1, a2, b2, &m1, &m2);
  if (search(c, o, h2, a1, m1, a2, m2, va, vm) >= 0) return c->thr_o;
  return search(c, m, h2, m1, b1, m2, b2, vm, vb);
}

/* Adds the step function of w's jumps inside the current step (offsets jo, sizes jd, nj of
 * them, increasing) to the e row of working cell j of component comp. */
static void eadd(hd_eps_sampler *s, int comp, long j, long nsub, long nj) {
  double *row = (comp == 1 ? s->e1 : s->e2) + j * nsub;
  unsigned *t = comp == 1 ? s->t1 : s->t2;
  long *lo = comp == 1 ? s->lo1 : s->lo2, o0 = s->jo[0];
  if (t[j] != s->gen) { /* a row not yet used by this solve: it starts at o0 */
    t[j] = s->gen;
    lo[j] = nsub;
  }
  for (long o = o0; o < lo[j]; o++) row[o] = 0;
  if (o0 < lo[j]) lo[j] = o0;
  double cum = 0;
  long q = 0;
  for (long o = o0; o < nsub; o++) {
    while (q < nj && s->jo[q] == o) cum += s->jd[q++];
    row[o] += cum;
  }
}

/* One collision on the current path with working stride d (finest units) refined lev levels
 * below it (docs/mc-eps.md section 2b).  Returns eps = W - 1. */
static double solve_refined(hd_eps_sampler *s, long d, int lev, double sig1, double sig2,
                            double uph, gsl_rng *rng) {
  const long n1 = s->n1 * s->f / d, n2 = s->n2 * s->f / d, nsub = 1L << lev;
  const double hd = s->h * (double)d / (double)s->f;
  const double *B1 = s->b1, *B2 = s->b2;
  const double qmax = sig1 * s->qmax1 + sig2 * s->qmax2;
  const double gam2 = (double)n2 * hd;
  rctx c = {.s = s,
            .rng = rng,
            .sig1 = sig1,
            .sig2 = sig2,
            .v = sig1 * sig1 + sig2 * sig2,
            .d = d,
            .sh = s->lv - lev,
            .nsub = nsub,
            .hu = hd / (double)nsub,
            .ke = HD_EPS_KE};
  c.zst = 16 * s->pgen + (unsigned)log2((double)d);
  if (++s->gen == 0) { /* wrapped: forget every row */
    memset(s->t1, 0, (size_t)(s->n1 * s->r) * sizeof(unsigned));
    memset(s->t2, 0, (size_t)(s->n2 * s->r) * sizeof(unsigned));
    s->gen = 1;
  }
  /* the same random level as solve(); the scan starts early enough that no point between the
   * working points before it can reach the level (6 sd of a bridge above the grid's max) */
  const double pst = uph * (double)s->period * (double)s->f / (double)d;
  const long kstart = (long)floor(pst);
  const long early = (long)ceil(6 * sqrt(c.v / hd)) + 1;
  c.thr = qmax + (pst - (double)kstart) * hd;
  long k = kstart - early;
  long j1 = ((k % n1) + n1) % n1, j2 = ((k % n2) + n2) % n2;
  double va = (double)(k - kstart) * hd + sig1 * B1[j1 * d] + sig2 * B2[j2 * d];
  long found = -1;
  for (;;) {
    long i1 = j1 + 1 == n1 ? 0 : j1 + 1, i2 = j2 + 1 == n2 ? 0 : j2 + 1;
    double a1 = B1[j1 * d], a2 = B2[j2 * d], b1 = B1[(j1 + 1) * d], b2 = B2[(j2 + 1) * d];
    double vb = (double)(k + 1 - kstart) * hd + sig1 * b1 + sig2 * b2;
    if (vb >= c.thr || may_cross(&c, nsub, va, vb, c.thr)) {
      c.j1 = j1;
      c.j2 = j2;
      c.t0 = (double)(k - kstart) * hd;
      found = search(&c, 0, nsub, a1, b1, a2, b2, va, vb);
      if (found >= 0) break;
    }
    va = vb;
    j1 = i1;
    j2 = i2;
    k++;
  }
  /* the loop starts at the working point k before the contact (offset found, V = thr_v): every
   * drawn point before the contact has V < thr <= vc, i.e. g < 0 and w stays 0 there */
  const double tc = (double)found * c.hu, qc = c.thr_v - (double)(k - kstart) * hd - tc;
  c.vc = tc + qc; /* V relative to the loop's origin */
  const long pc = found;
  c.force[0] = pc + n1 * nsub;
  c.force[1] = pc + n2 * nsub;
  c.force[2] = pc + s->period * s->f / d * nsub;
  c.wcap = sig1 > 0 && sig2 > 0 ? (double)s->period * s->h
           : sig2 > 0           ? (double)s->n2 * s->h
                                : (double)s->n1 * s->h;
  double *S1 = s->s1, *S2 = s->s2;
  memset(S1, 0, (size_t)n1 * sizeof(double));
  memset(S2, 0, (size_t)n2 * sizeof(double));
  const long tmax = (long)(s->max_tau / hd) + 1;
  const double qm = qmax + 6 * sqrt(c.v * hd); /* q anywhere, bar 6 sd of a bridge */
  double w = 0, A = 0, vcur = (double)0 + sig1 * B1[j1 * d] + sig2 * B2[j2 * d];
  long stop = -1, t;
  c.w = 0;
  for (t = 0;; t++) {
    long i1 = j1 + 1 == n1 ? 0 : j1 + 1, i2 = j2 + 1 == n2 ? 0 : j2 + 1;
    double a1 = B1[j1 * d], a2 = B2[j2 * d], b1 = B1[(j1 + 1) * d], b2 = B2[(j2 + 1) * d];
    double vb = (double)(t + 1) * hd + sig1 * b1 + sig2 * b2;
    double m0 = S1[j1] + S2[j2];
    const double wt = w; /* w at this working point */
    c.nj = 0;
    c.w = w;
    c.j1 = j1;
    c.j2 = j2;
    c.pabs = t * nsub;
    c.t0 = (double)t * hd;
    c.m0 = m0;
    c.x1 = s->t1[j1] == s->gen ? s->e1 + j1 * nsub : NULL;
    c.x2 = s->t2[j2] == s->gen ? s->e2 + j2 * nsub : NULL;
    c.xl1 = s->lo1[j1];
    c.xl2 = s->lo2[j2];
    interval(&c, 0, nsub, a1, b1, a2, b2, vcur, vb, m0);
    w = c.w;
    /* the echo sums of this cell take w over the whole step: wt, plus its jumps inside */
    S1[j1] += wt;
    S2[j2] += wt;
    if (c.nj) {
      eadd(s, 1, j1, nsub, c.nj);
      eadd(s, 2, j2, nsub, c.nj);
    }
    A += wt;
    /* the next working point */
    double g = vb - c.vc - S1[i1] - S2[i2];
    if (g > c.wcap) g = c.wcap;
    if (g > w) w = g;
    vcur = vb;
    j1 = i1;
    j2 = i2;
    if (stop < 0) {
      /* section 2's stopping rule from working point t+1, with margins for the points between
       * working points: q <= qm, the echo sum at least its value at the step's start */
      double tk = (double)(t + 1) * hd - tc;
      if (((t + 1) & 31) == 0 && w > 1 &&
          tk + gam2 + qm - qc - hd * (A + w) - w * gam2 + w + w * hd <= 0)
        stop = t + 1 + n2;
    } else if (t + 1 >= stop) {
      break;
    }
    if (t >= tmax) {
      s->st.truncated++;
      break;
    }
  }
  s->st.steps += (double)t;
  return w - 1.0;
}

/* One solve: the plain grid at lev = 0, else refined. */
static double solve_at(hd_eps_sampler *s, long d, int lev, double sig1, double sig2, double uph,
                       gsl_rng *rng) {
  if (lev <= 0) return solve(s, d, sig1, sig2, uph);
  return solve_refined(s, d, lev, sig1, sig2, uph, rng);
}

double hd_eps_sample2(hd_eps_sampler *s, double beta1, double beta2, gsl_rng *rng) {
  double sg1, sg2;
  if (!sigmas(s, beta1, beta2, &sg1, &sg2)) return NAN;
  long d = work_stride(s, sg1, sg2); /* the working (coarse) stride */
  long df = s->richardson ? d / 4 : d;
  sample_path(s, df, sg1, sg2, rng);
  double u = gsl_rng_uniform(rng);
  s->st.samples++;
  double ef = solve_at(s, df, s->lv, sg1, sg2, u, rng);
  if (!s->richardson) return ef;
  double ec = solve_at(s, d, s->lv, sg1, sg2, u, rng);
  double e = 2.0 * ef - ec; /* error ~ c sqrt(step): eps_f + (eps_f - eps_c)/(sqrt(4) - 1) */
  if (e < 0) {
    s->st.clamped++;
    e = 0;
  }
  return e;
}

double hd_eps_sample(hd_eps_sampler *s, double beta, gsl_rng *rng) {
  return hd_eps_sample2(s, beta, beta, rng);
}

int hd_eps_sample_pair(hd_eps_sampler *s, double beta1, double beta2, double *coarse, double *fine,
                       gsl_rng *rng) {
  double sg1, sg2;
  if (!s->richardson || !sigmas(s, beta1, beta2, &sg1, &sg2)) return HD_EINPUT;
  long d = work_stride(s, sg1, sg2);
  sample_path(s, d / 4, sg1, sg2, rng);
  double u = gsl_rng_uniform(rng);
  s->st.samples++;
  *fine = solve_at(s, d / 4, s->lv, sg1, sg2, u, rng);
  *coarse = solve_at(s, d, s->lv, sg1, sg2, u, rng);
  return HD_OK;
}

int hd_eps_sample_levels(hd_eps_sampler *s, double beta1, double beta2, const int *strides,
                         const int *levels, int n, double *out, gsl_rng *rng) {
  double sg1, sg2;
  if (!sigmas(s, beta1, beta2, &sg1, &sg2)) return HD_EINPUT;
  int dmin = s->r;
  for (int m = 0; m < n; m++) {
    if (strides[m] < 1 || s->r % strides[m]) return HD_EINPUT;
    if (levels && (levels[m] < 0 || levels[m] > s->lv)) return HD_EINPUT;
    if (strides[m] < dmin) dmin = strides[m];
  }
  for (int m = 0; m < n; m++)
    if (strides[m] % dmin) return HD_EINPUT;
  sample_path(s, dmin, sg1, sg2, rng);
  double u = gsl_rng_uniform(rng);
  s->st.samples++;
  for (int m = 0; m < n; m++)
    out[m] = solve_at(s, strides[m], levels ? levels[m] : 0, sg1, sg2, u, rng);
  return HD_OK;
}

int hd_eps_sample_strides(hd_eps_sampler *s, double beta1, double beta2, const int *strides, int n,
                          double *out, gsl_rng *rng) {
  return hd_eps_sample_levels(s, beta1, beta2, strides, NULL, n, out, rng);
}
