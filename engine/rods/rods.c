/* hd_rods: the ring of rods (rods.h).  Gaps are stored, not positions: gap k at time gt[k]
 * is g[k], and it changes only when one of its two rods changes velocity, so a collision
 * touches three gaps and three queue entries (hd_queue.h, O(1)), and a small gap keeps its full
 * relative precision however far the rods are from the origin. */
#include "rods.h"

#include <gsl/gsl_randist.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void hd_rods_params_default(hd_rods_params *p) {
  memset(p, 0, sizeof *p);
  p->gamma = HD_RODS_GAMMA_DEFAULT;
  p->nmod = HD_RODS_NMOD_DEFAULT;
  p->model = HD_RODS_STOCHASTIC;
  p->eps = HD_RODS_GAMMA_DEFAULT;
  p->temperature = HD_RODS_TEMPERATURE_DEFAULT;
  p->seed = 1;
}

void hd_rods_free(hd_rods *r) {
  if (!r) return;
  free(r->m);
  free(r->v);
  free(r->tb);
  free(r->tl);
  free(r->g);
  free(r->gt);
  free(r->key);
  hd_queue_free(r->q);
  if (r->rng) gsl_rng_free(r->rng);
  hd_eps_sampler_free(r->sampler);
  hd_eps_table_free(r->table);
  free(r->low_q);
  free(r->low_have);
  free(r);
}

static long nxt(const hd_rods *r, long i) {
  return i + 1 == r->p.n ? 0 : i + 1;
}
static long prv(const hd_rods *r, long i) {
  return i == 0 ? r->p.n - 1 : i - 1;
}

/* exp(-nu (t - tl)) for a bath last updated at tl. */
static double decay(const hd_rods *r, double tl, double t) {
  if (!(r->p.damping > 0) || !isfinite(tl)) return 1.0;
  return exp(-r->p.damping * (t - tl));
}

/* Predicts gap k's closing time into key[k] (>= now). */
static void predict(hd_rods *r, long k) {
  long j = nxt(r, k);
  double dv = r->v[j] - r->v[k];
  if (!(dv < 0)) {
    r->key[k] = INFINITY;
    return;
  }
  double tk = r->gt[k] + fmax(r->g[k], 0.0) / -dv;
  r->key[k] = fmax(tk, r->t);
}

/* Brings gap k to the current time. */
static void advance_gap(hd_rods *r, long k) {
  if (r->gt[k] == r->t) return;
  r->g[k] += (r->v[nxt(r, k)] - r->v[k]) * (r->t - r->gt[k]);
  r->gt[k] = r->t;
}

/* Brings rod 0's position (the ring's anchor) to the current time. */
static void advance_x0(hd_rods *r) {
  r->x0 += r->v[0] * (r->t - r->x0t);
  r->x0t = r->t;
}

/* After a collision of rods a, b that approached at u while moving at va, vb: if they moved
 * together much faster than they approached, and the whole ring drifts at that speed (the
 * round-off left of the zero total momentum: ~1e-19 of the initial speeds), the ring is taken
 * to its centre-of-mass frame.  Otherwise a ring that cools for ever (constant eps) reaches
 * speeds at the drift's round-off, 1e-16 of it, where a collision no longer changes the
 * velocities.  Gaps depend on velocity differences only: they are brought to now, the drift is
 * subtracted and every gap predicted again.  Checked at most once per N collisions. */
static void keep_frame(hd_rods *r, double u, double va, double vb) {
  long n = r->p.n;
  if (!(fabs(u) < 1e-6 * (fabs(va) + fabs(vb))) || r->collisions < r->frame_next) return;
  r->frame_next = r->collisions + n;
  double P = 0, M = 0;
  for (long i = 0; i < n; i++) P += r->m[i] * r->v[i], M += r->m[i];
  double V = P / M;
  if (!(fabs(V) > 1e-3 * (fabs(va) + fabs(vb)))) return; /* a cluster's own motion: real */
  for (long k = 0; k < n; k++) advance_gap(r, k);
  advance_x0(r);
  for (long i = 0; i < n; i++) r->v[i] -= V;
  for (long k = 0; k < n; k++) predict(r, k);
  hd_queue_build(r->q, (int32_t)n, r->key, 1);
  r->frames++;
}

