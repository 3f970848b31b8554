/* hd_runfit: the per-run analysis behind `haff haff-fit`, `table1`, `table2` and `energy`
 * (detect the homogeneous part, fit eq. 31 to it, fit K = e_tr/e_rot = a0 + a1 cpd), and the
 * grouping of runs with equal scene parameters (species, alpha, a/d) into ensembles. */
#ifndef HD_RUNFIT_H
#define HD_RUNFIT_H

#include <sqlite3.h>
#include <stddef.h>

#include "hd_anadb.h"
#include "hd_error.h"
#include "hd_fit.h"
#include "hd_homog.h"

/* What part of a run the fits use. */
typedef struct hd_fit_opts {
  hd_homog_opts homog; /* detector settings */
  int detect;          /* 1 [default]: stop at the end of homogeneous cooling (hd_homog) */
  double cpd_max;      /* > 0: also stop at this cpd [0: no limit] */
  double cpd_min_k;    /* the K fit skips samples with cpd < this (initial transient) [0] */
  double level;        /* confidence level of the K intervals [0.99] */
  hd_hcs_opts hcs;     /* the HCS window from the state measures (used when detect = 1) */
  double s_flag;       /* a group whose window-mean s_perp exceeds this is flagged [2.5] */
  double min_window;   /* ... and one whose HCS ended within this many cpd of its start [40] */
  int stored;          /* 1 [default]: a run's stored window (runs.hcs_*) is used when the
                        * detection options (homog, hcs) are the defaults; 0: always recomputed */
  double reject_z;     /* a run whose eq. (31) D_e is more than this many robust standard
                        * deviations from its group's median is rejected (hd_group_outliers)
                        * [HD_FIT_REJECT_Z]; 0: none is */
} hd_fit_opts;

/* Where a run's window came from (hd_run_fit.window). */
enum {
  HD_WINDOW_WHOLE = 0,   /* detect = 0: the whole run */
  HD_WINDOW_STORED = 1,  /* runs.hcs_* as the run stored it (hd_db_run_hcs) */
  HD_WINDOW_COMPUTED = 2 /* found now from the samples (options not the defaults, or no stored
                          * window: a file from before, or a run still going) */
};

/* The shortest window the eq. (31) fit is trusted on (docs/analysis.md, "Short windows: the
 * rule").  Measured: 12 runs of 400 dimers (a = d, alpha = 0.9, area fraction 0.05, a sample
 * every 0.1 cpd), windows from cpd 5 of 1 to 50 cpd: while E decays by less than a factor e over
 * the window, eq. (31)'s D_e over the seeds is biased (0.34 and 0.69 at 1 and 2 cpd, against
 * 3.05) or scatters by 50-450 % of itself (3 to 10 cpd), its formal error 10-100 times below
 * that; from one e-fold on (15-20 cpd there) the scatter falls to 20 %, 14 %, 6.5 %, 3.6 %, 2.6 %
 * at ln(E0/E) = 0.93, 1.25, 1.56, 2.2, 3.1. */
#define HD_FIT_MIN_DECAY 1.0  /* ln(E_start / E_end) over the window, alpha < 1 */
#define HD_FIT_MIN_SAMPLES 10 /* samples in the window (any alpha) */

/* The fewest window samples whose per-run fit errors are printed (docs/analysis.md, "Short
 * windows: the errors"); fewer: D_e_err, nu0_err, chi2 (so ratio_err and chi2/dof) are NaN,
 * printed empty.  eq. (31)'s first sample is its origin (t = 0, tau = 0), which the model
 * passes through whatever D_e and nu0 are: n samples give n - 1 residuals that constrain it
 * and n - 3 degrees of freedom (n = 3: none; the curve passes through every point, chi2/dof
 * 1e-25 and errors 1e-12).  A standard error needs residuals to estimate the scatter from, and
 * the autocorrelation time the per-run line fits correct their errors with (hd_tau_int, for
 * D_e_slope_err and K) is not estimated below 4 residuals (it returns 0.5, "independent"): so
 * 4 informative residuals, n >= 5, 2 degrees of freedom.  D_e_slope_err, a line through all m
 * window samples: m >= 4 likewise, and n_eff >= 3 (its autocorrelation-corrected dof n_eff - 2
 * at least 1 without hd_fit_linear_t's clamp to 1). */
#define HD_FIT_ERR_MIN_SAMPLES 5

