/* hd_homog: where homogeneous cooling ends, from the `samples` series alone.  Pure numerics on
 * arrays (no database): the run layer stores each run's window with it at the run's end
 * (runs.hcs_*, hd_db_run_hcs) and the analyses (analysis/hd_runfit.c) use the same code.
 * In the homogeneous cooling state Haff's law (eq. 27) and the collision count (eq. 31) give a
 * collision rate per particle d(cpd)/dt = nu0 sqrt(T/T0): the ratio
 *     r = (d cpd / dt) / sqrt(E)        (E = e_tr + e_rot, the energy per body)
 * is constant whatever D_e and nu0 are.  Clustering raises it (g(sigma) grows in the clusters),
 * a shear/vortex flow lowers it (flow energy counts in E but causes no collisions).  The
 * detector cuts the series into windows of at least `min_coll` pair collisions, takes r0 as the
 * median of r over the first `n_ref` windows and declares the end of homogeneous cooling at the
 * start of the first run of `persist` consecutive windows with |r/r0 - 1| > thr. */
#ifndef HD_HOMOG_H
#define HD_HOMOG_H

#include <stddef.h>

#include "hd_error.h"

/* Options of hd_homog_detect. */
typedef struct hd_homog_opts {
  double thr;      /* relative deviation of r that ends homogeneity [0.1] */
  double min_coll; /* pair collisions per window [2000]: relative noise of r ~ 1/sqrt(min_coll) */
  int n_ref;       /* windows for the reference r0 [5] */
  int persist;     /* consecutive deviating windows needed [3] */
} hd_homog_opts;

/* Result of hd_homog_detect. */
typedef struct hd_homog {
  size_t n_end;     /* samples [0, n_end) are homogeneous (n if no end was found) */
  int detected;     /* 1 if the end was found before the last sample */
  double t_end;     /* t of the last homogeneous sample */
  double r0;        /* reference rate per sqrt(energy) */
  size_t n_windows; /* windows formed */
  double max_dev;   /* max |r/r0 - 1| over the homogeneous windows */
} hd_homog;

/* The defaults above. */
hd_homog_opts hd_homog_defaults(void);

/* Runs the detector on n samples (t ascending, coll = pair collisions so far, e = energy per
 * body, all > 0 after the first).  Fewer than n_ref + persist windows: nothing is detected and
 * n_end = n.  Returns HD_OK or HD_EINPUT (n < 2, bad options, non-positive energy). */
int hd_homog_detect(const double *t, const double *coll, const double *e, size_t n,
                    const hd_homog_opts *o, hd_homog *out, hd_error *err);

/* The homogeneous cooling state's window from the state measures of `samples` (schema 2):
 * it starts after the initial transient (cpd >= cpd_skip: the velocity distribution relaxes
 * from the initial Maxwellian to the HCS's within a few cpd, and eq. 31 fitted across it is
 * biased up) and ends where the box's shear modes have grown: at the start of the first block
 * of samples (spanning >= block_cpd) whose mean s_perp (the transverse momentum structure factor
 * at the box's smallest wave vectors, 1 without correlations) exceeds s_end.  docs/analysis.md,
 * "The HCS window". */
typedef struct hd_hcs_opts {
  double cpd_skip;  /* transient left out [5] */
  double block_cpd; /* cpd per block of s_perp [5] */
  double s_end;     /* block mean of s_perp that ends the HCS [10] */
} hd_hcs_opts;

/* Result of hd_hcs_detect. */
typedef struct hd_hcs {
  int have;           /* 1 if the samples carry state measures (else only n_start is set) */
  size_t n_start;     /* first sample of the window (first with cpd >= cpd_skip) */
  size_t n_end;       /* samples [n_start, n_end) are in the window (n if it did not end) */
  int ended;          /* 1 if s_perp ended it before the last sample */
  double s_perp;      /* mean s_perp over the window */
  double flow_excess; /* mean over the window of flow_frac - flow_chaos: the fraction of the
                       * energy in correlated flow at the box's largest scales */
} hd_hcs;

/* The defaults above. */
hd_hcs_opts hd_hcs_defaults(void);

/* Finds the window on n samples (cpd ascending; s_perp, flow_frac, flow_chaos NaN where not
 * recorded).  Returns HD_OK or HD_EINPUT (n < 1, bad options, or no sample with cpd >=
 * cpd_skip: the window is not moved to the last sample). */
int hd_hcs_detect(const double *cpd, const double *s_perp, const double *flow_frac,
                  const double *flow_chaos, size_t n, const hd_hcs_opts *o, hd_hcs *out,
                  hd_error *err);

/* How a window ended (runs.hcs_end). */
enum {
  HD_HCS_END_NONE = 0,  /* it reaches the last sample */
  HD_HCS_END_SPERP = 1, /* s_perp's block mean passed s_end (hd_hcs_detect); the window may
                         * end earlier, where the rate detector fired */
  HD_HCS_END_RATE = 2   /* the rate/sqrt(E) detector ended it, s_perp did not */
};

/* The window the fits use: the state measures' (hd_hcs_detect) cut also by the rate/sqrt(E)
 * detector's end (hd_homog_detect), whichever ends first; a window of fewer than 3 samples is
 * moved to start 3 samples before its end (so that a line can be fitted).  A run whose last
 * sample is below cpd_skip: with the default cpd_skip (hd_hcs_defaults) its window is its last
 * 3 samples; with another cpd_skip it has none (HD_EINPUT, err says why). */
typedef struct hd_hcs_window {
  size_t n_start, n_end; /* samples [n_start, n_end), n_end - n_start >= min(n, 3) */
  int end;               /* HD_HCS_END_* */
  int homog_ok, hcs_ok;  /* 1 if each detector ran (0: bad input to it, e.g. energy <= 0) */
  hd_homog homog;        /* the rate detector's result (when homog_ok) */
  hd_hcs hcs;            /* the state measures' result (when hcs_ok) */
  char why[160];         /* "" or why a detector could not run */
} hd_hcs_window;

/* Runs both detectors on n samples (t, coll, cpd ascending; e the energy per body; the
 * measures NaN where not recorded) and combines them into *w.  A detector that cannot run
 * (its input is bad) leaves its bound out and says why in w->why.  Returns HD_OK, or
 * HD_EINPUT for n < 1, bad options, or a cpd_skip other than the default past the last sample
 * (err set). */
int hd_hcs_window_find(const double *t, const double *coll, const double *e, const double *cpd,
                       const double *s_perp, const double *flow_frac, const double *flow_chaos,
                       size_t n, const hd_homog_opts *ho, const hd_hcs_opts *hc, hd_hcs_window *w,
                       hd_error *err);

/* Whether the options are the defaults (the runs' stored windows used them). */
int hd_hcs_opts_default(const hd_homog_opts *ho, const hd_hcs_opts *hc);

#endif