void hd_rods_eps_opts(double eps_step, hd_eps_opts *o) {
  hd_eps_opts_default(o);
  if (eps_step > 0) o->step = eps_step;
}

static int check_params(const hd_rods_params *p, hd_error *err) {
  if (p->n < 2 || p->n % 2)
    return hd_error_set(err, HD_EINPUT, "rods: count %ld must be even and >= 2", p->n);
  if (p->n > INT32_MAX / 2) return hd_error_set(err, HD_EINPUT, "rods: count %ld too large", p->n);
  if (!(p->gamma > 0 && p->gamma <= 1))
    return hd_error_set(err, HD_EINPUT, "rods: gamma %g must be in (0, 1]", p->gamma);
  if (p->nmod < 1) return hd_error_set(err, HD_EINPUT, "rods: nmod %ld must be >= 1", p->nmod);
  if (!(p->eps >= 0 && p->eps <= 1))
    return hd_error_set(err, HD_EINPUT, "rods: eps %g must be in [0, 1]", p->eps);
  if (!(p->damping >= 0) || !(p->tc >= 0) || !(p->temperature > 0))
    return hd_error_set(err, HD_EINPUT, "rods: damping and tc must be >= 0, temperature > 0");
  if (p->table && p->unequal)
    return hd_error_set(err, HD_EINPUT, "rods: the eps table needs equal (mean) bath temperatures");
  return HD_OK;
}

/* Everything but the initial state. */
static int alloc_bare(hd_rods **out, const hd_rods_params *p, hd_error *err) {
  *out = NULL;
  int rc = check_params(p, err);
  if (rc) return rc;
  hd_rods *r = calloc(1, sizeof *r);
  if (!r) return hd_error_set(err, HD_ENOMEM, "rods: out of memory");
  r->p = *p;
  size_t n = (size_t)p->n;
  r->m = malloc(n * sizeof(double));
  r->v = calloc(n, sizeof(double));
  r->tb = calloc(n, sizeof(double));
  r->tl = malloc(n * sizeof(double));
  r->g = calloc(n, sizeof(double));
  r->gt = calloc(n, sizeof(double));
  r->key = malloc(n * sizeof(double));
  r->rng = gsl_rng_alloc(gsl_rng_mt19937);
  r->q = hd_queue_alloc((int32_t)n);
  if (!r->m || !r->v || !r->tb || !r->tl || !r->g || !r->gt || !r->key || !r->rng || !r->q) {
    hd_rods_free(r);
    return hd_error_set(err, HD_ENOMEM, "rods: out of memory for %ld rods", p->n);
  }
  gsl_rng_set(r->rng, (unsigned long)p->seed);
  double g1 = 1 + p->gamma, g2 = 1 + 1 / p->gamma;
  for (size_t i = 0; i < n; i++) {
    r->m[i] = i % 2 ? g2 : g1;
    r->tl[i] = -INFINITY;
  }
  if (p->model == HD_RODS_STOCHASTIC && p->gamma < 1) {
    hd_eps_opts o;
    hd_rods_eps_opts(p->eps_step, &o);
    /* the table (and its direct fallback below its nodes) stays on the plain grid: its balance
     * removes the moment that moves E_kin (docs/mc-eps.md 4c); direct draws are refined (2b) */
    if (p->table) o.refine = 0;
    rc = hd_eps_sampler_alloc(&r->sampler, p->gamma, &o, err);
    if (!rc && p->table) {
      gsl_rng *tr = gsl_rng_alloc(gsl_rng_mt19937);
      if (!tr)
        rc = hd_error_set(err, HD_ENOMEM, "rods: out of memory");
      else {
        gsl_rng_set(tr, HD_RODS_TABLE_SEED);
        rc = hd_eps_table_build(&r->table, r->sampler, 1e-3, 1e3, 25, 129, 1000, tr, err);
        /* its detailed-balance moment projected to 0 (eq. 19): the table's noise and step bias
         * otherwise move the stationary E_kin by -6 % (docs/mc-eps.md section 4c) */
        if (!rc) rc = hd_eps_table_balance(r->table, &r->table_scale, err);
        gsl_rng_free(tr);
        if (!rc) {
          r->low_q = malloc((size_t)HD_RODS_LOW_NODES * (size_t)r->table->nu * sizeof(double));
          r->low_have = calloc(HD_RODS_LOW_NODES, 1);
          if (!r->low_q || !r->low_have) rc = hd_error_set(err, HD_ENOMEM, "rods: out of memory");
        }
      }
    }
    if (rc) {
      hd_rods_free(r);
      return rc;
    }
  }
  *out = r;
  return HD_OK;
}