/* Runs a group rejects (docs/analysis.md, "Outlier runs: the rule"): |D_e - median| > z s, s =
 * 1.4826 MAD of the D_e of the group's fitted runs (the standard deviation of a normal sample),
 * tested when the group has at least HD_FIT_REJECT_MIN such runs.  Measured on the default
 * build's 1499 tested runs in 22 groups: apart from 3 runs the largest |z| is 5.15 (a group of
 * 8 runs, where the MAD is least certain; 4.0 in the groups of >= 16), 5 runs pass 3 (a normal
 * sample: 4); the 3 are at z = 7.2, 7.9 and 89, and are as far out in D_e_slope (z = +12 to
 * +36) and in the time their run took to its stop cpd (z = -11 to -22): near-collapse bursts,
 * collisions that race on and dissipate little.  z = 6 keeps a normal run with probability
 * 1 - 2e-9. */
#define HD_FIT_REJECT_Z 6.0
#define HD_FIT_REJECT_MIN 5
/* a group more than this fraction of whose tested runs are rejected is flagged `outliers`: its
 * bursts are no longer rare, and its D_e would depend on the rule */
#define HD_FIT_REJECT_FLAG 0.1

/* The defaults above. */
hd_fit_opts hd_fit_opts_defaults(void);

/* Everything measured on one run. */
typedef struct hd_run_fit {
  hd_run_info info;
  size_t n_samples;          /* rows in samples */
  size_t n_start;            /* first sample used by the fits (0 when detect = 0) */
  size_t n_used;             /* end of the samples used by the fits: [n_start, n_used) (an
                              * index; haff-fit's column n_used prints n_used - n_start, the
                              * samples in the window) */
  int window;                /* HD_WINDOW_*: where [n_start, n_used) came from (before cpd_max) */
  hd_homog homog;            /* rate/sqrt(E) detector result (n_end = n_samples when detect = 0) */
  hd_hcs hcs;                /* the state measures' HCS window (detect = 1; have = 0 otherwise) */
  double t_start, cpd_start; /* first sample used */
  double t_end, cpd_end;     /* last sample used */
  double E0;                 /* e_tr + e_rot of the first sample used */
  double T0;                 /* translational temperature of the first sample used (= e_tr in 2D) */
  double T0_avg;             /* the same from every sample of the window: the mean of
                              * e_tr (1 + gamma nu0 t)^2 (Haff's law with the eq. (31) fit's
                              * gamma, nu0; the mean of e_tr at alpha = 1); NaN without a fit */
  int slope_ok;              /* 1 if the ln E against cpd fit succeeded */
  double D_e_slope;          /* -(1 - alpha^2) / (slope of ln E against cpd): needs no nu0 */
  double D_e_slope_err;      /* its error from the residuals' autocorrelation-corrected OLS
                              * error; NaN with < HD_FIT_ERR_MIN_SAMPLES - 1 samples or n_eff < 3 */
  double D_e_half[2];        /* D_e_slope over the first and second half (in cpd) of the window
                              * (NaN if a half has < 3 samples): the window's systematic error */
  int haff_ok;               /* 1 if the eq. (31) fit succeeded */
  hd_haff_fit haff;          /* its result; D_e_err, nu0_err and chi2 NaN (unresolved) when
                              * the window has < HD_FIT_ERR_MIN_SAMPLES samples */
  double nu0_enskog;         /* eq. (29) for disks of diameter d, body mass, density n, T0_avg (T0
                              * without a fit), eta_disk */
  double ratio, ratio_err;   /* nu0_eff / nu0_enskog and its standard error */
  int K_ok;                  /* 1 if the K fit succeeded */
  hd_linfit K;               /* K = e_tr/e_rot = a0 + a1 cpd */
  int K_half_ok[2];          /* 1 if the K fit on the first / second half (in cpd) succeeded */
  hd_linfit K_half[2];       /* ... its result: the window's systematic error of a0, a1 */
  char why[256];             /* why a fit failed ("" if both succeeded) */
  double decay;              /* ln(E_start / E_end) over the window (NaN if an energy is <= 0) */
  int short_window;          /* 1: the window is too short for eq. (31): fewer than
                              * HD_FIT_MIN_SAMPLES samples, or alpha < 1 and decay <
                              * HD_FIT_MIN_DECAY.  Its D_e is printed, flagged `short`, and left
                              * out of the groups' means */
} hd_run_fit;

/* Reads the samples of ri and fills *out.  A failed fit is not an error (haff_ok/K_ok = 0 and
 * `why` says why); HD_EIO/HD_ENOMEM when the database cannot be read; HD_EINPUT when the run
 * has fewer than 3 samples. */
