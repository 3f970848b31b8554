/* fmean: the mean orientation factor <f> of dimer-dimer collisions and the paper's effective
 * dimension D_e = D/<f> (Costantini et al. 2005, eq. 36-40, Fig. 4), for any elongation a/d,
 * under three models of the contact-angle distribution:
 *
 *   heuristic  the paper's assumption: theta_1, theta_2 independent, uniform on
 *              [-theta_max, theta_max] (theta_max from hd_fmean_theta_max); also by quadrature.
 *   exclusion  uniform over all non-overlapping contact configurations of two dimers.
 *   collision  exclusion configurations weighted by the rate at which contacts are entered in
 *              a dilute elastic gas at equipartition (Maxwellian V, omega; weight max(0, -v_n)).
 *
 * Angles follow DESIGN.md: theta is the signed angle from a dimer's outward axis at its
 * contacting disk (partner disk -> contacting disk) to the contact normal (contacting disk ->
 * other dimer's contacting disk); f = 1 / (2 - (cos^2 theta_1 + cos^2 theta_2)/2).
 * Units: disk diameter d, disk mass m = 1, temperature T = 1.  docs/mc-fmean.md has the
 * derivations and the discussion of the D_e normalisation. */
#ifndef HD_FMEAN_H
#define HD_FMEAN_H

#include <gsl/gsl_rng.h>
#include <stddef.h>

#include "hd_body.h"
#include "hd_error.h"

/* The contact-angle model. */
typedef enum hd_fmean_model {
  HD_FMEAN_HEURISTIC = 0, /* independent uniform angles on [-theta_max, theta_max] */
  HD_FMEAN_EXCLUSION = 1, /* uniform non-overlapping contact configurations */
  HD_FMEAN_COLLISION = 2  /* exclusion configurations weighted by the contact entry rate */
} hd_fmean_model;

/* Options of one Monte Carlo estimate.  hd_fmean_opts_default fills the defaults. */
typedef struct hd_fmean_opts {
  hd_fmean_model model;   /* which distribution of the contact angles */
  double a_over_d;        /* elongation a/d, > 0 and finite */
  double dim;             /* D in D_e = D/<f>; 2 (the paper's) by default, > 0 */
  unsigned long samples;  /* accepted samples to draw; 0 means: sample until `seconds` elapse */
  double seconds;         /* wall-clock budget when samples == 0 (> 0); ignored otherwise */
  unsigned long seed;     /* seed of the gsl_rng_mt19937 stream */
  int no_partner_partner; /* exclusion/collision only: if nonzero, do not reject overlaps of
                             A's partner disk with B's partner disk (a test switch: the model
                             then factorises into the heuristic one) */
  const hd_shape *shape;  /* NULL: two dimers of a_over_d (the paper's case, above).  Else two
                             bodies of this shape (any rigid cluster, hd_body.h), the contacts
                             drawn by hd_fmean_sample_shape and f, mu and vn taken from the
                             engine's own rule (hd_pair_info, hd_side_inv_mass); a_over_d is
                             then ignored and the heuristic model has no quadrature */
} hd_fmean_opts;

/* The result of one estimate.  Fields that do not apply to the model are NaN. */
typedef struct hd_fmean_result {
  double f_mean;     /* <f>: plain mean (heuristic, exclusion) or rate-weighted ratio (collision) */
  double f_stderr;   /* its standard error: sd/sqrt(N), or the ratio estimator's delta method */
  double d_e;        /* the paper's D_e = dim / f_mean */
  double d_e_stderr; /* dim * f_stderr / f_mean^2 (first-order error propagation) */
  unsigned long samples; /* accepted configurations used (collision: receding ones included,
                            with weight 0) */
  unsigned long tried;   /* configurations drawn, rejected ones included */
  double seconds;        /* wall-clock time of the sampling */
  double f_quad;         /* heuristic: <f> by GSL quadrature; NaN for the other models */
  double f_quad_abserr;  /* heuristic: the quadrature's error estimate; NaN otherwise */
  double fvn2;           /* collision: <f v_n^2>_coll in units T/m (exactly 2 for a Maxwellian
                            at equipartition, see docs); with a shape: <mu_eff v_n^2>_coll in
                            units of T (2 for any shape); NaN otherwise */
  double fvn2_stderr;    /* its delta-method standard error; NaN otherwise */
  double d_e_energy;     /* collision: the consistent effective dimension 4 E / (m <f v_n^2>_coll)
                            with E = 3T/2 per dimer (exactly 3); with a shape 4 E / <mu v_n^2>,
                            E = T (2 + [I > 0]) / 2 per body; NaN otherwise */
  double d_e_energy_stderr; /* its standard error; NaN otherwise */
} hd_fmean_result;