int hd_rods_alloc(hd_rods **out, const hd_rods_params *p, hd_error *err) {
  hd_rods *r;
  int rc = alloc_bare(&r, p, err);
  if (rc) return rc;
  long n = p->n;
  /* uniform positions: exponential spacings normalised to the ring length n */
  double sum = 0;
  for (long k = 0; k < n; k++) sum += r->g[k] = gsl_ran_exponential(r->rng, 1.0);
  for (long k = 0; k < n; k++) r->g[k] *= (double)n / sum;
  r->x0 = gsl_rng_uniform(r->rng) * (double)n;
  /* Maxwell velocities, zero momentum, E_kin = n T0 / 2 exactly */
  double P = 0, M = 0;
  for (long i = 0; i < n; i++) {
    r->v[i] = gsl_ran_gaussian_ziggurat(r->rng, sqrt(p->temperature / r->m[i]));
    P += r->m[i] * r->v[i];
    M += r->m[i];
  }
  double ek = 0;
  for (long i = 0; i < n; i++) {
    r->v[i] -= P / M;
    ek += 0.5 * r->m[i] * r->v[i] * r->v[i];
  }
  double s = sqrt(0.5 * (double)n * p->temperature / ek);
  for (long i = 0; i < n; i++) r->v[i] *= s;
  for (long k = 0; k < n; k++) predict(r, k);
  hd_queue_build(r->q, (int32_t)n, r->key, 1);
  *out = r;
  return HD_OK;
}

void hd_rods_positions(const hd_rods *r, double *x) {
  double L = (double)r->p.n, xi = r->x0 + r->v[0] * (r->t - r->x0t);
  for (long i = 0; i < r->p.n; i++) {
    double y = fmod(xi, L);
    x[i] = y < 0 ? y + L : y;
    if (i + 1 < r->p.n) xi += r->g[i] + (r->v[i + 1] - r->v[i]) * (r->t - r->gt[i]);
  }
}

double hd_rods_tb(const hd_rods *r, long i) {
  return r->tb[i] * decay(r, r->tl[i], r->t);
}

void hd_rods_energy(const hd_rods *r, double *e_kin, double *e_bath, double *e_lost) {
  double ek = 0, eb = 0, el = r->e_lost;
  for (long i = 0; i < r->p.n; i++) {
    ek += 0.5 * r->m[i] * r->v[i] * r->v[i];
    double tb = hd_rods_tb(r, i);
    eb += (double)r->p.nmod * tb;
    el += (double)r->p.nmod * (r->tb[i] - tb);
  }
  if (e_kin) *e_kin = ek;
  if (e_bath) *e_bath = eb;
  if (e_lost) *e_lost = el;
}

/* The cluster of the last tiny collisions: the shortest arc of rods covering their gaps. */
static void cluster(const hd_rods *r, long *first, long *last) {
  long n = r->p.n, m = HD_RODS_TINY_RUN;
  long gs[HD_RODS_TINY_RUN];
  for (long k = 0; k < m; k++) gs[k] = r->recent[k];
  /* sort the gap indices (insertion sort, m is small) */
  for (long a = 1; a < m; a++) {
    long x = gs[a], b = a - 1;
    while (b >= 0 && gs[b] > x) {
      gs[b + 1] = gs[b];
      b--;
    }
    gs[b + 1] = x;
  }
  /* the largest circular hole between consecutive marked gaps; the arc is its complement */
  long best = -1, at = 0;
  for (long k = 0; k < m; k++) {
    long a = gs[k], b = k + 1 < m ? gs[k + 1] : gs[0] + n;
    if (b - a > best) best = b - a, at = k;
  }
  long g_first = at + 1 < m ? gs[at + 1] : gs[0], g_last = gs[at];
  *first = g_first;
  *last = (g_last + 1) % n;
}

