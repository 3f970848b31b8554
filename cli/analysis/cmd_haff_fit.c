/* `haff haff-fit`: the fit of eq. (31) per run, or per group of runs with equal (alpha, a/d). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "haff.h"

const hd_optspec hd_cmd_haff_fit_spec = {
    HD_CLI_SPEC("haff-fit", HD_OPT_RUN | HD_OPT_ALL | HD_OPT_FIT | HD_OPT_GROUP),
    .head =
        "usage: haff haff-fit DB [--run ID | --all] [--alpha-group] [fit options] [-o FILE]\n"
        "Fits eq. (31) tau(t) = ln(1 + gamma nu0 t)/gamma, gamma = (1-alpha^2)/(2 D_e), to the\n"
        "HCS window of each run (tau = cpd counted from the window's start): after the initial\n"
        "transient (--cpd-skip), up to where the state measures (s_perp) or the collision rate\n"
        "per sqrt(E) say the homogeneous cooling state ended; D_e_slope = -(1-alpha^2)/(slope of\n"
        "ln E against cpd) on the same window needs no nu0.  Per group: D_e_sys, the systematic\n"
        "error (window drift, estimator difference, correlated flow: docs/analysis.md), and flag\n"
        "'inhomogeneous' for a box past the HCS's validity.  One line per run, or per group of "
        "runs "
        "with\n"
        "equal (alpha, a/d) with --alpha-group (also equal species, walls, N, d, m and density;\n"
        "mean +- standard error over the runs; empty with one run).  Per run, *_fit_err are the\n"
        "formal least-squares errors, which take the residuals of the cumulative cpd(t) as\n"
        "independent: several times too small.  window: 'stored' (the run's runs.hcs_* window,\n"
        "used when the detection options are the defaults), 'computed' (found now: other options,\n"
        "or a file without it), 'whole' (--no-detect).  A run that cannot be fitted gets nan and a "
        "note;\n"
        "exit 2 when none can.  flag 'short' (per run; per group when most of its runs are): the\n"
        "window has < 10 samples or E decays by less than a factor e over it; eq. (31) is not\n"
        "constrained there, and groups leave such runs out.  A missing value, or a systematic\n"
        "term not resolved from its noise, is printed empty (never nan or 0).\n"};

int hd_cmd_haff_fit(int argc, char **argv) {
  hd_cli_args a;
  int rc = hd_cli_parse(&hd_cmd_haff_fit_spec, argc, argv, &a);
  if (rc) return rc < 0 ? 0 : rc;
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
                 "hcs_ended\twindow\tdecay\tflag\n");
    size_t nshort = 0;
    for (size_t i = 0; i < n; i++) {
      const hd_run_fit *f = &fits[i];
      double nan = NAN;
      const hd_haff_fit *h = &f->haff;
      int ok = f->haff_ok;
      nshort += f->short_window != 0;
#define N(fmt, x) hd_cli_num(fmt, x, 0)
      fprintf(out,
              "%lld\t%s\t%s\t%s\t%zu\t%d\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%"
              "s\t%d\t%s\t%s\t%s\n",
              (long long)f->info.id, f->info.label, N("%g", f->info.alpha),
              N("%g", f->info.a_over_d), f->n_used, f->homog.detected, N("%.6g", f->t_end),
              N("%.6g", f->cpd_end), N("%.6g", ok ? h->D_e : nan), N("%.3g", ok ? h->D_e_err : nan),
              N("%.6g", ok ? h->nu0 : nan), N("%.3g", ok ? h->nu0_err : nan),
              N("%.6g", f->nu0_enskog), N("%.6g", f->ratio), N("%.3g", f->ratio_err),
              N("%.3g", ok ? h->chi2 / (double)h->dof : nan), N("%.6g", f->cpd_start),
              N("%.6g", f->D_e_slope), N("%.3g", f->D_e_slope_err),
              N("%.4g", f->hcs.have ? f->hcs.s_perp : nan),
              N("%.4g", f->hcs.have ? f->hcs.flow_excess : nan), f->hcs.ended,
              hd_cli_window_name(f->window), N("%.3g", f->decay), f->short_window ? "short" : "");
    }
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
                 "sys_window\tsys_estimator\tsys_box\ts_perp\tflag\n");
    for (size_t j = 0; j < ng; j++) {
      hd_group_fit q;
      hd_group_fit_do(fits, &g[j], &a.fit, &q);
      hd_cli_one_run_note(argv[0], &g[j], q.m);
      hd_cli_short_note(argv[0], &g[j], &q);
#define N(fmt, x) hd_cli_num(fmt, x, 0)
      fprintf(out,
              "%s\t%s\t%s\t%zu\t%s\t%s\t%s\t%s\t%s\t%s\t%ld\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%"
              "s\n",
              N("%g", g[j].alpha), N("%g", g[j].a_over_d), g[j].label, q.m, N("%.6g", q.D_e),
              N("%.3g", q.D_e_err), N("%.6g", q.nu0), N("%.3g", q.nu0_err), N("%.6g", q.ratio),
              N("%.3g", q.ratio_err), g[j].nbodies, N("%.4g", q.cpd_start), N("%.4g", q.cpd_end),
              N("%.6g", q.D_e_slope), N("%.3g", q.D_e_slope_err), N("%.3g", q.D_e_sys),
              N("%.3g", q.sys_window), N("%.3g", q.sys_est), N("%.3g", q.sys_box),
              N("%.4g", q.s_perp), hd_group_flag_name(q.flagged));
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