/* One row of a convergence study (hd_fmean_convergence). */
typedef struct hd_fmean_conv_row {
  unsigned long n;    /* samples per replicate */
  unsigned long reps; /* independent replicates at this n */
  double f_mc;        /* the first replicate's estimate of <f> */
  double f_stderr;    /* the first replicate's standard error sd/sqrt(n) */
  double abs_err;     /* |f_mc - quadrature| of the first replicate */
  double rms_err;     /* root mean square of (estimate - quadrature) over the replicates */
  double seconds;     /* wall-clock time of the first replicate */
} hd_fmean_conv_row;

/* The model's name ("heuristic", "exclusion", "collision"). */
const char *hd_fmean_model_name(hd_fmean_model model);

/* Fills opts with the defaults: heuristic, a/d = 1, dim = 2, 10^6 samples, seed 1. */
void hd_fmean_opts_default(hd_fmean_opts *opts);

/* The largest allowed |theta| at contact for elongation a/d > 0: the other dimer's contacting
 * disk must not overlap this dimer's partner disk, |d n + a u| >= d, i.e. cos theta >= -a/(2d):
 * pi - arccos(a/(2d)) for a < 2d, pi for a >= 2d.  Returns NaN for a/d <= 0 or NaN. */
double hd_fmean_theta_max(double a_over_d);

/* The orientation factor f = 1 / (2 - (cos^2 th1 + cos^2 th2)/2) of eq. 36. */
double hd_fmean_f(double th1, double th2);

/* <f> of the heuristic model by GSL quadrature: the inner integral over theta_2 done
 * analytically, the outer by gsl_integration_qag (relative tolerance 1e-12).  Sets *f and
 * *abserr (GSL's error estimate); returns HD_OK, HD_EINPUT for a/d <= 0, or HD_EPHYS if GSL
 * reports a failure. */
int hd_fmean_quadrature(double a_over_d, double *f, double *abserr);

/* Draws one contact configuration of two dimers (A's contacting disk at the origin, axis along
 * +x; contact normal and B's axis uniform) and sets the contact angles *th_a, *th_b in
 * (-pi, pi].  Returns 1 if no disk of A overlaps a disk of B other than the touching pair
 * (A's partner vs B's partner ignored when no_partner_partner), 0 if rejected.  If cfg is not
 * NULL it receives {normal angle, B's axis angle}. */
int hd_fmean_sample_contact(gsl_rng *rng, double a_over_d, int no_partner_partner, double *th_a,
                            double *th_b, double cfg[2]);

/* Draws one contact configuration of two bodies of shape sh, uniform over the configurations
 * in contact (the measure of the contact manifold: touching disks (i, j) with weight their
 * contact distance D_ij, contact normal and B's orientation uniform; A at the origin with
 * phi = 0, by rotational symmetry), into *A, *B (positions and orientations; velocities 0) and
 * the touching disks *ka, *kb.  Returns 1 if it is accepted: for exclusion (all = 1) no other
 * disk pair overlaps; for the heuristic (all = 0) only the touching disks are checked against
 * the other body's other disks (for a dimer: the paper's independent angles), 0 if rejected. */
int hd_fmean_sample_shape(gsl_rng *rng, const hd_shape *sh, int all, hd_kin *A, hd_kin *B, int *ka,
                          int *kb);

/* Runs one Monte Carlo estimate with opts and fills *res.  Returns HD_OK, or HD_EINPUT
 * (with err set) for invalid options, HD_ENOMEM if the RNG cannot be allocated, HD_EPHYS if
 * no configuration was accepted. */
int hd_fmean_run(const hd_fmean_opts *opts, hd_fmean_result *res, hd_error *err);

/* Convergence study of the heuristic Monte Carlo against its quadrature at a/d: rows at
 * n = 10^3, 10^4, ... while the projected total time stays within max_seconds (and n <= n_max
 * if n_max > 0), at most max_rows rows.  Replicates per row: max(1, 10^6 / n).  Fits
 * log(rms_err) = c + slope log(n) with gsl_fit_wlinear: log rms over R replicates is
 * log sigma + log(chi2_R/R)/2, so its bias (psi(R/2) + ln(2/R))/2 is subtracted and its variance
 * psi_1(R/2)/4 sets the weight.  Sets *slope and *slope_err (NaN if fewer than 2 rows).
 * Returns HD_OK, HD_EINPUT or HD_ENOMEM. */
int hd_fmean_convergence(double a_over_d, unsigned long seed, double max_seconds,
                         unsigned long n_max, hd_fmean_conv_row *rows, size_t max_rows,
                         size_t *n_rows, double *slope, double *slope_err, hd_error *err);

#endif