int hd_run_fit_do(sqlite3 *db, const hd_run_info *ri, const hd_fit_opts *o, hd_run_fit *out,
                  hd_error *err);

/* A group of runs of one ensemble: the same species, alpha and a/d (equal to 1e-9), number of
 * bodies, disk diameter and mass, and number density (equal to 1e-9 relative), and the same
 * bodies and collision rule (hd_ana_same_physics: rough or smooth, beta, q, the shapes of named
 * species, every pair's restitution, the walls' alpha).  Runs that differ only in N or density
 * used to be pooled into one Table I row (an average of two different ensembles), as did runs
 * that differ in roughness, shape or wall restitution; they now form groups of their own with
 * the same (alpha, a/d) label (hd_group_same_label, hd_group_differ). */
typedef struct hd_group {
  int species;                  /* hd_run_info.species of its runs */
  int mixture;                  /* and their mixture flag */
  int walls;                    /* and their walls flag */
  char label[HD_ANA_LABEL_MAX]; /* and their label (hd_run_info.label) */
  double alpha, a_over_d;
  long nbodies;      /* N of the species */
  double density;    /* its number density (hd_run_info.density) */
  double d, m;       /* disk diameter and mass */
  int rough;         /* its runs' hd_run_info.rough: eq. (31) does not describe them (flag rough) */
  hd_run_info first; /* its first run's info (the physics every run shares) */
  size_t n;          /* runs in the group */
  size_t *idx;       /* their indices in the array given to hd_group_runs */
} hd_group;

/* Groups fits[0..n-1] (in order of first appearance).  *groups malloc'd; hd_groups_free. */
/* Whether groups a and b carry the same (species, alpha, a/d) label, so that a table cannot tell
 * them apart (they differ in N, density, d, m or physics, or are dimers of [dimers] and of a
 * named species: hd_run_info.named_dimers). */
int hd_group_same_label(const hd_group *a, const hd_group *b);
int hd_group_runs(const hd_run_fit *fits, size_t n, hd_group **groups, size_t *ng, hd_error *err);
/* What groups a and b of the same label differ in, into buf: some of "N", "density", "d", "m",
 * "roughness (beta, q)", "shapes", "restitutions", "walls' alpha", "species label",
 * comma-separated. */
void hd_group_differ(const hd_group *a, const hd_group *b, char *buf, size_t len);
void hd_groups_free(hd_group *g, size_t ng);

/* The ensemble's D_e with its statistical and systematic errors (docs/analysis.md, "Errors of
 * D_e").  Every mean below is over the group's fitted runs, every *_err its standard error. */
typedef struct hd_group_fit {
  size_t m;            /* runs whose eq. (31) fit succeeded */
  double D_e, D_e_err; /* eq. (31) on the HCS windows */
  double nu0, nu0_err, ratio, ratio_err;
  double D_e_slope, D_e_slope_err; /* the slope of ln E against cpd */
  double sys_window;         /* half the drift D_e(second half) - D_e(first half), less its noise */
  double sys_est;            /* |eq. (31) - slope| less its noise */
  double sys_box;            /* D_e |flow_resolved|: the correlated flow's bias (NaN when the
                              * flow excess is not resolved, or without state measures) */
  double D_e_sys;            /* sqrt of the sum of the three squares (NaN terms count 0) */
  double cpd_start, cpd_end; /* mean window */
  double s_perp;             /* mean window s_perp (NaN without state measures) */
  size_t ended;              /* runs whose HCS ended within min_window cpd of its start */
  int flagged;               /* HD_FLAG_* bits: inhomogeneous (s_perp > s_flag, or most runs
                              * ended early), short (most runs' windows too short, or none
                              * left to fit: hd_run_fit.short_window); 0 if none */
  size_t n_short;            /* runs left out for a short window (hd_run_fit.short_window) */
  size_t n_rejected;         /* runs left out as outliers (hd_group_outliers) */
  int measured;              /* 1 if the runs carry state measures (else no flag can be given) */
  double flow_excess;        /* mean window flow_frac - flow_chaos (NaN without state measures) */
  double flow_resolved;      /* its part that its standard error se does not explain:
                              * sign(fx) sqrt(fx^2 - se^2) when |fx| > 2 se, else NaN (not
                              * resolved from zero, so sys_box and K's box are not measured) */
} hd_group_fit;

