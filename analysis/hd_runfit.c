/* hd_runfit: per-run fits and ensembles of runs. */
#include "hd_runfit.h"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_sort_double.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_enskog.h"

hd_fit_opts hd_fit_opts_defaults(void) {
  hd_fit_opts o;
  o.homog = hd_homog_defaults();
  o.detect = 1;
  o.cpd_max = 0;
  o.cpd_min_k = 0;
  o.level = 0.99;
  o.hcs = hd_hcs_defaults();
  o.s_flag = 2.5;
  o.min_window = 40;
  o.stored = 1;
  o.reject_z = HD_FIT_REJECT_Z;
  return o;
}

int hd_run_fit_do(sqlite3 *db, const hd_run_info *ri, const hd_fit_opts *o, hd_run_fit *out,
                  hd_error *err) {
  memset(out, 0, sizeof *out);
  out->info = *ri;
  hd_series s;
  int rc = hd_ana_samples(db, ri->id, &s, err);
  if (rc) return rc;
  out->n_samples = s.n;
  if (s.n < 3) {
    hd_series_free(&s);
    return hd_error_set(err, HD_EINPUT, "run %lld: %zu samples, need >= 3", (long long)ri->id,
                        out->n_samples);
  }
  double *e = malloc(s.n * sizeof *e), *k = malloc(s.n * sizeof *k), *x = malloc(s.n * sizeof *x);
  if (!e || !k || !x) {
    rc = hd_error_set(err, HD_ENOMEM, "out of memory");
    goto done;
  }
  for (size_t i = 0; i < s.n; i++) e[i] = s.e_tr[i] + s.e_rot[i];
  size_t nu = s.n, n0 = 0;
  out->window = HD_WINDOW_WHOLE;
  if (o->detect && o->stored && ri->hcs_stored && hd_hcs_opts_default(&o->homog, &o->hcs)) {
    /* the window the run stored when it ended (runs.hcs_*): the same detection on the same
     * samples; recomputed below if it does not fit them (samples logged after it was stored) */
    size_t a = 0, b;
    while (a < s.n && s.cpd[a] < ri->hcs_cpd_start) a++;
    for (b = a; b < s.n && s.cpd[b] <= ri->hcs_cpd_end; b++) {
    }
    if (a < s.n && b > a && s.cpd[a] == ri->hcs_cpd_start && s.cpd[b - 1] == ri->hcs_cpd_end &&
        (ri->hcs_end != HD_HCS_END_NONE || b == s.n)) {
      out->window = HD_WINDOW_STORED;
      n0 = a, nu = b;
      out->homog.n_end = nu, out->homog.detected = ri->hcs_end == HD_HCS_END_RATE;
      out->homog.t_end = s.t[nu - 1], out->homog.r0 = NAN;
      out->hcs.have = !isnan(ri->hcs_s_perp);
      out->hcs.n_start = n0, out->hcs.n_end = nu;
      out->hcs.ended = ri->hcs_end == HD_HCS_END_SPERP;
      out->hcs.s_perp = ri->hcs_s_perp, out->hcs.flow_excess = ri->hcs_flow_excess;
    }
  }
  if (o->detect && out->window != HD_WINDOW_STORED) {
    hd_hcs_window w;
    hd_error e2;
    rc = hd_hcs_window_find(s.t, s.coll, e, s.cpd, s.s_perp, s.flow_frac, s.flow_chaos, s.n,
                            &o->homog, &o->hcs, &w, &e2);
    if (rc) {
      hd_error_set(err, rc, "run %lld: %s", (long long)ri->id, e2.msg);
      goto done;
    }
    out->window = HD_WINDOW_COMPUTED;
    if (w.why[0]) snprintf(out->why, sizeof out->why, "%.200s", w.why);
    if (w.homog_ok) out->homog = w.homog;
    if (w.hcs_ok) out->hcs = w.hcs;
    n0 = w.n_start, nu = w.n_end;
  } else if (!o->detect) {
    out->homog.n_end = s.n;
  }
  if (o->cpd_max > 0)
    while (nu > n0 + 1 && s.cpd[nu - 1] > o->cpd_max) nu--;
  if (o->detect && s.cpd[n0] < o->hcs.cpd_skip && !out->why[0])
    snprintf(out->why, sizeof out->why,
             "the window starts at cpd %g, before the transient's end (--cpd-skip %g): the run "
             "or its HCS is shorter than the transient, its last 3 samples are fitted",
             s.cpd[n0], o->hcs.cpd_skip);
  out->n_start = n0;
  out->n_used = nu;
  out->t_start = s.t[n0];
  out->cpd_start = s.cpd[n0];
  out->t_end = s.t[nu - 1];
  out->cpd_end = s.cpd[nu - 1];
  out->E0 = e[n0];
  out->T0 = s.e_tr[n0];
  out->decay = e[n0] > 0 && e[nu - 1] > 0 ? log(e[n0] / e[nu - 1]) : NAN;
  out->short_window =
      nu - n0 < HD_FIT_MIN_SAMPLES || (ri->alpha < 1 && !(out->decay >= HD_FIT_MIN_DECAY));
  /* eq. (31) from the window's first sample: t and cpd counted from there (Haff's law is the
   * same from any origin, with nu0 the rate there) */
  for (size_t i = n0; i < nu; i++) k[i - n0] = s.t[i] - s.t[n0], x[i - n0] = s.cpd[i] - s.cpd[n0];

  hd_error fe;
  if (isnan(ri->alpha)) {
    /* named species whose pairs collide with different restitutions: eq. (31) has one alpha */
    out->haff_ok = 0;
    snprintf(out->why, sizeof out->why,
             "no eq. 31 fit: the species' restitutions differ (alpha %g to %g), eq. 31 has one "
             "alpha; haff energy draws the decay",
             ri->alpha_lo, ri->alpha_hi);
  } else {
    out->haff_ok = hd_fit_haff_log(k, x, nu - n0, ri->alpha, &out->haff, &fe) == HD_OK;
    if (!out->haff_ok) snprintf(out->why, sizeof out->why, "eq. 31 fit: %.200s", fe.msg);
    /* too few samples for an error (HD_FIT_ERR_MIN_SAMPLES): the values stay, their errors
     * and chi2 are unresolved (NaN, printed empty), not a formal 1e-12 */
    if (out->haff_ok && nu - n0 < HD_FIT_ERR_MIN_SAMPLES)
      out->haff.D_e_err = out->haff.nu0_err = out->haff.chi2 = NAN;
  }
  /* T at the window's start from all its samples, not one: Haff's law T(t) = T0 / u(t)^2,
   * u = 1 + gamma nu0 t with the fit's gamma and nu0 (u = 1 at alpha = 1), so T0 is the mean of
   * e_tr u^2 over the window; one sample's T fluctuates by ~sqrt(2/N) */
  out->T0_avg = NAN;
  if (out->haff_ok && nu > n0) {
    double gam = ri->alpha < 1 ? (1 - ri->alpha * ri->alpha) / (2 * out->haff.D_e) : 0, sum = 0;
    for (size_t i = n0; i < nu; i++) {
      double u = 1 + gam * out->haff.nu0 * (s.t[i] - s.t[n0]);
      sum += s.e_tr[i] * u * u;
    }
    out->T0_avg = sum / (double)(nu - n0);
  }
  out->nu0_enskog = hd_enskog_nu0(ri->density, ri->d, isnan(out->T0_avg) ? out->T0 : out->T0_avg,
                                  ri->mass, ri->eta_disk);
  if (out->haff_ok && out->nu0_enskog > 0) {
    out->ratio = out->haff.nu0 / out->nu0_enskog;
    out->ratio_err = out->haff.nu0_err / out->nu0_enskog;
  } else {
    out->ratio = out->ratio_err = NAN;
  }
  /* the slope of ln E against cpd on the window and on its two halves */
  double g1 = 1 - ri->alpha * ri->alpha, mid = 0.5 * (s.cpd[n0] + s.cpd[nu - 1]);
  out->D_e_slope = out->D_e_slope_err = out->D_e_half[0] = out->D_e_half[1] = NAN;
  for (int h = -1; h < 2; h++) {
    size_t m = 0;
    for (size_t i = n0; i < nu; i++)
      if (e[i] > 0 && (h < 0 || (h == 0) == (s.cpd[i] <= mid))) x[m] = s.cpd[i], k[m++] = log(e[i]);
    hd_linfit lf;
    if (g1 > 0 && hd_fit_linear_t(x, k, m, 0.68, &lf, &fe) == HD_OK && lf.a1 < 0) {
      double D = -g1 / lf.a1;
      if (h < 0) /* its error: HD_FIT_ERR_MIN_SAMPLES's rule for a line */
        out->slope_ok = 1, out->D_e_slope = D,
        out->D_e_slope_err =
            m >= HD_FIT_ERR_MIN_SAMPLES - 1 && lf.n_eff >= 3 ? D * lf.a1_err_ac / -lf.a1 : NAN;
      else
        out->D_e_half[h] = D;
    }
  }
  size_t m = 0;
  for (size_t i = n0; i < nu; i++)
    if (s.cpd[i] >= o->cpd_min_k && s.e_rot[i] > 0)
      x[m] = s.cpd[i], k[m++] = s.e_tr[i] / s.e_rot[i];
  if (ri->rotates) {
    out->K_ok = hd_fit_linear_t(x, k, m, o->level, &out->K, &fe) == HD_OK;
    if (!out->K_ok && !out->why[0]) snprintf(out->why, sizeof out->why, "K fit: %.200s", fe.msg);
    /* the same fit on the two halves (in cpd) of its samples: K's window error */
    if (m >= 6) {
      double kmid = 0.5 * (x[0] + x[m - 1]);
      size_t h1 = 0;
      while (h1 < m && x[h1] <= kmid) h1++;
      out->K_half_ok[0] = hd_fit_linear_t(x, k, h1, o->level, &out->K_half[0], &fe) == HD_OK;
      out->K_half_ok[1] =
          hd_fit_linear_t(x + h1, k + h1, m - h1, o->level, &out->K_half[1], &fe) == HD_OK;
    }
  }
done:
  free(e), free(k), free(x);
  hd_series_free(&s);
  return rc;
}