/* Whether the collision of rods a and b now is elastic by the TC model (either collided less
 * than tc ago): eps = 1 and the baths are left alone. */
static int tc_elastic(const hd_rods *r, long a, long b) {
  const hd_rods_params *p = &r->p;
  return p->tc > 0 && (r->t - r->tl[a] < p->tc || r->t - r->tl[b] < p->tc);
}

/* Draws eps for a collision of rods a (left) and b with relative energy e_tr (not TC-elastic).
 * Returns NaN if no draw fits what the baths hold (the caller reports it). */
/* a / b, with the IEEE result of a division by zero written out (the sanitizer build checks
 * float-divide-by-zero): +-inf for a != 0 (cold baths: beta = E_tr / T_B = inf; a collision
 * without energy: no cap on eps), NaN for 0 / 0 (no draw fits: redrawn, then reported). */
static double ratio(double a, double b) {
  if (b == 0.0) return a > 0.0 ? INFINITY : a < 0.0 ? -INFINITY : NAN;
  return a / b;
}

/* ln of the table's node spacing, ln(beta_max/beta_min)/(nbeta - 1): the extension's too. */
static double low_step(const hd_rods *r) {
  const hd_eps_table *t = r->table;
  return (t->log_span != 0 ? t->log_span : log(t->beta_max / t->beta_min)) / (double)(t->nbeta - 1);
}

/* beta of node j of the extension below the table's grid (j = 0: the table's first node). */
static double low_beta(const hd_rods *r, int j) {
  return r->table->beta_min * exp(-(double)j * low_step(r));
}

/* The quantile row of node j >= 1 below the table's grid, built on first use as the table
 * builds its nodes (hd_eps_table_row, seed HD_RODS_TABLE_SEED + j) and scaled by the table's
 * balance factor; NULL when out of memory (the caller then draws directly). */
static const double *low_row(hd_rods *r, int j) {
  double *row = r->low_q + (size_t)(j - 1) * (size_t)r->table->nu;
  if (r->low_have[j - 1]) return row;
  gsl_rng *g = gsl_rng_alloc(gsl_rng_mt19937);
  if (!g) return NULL;
  gsl_rng_set(g, HD_RODS_TABLE_SEED + (unsigned long)j);
  hd_error e;
  int rc = hd_eps_table_row(r->table, r->sampler, low_beta(r, j), row, g, &e);
  gsl_rng_free(g);
  if (rc) return NULL;
  for (int k = 0; k < r->table->nu; k++) row[k] *= r->table_scale;
  r->low_have[j - 1] = 1;
  return row;
}

/* One eps at beta in [low_beta(LOW_NODES), beta_min): the two nodes around beta, same u,
 * linear in ln beta as within the table. */
static double low_sample(hd_rods *r, double beta) {
  double s = log(r->table->beta_min / beta) / low_step(r); /* in (0, LOW_NODES] */
  int j = (int)s, nu = r->table->nu;
  if (j >= HD_RODS_LOW_NODES) j = HD_RODS_LOW_NODES - 1;
  const double *lo = j > 0 ? low_row(r, j) : r->table->q, *hi = low_row(r, j + 1);
  if (!lo || !hi) return hd_eps_sample(r->sampler, beta, r->rng);
  double f = s - j, u = gsl_rng_uniform(r->rng);
  return (1 - f) * hd_eps_row_quantile(lo, nu, u) + f * hd_eps_row_quantile(hi, nu, u);
}

