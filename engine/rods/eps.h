/* hd_eps: the stochastic coefficient of restitution of two elastic rods (Aspelmeier, Giese,
 * Zippelius 1998, Sec. II A-B), solved in the hard-core limit (eqs. 13-14) for one collision,
 * and tabulated as inverse CDFs on a logarithmic beta grid.  docs/mc-eps.md states exactly what
 * is solved, the numerical scheme, its bias and the paper's ambiguities.
 *
 * Rod 1 is the rod of length l1, rod 2 of length l2, gamma = l1/l2 (any gamma > 0; the law of
 * eps depends on gamma only through {gamma, 1/gamma}).  beta = E_tr/T_B, where E_tr is the
 * translational energy of the relative motion before the collision and T_B the bath
 * temperature; the noise of rod i has sigma_i^2 = T_B(i)/(2 E_tr) = 1/(2 beta_i) (eq. 12). */
#ifndef HD_EPS_H
#define HD_EPS_H

#include <gsl/gsl_rng.h>
#include <stdint.h>

#include "hd_error.h"

/* Options of the direct sampler.  hd_eps_opts_default() fills the defaults in brackets. */
typedef struct hd_eps_opts {
  double step;    /* target grid step in tau = c t / l; the actual step divides both round-trip
                     times Gamma_1 = 1+gamma, Gamma_2 = 1+1/gamma exactly [0.01] */
  int adapt;      /* the step is halved for each halving of beta below 1, down to step/adapt
                     (a power of 2), because the grid bias grows with the noise [16] */
  int richardson; /* 1: solve each path also on a 4x finer grid and return
                     2 eps_fine - eps_coarse (bias ~ sqrt(step) removed per path; widens the
                     distribution at beta < 1, see docs/mc-eps.md); 0: plain grid [0] */
  double max_tau; /* cap on the duration of one collision, in tau [1e4] */
  double refine;  /* 0: plain grid; > 0: the working steps near the running maximum are refined
                     dyadically, down to this step (or the finest 2^12 division that fits), the
                     noise drawn per rod between the grid points (docs/mc-eps.md section 2b)
                     [0.01/128]; ignored with richardson */
} hd_eps_opts;

/* Fills opts with the defaults. */
void hd_eps_opts_default(hd_eps_opts *opts);

/* Whether the sampler's grid for gamma > 0 and o fits (about (1 + 1/gamma)/step x adapt
 * points, x 4 with richardson, at most 5e7): what hd_eps_sampler_alloc checks, so that a scene
 * can refuse a gamma at its key.  1 or 0. */
int hd_eps_grid_fits(double gamma, const hd_eps_opts *o);

/* A direct sampler for one length ratio (owns its work arrays; not thread-safe). */
typedef struct hd_eps_sampler hd_eps_sampler;

/* Allocates a sampler for length ratio gamma > 0 (opts NULL = defaults).  gamma is replaced by
 * the nearest rational N1/N2 that the grid resolves (exact for gamma = 4/5 and other small
 * denominators; see hd_eps_sampler_gamma).  Returns HD_OK, HD_EINPUT (bad gamma or options) or
 * HD_ENOMEM, with err set. */
int hd_eps_sampler_alloc(hd_eps_sampler **out, double gamma, const hd_eps_opts *opts,
                         hd_error *err);

/* Frees the sampler.  NULL is allowed. */
void hd_eps_sampler_free(hd_eps_sampler *s);

/* One eps for equal bath temperatures (the paper's rule: T_B = mean of the two rods' bath
 * temperatures, beta = E_tr/T_B).  beta = +inf (cold baths) gives min(gamma, 1/gamma).
 * Returns eps >= 0, or NaN if beta is NaN or <= 0. */
double hd_eps_sample(hd_eps_sampler *s, double beta, gsl_rng *rng);

/* One eps for unequal bath temperatures: beta1 = E_tr/T_B(rod 1), beta2 = E_tr/T_B(rod 2),
 * each may be +inf.  Returns eps >= 0, or NaN on a NaN or non-positive beta. */
double hd_eps_sample2(hd_eps_sampler *s, double beta1, double beta2, gsl_rng *rng);

