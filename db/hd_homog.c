/* hd_homog_detect: end of homogeneous cooling from the collision rate per sqrt(energy). */
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_homog.h"

hd_homog_opts hd_homog_defaults(void) {
  hd_homog_opts o = {0.1, 2000.0, 5, 3};
  return o;
}

int hd_homog_detect(const double *t, const double *coll, const double *e, size_t n,
                    const hd_homog_opts *o, hd_homog *out, hd_error *err) {
  if (n < 2) return hd_error_set(err, HD_EINPUT, "homogeneity: need >= 2 samples, got %zu", n);
  if (!(o->thr > 0) || !(o->min_coll >= 1) || o->n_ref < 1 || o->persist < 1)
    return hd_error_set(err, HD_EINPUT, "homogeneity: bad options");
  for (size_t i = 0; i < n; i++)
    if (!(e[i] > 0))
      return hd_error_set(err, HD_EINPUT, "homogeneity: energy <= 0 at sample %zu", i);
  out->n_end = n, out->detected = 0;
  out->t_end = t[n - 1];
  out->r0 = NAN, out->n_windows = 0, out->max_dev = 0;

  /* windows [start[w], end[w]] of sample indices, each >= min_coll collisions */
  size_t *start = malloc(n * sizeof *start), *end = malloc(n * sizeof *end);
  double *r = malloc(n * sizeof *r), *tmp = malloc(n * sizeof *tmp);
  if (!start || !end || !r || !tmp) {
    free(start), free(end), free(r), free(tmp);
    return hd_error_set(err, HD_ENOMEM, "homogeneity: out of memory");
  }
  size_t nw = 0, s = 0;
  for (size_t i = 1; i < n; i++) {
    if (coll[i] - coll[s] >= o->min_coll && t[i] > t[s]) {
      double rate = (coll[i] - coll[s]) / (t[i] - t[s]);
      start[nw] = s, end[nw] = i;
      r[nw] = rate / sqrt(sqrt(e[s] * e[i])); /* geometric mean of E at the window ends */
      nw++;
      s = i;
    }
  }
  out->n_windows = nw;
  if (nw >= (size_t)(o->n_ref + o->persist)) {
    for (int k = 0; k < o->n_ref; k++) tmp[k] = r[k];
    gsl_sort(tmp, 1, (size_t)o->n_ref);
    double r0 = gsl_stats_median_from_sorted_data(tmp, 1, (size_t)o->n_ref);
    out->r0 = r0;
    int run = 0;
    for (size_t w = 0; w < nw; w++) {
      double dev = fabs(r[w] / r0 - 1.0);
      if (dev > o->thr) {
        if (++run >= o->persist) {
          size_t first = w + 1 - (size_t)o->persist;
          out->detected = 1;
          out->n_end = start[first] + 1; /* the deviating window's first sample is kept */
          break;
        }
      } else {
        run = 0;
      }
    }
    for (size_t w = 0; w < nw && end[w] < out->n_end; w++)
      out->max_dev = fmax(out->max_dev, fabs(r[w] / r0 - 1.0));
  }
  out->t_end = t[out->n_end - 1];
  free(start), free(end), free(r), free(tmp);
  return HD_OK;
}

hd_hcs_opts hd_hcs_defaults(void) {
  hd_hcs_opts o = {5.0, 5.0, 10.0};
  return o;
}

