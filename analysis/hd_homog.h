/* hd_homog: where homogeneous cooling ends, from the `samples` series alone.
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

#endif