/* The canonical length ratio actually simulated, min(gamma', 1/gamma') with gamma' = N1/N2. */
double hd_eps_sampler_gamma(const hd_eps_sampler *s);

/* The length ratio given to hd_eps_sampler_alloc. */
double hd_eps_sampler_gamma_in(const hd_eps_sampler *s);

/* The grid step actually used at beta >= 1 (Gamma_2 / N2). */
double hd_eps_sampler_step(const hd_eps_sampler *s);

/* The options the sampler was made with. */
void hd_eps_sampler_opts(const hd_eps_sampler *s, hd_eps_opts *opts);

/* Counters since allocation: samples drawn, collisions cut at max_tau (eps then is the value
 * reached), Richardson estimates clamped to 0, and grid steps solved (fine + coarse). */
typedef struct hd_eps_stats {
  long samples;   /* calls that solved a collision */
  long truncated; /* collisions still running at max_tau */
  long clamped;   /* Richardson combinations < 0 set to 0 */
  double steps;   /* grid steps solved, all levels */
  double refined; /* noise values drawn by refinement between grid points */
} hd_eps_stats;

/* Copies the counters. */
void hd_eps_sampler_stats(const hd_eps_sampler *s, hd_eps_stats *st);

/* One collision on one sampled path solved at the working step (the step hd_eps_sample2 would use
 * for these betas) into *coarse and at a quarter of it into *fine, same path and phase.  Needs a
 * sampler with richardson = 1 (HD_EINPUT otherwise or on a bad beta).  The tables build their
 * quantile-level extrapolation 2 Q_fine - Q_coarse from these pairs (docs/mc-eps.md). */
int hd_eps_sample_pair(hd_eps_sampler *s, double beta1, double beta2, double *coarse, double *fine,
                       gsl_rng *rng);

/* Solves one collision on one sampled path at several grid steps: out[m] is eps on the grid of
 * step (opts step)*strides[m]/R, R = adapt (times 4 with richardson), each stride a divisor of
 * R and a multiple of the smallest, all on the same path and the same random phase.  No
 * extrapolation. Used by the convergence study (`haff mc eps --convergence`).  Returns HD_OK or
 * HD_EINPUT. */
int hd_eps_sample_strides(hd_eps_sampler *s, double beta1, double beta2, const int *strides, int n,
                          double *out, gsl_rng *rng);

/* As hd_eps_sample_strides, each solve m refined levels[m] levels below its stride (0: plain
 * grid; at most hd_eps_sampler_levels), all on one path: the refined points are drawn once per
 * path, by Brownian-bridge interpolation per rod.  levels NULL = all 0.  HD_OK or HD_EINPUT. */
int hd_eps_sample_levels(hd_eps_sampler *s, double beta1, double beta2, const int *strides,
                         const int *levels, int n, double *out, gsl_rng *rng);

/* The sampler's refinement levels below its working step (0: plain grid). */
int hd_eps_sampler_levels(const hd_eps_sampler *s);

/* ---- tables: p_beta(eps) as inverse CDFs on a logarithmic beta grid (equal temperatures) --- */

/* A table Q_k(u_j), k < nbeta, j < nu, u_j = j/(nu-1), beta_k = beta_min
 * (beta_max/beta_min)^(k/(nbeta-1)). */
typedef struct hd_eps_table {
  double gamma;              /* length ratio requested */
  double gamma_eff;          /* canonical ratio simulated (<= 1) */
  int nbeta, nu;             /* grid sizes, nbeta >= 2, nu >= 2 */
  double beta_min, beta_max; /* beta grid ends, 0 < beta_min < beta_max */
  long samples;              /* direct samples per beta node */
  double step;               /* grid step of the direct sampler */
  int adapt;                 /* its adapt option */
  int richardson;            /* its richardson option */
  double seconds;            /* build time */
  double *q;                 /* nbeta*nu quantiles, q[k*nu + j], nondecreasing in j */
  double log_span;           /* ln(beta_max/beta_min) as hd_eps_table_build computed it (each
                                draw's node position needs it); 0: not set, each draw computes
                                it (a table filled by other means) */
} hd_eps_table;