/* hd_group_fit.flagged bits. */
enum { HD_FLAG_INHOMOG = 1, HD_FLAG_SHORT = 2, HD_FLAG_OUTLIERS = 4, HD_FLAG_ROUGH = 8 };
/* HD_FLAG_ROUGH is a caveat, not a reason to leave a group out of a table: its bodies are rough
 * (hd_run_info.rough), and eq. (31)'s D_e, Haff's law of smooth bodies, is a fit parameter for
 * them (docs/analysis.md, "Rough bodies"). */

/* The flag column's text for bits: "" or the names of the bits set, comma-separated, in the
 * order inhomogeneous, short, outliers, rough. */
const char *hd_group_flag_name(int flagged);

/* The outlier rule (HD_FIT_REJECT_Z): of group g's runs whose eq. (31) fit succeeded on a window
 * that is not short, those whose D_e is more than o->reject_z robust standard deviations (1.4826
 * MAD) from the median of theirs get out[k] = 1 (k indexes g->idx; 0 for every other run).
 * Nothing is rejected when fewer than HD_FIT_REJECT_MIN runs are tested, when o->reject_z <= 0
 * or when the MAD is 0.  Returns the number rejected; *tested (if not NULL) the number tested
 * (0 when the rule did not apply). */
size_t hd_group_outliers(const hd_run_fit *fits, const hd_group *g, const hd_fit_opts *o,
                         unsigned char *out, size_t *tested);

/* Fills *out for the runs fits[g->idx[..]] with the rules of o (s_flag, min_window).  Runs whose
 * window is short (hd_run_fit.short_window) are left out of every mean and counted in n_short;
 * so are outliers (hd_group_outliers), counted in n_rejected (flag `outliers` when they are more
 * than HD_FIT_REJECT_FLAG of the runs tested).
 * A systematic term that its own noise explains (|d| <= 2 se) was not measured: NaN, as is
 * sys_box without state measures, and D_e_sys when no term was measured. */
void hd_group_fit_do(const hd_run_fit *fits, const hd_group *g, const hd_fit_opts *o,
                     hd_group_fit *out);

/* Ensemble of one quantity over runs: the mean of vals[0..n-1] and its standard error
 * sd/sqrt(n) (n >= 2); with n == 1, vals[0] and NaN: one run has no ensemble error, and the
 * eq. (31) fit's own error is formal, 10-25 times below the scatter between runs (it used to
 * be returned here; docs/analysis.md); n == 0: NaN, NaN. */
void hd_ensemble_mean(const double *vals, size_t n, double *mean, double *se);

/* Systematic errors of a group's K = a0 + a1 cpd (docs/analysis.md, "Errors of K"), for a0
 * ([0]) and a1 ([1]); each term the part of a measured difference its standard error does not
 * explain, as for D_e_sys. */
typedef struct hd_k_sys {
  size_t mh;     /* runs with both half-window K fits */
  double win[2]; /* half the mean (second half - first half) of a0 and of a1 over the runs, less
                  * its noise; NaN when the noise explains it (not measured) */
  double box[2]; /* correlated flow counted in e_tr: |a0 + 1| |fx| and |a1| |fx|, fx = the
                  * group's resolved flow excess (hd_group_fit.flow_resolved; NaN when it is
                  * not resolved or there are no state measures: not measured) */
  double sys[2]; /* sqrt(win^2 + box^2) over the terms measured; NaN if neither was */
} hd_k_sys;

/* Fills *out from the runs fits[idx[0..n)] (their K_half fits), the combined a0, a1 (a[0],
 * a[1]) and the group's resolved flow excess fx (hd_group_fit.flow_resolved, NaN if none). */
void hd_k_sys_do(const hd_run_fit *fits, const size_t *idx, size_t n, const double a[2], double fx,
                 hd_k_sys *out);

/* How table2 combines the K fits of the runs of a group. */
typedef enum hd_kmode {
  HD_K_AC = 0,  /* inverse-variance mean with autocorrelation-corrected errors [default] */
  HD_K_OLS = 1, /* the same with plain OLS errors (the paper's t-test, too narrow) */
  HD_K_RUNS = 2 /* plain mean over runs, sd/sqrt(R), t with R-1 dof (needs R >= 2) */
} hd_kmode;

/* Combined a0 and a1 with their intervals at fits[idx[0..n-1]].K's level.  Returns HD_OK or
 * HD_EINPUT (no K fit, or HD_K_RUNS with fewer than 2 runs). */
int hd_combine_k(const hd_run_fit *fits, const size_t *idx, size_t n, hd_kmode mode, double level,
                 double out[6], hd_error *err);

#endif