/* x and y equal to 1e-9 relative (NaN equals NaN: runs whose density is unknown). */
static int rel_eq(double x, double y) {
  if (isnan(x) || isnan(y)) return isnan(x) && isnan(y);
  return fabs(x - y) <= 1e-9 * fmax(fabs(x), fabs(y));
}

/* x and y within 1e-9 (NaN equals NaN: a/d of shapes, alpha of mixed restitutions). */
static int abs_eq(double x, double y) {
  if (isnan(x) || isnan(y)) return isnan(x) && isnan(y);
  return fabs(x - y) < 1e-9;
}

int hd_group_same_label(const hd_group *a, const hd_group *b) {
  /* a table's dimer rows do not print the label: [dimers] and named dimers look alike there */
  int dimers = a->species == HD_KIND_DIMER && !a->mixture && !b->mixture;
  return a->species == b->species && a->walls == b->walls &&
         (dimers || !strcmp(a->label, b->label)) && abs_eq(a->alpha, b->alpha) &&
         abs_eq(a->a_over_d, b->a_over_d);
}

int hd_group_runs(const hd_run_fit *fits, size_t n, hd_group **groups, size_t *ng, hd_error *err) {
  *groups = calloc(n ? n : 1, sizeof **groups);
  *ng = 0;
  if (!*groups) return hd_error_set(err, HD_ENOMEM, "out of memory");
  for (size_t i = 0; i < n; i++) {
    const hd_run_info *r = &fits[i].info;
    hd_group *g = NULL;
    for (size_t j = 0; j < *ng && !g; j++) {
      const hd_group *q = &(*groups)[j];
      if (q->species == r->species && q->mixture == r->mixture && q->walls == r->walls &&
          !strcmp(q->label, r->label) && abs_eq(q->alpha, r->alpha) &&
          abs_eq(q->a_over_d, r->a_over_d) && q->nbodies == r->n && rel_eq(q->d, r->d) &&
          rel_eq(q->m, r->m) && rel_eq(q->density, r->density) && hd_ana_same_physics(&q->first, r))
        g = &(*groups)[j];
    }
    if (!g) {
      g = &(*groups)[(*ng)++];
      g->species = r->species, g->mixture = r->mixture, g->walls = r->walls, g->alpha = r->alpha;
      g->a_over_d = r->a_over_d;
      snprintf(g->label, sizeof g->label, "%s", r->label);
      g->nbodies = r->n, g->density = r->density, g->d = r->d, g->m = r->m;
      g->rough = r->rough, g->first = *r;
      g->idx = malloc(n * sizeof *g->idx);
      if (!g->idx) {
        hd_groups_free(*groups, *ng), *groups = NULL, *ng = 0;
        return hd_error_set(err, HD_ENOMEM, "out of memory");
      }
    }
    g->idx[g->n++] = i;
  }
  return HD_OK;
}