double hd_rods_table_eps(hd_rods *r, double beta) {
  if (r->table && beta >= r->table->beta_min) return hd_eps_table_sample(r->table, beta, r->rng);
  /* below the table's grid the table only repeats its end node (mean 3.39 against 5.71 at
   * beta = 1e-5): the lazily built nodes below it (rods.h), then direct draws */
  if (r->table && beta >= low_beta(r, HD_RODS_LOW_NODES)) return low_sample(r, beta);
  return hd_eps_sample(r->sampler, beta, r->rng);
}

static double draw_eps(hd_rods *r, long a, long b, double e_tr, double tba, double tbb) {
  const hd_rods_params *p = &r->p;
  if (p->model == HD_RODS_CONSTANT) return p->eps;
  if (!r->sampler) return 1.0; /* gamma = 1: eps = 1 for every realisation */
  /* the two baths hold 2 N_mod T_B: eps^2 <= 1 + 2 N_mod T_B / E_tr */
  double tbm = 0.5 * (tba + tbb), cap = 1 + ratio(2 * (double)p->nmod * tbm, e_tr), eps = 1;
  for (int tries = 0; tries < 1000; tries++) {
    if (p->unequal) {
      long s = a % 2 ? b : a, l = a % 2 ? a : b; /* short (even) and long (odd) rod */
      double ts = s == a ? tba : tbb, tl = l == a ? tba : tbb;
      eps = hd_eps_sample2(r->sampler, ratio(e_tr, ts), ratio(e_tr, tl), r->rng);
    } else if (r->table) {
      eps = hd_rods_table_eps(r, ratio(e_tr, tbm));
    } else {
      eps = hd_eps_sample(r->sampler, ratio(e_tr, tbm), r->rng);
    }
    if (eps * eps <= cap) return eps; /* false for NaN: redrawn */
    r->resampled++;
  }
  return NAN;
}

/* Whether a collision of rods a, b at time t with relative energy e_tr is cold (collapse
 * detection, rods.h): eps fixed (constant model), or drawn at beta >= HD_RODS_COLD_BETA from the
 * warmer of the two baths; a TC-elastic collision and gamma = 1 (eps = 1) are not. */
static int cold(const hd_rods *r, long a, long b, double t, double e_tr) {
  if (tc_elastic(r, a, b)) return 0;
  if (r->p.model == HD_RODS_CONSTANT) return 1;
  if (!r->sampler) return 0;
  double ta = r->tb[a] * decay(r, r->tl[a], t), tb = r->tb[b] * decay(r, r->tl[b], t);
  return e_tr >= HD_RODS_COLD_BETA * fmax(ta, tb);
}

