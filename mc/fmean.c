/* fmean: geometry, quadrature and Monte Carlo sampling of <f> (see fmean.h). */
#include "fmean.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_math.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fmean_stats.h"
#include "hd_body_impulse.h"

/* Samples per batch: statistics are taken per batch with gsl_stats and merged exactly. */
#define BATCH 4096

const char *hd_fmean_model_name(hd_fmean_model model) {
  switch (model) {
  case HD_FMEAN_HEURISTIC:
    return "heuristic";
  case HD_FMEAN_EXCLUSION:
    return "exclusion";
  case HD_FMEAN_COLLISION:
    return "collision";
  }
  return "?";
}

void hd_fmean_opts_default(hd_fmean_opts *opts) {
  memset(opts, 0, sizeof *opts);
  opts->model = HD_FMEAN_HEURISTIC;
  opts->a_over_d = 1.0;
  opts->dim = 2.0;
  opts->samples = 1000000UL;
  opts->seconds = 0.0;
  opts->seed = 1UL;
  opts->no_partner_partner = 0;
}

double hd_fmean_theta_max(double a_over_d) {
  if (!(a_over_d > 0.0)) return NAN;
  if (a_over_d >= 2.0) return M_PI;
  return M_PI - acos(0.5 * a_over_d);
}

double hd_fmean_f(double th1, double th2) {
  double c1 = cos(th1), c2 = cos(th2);
  return 1.0 / (2.0 - 0.5 * (c1 * c1 + c2 * c2));
}

/* ---- quadrature --------------------------------------------------------------------------- */

/* Parameters of the outer integrand. */
typedef struct quad_par {
  double theta_max; /* upper limit of both angles */
} quad_par;

/* Inner integral over theta_2 in [0, tm] of f = 2 / (p - cos^2 theta_2), p = 4 - cos^2 theta_1:
 * with t = tan theta, int dtheta / (p - cos^2) = atan(k tan theta) / sqrt(p (p-1)),
 * k = sqrt(p / (p-1)); atan2(k sin, cos) is its continuous branch on [0, pi]. */
static double quad_outer(double th1, void *vp) {
  const quad_par *qp = vp;
  double c = cos(th1);
  double p = 4.0 - c * c;
  double k = sqrt(p / (p - 1.0));
  double tm = qp->theta_max;
  return 2.0 * atan2(k * sin(tm), cos(tm)) / sqrt(p * (p - 1.0));
}

int hd_fmean_quadrature(double a_over_d, double *f, double *abserr) {
  double tm = hd_fmean_theta_max(a_over_d);
  if (!(tm > 0.0) || !isfinite(a_over_d)) return HD_EINPUT;
  gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
  if (!w) return HD_ENOMEM;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  quad_par qp = {tm};
  gsl_function F = {quad_outer, &qp};
  double val = 0.0, err = 0.0;
  /* The integrand is even in both angles: average over [0, tm]^2. */
  int st = gsl_integration_qag(&F, 0.0, tm, 0.0, 1e-12, 1000, GSL_INTEG_GAUSS61, w, &val, &err);
  gsl_set_error_handler(old);
  gsl_integration_workspace_free(w);
  if (st) return HD_EPHYS;
  *f = val / (tm * tm);
  *abserr = err / (tm * tm);
  return HD_OK;
}

/* ---- configurations ----------------------------------------------------------------------- */

/* The angle x wrapped into (-pi, pi]. */
static double wrap_angle(double x) {
  double y = fmod(x + M_PI, 2.0 * M_PI); /* in (-2pi, 2pi) */
  if (y <= 0.0) y += 2.0 * M_PI;         /* (0, 2pi] */
  return y - M_PI;
}

int hd_fmean_sample_contact(gsl_rng *rng, double a_over_d, int no_partner_partner, double *th_a,
                            double *th_b, double cfg[2]) {
  const double a = a_over_d; /* lengths in units of d */
  /* A: contacting disk A1 at the origin, outward axis +x, partner A2 at (-a, 0). */
  double psi = 2.0 * M_PI * gsl_rng_uniform(rng) - M_PI;  /* contact normal A1 -> B1 */
  double phib = 2.0 * M_PI * gsl_rng_uniform(rng) - M_PI; /* B's outward axis at B1 */
  double nx = cos(psi), ny = sin(psi);
  double ux = cos(phib), uy = sin(phib);
  double b1x = nx, b1y = ny;                     /* B1 at distance d along the normal */
  double b2x = b1x - a * ux, b2y = b1y - a * uy; /* B's partner disk */
  if (cfg) {
    cfg[0] = psi;
    cfg[1] = phib;
  }
  *th_a = psi;                           /* from A's outward axis (+x) to the normal */
  *th_b = wrap_angle(psi + M_PI - phib); /* from B's outward axis to -n (B1 -> A1) */
  /* Overlap means centre distance < d (touching, == d, is allowed). */
  double dx = b1x + a, dy = b1y; /* A2 - B1 */
  if (dx * dx + dy * dy < 1.0) return 0;
  if (b2x * b2x + b2y * b2y < 1.0) return 0; /* A1 - B2 */
  if (!no_partner_partner) {
    dx = b2x + a, dy = b2y; /* A2 - B2 */
    if (dx * dx + dy * dy < 1.0) return 0;
  }
  return 1;
}