void hd_group_differ(const hd_group *a, const hd_group *b, char *buf, size_t len) {
  const hd_run_info *x = &a->first, *y = &b->first;
  const char *what[9] = {"N",
                         "density",
                         "d",
                         "m",
                         "roughness (beta, q)",
                         "shapes",
                         "restitutions",
                         "walls' alpha",
                         "species label"};
  int diff[9] = {a->nbodies != b->nbodies,
                 !rel_eq(a->density, b->density),
                 !rel_eq(a->d, b->d),
                 !rel_eq(a->m, b->m),
                 x->rough_key != y->rough_key,
                 x->shape_key != y->shape_key,
                 0,
                 !rel_eq(x->wall_alpha, y->wall_alpha),
                 strcmp(a->label, b->label) != 0};
  /* the restitutions' hash holds the walls' alpha too: a difference there alone is named so */
  diff[6] = x->coll_key != y->coll_key && !diff[7];
  size_t at = 0;
  if (len) buf[0] = 0;
  for (int k = 0; k < 9; k++)
    if (diff[k] && at < len) {
      int w = snprintf(buf + at, len - at, "%s%s", at ? ", " : "", what[k]);
      if (w > 0) at += (size_t)w;
    }
}

void hd_groups_free(hd_group *g, size_t ng) {
  for (size_t i = 0; g && i < ng; i++) free(g[i].idx);
  free(g);
}