int hd_rods_next(hd_rods *r, double t_stop, hd_rods_event *ev, hd_error *err) {
  long k = hd_queue_top(r->q);
  double tk = r->key[k];
  if (tk == INFINITY) {
    if (isfinite(t_stop)) {
      r->t = t_stop;
      return HD_SIM_STOPTIME;
    }
    return HD_SIM_IDLE;
  }
  if (tk > t_stop) {
    r->t = t_stop;
    return HD_SIM_STOPTIME;
  }
  long a = k, b = nxt(r, k), n = r->p.n;
  double u = r->v[b] - r->v[a];
  /* collapse detection, before anything changes: the collision rate diverges, i.e. the time
   * since the previous collision falls below HD_RODS_TINY t */
  long kl = prv(r, a), kr = b;
  r->stall = tk == r->t ? r->stall + 1 : 0;
  double gap = tk - r->t, e_now = 0.5 * u * u;
  int tiny = 0;
  if (gap <= HD_RODS_TINY * tk) {
    if (r->tiny_run > 0 && !(tk - r->tiny_t0 <= HD_RODS_EPISODE * tk)) r->tiny_run = 0;
    if (r->tiny_run == 0) r->tiny_t0 = tk, r->tiny_low = 0, r->tiny_e0 = 0;
    /* blocks of HD_RODS_TINY_RUN tiny collisions: the largest E_tr of each against the first's */
    if (r->tiny_run % HD_RODS_TINY_RUN == 0) r->tiny_eblk = 0, r->tiny_warm = 0;
    r->tiny_eblk = fmax(r->tiny_eblk, e_now);
    if (!cold(r, a, b, tk, e_now)) r->tiny_warm++;
    r->recent[r->tiny_run % HD_RODS_TINY_RUN] = (int32_t)k;
    r->tiny_run++;
    if (r->tiny_run % HD_RODS_TINY_RUN == 0) {
      if (r->tiny_run == HD_RODS_TINY_RUN)
        r->tiny_e0 = r->tiny_eblk;
      else
        r->tiny_low =
            r->tiny_eblk <= HD_RODS_TINY_FALL * r->tiny_e0 && !r->tiny_warm ? r->tiny_low + 1 : 0;
      tiny = r->tiny_low >= HD_RODS_TINY_LOW;
    }
  }
  int stalled = r->stall >= HD_RODS_STALL + (int64_t)n * n; /* safety net (rods.h) */
  if (tiny || stalled) {
    long c0 = a, c1 = b;
    char why[200];
    /* every collision at one time is tiny: the arc of the last HD_RODS_TINY_RUN of them */
    if (r->tiny_run >= HD_RODS_TINY_RUN) cluster(r, &c0, &c1);
    if (tiny) {
      snprintf(why, sizeof why,
               "%lld collisions less than 1e-12 t after the previous one within %.3g, the "
               "largest relative energy of %d of them down from %.3g to %.3g",
               (long long)r->tiny_run, tk - r->tiny_t0, HD_RODS_TINY_RUN, r->tiny_e0, r->tiny_eblk);
    } else {
      snprintf(why, sizeof why, "%lld successive collisions at the same time", (long long)r->stall);
    }
    long size = (c1 - c0 + n) % n + 1;
    return hd_error_set(err, HD_ECOLLAPSE,
                        "inelastic collapse at t = %.10g after %lld collisions: %s in the cluster "
                        "of rods %ld..%ld (%ld rods)",
                        tk, (long long)r->collisions, why, c0, c1, size);
  }
  r->t = tk;
  /* gaps next to the pair move with the old velocities up to now */
  advance_gap(r, kl);
  if (kr != kl) advance_gap(r, kr);
  if (a == 0 || b == 0) advance_x0(r);
  /* baths up to now (damping) */
  double da = decay(r, r->tl[a], r->t), db = decay(r, r->tl[b], r->t);
  double tba = r->tb[a] * da, tbb = r->tb[b] * db;
  double e_tr = e_now;
  int tc = tc_elastic(r, a, b);
  double eps = tc ? 1.0 : draw_eps(r, a, b, e_tr, tba, tbb);
  if (!isfinite(eps))
    return hd_error_set(err, HD_EPHYS,
                        "rods %ld and %ld at t = %.10g: no coefficient of restitution drawn in "
                        "1000 tries fits what their baths hold (E_tr = %.3g, T_B = %.3g, %.3g)",
                        a, b, r->t, e_tr, tba, tbb);
  r->e_lost += (double)r->p.nmod * (r->tb[a] - tba + r->tb[b] - tbb);
  /* eq. (28-29): both baths take the mean plus their share of the loss; a TC-elastic collision
   * leaves them alone (docs/rods.md) */
  double tbn_a = tba, tbn_b = tbb;
  if (!tc) {
    double tbn = 0.5 * (tba + tbb) + (1 - eps * eps) * e_tr / (2 * (double)r->p.nmod);
    if (tbn < 0) tbn = 0; /* round-off only: draw_eps keeps eps^2 within what the baths hold */
    tbn_a = tbn_b = tbn;
  }
  r->tb[a] = tbn_a, r->tb[b] = tbn_b;
  r->tl[a] = r->tl[b] = r->t;
  /* momentum conservation with the true masses: u -> -eps u (eq. 30-32 are gamma = 1) */
  double va = r->v[a], vb = r->v[b];
  double mu = r->m[a] * r->m[b] / (r->m[a] + r->m[b]);
  r->v[a] += (1 + eps) * u * mu / r->m[a];
  r->v[b] -= (1 + eps) * u * mu / r->m[b];
  r->g[k] = 0;
  r->gt[k] = r->t;
  predict(r, k);
  hd_queue_update(r->q, (int32_t)k, r->key[k]);
  predict(r, kl);
  hd_queue_update(r->q, (int32_t)kl, r->key[kl]);
  if (kr != kl) {
    predict(r, kr);
    hd_queue_update(r->q, (int32_t)kr, r->key[kr]);
  }
  r->collisions++;
  keep_frame(r, u, va, vb);
  *ev = (hd_rods_event){r->t, a, b, eps, e_tr, u, tbn_a, tbn_b, -(1 - eps * eps) * e_tr};
  return HD_OK;
}

