/* cli_grid: the common cpd grid on which `haff energy` (and `energy --by-species`) average the
 * runs of a group, and the interpolation of each run's series onto it.  Runs logged with
 * different samples_every, or of different lengths, are averaged at matching cpd, over the cpd
 * range that every run covers. */
#ifndef HD_CLI_GRID_H
#define HD_CLI_GRID_H

#include <stddef.h>

#include "hd_error.h"

/* A common grid: n cpd values, ascending and distinct, in [lo, hi]. */
typedef struct hd_cli_grid {
  size_t n;
  double *cpd;    /* malloc'd; hd_cli_grid_free */
  double lo, hi;  /* the range every run covers: the latest first cpd, the earliest last one */
  double longest; /* the largest last cpd of any run (> hi: the longer runs were cut at hi) */
} hd_cli_grid;

/* The grid of m runs, run k's samples at cpd[k][0..n[k]) (ascending; NaN entries are skipped):
 * the distinct cpd values in [lo, hi] of the run with the most of them (the finest sampling;
 * the first such run on a tie).  HD_EINPUT (err says why) when a run has no finite cpd or the
 * runs share no range (lo > hi); HD_ENOMEM. */
int hd_cli_grid_make(const double *const *cpd, const size_t *n, size_t m, hd_cli_grid *g,
                     hd_error *err);
void hd_cli_grid_free(hd_cli_grid *g);

/* The value at cpd c of a run's series y (y[i * stride] belongs to x[i]; x ascending, NaN
 * entries skipped, lo <= c <= hi of its grid).  At a sample's own cpd its value exactly (the
 * first sample of a repeated cpd); between two samples linear in cpd, or with logy (y > 0 at
 * both ends) linear in ln y: an energy that cools by Haff's law is exp(-(1 - alpha^2) cpd /
 * D_e), linear in cpd in the log, so the log interpolation is exact for it and the linear one
 * is biased up by the curvature.  *hint: the index to search from (0 at first, then the last
 * call's, for ascending c).  NaN when c is outside the series. */
double hd_cli_interp(const double *x, const double *y, size_t stride, size_t n, double c, int logy,
                     size_t *hint);

#endif