/* sqrt(d^2 - se^2): the part of a mean difference d that its standard error se does not explain,
 * when d is resolved (|d| > 2 se); NaN otherwise (not measured: it was printed as 0, or as a
 * clipped 8e-08 when |d| was just above se) and for d NaN. */
static double excess(double d, double se) {
  double s2 = isnan(se) ? 0 : se * se;
  return isnan(d) || !(d * d > 4 * s2) ? NAN : sqrt(d * d - s2);
}

/* Sum of squares of the terms that are not NaN, or NaN if all are. */
static double quad_sum(const double *t, int n) {
  double s = 0;
  int k = 0;
  for (int i = 0; i < n; i++)
    if (!isnan(t[i])) s += t[i] * t[i], k++;
  return k ? sqrt(s) : NAN;
}

const char *hd_group_flag_name(int flagged) {
  static const char *const names[16] = {"",
                                        "inhomogeneous",
                                        "short",
                                        "inhomogeneous,short",
                                        "outliers",
                                        "inhomogeneous,outliers",
                                        "short,outliers",
                                        "inhomogeneous,short,outliers",
                                        "rough",
                                        "inhomogeneous,rough",
                                        "short,rough",
                                        "inhomogeneous,short,rough",
                                        "outliers,rough",
                                        "inhomogeneous,outliers,rough",
                                        "short,outliers,rough",
                                        "inhomogeneous,short,outliers,rough"};
  return names[flagged & 15];
}