/* ---- checkpoints ---------------------------------------------------------------------------- */

/* Scalars of the blob. */
typedef struct ck_head {
  uint64_t magic;
  int64_t n, collisions, resampled, tiny_run, tiny_low, tiny_warm, stall, frame_next, frames;
  double t, x0, x0t, e_lost, tiny_t0, tiny_e0, tiny_eblk;
  int32_t recent[HD_RODS_TINY_RUN];
  uint64_t rng_size;
} ck_head;
#define CK_MAGIC                                                                                   \
  0x68646f7230303033ULL /* "hdor0003" (0002: the spacing-fall detector; 0001:                      \
                           before it and the frame) */

int hd_rods_checkpoint(const hd_rods *r, void **blob, size_t *n, hd_error *err) {
  size_t nr = (size_t)r->p.n, rs = gsl_rng_size(r->rng);
  size_t total = sizeof(ck_head) + 6 * nr * sizeof(double) + rs;
  unsigned char *b = malloc(total);
  if (!b) return hd_error_set(err, HD_ENOMEM, "rods: out of memory for a checkpoint");
  ck_head h;
  memset(&h, 0, sizeof h);
  h.magic = CK_MAGIC;
  h.n = r->p.n;
  h.collisions = r->collisions;
  h.resampled = r->resampled;
  h.tiny_run = r->tiny_run;
  h.tiny_low = r->tiny_low;
  h.tiny_warm = r->tiny_warm;
  h.tiny_t0 = r->tiny_t0;
  h.tiny_e0 = r->tiny_e0;
  h.tiny_eblk = r->tiny_eblk;
  h.stall = r->stall;
  h.frame_next = r->frame_next;
  h.frames = r->frames;
  h.t = r->t;
  h.x0 = r->x0;
  h.x0t = r->x0t;
  h.e_lost = r->e_lost;
  memcpy(h.recent, r->recent, sizeof h.recent);
  h.rng_size = rs;
  unsigned char *p = b;
  memcpy(p, &h, sizeof h);
  p += sizeof h;
  const double *arr[6] = {r->v, r->tb, r->tl, r->g, r->gt, r->key};
  for (int j = 0; j < 6; j++) {
    memcpy(p, arr[j], nr * sizeof(double));
    p += nr * sizeof(double);
  }
  memcpy(p, gsl_rng_state(r->rng), rs);
  *blob = b;
  *n = total;
  return HD_OK;
}

/* What a restored ring must satisfy to be run: counters >= 0, clocks finite, every rod's and
 * gap's numbers finite and not ahead of the ring's time, every gap's key not behind it, the
 * recent gaps' indices in range, the generator's position in its table.  A blob written whole
 * but wrong (hd_run.c's checksum catches a flipped bit) is refused instead of crashing the ring.
 * HD_OK or HD_EINPUT. */