/* Builds a table by direct sampling (samples per node, sorted, empirical quantiles).  The
 * sampler fixes gamma, step, adapt and richardson; with richardson the node quantiles are the
 * quantile-level extrapolation 2 Q_fine - Q_coarse of paired paths (hd_eps_sample_pair; ~5x the
 * build time), made nondecreasing and >= 0, instead of quantiles of per-path Richardson samples.
 * Returns HD_OK, HD_EINPUT or HD_ENOMEM. */
int hd_eps_table_build(hd_eps_table **out, hd_eps_sampler *s, double beta_min, double beta_max,
                       int nbeta, int nu, long samples, gsl_rng *rng, hd_error *err);

/* One more node for table t at beta, built as hd_eps_table_build builds its nodes (t->samples
 * draws from s, t->nu quantiles; s must have the options t was built with) into row (t->nu
 * doubles), from rng.  Not scaled by any balance.  HD_OK or HD_ENOMEM. */
int hd_eps_table_row(const hd_eps_table *t, hd_eps_sampler *s, double beta, double *row,
                     gsl_rng *rng, hd_error *err);

/* Q(u) of one quantile row of nu >= 2 entries at u_j = j/(nu-1): linear in u, clamped to the
 * row's ends (a table node's inverse CDF). */
double hd_eps_row_quantile(const double *row, int nu, double u);

/* Frees a table.  NULL is allowed. */
void hd_eps_table_free(hd_eps_table *t);

/* An empty table of nbeta x nu nodes (q not set, the other fields 0), or NULL when out of
 * memory; for a reader that fills it (db/hd_epsdb.c).  Free with hd_eps_table_free. */
hd_eps_table *hd_eps_table_alloc(int nbeta, int nu);

/* beta_k of node k < nbeta: beta_min (beta_max/beta_min)^(k/(nbeta-1)). */
double hd_eps_table_beta(const hd_eps_table *t, int k);

/* One eps from the table: u ~ U(0,1), Q linear in u within a node and linear in ln beta between
 * nodes (same u).  Below beta_min the beta_min node is used as is (p_beta has no simple scaling
 * there, docs/mc-eps.md); above beta_max, eps = g + (Q(beta_max) - g) sqrt(beta_max/beta) with
 * g = gamma_eff (the O(sigma) approach to the cold limit; beta = +inf gives g).  Returns NaN for a
 * NaN or non-positive beta. */
double hd_eps_table_sample(const hd_eps_table *t, double beta, gsl_rng *rng);

/* The inverse CDF of the table at (beta, u), u in [0,1], with the interpolation above. */
double hd_eps_table_quantile(const hd_eps_table *t, double beta, double u);

/* The table's detailed-balance moment M = int_0^inf E e^-E <eps^2>_T(beta = E) dE, the mean of
 * eps^2 of the table at beta = E over the collision-weighted law E ~ Exp(1) at T_B = 1 (eq. 19);
 * the exact p_beta has M = 1, i.e. F(1) = <E (1 - eps^2)> = 1 - M = 0 (docs/mc-eps.md 4b-4c;
 * the D of section 4b is M - 1).
 * <eps^2> is exact for the interpolation of hd_eps_table_quantile (piecewise linear in u and in
 * ln beta); the integral over E is gsl_integration_qags per node interval, relative error 1e-10.
 * Below beta_min the beta_min node counts (weight 5e-7); above beta_max the weight (< 1e-430 for
 * beta_max = 1e3) is left out.  Returns M, or NaN if the integration fails. */
double hd_eps_table_moment(const hd_eps_table *t);

/* Projects the table onto the detailed-balance identity: multiplies every node quantile by
 * c = 1/sqrt(M) (M of hd_eps_table_moment), so that the table's M - 1 becomes 0 to the quadrature's
 * precision.  This removes the one moment of the table's error (grid step and Monte Carlo noise)
 * that sets the rods ring's stationary kinetic energy; it is a correction toward eq. (19), not a
 * property of the sampler.  *scale (if not NULL) gets c.  HD_OK, or HD_EINPUT if M is not
 * finite and positive (the table is then unchanged). */
int hd_eps_table_balance(hd_eps_table *t, double *scale, hd_error *err);

#endif
