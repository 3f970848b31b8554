/* `haff haff-fit`: the fit of eq. (31) per run, or per group of runs with equal (alpha, a/d). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "cli_species.h"
#include "haff.h"
#include "hd_rough.h"

const hd_optspec hd_cmd_haff_fit_spec = {
    HD_CLI_SPEC("haff-fit", HD_OPT_RUN | HD_OPT_ALL | HD_OPT_FIT | HD_OPT_GROUP | HD_OPT_SPECIES),
    .head =
        "usage: haff haff-fit DB [--run ID | --all] [--alpha-group | --by-species] [fit options]\n"
        "       [-o FILE]\n"
        "Fits eq. (31) tau(t) = ln(1 + gamma nu0 t)/gamma, gamma = (1-alpha^2)/(2 D_e), to the\n"
        "HCS window of each run (tau = cpd counted from the window's start): after the initial\n"
        "transient (--cpd-skip), up to where the state measures (s_perp) or the collision rate\n"
        "per sqrt(E) say the homogeneous cooling state ended; D_e_slope = -(1-alpha^2)/(slope of\n"
        "ln E against cpd) on the same window needs no nu0.  Per group: D_e_sys, the systematic\n"
        "error (window drift, estimator difference, correlated flow: docs/analysis.md), and flag\n"
        "'inhomogeneous' for a box past the HCS's validity.  One line per run, or per group of "
        "runs "
        "with\n"
        "equal (alpha, a/d) with --alpha-group (also equal species, walls, N, d, m, density,\n"
        "roughness, shapes and wall alpha;\n"
        "mean +- standard error over the runs; empty with one run).  Per run, *_fit_err are the\n"
        "formal least-squares errors, which take the residuals of the cumulative cpd(t) as\n"
        "independent: several times too small; empty (with chi2_dof) when the window has\n"
        "fewer than 5 samples (D_e_slope_err: 4), too few to estimate an error from.  n_used:\n"
        "the samples in the window [cpd_start, cpd_end]; a --cpd-skip past a run's end is\n"
        "refused.  window: 'stored' (the run's runs.hcs_* window, used when the detection\n"
        "options are the defaults), 'computed' (found now: other options, or a file without\n"
        "it), 'whole' (--no-detect).  A run that cannot be fitted gets nan and a "
        "note;\n"
        "exit 2 when none can.  flag 'short' (per run; per group when most of its runs are): the\n"
        "window has < 10 samples or E decays by less than a factor e over it; eq. (31) is not\n"
        "constrained there, and groups leave such runs out.  flag 'outlier' (per run): its D_e is\n"
        "more than 6 robust standard deviations from its group's median (a near-collapse burst);\n"
        "groups leave it out and count it in 'rejected', and are flagged 'outliers' when more\n"
        "than 1 in 10 of their runs are.  flag 'rough' (per run and group): rough bodies (beta\n"
        "> -1), whose D_e is a fit parameter, not eq. (31)'s.  A missing value, or a systematic\n"
        "term not resolved from its noise, is printed empty (never nan or 0).\n"
        "--by-species: instead, one row per species of each ensemble of runs (the same species,\n"
        "counts, masses, sizes, restitutions and box; --run: that run alone): group run runs\n"
        "species N T_ratio T_ratio_err err_from T_ratio_theory K K_err mass sigma alpha cpd_start\n"
        "cpd_end.  T_ratio = <T_i/T> over each run's HCS window, T = sum_j x_j T_j the mixture's\n"
        "translational temperature (x_j = N_j/N; T_i = e_tr of species i), mean over the runs;\n"
        "T_ratio_err its standard error over the runs (err_from 'runs') or, for one run, over 8\n"
        "blocks of its window ('blocks'); T_ratio_theory Garzo-Dufty's HCS of smooth disks in the\n"
        "Maxwellian approximation, d = 2 (empty unless every species is one disk and the box is\n"
        "periodic); K = <e_tr/e_rot> of a rotating species likewise (docs/analysis.md).\n"
        "T_rot_tr: T_rot/T_tr = 2 e_rot/e_tr over the window for a gas whose bodies all turn\n"
        "(dimers; disks of q > 0), T_rot_tr_err its error from 8 blocks, T_rot_tr_theory the\n"
        "Maxwellian HCS ratio of rough disks (docs/analysis.md, \"Rough bodies\").\n"};

/* T_rot/T_tr over the fit's window for a run whose every body turns (dimers of a > 0, disks of
 * q > 0), with its block error, and for rough disks the Maxwellian HCS theory (hd_rough.h);
 * NaN (printed empty) otherwise. */