int hd_fmean_sample_shape(gsl_rng *rng, const hd_shape *sh, int all, hd_kin *A, hd_kin *B, int *ka,
                          int *kb) {
  int n = sh->n, i = 0, j = 0;
  double wsum = 0.0; /* touching pair (i, j) with probability D_ij / sum */
  for (int p = 0; p < n; p++)
    for (int q = 0; q < n; q++) wsum += 0.5 * (sh->dk[p] + sh->dk[q]);
  double u = wsum * gsl_rng_uniform(rng), acc = 0.0;
  for (int p = 0; p < n * n; p++) {
    i = p / n, j = p % n;
    acc += 0.5 * (sh->dk[i] + sh->dk[j]);
    if (u < acc) break;
  }
  double psi = 2.0 * M_PI * gsl_rng_uniform(rng) - M_PI;  /* contact normal A_i -> B_j */
  double phib = 2.0 * M_PI * gsl_rng_uniform(rng) - M_PI; /* B's orientation */
  double D = 0.5 * (sh->dk[i] + sh->dk[j]), cb = cos(phib), sb = sin(phib);
  double bjx = sh->ox[i] + D * cos(psi), bjy = sh->oy[i] + D * sin(psi); /* B_j's centre */
  *A = (hd_kin){0, 0, 0, 0, 0, 0};
  *B = (hd_kin){bjx - (sh->ox[j] * cb - sh->oy[j] * sb),
                bjy - (sh->ox[j] * sb + sh->oy[j] * cb),
                0,
                0,
                phib,
                0};
  *ka = i;
  *kb = j;
  for (int p = 0; p < n; p++) {
    double ax, ay;
    hd_kin_disk_pos(A, sh, p, &ax, &ay);
    for (int q = 0; q < n; q++) {
      if ((p == i && q == j) || (!all && p != i && q != j)) continue;
      double bx, by, Dq = 0.5 * (sh->dk[p] + sh->dk[q]);
      hd_kin_disk_pos(B, sh, q, &bx, &by);
      if ((bx - ax) * (bx - ax) + (by - ay) * (by - ay) < Dq * Dq) return 0;
    }
  }
  return 1;
}

/* ---- Monte Carlo -------------------------------------------------------------------------- */

