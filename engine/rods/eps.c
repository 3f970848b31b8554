/* hd_eps sampler: one rod collision in the hard-core limit (eqs. 13-14) on a grid aligned with
 * both round-trip times.  See docs/mc-eps.md for the derivation of every step. */
#include "eps.h"

#include <gsl/gsl_randist.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct hd_eps_sampler {
  double gamma_in; /* as requested */
  double gamma;    /* canonical simulated ratio N1/N2 <= 1 */
  int swap;        /* 1 when gamma_in > 1: the caller's rod 1 is our (longer) rod 2 */
  int r;           /* finest grid = coarse step / r */
  int adapt;       /* largest step reduction at small beta (power of 2) */
  int richardson;  /* 1: per-path Richardson with a 4x finer grid */
  long n1, n2;     /* coarse steps per period Gamma_1, Gamma_2 */
  double h;        /* coarse step */
  long period;     /* lcm(n1, n2): q is periodic with this many coarse steps */
  double max_tau;
  hd_eps_opts opts;    /* as given */
  double *b1, *b2;     /* unit-diffusion periodic bridges at the fine step, r*n+1 points */
  double *s1, *s2;     /* ring buffers of the echo sums, r*n each */
  double qmax1, qmax2; /* max of b1, b2 over the fine points */
  hd_eps_stats st;
};

void hd_eps_opts_default(hd_eps_opts *o) {
  o->step = 0.01;
  o->adapt = 16;
  o->richardson = 0;
  o->max_tau = 1e4;
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
  size_t f1 = (size_t)(s->n1 * s->r), f2 = (size_t)(s->n2 * s->r);
  s->b1 = malloc((f1 + 1) * sizeof(double));
  s->b2 = malloc((f2 + 1) * sizeof(double));
  s->s1 = malloc(f1 * sizeof(double));
  s->s2 = malloc(f2 * sizeof(double));
  if (!s->b1 || !s->b2 || !s->s1 || !s->s2) {
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
  free(s);
}

double hd_eps_sampler_gamma(const hd_eps_sampler *s) {
  return s->gamma;
}
double hd_eps_sampler_gamma_in(const hd_eps_sampler *s) {
  return s->gamma_in;
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
static double bridge(double *b, long n, int d, double dt, gsl_rng *rng) {
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
static double solve(hd_eps_sampler *s, int d, double sig1, double sig2, double uph) {
  const long n1 = s->n1 * s->r / d, n2 = s->n2 * s->r / d;
  const double hd = s->h * d / s->r;
  const double *b1 = s->b1, *b2 = s->b2;
  const double qmax = sig1 * s->qmax1 + sig2 * s->qmax2;
  const double gam2 = (double)n2 * hd; /* the longer round trip */
  /* Random level L = Qmax + U * P (P the common period) so that the first-contact point is at
   * a uniformly random phase of the quasi-periodic noise; before k_start, Y_k < L for sure. */
  const double pst = uph * (double)s->period * s->r / d;
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
static void sample_path(hd_eps_sampler *s, int d, double sig1, double sig2, gsl_rng *rng) {
  const double hd = s->h * d / s->r;
  const long f1 = s->n1 * s->r / d, f2 = s->n2 * s->r / d;
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

double hd_eps_sample2(hd_eps_sampler *s, double beta1, double beta2, gsl_rng *rng) {
  double sg1, sg2;
  if (!sigmas(s, beta1, beta2, &sg1, &sg2)) return NAN;
  int d = work_stride(s, sg1, sg2); /* the working (coarse) stride */
  int df = s->richardson ? d / 4 : d;
  sample_path(s, df, sg1, sg2, rng);
  double u = gsl_rng_uniform(rng);
  s->st.samples++;
  double ef = solve(s, df, sg1, sg2, u);
  if (!s->richardson) return ef;
  double ec = solve(s, d, sg1, sg2, u);
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
  int d = work_stride(s, sg1, sg2);
  sample_path(s, d / 4, sg1, sg2, rng);
  double u = gsl_rng_uniform(rng);
  s->st.samples++;
  *fine = solve(s, d / 4, sg1, sg2, u);
  *coarse = solve(s, d, sg1, sg2, u);
  return HD_OK;
}

int hd_eps_sample_strides(hd_eps_sampler *s, double beta1, double beta2, const int *strides, int n,
                          double *out, gsl_rng *rng) {
  double sg1, sg2;
  if (!sigmas(s, beta1, beta2, &sg1, &sg2)) return HD_EINPUT;
  int dmin = s->r;
  for (int m = 0; m < n; m++) {
    if (strides[m] < 1 || s->r % strides[m]) return HD_EINPUT;
    if (strides[m] < dmin) dmin = strides[m];
  }
  for (int m = 0; m < n; m++)
    if (strides[m] % dmin) return HD_EINPUT;
  sample_path(s, dmin, sg1, sg2, rng);
  double u = gsl_rng_uniform(rng);
  s->st.samples++;
  for (int m = 0; m < n; m++) out[m] = solve(s, strides[m], sg1, sg2, u);
  return HD_OK;
}