static int rot_ratio(sqlite3 *db, const hd_run_fit *f, double *r, double *err, double *th,
                     hd_error *e) {
  const hd_run_info *ri = &f->info;
  *r = *err = *th = NAN;
  if (!((ri->species == HD_KIND_DIMER && ri->a > 0) || (ri->species == HD_KIND_DISK && ri->q > 0)))
    return HD_OK;
  hd_series s;
  int rc = hd_ana_samples(db, ri->id, &s, e);
  if (rc) return rc;
  hd_rough_window_ratio(s.e_tr, s.e_rot, f->n_start, f->n_used < s.n ? f->n_used : s.n, r, err);
  hd_series_free(&s);
  if (ri->species == HD_KIND_DISK) *th = hd_rough_hcs_ratio(ri->alpha, ri->beta, ri->q);
  return HD_OK;
}

int hd_cmd_haff_fit(int argc, char **argv) {
  hd_cli_args a;
  int rc = hd_cli_parse(&hd_cmd_haff_fit_spec, argc, argv, &a);
  if (rc) return rc < 0 ? 0 : rc;
  if (a.by_species && a.group) {
    fprintf(stderr,
            "haff %s: --by-species and --alpha-group exclude each other (--by-species "
            "groups the runs of one ensemble itself)\n",
            argv[0]);
    return 2;
  }
  if (a.by_species) return hd_cli_species_fit(&a, argv[0]);
  sqlite3 *db;
  hd_run_fit *fits;
  size_t n;
  if ((rc = hd_cli_fits(&a, argv[0], &db, &fits, &n))) return rc;
  FILE *out = hd_cli_out(&a);
  if (!out) {
    free(fits), hd_ana_close(db);
    return 1;
  }
  if (!a.group) {
    /* *_fit_err: the least-squares errors, formal (docs/analysis.md): the residuals of the
     * cumulative count cpd(t) are not independent, and runs scatter 10-25 times more */
    fprintf(out, "run\tspecies\talpha\ta_over_d\tn_used\tdetected\tt_end\tcpd_end\tD_e\t"
                 "D_e_fit_err\tnu0_eff\tnu0_eff_fit_err\tnu0_enskog\tratio\tratio_fit_err\t"
                 "chi2_dof\tcpd_start\tD_e_slope\tD_e_slope_err\ts_perp\tflow_excess\t"
                 "hcs_ended\twindow\tdecay\tflag\tT_rot_tr\tT_rot_tr_err\tT_rot_tr_theory\n");
    /* each run's verdict under its group's outlier rule (hd_group_outliers) */
    unsigned char *rej = calloc(n ? n : 1, 1), *rk = malloc(n ? n : 1);
    hd_group *g = NULL;
    size_t ng = 0, nrej = 0;
    hd_error err;
    if (!rej || !rk || hd_group_runs(fits, n, &g, &ng, &err)) {
      free(rej), free(rk), free(fits), hd_ana_close(db), hd_cli_close(out, &a);
      return rej && rk ? hd_cli_fail(argv[0], &err)
                       : (fprintf(stderr, "haff %s: out of memory\n", argv[0]), 1);
    }
    for (size_t j = 0; j < ng; j++) {
      nrej += hd_group_outliers(fits, &g[j], &a.fit, rk, NULL);
      for (size_t k = 0; k < g[j].n; k++) rej[g[j].idx[k]] = rk[k];
    }
    hd_groups_free(g, ng);
    free(rk);
    size_t nshort = 0;
    for (size_t i = 0; i < n; i++) {
      const hd_run_fit *f = &fits[i];
      double nan = NAN;
      const hd_haff_fit *h = &f->haff;
      int ok = f->haff_ok;
      nshort += f->short_window != 0;
      double rr, rr_err, rr_th;
      hd_error rerr;
      if (rot_ratio(db, f, &rr, &rr_err, &rr_th, &rerr)) {
        free(rej), free(fits), hd_ana_close(db), hd_cli_close(out, &a);
        return hd_cli_fail(argv[0], &rerr);
      }
#define N(fmt, x) hd_cli_num(fmt, x, 0)
      fprintf(out,
              "%lld\t%s\t%s\t%s\t%zu\t%d\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%"
              "s\t%d\t%s\t%s\t%s\t%s\t%s\t%s\n",
              (long long)f->info.id, f->info.label, N("%g", f->info.alpha),
              N("%g", f->info.a_over_d), f->n_used - f->n_start, f->homog.detected,
              N("%.6g", f->t_end), N("%.6g", f->cpd_end), N("%.6g", ok ? h->D_e : nan),
              N("%.3g", ok ? h->D_e_err : nan), N("%.6g", ok ? h->nu0 : nan),
              N("%.3g", ok ? h->nu0_err : nan), N("%.6g", f->nu0_enskog), N("%.6g", f->ratio),
              N("%.3g", f->ratio_err), N("%.3g", ok ? h->chi2 / (double)h->dof : nan),
              N("%.6g", f->cpd_start), N("%.6g", f->D_e_slope), N("%.3g", f->D_e_slope_err),
              N("%.4g", f->hcs.have ? f->hcs.s_perp : nan),
              N("%.4g", f->hcs.have ? f->hcs.flow_excess : nan), f->hcs.ended,
              hd_cli_window_name(f->window), N("%.3g", f->decay),
              f->info.rough     ? (f->short_window ? "short,rough"
                                   : rej[i]        ? "outlier,rough"
                                                   : "rough")
              : f->short_window ? "short"
              : rej[i]          ? "outlier"
                                : "",
              N("%.5g", rr), N("%.2g", rr_err), N("%.5g", rr_th));
    }
    free(rej);
    size_t nrough = 0;
    for (size_t i = 0; i < n; i++) nrough += fits[i].info.rough != 0;
    if (nrough)
      fprintf(stderr,
              "haff %s: note: %zu run%s flagged rough: tangential restitution beta > -1; eq. (31) "
              "is Haff's law of smooth bodies, so their D_e is a fit parameter, not eq. (31)'s "
              "(docs/analysis.md, \"Rough bodies\")\n",
              argv[0], nrough, nrough == 1 ? "" : "s");
    if (nrej)
      fprintf(stderr,
              "haff %s: note: %zu run%s flagged outlier: D_e more than %g robust standard "
              "deviations (1.4826 MAD) from the median of its group (same alpha, a/d, N, "
              "density): a near-collapse burst (docs/analysis.md, \"Outlier runs\"); the groups "
              "leave them out\n",
              argv[0], nrej, nrej == 1 ? "" : "s", HD_FIT_REJECT_Z);
    if (nshort)
      fprintf(stderr,
              "haff %s: note: %zu run%s flagged short: the window has fewer than %d samples or E "
              "decays by less than a factor e over it (ln(E_start/E_end) < %g): eq. (31) cannot "
              "separate D_e from nu0 there, whatever its formal error says "
              "(docs/analysis.md, \"Short windows\"); the groups leave them out\n",
              argv[0], nshort, nshort == 1 ? "" : "s", HD_FIT_MIN_SAMPLES, HD_FIT_MIN_DECAY);
  } else {
    hd_group *g;
    size_t ng;
    hd_error err;
    if (hd_group_runs(fits, n, &g, &ng, &err)) {
      free(fits), hd_ana_close(db), hd_cli_close(out, &a);
      return hd_cli_fail(argv[0], &err);
    }
    hd_cli_groups_warn(argv[0], g, ng);
    fprintf(out, "alpha\ta_over_d\tspecies\truns\tD_e\tD_e_err\tnu0_eff\tnu0_eff_err\tratio\t"
                 "ratio_err\tn\tcpd_start\tcpd_end\tD_e_slope\tD_e_slope_err\tD_e_sys\t"
                 "sys_window\tsys_estimator\tsys_box\ts_perp\tflag\trejected\n");
    for (size_t j = 0; j < ng; j++) {
      hd_group_fit q;
      hd_group_fit_do(fits, &g[j], &a.fit, &q);
      hd_cli_one_run_note(argv[0], &g[j], q.m);
      hd_cli_short_note(argv[0], &g[j], &q);
#define N(fmt, x) hd_cli_num(fmt, x, 0)
      fprintf(out,
              "%s\t%s\t%s\t%zu\t%s\t%s\t%s\t%s\t%s\t%s\t%ld\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%"
              "s\t%zu\n",
              N("%g", g[j].alpha), N("%g", g[j].a_over_d), g[j].label, q.m, N("%.6g", q.D_e),
              N("%.3g", q.D_e_err), N("%.6g", q.nu0), N("%.3g", q.nu0_err), N("%.6g", q.ratio),
              N("%.3g", q.ratio_err), g[j].nbodies, N("%.4g", q.cpd_start), N("%.4g", q.cpd_end),
              N("%.6g", q.D_e_slope), N("%.3g", q.D_e_slope_err), N("%.3g", q.D_e_sys),
              N("%.3g", q.sys_window), N("%.3g", q.sys_est), N("%.3g", q.sys_box),
              N("%.4g", q.s_perp), hd_group_flag_name(q.flagged), q.n_rejected);
#undef N
    }
    hd_groups_free(g, ng);
  }
  size_t fitted = 0; /* a script reading a row of nan should see a failure */
  for (size_t i = 0; i < n; i++) fitted += fits[i].haff_ok != 0;
  free(fits);
  hd_ana_close(db);
  int crc = hd_cli_close(out, &a);
  if (!crc && fitted == 0) {
    fprintf(stderr, "haff %s: no run could be fitted (why: above)\n", argv[0]);
    return 2;
  }
  return crc;
}
