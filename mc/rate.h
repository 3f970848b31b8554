/* rate: the low-density equilibrium collision frequency of hard bodies of one shape (any rigid
 * cluster of disks, hd_body.h; the paper's dimers in particular) from the molecular-chaos
 * integral over the exact excluded region, with equipartition (translational and rotational
 * Maxwell-Boltzmann velocities at one temperature T), by Monte Carlo (docs/mc-rate.md).
 *
 * Per body, nu = n sum_{ij} D_ij int dpsi int dphi_B / (2 pi) [no other disk pair overlaps]
 *                <(-g_n)_+>,
 * the flux of relative configurations into the excluded region of two bodies: B's disk j
 * touching A's disk i at contact distance D_ij with normal angle psi, B's orientation phi_B
 * (A's fixed by rotational invariance), the boundary arc length D_ij dpsi where no other disk
 * pair overlaps.  At a fixed configuration the normal relative velocity of the contact points g_n
 * is Gaussian with variance T / mu_eff (1/mu_eff = the two sides' 1/M + (rho x n)^2 / I: the
 * engine's hd_side_inv_mass), so <(-g_n)_+> = sqrt(T / mu_eff) / sqrt(2 pi) exactly (no
 * velocity sampling).  The reference is eq. (29)'s nu0 at low density in haff's convention:
 * nu0 = 2 sigma n sqrt(pi T / M), sigma = the shape's largest disk diameter, M its mass, T the
 * translational temperature; for disks the ratio is exactly 1. */
#ifndef HD_RATE_H
#define HD_RATE_H

#include "hd_body.h"
#include "hd_error.h"

/* Options of one estimate. */
typedef struct hd_rate_opts {
  const hd_shape *shape; /* both bodies' shape (hd_shape_dimer, hd_shape_cluster, ...) */
  unsigned long samples; /* configurations to draw (rejected ones count, with weight 0); 0: until
                          * `seconds` elapse */
  double seconds;        /* wall-clock budget when samples == 0 (> 0) */
  unsigned long seed;    /* gsl_rng_mt19937 seed */
} hd_rate_opts;

/* The result. */
typedef struct hd_rate_result {
  double ratio;           /* nu / nu0 (eq. 29, low density, sigma = shape->d, mass shape->mass) */
  double ratio_err;       /* its standard error sd/sqrt(N) */
  double k;               /* nu / n in units sigma sqrt(T / m_disk0) (the rate constant) */
  unsigned long samples;  /* configurations drawn */
  unsigned long accepted; /* of which no other disk pair overlapped (on the excluded boundary) */
  double seconds;         /* wall-clock time */
} hd_rate_result;

/* Runs one estimate.  Returns HD_OK, HD_EINPUT (no shape, samples == 1, or neither samples nor
 * seconds > 0), or HD_ENOMEM. */
int hd_rate_run(const hd_rate_opts *o, hd_rate_result *r, hd_error *err);

#endif