int hd_hcs_detect(const double *cpd, const double *s_perp, const double *flow_frac,
                  const double *flow_chaos, size_t n, const hd_hcs_opts *o, hd_hcs *out,
                  hd_error *err) {
  if (n < 1) return hd_error_set(err, HD_EINPUT, "HCS window: no samples");
  if (!(o->cpd_skip >= 0) || !(o->block_cpd > 0) || !(o->s_end > 0))
    return hd_error_set(err, HD_EINPUT, "HCS window: bad options");
  memset(out, 0, sizeof *out);
  size_t i0 = 0;
  while (i0 < n && cpd[i0] < o->cpd_skip) i0++;
  if (i0 == n) /* no window: not moved to the last sample, which nobody asked for */
    return hd_error_set(err, HD_EINPUT,
                        "HCS window: the transient cut (--cpd-skip %g) is past the run's last "
                        "sample (cpd %g)",
                        o->cpd_skip, cpd[n - 1]);
  out->n_start = i0, out->n_end = n;
  out->s_perp = out->flow_excess = NAN;
  for (size_t i = i0; i < n; i++) out->have |= !isnan(s_perp[i]);
  if (!out->have) return HD_OK;
  for (size_t b = i0; b < n;) { /* block [b, e) */
    size_t e = b, m = 0;
    double sum = 0;
    while (e < n && (e == b || cpd[e] - cpd[b] < o->block_cpd)) {
      if (!isnan(s_perp[e])) sum += s_perp[e], m++;
      e++;
    }
    if (e == n && cpd[n - 1] - cpd[b] < o->block_cpd) break; /* a short last block says little */
    if (m > 0 && sum / (double)m > o->s_end) {
      out->ended = 1;
      out->n_end = b + 1 > i0 + 1 ? b + 1 : i0 + 1; /* the block's first sample is kept */
      break;
    }
    b = e;
  }
  double ss = 0, fe = 0;
  size_t ms = 0, mf = 0;
  for (size_t i = out->n_start; i < out->n_end; i++) {
    if (!isnan(s_perp[i])) ss += s_perp[i], ms++;
    if (!isnan(flow_frac[i]) && !isnan(flow_chaos[i])) fe += flow_frac[i] - flow_chaos[i], mf++;
  }
  out->s_perp = ms ? ss / (double)ms : NAN;
  out->flow_excess = mf ? fe / (double)mf : NAN;
  return HD_OK;
}

int hd_hcs_window_find(const double *t, const double *coll, const double *e, const double *cpd,
                       const double *s_perp, const double *flow_frac, const double *flow_chaos,
                       size_t n, const hd_homog_opts *ho, const hd_hcs_opts *hc, hd_hcs_window *w,
                       hd_error *err) {
  memset(w, 0, sizeof *w);
  if (n < 1) return hd_error_set(err, HD_EINPUT, "HCS window: no samples");
  if (!(ho->thr > 0) || !(ho->min_coll >= 1) || ho->n_ref < 1 || ho->persist < 1 ||
      !(hc->cpd_skip >= 0) || !(hc->block_cpd > 0) || !(hc->s_end > 0))
    return hd_error_set(err, HD_EINPUT, "HCS window: bad options");
  size_t nu = n, n0 = 0;
  hd_error e2;
  if (hd_homog_detect(t, coll, e, n, ho, &w->homog, &e2) != HD_OK) {
    snprintf(w->why, sizeof w->why, "%.150s", e2.msg);
  } else {
    w->homog_ok = 1;
    nu = w->homog.n_end;
    if (w->homog.detected) w->end = HD_HCS_END_RATE;
  }
  /* a run that ends within the transient: an explicit cpd_skip past its end is refused; the
   * default one (the run layer's stored window, and analyses that did not ask) starts the
   * window at the last sample, 3 samples before the end below: a short window (its fit flagged
   * `short`, its errors empty: hd_run_fit_do) */
  hd_hcs_opts hc2 = *hc;
  if (!(cpd[n - 1] >= hc->cpd_skip)) {
    if (hc->cpd_skip != hd_hcs_defaults().cpd_skip)
      return hd_error_set(err, HD_EINPUT,
                          "HCS window: --cpd-skip %g is past the run's last sample (cpd %g): no "
                          "sample after the transient; give a smaller --cpd-skip, or --no-detect",
                          hc->cpd_skip, cpd[n - 1]);
    hc2.cpd_skip = cpd[n - 1];
  }
  if (hd_hcs_detect(cpd, s_perp, flow_frac, flow_chaos, n, &hc2, &w->hcs, &e2) != HD_OK) {
    snprintf(w->why, sizeof w->why, "%.150s", e2.msg);
  } else {
    w->hcs_ok = 1;
    n0 = w->hcs.n_start;
    if (w->hcs.n_end < nu) nu = w->hcs.n_end;
    if (w->hcs.ended) w->end = HD_HCS_END_SPERP; /* even where the rate ended the window first */
  }
  if (nu < n0 + 3) n0 = nu > 3 ? nu - 3 : 0; /* too short a window: the fit starts earlier */
  w->n_start = n0, w->n_end = nu;
  return HD_OK;
}

int hd_hcs_opts_default(const hd_homog_opts *ho, const hd_hcs_opts *hc) {
  hd_homog_opts h = hd_homog_defaults();
  hd_hcs_opts c = hd_hcs_defaults();
  return ho->thr == h.thr && ho->min_coll == h.min_coll && ho->n_ref == h.n_ref &&
         ho->persist == h.persist && hc->cpd_skip == c.cpd_skip && hc->block_cpd == c.block_cpd &&
         hc->s_end == c.s_end;
}