size_t hd_group_outliers(const hd_run_fit *fits, const hd_group *g, const hd_fit_opts *o,
                         unsigned char *out, size_t *tested) {
  size_t n = g->n, m = 0, rej = 0;
  if (tested) *tested = 0;
  memset(out, 0, n);
  double *D = malloc(2 * (n ? n : 1) * sizeof *D);
  if (!D) return 0; /* no test: every run stays in (its scatter stays in the error) */
  for (size_t k = 0; k < n; k++) {
    const hd_run_fit *f = &fits[g->idx[k]];
    if (f->haff_ok && !f->short_window && !isnan(f->haff.D_e)) D[m++] = f->haff.D_e;
  }
  if (o->reject_z > 0 && m >= HD_FIT_REJECT_MIN) {
    double s = gsl_stats_mad(D, 1, m, D + n); /* 1.4826 MAD */
    gsl_sort(D, 1, m);
    double med = gsl_stats_median_from_sorted_data(D, 1, m);
    if (s > 0) {
      if (tested) *tested = m;
      for (size_t k = 0; k < n; k++) {
        const hd_run_fit *f = &fits[g->idx[k]];
        if (f->haff_ok && !f->short_window && !isnan(f->haff.D_e) &&
            fabs(f->haff.D_e - med) > o->reject_z * s)
          out[k] = 1, rej++;
      }
    }
  }
  free(D);
  return rej;
}