static int check_restored(const hd_rods *r, hd_error *err) {
  if (r->collisions < 0 || r->resampled < 0 || r->tiny_run < 0 || r->tiny_low < 0 ||
      r->tiny_warm < 0 || r->stall < 0 || r->frame_next < 0 || r->frames < 0 || !isfinite(r->t) ||
      !isfinite(r->x0) || !isfinite(r->x0t) || !isfinite(r->e_lost) || isnan(r->tiny_t0) ||
      isnan(r->tiny_e0) || isnan(r->tiny_eblk))
    return hd_error_set(err, HD_EINPUT, "rods checkpoint: counters or clocks out of range");
  long n = r->p.n;
  for (long k = 0; k < HD_RODS_TINY_RUN; k++)
    if (r->recent[k] < 0 || r->recent[k] >= n)
      return hd_error_set(err, HD_EINPUT, "rods checkpoint: a gap index out of range");
  for (long i = 0; i < n; i++)
    if (!isfinite(r->v[i]) || !isfinite(r->tb[i]) || !(r->tb[i] >= 0) || isnan(r->tl[i]) ||
        !(r->tl[i] <= r->t) || !isfinite(r->g[i]) || !isfinite(r->gt[i]) || !(r->gt[i] <= r->t) ||
        isnan(r->key[i]) || !(r->key[i] >= r->t))
      return hd_error_set(err, HD_EINPUT, "rods checkpoint: rod or gap %ld out of range", i);
  if (gsl_rng_size(r->rng) == sizeof(unsigned long) * 624 + sizeof(int)) { /* gsl's mt19937 */
    int mti;
    memcpy(&mti, (const unsigned char *)gsl_rng_state(r->rng) + sizeof(unsigned long) * 624,
           sizeof mti);
    if (mti < 0 || mti > 624)
      return hd_error_set(err, HD_EINPUT, "rods checkpoint: random generator state out of range");
  }
  return HD_OK;
}

int hd_rods_alloc_restore(hd_rods **out, const hd_rods_params *p, const void *blob, size_t n,
                          hd_error *err) {
  *out = NULL;
  ck_head h;
  if (n < sizeof h) return hd_error_set(err, HD_EINPUT, "rods checkpoint: truncated");
  memcpy(&h, blob, sizeof h);
  if (h.magic != CK_MAGIC || h.n != p->n)
    return hd_error_set(err, HD_EINPUT, "rods checkpoint: not a checkpoint of this ring");
  hd_rods *r;
  int rc = alloc_bare(&r, p, err);
  if (rc) return rc;
  size_t nr = (size_t)p->n, rs = gsl_rng_size(r->rng);
  if (h.rng_size != rs || n != sizeof h + 6 * nr * sizeof(double) + rs) {
    hd_rods_free(r);
    return hd_error_set(err, HD_EINPUT, "rods checkpoint: wrong size");
  }
  r->collisions = h.collisions;
  r->resampled = h.resampled;
  r->tiny_run = h.tiny_run;
  r->tiny_low = h.tiny_low;
  r->tiny_warm = h.tiny_warm;
  r->tiny_t0 = h.tiny_t0;
  r->tiny_e0 = h.tiny_e0;
  r->tiny_eblk = h.tiny_eblk;
  r->stall = h.stall;
  r->frame_next = h.frame_next;
  r->frames = h.frames;
  r->t = h.t;
  r->x0 = h.x0;
  r->x0t = h.x0t;
  r->e_lost = h.e_lost;
  memcpy(r->recent, h.recent, sizeof h.recent);
  const unsigned char *q = (const unsigned char *)blob + sizeof h;
  double *arr[6] = {r->v, r->tb, r->tl, r->g, r->gt, r->key};
  for (int j = 0; j < 6; j++) {
    memcpy(arr[j], q, nr * sizeof(double));
    q += nr * sizeof(double);
  }
  memcpy(gsl_rng_state(r->rng), q, rs);
  rc = check_restored(r, err);
  if (rc) {
    hd_rods_free(r);
    return rc;
  }
  hd_queue_build(r->q, (int32_t)nr, r->key, 1);
  *out = r;
  return HD_OK;
}

/* ---- theory --------------------------------------------------------------------------------- */

double hd_rods_ekin_stat(long n, long nmod, double e_tot) {
  double f = (double)(n - 1);
  return e_tot * f / (f + 2.0 * (double)n * (double)nmod);
}

double hd_rods_rate_ideal(long n, double T) {
  return (double)(n - 1) * sqrt(T / (2 * M_PI));
}

double hd_rods_rate_eq35(long n, long nmod) {
  return (double)n / (2 * sqrt(M_PI * (2.0 * (double)nmod + 1)));
}

double hd_rods_my_ncrit(double r) {
  if (!(r < 1)) return INFINITY;
  return -log(1 - r) / (1 - r);
}