static double now_seconds(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Sampling state of one run. */
typedef struct mc_state {
  gsl_rng *rng;
  hd_fmean_model model;
  double a;           /* a/d */
  double theta_max;   /* heuristic range */
  int no_pp;          /* no partner-partner rejection */
  const hd_shape *sh; /* NULL, or the shape of both bodies (hd_fmean_opts.shape) */
  unsigned long tried;
  double fb[BATCH], wb[BATCH], yb[BATCH], zb[BATCH]; /* batch: f, w, w f, w f v_n^2 */
} mc_state;

/* Fills up to n (<= BATCH) accepted samples into the batch buffers; returns how many (fewer
 * only if 100 n + 1000 consecutive draws are all rejected). */
static size_t fill_batch(mc_state *s, size_t n) {
  size_t k = 0;
  unsigned long misses = 0;
  if (s->sh) { /* any shape: the engine's f, mu and vn of each contact configuration */
    const hd_shape *sh = s->sh;
    const double sv = sqrt(1.0 / sh->mass), sw = sh->inertia > 0 ? sqrt(1.0 / sh->inertia) : 0;
    while (k < n) {
      hd_kin A, B;
      int ka, kb;
      s->tried++;
      if (!hd_fmean_sample_shape(s->rng, sh, s->model != HD_FMEAN_HEURISTIC, &A, &B, &ka, &kb)) {
        if (++misses > 100 * n + 1000) break;
        continue;
      }
      misses = 0;
      if (s->model == HD_FMEAN_COLLISION) { /* equipartition at T = 1 */
        A.vx = gsl_ran_gaussian_ziggurat(s->rng, sv), A.vy = gsl_ran_gaussian_ziggurat(s->rng, sv);
        B.vx = gsl_ran_gaussian_ziggurat(s->rng, sv), B.vy = gsl_ran_gaussian_ziggurat(s->rng, sv);
        A.omega = sw > 0 ? gsl_ran_gaussian_ziggurat(s->rng, sw) : 0.0;
        B.omega = sw > 0 ? gsl_ran_gaussian_ziggurat(s->rng, sw) : 0.0;
      }
      hd_collision_info in;
      hd_pair_info(&A, sh, &B, sh, ka, kb, 1.0, &in);
      s->fb[k] = in.f;
      if (s->model == HD_FMEAN_COLLISION) {
        hd_side a, b;
        double nx, ny;
        hd_side_of(&A, sh, ka, &a);
        hd_side_of(&B, sh, kb, &b);
        hd_pair_normal(&A, &a, &B, &b, &nx, &ny);
        double mu = 1.0 / (hd_side_inv_mass(&a, nx, ny) + hd_side_inv_mass(&b, nx, ny));
        double w = in.vn < 0.0 ? -in.vn : 0.0;
        s->wb[k] = w;
        s->yb[k] = w * in.f;
        s->zb[k] = w * mu * in.vn * in.vn;
      }
      k++;
    }
    return k;
  }
  if (s->model == HD_FMEAN_HEURISTIC) {
    /* The paper's model: both angles independent and uniform on [-theta_max, theta_max]. */
    const double tm2 = 2.0 * s->theta_max, tm = s->theta_max;
    gsl_rng *rng = s->rng;
    for (k = 0; k < n; k++) {
      double c1 = cos(tm2 * gsl_rng_uniform(rng) - tm);
      double c2 = cos(tm2 * gsl_rng_uniform(rng) - tm);
      s->fb[k] = 1.0 / (2.0 - 0.5 * (c1 * c1 + c2 * c2));
    }
    s->tried += n;
    return n;
  }
  while (k < n) {
    double t1, t2;
    double cfg[2];
    s->tried++;
    if (!hd_fmean_sample_contact(s->rng, s->a, s->no_pp, &t1, &t2, cfg)) {
      if (++misses > 100 * n + 1000) break;
      continue;
    }
    misses = 0;
    double f = hd_fmean_f(t1, t2);
    s->fb[k] = f;
    if (s->model == HD_FMEAN_COLLISION) {
      /* Equipartition, T = m = 1: V ~ N(0, T/2m) per component (mass 2m), omega ~ N(0, T/I),
       * I = m a^2/2.  Contact-point velocity v = V + omega z x (a/2) u. */
      const double sv = sqrt(0.5), sw = sqrt(2.0) / s->a, h = 0.5 * s->a;
      double vax = gsl_ran_gaussian_ziggurat(s->rng, sv);
      double vay = gsl_ran_gaussian_ziggurat(s->rng, sv);
      double vbx = gsl_ran_gaussian_ziggurat(s->rng, sv);
      double vby = gsl_ran_gaussian_ziggurat(s->rng, sv);
      double wa = gsl_ran_gaussian_ziggurat(s->rng, sw);
      double wb = gsl_ran_gaussian_ziggurat(s->rng, sw);
      double nx = cos(cfg[0]), ny = sin(cfg[0]);
      double ux = cos(cfg[1]), uy = sin(cfg[1]);
      /* A's axis is +x: z x (h, 0) = (0, h). */
      double a1x = vax, a1y = vay + wa * h;
      double b1x = vbx - wb * h * uy, b1y = vby + wb * h * ux;
      double vn = (b1x - a1x) * nx + (b1y - a1y) * ny; /* > 0: separating */
      double w = vn < 0.0 ? -vn : 0.0;
      s->wb[k] = w;
      s->yb[k] = w * f;
      s->zb[k] = w * f * vn * vn;
    }
    k++;
  }
  return k;
}

static void result_nan(hd_fmean_result *res) {
  res->f_mean = res->f_stderr = res->d_e = res->d_e_stderr = NAN;
  res->f_quad = res->f_quad_abserr = NAN;
  res->fvn2 = res->fvn2_stderr = res->d_e_energy = res->d_e_energy_stderr = NAN;
  res->samples = res->tried = 0;
  res->seconds = 0.0;
}

int hd_fmean_run(const hd_fmean_opts *o, hd_fmean_result *res, hd_error *err) {
  hd_error_clear(err);
  result_nan(res);
  if (!o->shape && (!(o->a_over_d > 0.0) || !isfinite(o->a_over_d)))
    return hd_error_set(err, HD_EINPUT, "a/d must be a positive number (got %g)", o->a_over_d);
  if (!(o->dim > 0.0) || !isfinite(o->dim))
    return hd_error_set(err, HD_EINPUT, "dimension D must be positive (got %g)", o->dim);
  if (o->model < HD_FMEAN_HEURISTIC || o->model > HD_FMEAN_COLLISION)
    return hd_error_set(err, HD_EINPUT, "unknown model %d", (int)o->model);
  if (o->samples == 0 && !(o->seconds > 0.0 && isfinite(o->seconds)))
    return hd_error_set(err, HD_EINPUT, "need samples > 0 or seconds > 0");
  if (o->samples == 1)
    return hd_error_set(err, HD_EINPUT, "need at least 2 samples for an error estimate");

  mc_state *s = malloc(sizeof *s);
  if (!s) return hd_error_set(err, HD_ENOMEM, "out of memory");
  s->rng = gsl_rng_alloc(gsl_rng_mt19937);
  if (!s->rng) {
    free(s);
    return hd_error_set(err, HD_ENOMEM, "cannot allocate the random number generator");
  }
  gsl_rng_set(s->rng, o->seed);
  s->model = o->model;
  s->a = o->a_over_d;
  s->theta_max = hd_fmean_theta_max(o->a_over_d);
  s->no_pp = o->no_partner_partner;
  s->sh = o->shape;
  s->tried = 0;

  hd_fmean_moments mf, mr; /* mf: f (plain); mr: (w, w f, w f v_n^2) for the ratio estimators */
  hd_fmean_moments_init(&mf, 1);
  hd_fmean_moments_init(&mr, 3);
  double t0 = now_seconds();
  int status = HD_OK;
  for (;;) {
    size_t want = BATCH;
    if (o->samples) {
      unsigned long left = o->samples - (unsigned long)mf.n;
      if (left == 0) break;
      if (left < want) want = (size_t)left;
    } else if (mf.n > 0 && now_seconds() - t0 >= o->seconds) {
      break;
    }
    size_t got = fill_batch(s, want);
    if (got == 0) {
      status =
          hd_error_set(err, HD_EPHYS, "no contact configuration accepted at a/d = %g", o->a_over_d);
      break;
    }
    const double *cols1[1] = {s->fb};
    hd_fmean_moments_add_batch(&mf, cols1, got);
    if (o->model == HD_FMEAN_COLLISION) {
      const double *cols3[3] = {s->wb, s->yb, s->zb};
      hd_fmean_moments_add_batch(&mr, cols3, got);
    }
  }
  res->seconds = now_seconds() - t0;
  res->tried = s->tried;
  res->samples = (unsigned long)mf.n;
  gsl_rng_free(s->rng);
  free(s);
  if (status) return status;
  if (mf.n < 2) return hd_error_set(err, HD_EPHYS, "fewer than 2 samples drawn");

  if (o->model == HD_FMEAN_COLLISION) {
    if (!(mr.mean[0] > 0.0)) return hd_error_set(err, HD_EPHYS, "no approaching contact sampled");
    hd_fmean_moments_ratio(&mr, 1, 0, &res->f_mean, &res->f_stderr);
    hd_fmean_moments_ratio(&mr, 2, 0, &res->fvn2, &res->fvn2_stderr);
    /* E = T_tr + T_rot/2 = 3T/2 per dimer at equipartition (a shape without a moment of
     * inertia: T); see docs/mc-fmean.md. */
    const double e_per_dimer = o->shape && !(o->shape->inertia > 0) ? 1.0 : 1.5;
    res->d_e_energy = 4.0 * e_per_dimer / res->fvn2;
    res->d_e_energy_stderr = 4.0 * e_per_dimer * res->fvn2_stderr / (res->fvn2 * res->fvn2);
  } else {
    res->f_mean = mf.mean[0];
    res->f_stderr = sqrt(hd_fmean_moments_var(&mf, 0) / mf.n);
  }
  res->d_e = o->dim / res->f_mean;
  res->d_e_stderr = o->dim * res->f_stderr / (res->f_mean * res->f_mean);
  if (o->model == HD_FMEAN_HEURISTIC && !o->shape) {
    int st = hd_fmean_quadrature(o->a_over_d, &res->f_quad, &res->f_quad_abserr);
    if (st) return hd_error_set(err, st, "quadrature failed at a/d = %g", o->a_over_d);
  }
  return HD_OK;
}