void hd_group_fit_do(const hd_run_fit *fits, const hd_group *g, const hd_fit_opts *o,
                     hd_group_fit *out) {
  memset(out, 0, sizeof *out);
  size_t n = g->n;
  double *v = malloc(11 * (n ? n : 1) * sizeof *v);
  if (!v) { /* every number NaN: the caller prints them as such */
    double nan = NAN;
    *out = (hd_group_fit){.D_e = nan,
                          .D_e_err = nan,
                          .nu0 = nan,
                          .nu0_err = nan,
                          .ratio = nan,
                          .ratio_err = nan,
                          .D_e_slope = nan,
                          .D_e_slope_err = nan,
                          .sys_window = nan,
                          .sys_est = nan,
                          .sys_box = nan,
                          .D_e_sys = nan,
                          .cpd_start = nan,
                          .cpd_end = nan,
                          .s_perp = nan,
                          .flow_excess = nan,
                          .flow_resolved = nan};
    return;
  }
  double *D = v, *nu = v + n, *ra = v + 2 * n, *Ds = v + 3 * n, *dh = v + 4 * n, *de = v + 5 * n,
         *c0 = v + 6 * n, *c1 = v + 7 * n, *sp = v + 8 * n, *fx = v + 9 * n;
  size_t m = 0, ms = 0, mh = 0, me = 0, mp = 0, mf = 0, tested = 0;
  unsigned char *rej = (unsigned char *)(v + 10 * n); /* the outlier rule's verdicts */
  out->n_rejected = hd_group_outliers(fits, g, o, rej, &tested);
  for (size_t k = 0; k < n; k++) {
    const hd_run_fit *f = &fits[g->idx[k]];
    if (f->hcs.have) out->measured = 1;
    if (!f->haff_ok) continue;
    if (f->short_window) { /* eq. (31) cannot be trusted there (HD_FIT_MIN_DECAY) */
      out->n_short++;
      continue;
    }
    if (rej[k]) continue; /* a burst the HCS does not have (HD_FIT_REJECT_Z) */
    D[m] = f->haff.D_e, nu[m] = f->haff.nu0, ra[m] = f->ratio;
    c0[m] = f->cpd_start, c1[m++] = f->cpd_end;
    if (f->slope_ok) Ds[ms++] = f->D_e_slope, de[me++] = f->haff.D_e - f->D_e_slope;
    if (!isnan(f->D_e_half[0]) && !isnan(f->D_e_half[1]))
      dh[mh++] = f->D_e_half[1] - f->D_e_half[0];
    if (f->hcs.have) {
      out->measured = 1;
      if (!isnan(f->hcs.s_perp)) sp[mp++] = f->hcs.s_perp;
      if (!isnan(f->hcs.flow_excess)) fx[mf++] = f->hcs.flow_excess;
      if (f->hcs.ended && f->cpd_end - f->cpd_start < o->min_window) out->ended++;
    }
  }
  out->m = m;
  double s, tmp;
  hd_ensemble_mean(D, m, &out->D_e, &out->D_e_err);
  hd_ensemble_mean(nu, m, &out->nu0, &out->nu0_err);
  hd_ensemble_mean(ra, m, &out->ratio, &out->ratio_err);
  hd_ensemble_mean(Ds, ms, &out->D_e_slope, &out->D_e_slope_err);
  hd_ensemble_mean(c0, m, &out->cpd_start, &tmp);
  hd_ensemble_mean(c1, m, &out->cpd_end, &tmp);
  hd_ensemble_mean(dh, mh, &tmp, &s);
  out->sys_window = 0.5 * excess(tmp, s);
  hd_ensemble_mean(de, me, &tmp, &s);
  out->sys_est = excess(tmp, s);
  hd_ensemble_mean(sp, mp, &out->s_perp, &tmp);
  hd_ensemble_mean(fx, mf, &tmp, &s);
  out->flow_excess = mf ? tmp : NAN;
  /* the flow excess counts where its noise does not explain it (|fx| > 2 se), as every other
   * term: D_e max(0, fx) printed 0 for a group whose fx was below 0 within its noise */
  out->flow_resolved = mf ? copysign(excess(tmp, s), tmp) : NAN;
  out->sys_box = isnan(out->D_e) ? NAN : out->D_e * fabs(out->flow_resolved);
  double terms[3] = {out->sys_window, out->sys_est, out->sys_box};
  out->D_e_sys = quad_sum(terms, 3);
  out->flagged = out->measured && ((mp && out->s_perp > o->s_flag) || 2 * out->ended > m)
                     ? HD_FLAG_INHOMOG
                     : 0;
  if (out->n_short && (m == 0 || 2 * out->n_short > m + out->n_short))
    out->flagged |= HD_FLAG_SHORT;
  if (out->n_rejected && (double)out->n_rejected > HD_FIT_REJECT_FLAG * (double)tested)
    out->flagged |= HD_FLAG_OUTLIERS;
  if (g->rough) out->flagged |= HD_FLAG_ROUGH;
  free(v);
}

void hd_k_sys_do(const hd_run_fit *fits, const size_t *idx, size_t n, const double a[2], double fx,
                 hd_k_sys *out) {
  memset(out, 0, sizeof *out);
  double *d = malloc(2 * (n ? n : 1) * sizeof *d);
  if (d) {
    for (size_t i = 0; i < n; i++) {
      const hd_run_fit *f = &fits[idx[i]];
      if (f->K_ok && f->K_half_ok[0] && f->K_half_ok[1]) {
        d[out->mh] = f->K_half[1].a0 - f->K_half[0].a0;
        d[n + out->mh++] = f->K_half[1].a1 - f->K_half[0].a1;
      }
    }
    for (int j = 0; j < 2; j++) {
      double mean, se;
      hd_ensemble_mean(d + (size_t)j * n, out->mh, &mean, &se);
      out->win[j] = 0.5 * excess(mean, se);
    }
  } else {
    out->win[0] = out->win[1] = NAN;
  }
  free(d);
  double f = fabs(fx); /* NaN: not resolved, or no state measures: not measured */
  out->box[0] = isnan(a[0]) ? NAN : fabs(a[0] + 1) * f;
  out->box[1] = isnan(a[1]) ? NAN : fabs(a[1]) * f;
  for (int j = 0; j < 2; j++) {
    double t[2] = {out->win[j], out->box[j]};
    out->sys[j] = quad_sum(t, 2);
  }
}

void hd_ensemble_mean(const double *vals, size_t n, double *mean, double *se) {
  if (n == 0) {
    *mean = *se = NAN;
  } else if (n == 1) {
    *mean = vals[0], *se = NAN;
  } else {
    *mean = gsl_stats_mean(vals, 1, n);
    *se = gsl_stats_sd_m(vals, 1, n, *mean) / sqrt((double)n);
  }
}

int hd_combine_k(const hd_run_fit *fits, const size_t *idx, size_t n, hd_kmode mode, double level,
                 double out[6], hd_error *err) {
  double p = 0.5 * (1 + level);
  size_t m = 0;
  for (size_t i = 0; i < n; i++) m += fits[idx[i]].K_ok != 0;
  if (m == 0) return hd_error_set(err, HD_EINPUT, "no K fit in the group");
  if (mode == HD_K_RUNS) {
    if (m < 2) return hd_error_set(err, HD_EINPUT, "--k-ci runs needs >= 2 runs per group");
    double *a0 = malloc(m * sizeof *a0), *a1 = malloc(m * sizeof *a1);
    if (!a0 || !a1) {
      free(a0), free(a1);
      return hd_error_set(err, HD_ENOMEM, "out of memory");
    }
    size_t j = 0;
    for (size_t i = 0; i < n; i++)
      if (fits[idx[i]].K_ok) a0[j] = fits[idx[i]].K.a0, a1[j++] = fits[idx[i]].K.a1;
    double m0 = gsl_stats_mean(a0, 1, m), m1 = gsl_stats_mean(a1, 1, m);
    double s0 = gsl_stats_sd_m(a0, 1, m, m0) / sqrt((double)m);
    double s1 = gsl_stats_sd_m(a1, 1, m, m1) / sqrt((double)m);
    double tq = gsl_cdf_tdist_Pinv(p, (double)(m - 1));
    out[0] = m0, out[1] = m0 - tq * s0, out[2] = m0 + tq * s0;
    out[3] = m1, out[4] = m1 - tq * s1, out[5] = m1 + tq * s1;
    free(a0), free(a1);
    return HD_OK;
  }
  double w0 = 0, w1 = 0, s0 = 0, s1 = 0, dof = 0;
  for (size_t i = 0; i < n; i++) {
    const hd_run_fit *f = &fits[idx[i]];
    if (!f->K_ok) continue;
    double e0 = mode == HD_K_AC ? f->K.a0_err_ac : f->K.a0_err;
    double e1 = mode == HD_K_AC ? f->K.a1_err_ac : f->K.a1_err;
    double v0 = 1 / (e0 * e0), v1 = 1 / (e1 * e1);
    w0 += v0, w1 += v1, s0 += v0 * f->K.a0, s1 += v1 * f->K.a1;
    dof += mode == HD_K_AC ? fmax(f->K.n_eff - 2, 1) : (double)f->K.n - 2;
  }
  double m0 = s0 / w0, m1 = s1 / w1, tq = gsl_cdf_tdist_Pinv(p, dof);
  double h0 = tq / sqrt(w0), h1 = tq / sqrt(w1);
  out[0] = m0, out[1] = m0 - h0, out[2] = m0 + h0;
  out[3] = m1, out[4] = m1 - h1, out[5] = m1 + h1;
  return HD_OK;
}
