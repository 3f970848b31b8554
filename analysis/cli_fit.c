/* `haff haff-fit`, `haff table1`, `haff table2`: fits of eq. (31) and of K(tau), per run and
 * per group of runs with equal (alpha, a/d). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "haff.h"

/* Whether group g is in the papers' tables: one species in a periodic box, dimers (and disks
 * when with_disks: Table I's reference; Table II's K needs rotation). */
static int in_table(const hd_group *g, int with_disks) {
  return !g->walls && (g->species == HD_ANA_DIMERS || (with_disks && g->species == HD_ANA_DISKS));
}

/* How many of the groups g[0..ng) are in the table; says on stderr which are left out for not
 * being the papers' case (a mixture, walls) and where they are fitted. */
static size_t table_groups(const char *cmd, const hd_group *g, size_t ng, int with_disks) {
  size_t in = 0;
  for (size_t j = 0; j < ng; j++) {
    if (in_table(&g[j], with_disks))
      in++;
    else if (g[j].species != HD_ANA_DISKS || g[j].walls) /* not the disks table2 has no use for */
      fprintf(stderr,
              "haff %s: note: left out %zu run%s of %s (alpha %g a/d %g): the table is for one "
              "species in a periodic box; haff-fit --alpha-group fits them\n",
              cmd, g[j].n, g[j].n == 1 ? "" : "s", hd_ana_species_name(g[j].species, g[j].walls),
              g[j].alpha, g[j].a_over_d);
  }
  return in;
}

/* Whether a table leaves group g out for being flagged inhomogeneous (not with keep); says so on
 * stderr, and that a group without state measures could not be checked. */
static int flagged_out(const char *cmd, const hd_group *g, const hd_group_fit *q, int keep) {
  if (!q->measured)
    fprintf(stderr,
            "haff %s: note: alpha %g a/d %g: no state measures in its samples (logged before "
            "schema 2): its homogeneity is not checked and D_e_sys has no box term\n",
            cmd, g->alpha, g->a_over_d);
  if (!q->flagged || keep) return 0;
  fprintf(stderr,
          "haff %s: note: left out alpha %g a/d %g N %ld: inhomogeneous (window mean s_perp %.3g, "
          "%zu of %zu runs left the HCS early); --keep-flagged keeps it\n",
          cmd, g->alpha, g->a_over_d, g->nbodies, q->s_perp, q->ended, q->m);
  return 1;
}

/* Says on stderr why a group fitted from one run has no error (hd_ensemble_mean). */
static void one_run_note(const char *cmd, const hd_group *g, size_t m) {
  if (m == 1)
    fprintf(stderr,
            "haff %s: note: alpha %g a/d %g: one fitted run, so its errors are nan (an ensemble "
            "error needs >= 2 runs; the fit's formal error, haff-fit's *_fit_err, is several times "
            "smaller than the scatter between runs)\n",
            cmd, g->alpha, g->a_over_d);
}

const hd_optspec haff_fit_spec = {
    .cmd = "haff-fit",
    .opts = hd_cli_opts,
    .allowed = HD_OPT_RUN | HD_OPT_ALL | HD_OPT_FIT | HD_OPT_GROUP,
    .npos_min = 1,
    .npos_max = 1,
    .pos = "one database argument",
    .head =
    "usage: haff haff-fit DB [--run ID | --all] [--alpha-group] [fit options] [-o FILE]\n"
    "Fits eq. (31) tau(t) = ln(1 + gamma nu0 t)/gamma, gamma = (1-alpha^2)/(2 D_e), to the\n"
    "HCS window of each run (tau = cpd counted from the window's start): after the initial\n"
    "transient (--cpd-skip), up to where the state measures (s_perp) or the collision rate\n"
    "per sqrt(E) say the homogeneous cooling state ended; D_e_slope = -(1-alpha^2)/(slope of\n"
    "ln E against cpd) on the same window needs no nu0.  Per group: D_e_sys, the systematic\n"
    "error (window drift, estimator difference, correlated flow: docs/analysis.md), and flag\n"
    "'inhomogeneous' for a box past the HCS's validity.  One line per run, or per group of runs "
    "with\n"
    "equal (alpha, a/d) with --alpha-group (also equal species, walls, N, d, m and density;\n"
    "mean +- standard error over the runs; nan with one run).  Per run, *_fit_err are the\n"
    "formal least-squares errors, which take the residuals of the cumulative cpd(t) as\n"
    "independent: several times too small.  window: 'stored' (the run's runs.hcs_* window,\n"
    "used when the detection options are the defaults), 'computed' (found now: other options,\n"
    "or a file without it), 'whole' (--no-detect).  A run that cannot be fitted gets nan and a "
    "note;\n"
    "exit 2 when none can.\n"};

int haff_fit_main(int argc, char **argv) {
  hd_cli_args a;
  int rc = hd_cli_parse(&haff_fit_spec, argc, argv, &a);
  if (rc) return rc < 0 ? 0 : rc;
  sqlite3 *db;
  hd_run_fit *fits;
  size_t n;
  if ((rc = hd_cli_fits(&a, argv[0], &db, &fits, &n))) return rc;
  FILE *out = hd_cli_out(&a);
  if (!out) {
    free(fits), sqlite3_close(db);
    return 1;
  }
  if (!a.group) {
    /* *_fit_err: the least-squares errors, formal (docs/analysis.md): the residuals of the
     * cumulative count cpd(t) are not independent, and runs scatter 10-25 times more */
    fprintf(out, "run\tspecies\talpha\ta_over_d\tn_used\tdetected\tt_end\tcpd_end\tD_e\t"
                 "D_e_fit_err\tnu0_eff\tnu0_eff_fit_err\tnu0_enskog\tratio\tratio_fit_err\t"
                 "chi2_dof\tcpd_start\tD_e_slope\tD_e_slope_err\ts_perp\tflow_excess\t"
                 "hcs_ended\twindow\n");
    for (size_t i = 0; i < n; i++) {
      const hd_run_fit *f = &fits[i];
      double nan = NAN;
      const hd_haff_fit *h = &f->haff;
      fprintf(
          out,
          "%lld\t%s\t%g\t%g\t%zu\t%d\t%.6g\t%.6g\t%.6g\t%.3g\t%.6g\t%.3g\t%.6g\t%.6g\t%.3g\t%.3g\t"
          "%.6g\t%.6g\t%.3g\t%.4g\t%.4g\t%d\t%s\n",
          (long long)f->info.id, hd_ana_species_name(f->info.species, f->info.walls), f->info.alpha,
          f->info.a_over_d, f->n_used, f->homog.detected, f->t_end, f->cpd_end,
          f->haff_ok ? h->D_e : nan, f->haff_ok ? h->D_e_err : nan, f->haff_ok ? h->nu0 : nan,
          f->haff_ok ? h->nu0_err : nan, f->nu0_enskog, f->ratio, f->ratio_err,
          f->haff_ok ? h->chi2 / (double)h->dof : nan, f->cpd_start, f->D_e_slope, f->D_e_slope_err,
          f->hcs.have ? f->hcs.s_perp : nan, f->hcs.have ? f->hcs.flow_excess : nan, f->hcs.ended,
          hd_cli_window_name(f->window));
    }
  } else {
    hd_group *g;
    size_t ng;
    hd_error err;
    if (hd_group_runs(fits, n, &g, &ng, &err)) {
      free(fits), sqlite3_close(db), hd_cli_close(out, &a);
      return hd_cli_fail(argv[0], &err);
    }
    hd_cli_groups_warn(argv[0], g, ng);
    fprintf(out, "alpha\ta_over_d\tspecies\truns\tD_e\tD_e_err\tnu0_eff\tnu0_eff_err\tratio\t"
                 "ratio_err\tn\tcpd_start\tcpd_end\tD_e_slope\tD_e_slope_err\tD_e_sys\t"
                 "sys_window\tsys_estimator\tsys_box\ts_perp\tflag\n");
    for (size_t j = 0; j < ng; j++) {
      hd_group_fit q;
      hd_group_fit_do(fits, &g[j], &a.fit, &q);
      one_run_note(argv[0], &g[j], q.m);
      fprintf(out,
              "%g\t%g\t%s\t%zu\t%.6g\t%.3g\t%.6g\t%.3g\t%.6g\t%.3g\t%ld\t%.4g\t%.4g\t%.6g\t%.3g\t"
              "%.3g\t%.3g\t%.3g\t%.3g\t%.4g\t%s\n",
              g[j].alpha, g[j].a_over_d, hd_ana_species_name(g[j].species, g[j].walls), q.m, q.D_e,
              q.D_e_err, q.nu0, q.nu0_err, q.ratio, q.ratio_err, g[j].nbodies, q.cpd_start,
              q.cpd_end, q.D_e_slope, q.D_e_slope_err, q.D_e_sys, q.sys_window, q.sys_est,
              q.sys_box, q.s_perp, q.flagged ? "inhomogeneous" : "");
    }
    hd_groups_free(g, ng);
  }
  size_t fitted = 0; /* a script reading a row of nan should see a failure */
  for (size_t i = 0; i < n; i++) fitted += fits[i].haff_ok != 0;
  free(fits);
  sqlite3_close(db);
  int crc = hd_cli_close(out, &a);
  if (!crc && fitted == 0) {
    fprintf(stderr, "haff %s: no run could be fitted (why: above)\n", argv[0]);
    return 2;
  }
  return crc;
}

const hd_optspec haff_table1_spec = {
    .cmd = "table1",
    .opts = hd_cli_opts,
    .allowed = HD_OPT_RUN | HD_OPT_ALL | HD_OPT_FIT | HD_OPT_MD,
    .npos_min = 1,
    .npos_max = 1,
    .pos = "one database argument",
    .head =
    "usage: haff table1 DB [--md] [--keep-flagged] [fit options] [-o FILE]\n"
    "Table I: D_e and nu0_eff/nu0 (nu0: Enskog eq. 29 for disks of diameter d, the body mass "
    "and\n"
    "density, at the initial translational temperature) per (alpha, a/d), mean +- standard "
    "error\n"
    "over the runs (nan when a group has one run).  a_over_d = 0: hard disks.\n"
    "Columns: alpha a_over_d D_e D_e_err ratio ratio_err runs D_e_sys cpd_start cpd_end flag\n"
    "(ratio = nu0_eff/nu0, as in haff-fit; D_e_sys the systematic error, cpd_* the mean HCS\n"
    "window; groups flagged inhomogeneous are left out, with a note)\n"};

int haff_table1_main(int argc, char **argv) {
  hd_cli_args a;
  int rc = hd_cli_parse(&haff_table1_spec, argc, argv, &a);
  if (rc) return rc < 0 ? 0 : rc;
  sqlite3 *db;
  hd_run_fit *fits;
  hd_group *g;
  size_t n, ng;
  if ((rc = hd_cli_groups(&a, argv[0], &db, &fits, &n, &g, &ng))) return rc;
  if (table_groups(argv[0], g, ng, 1) == 0) { /* nothing to tabulate is bad input */
    fprintf(stderr, "haff %s: no run of one species in a periodic box to tabulate\n", argv[0]);
    hd_cli_groups_free(db, fits, g, ng);
    return 2;
  }
  FILE *out = hd_cli_out(&a);
  if (!out) {
    hd_cli_groups_free(db, fits, g, ng);
    return 1;
  }
  if (a.md)
    fprintf(out, "| α | a/d | D_e | ±stat | ±sys | ν0_eff/ν0 | ±Δ | runs | cpd window | flag |\n"
                 "|---|---|---|---|---|---|---|---|---|---|\n");
  else
    fprintf(out, "alpha\ta_over_d\tD_e\tD_e_err\tratio\tratio_err\truns\tD_e_sys\tcpd_start\t"
                 "cpd_end\tflag\n");
  for (size_t j = 0; j < ng; j++) {
    if (!in_table(&g[j], 1)) continue;
    hd_group_fit q;
    hd_group_fit_do(fits, &g[j], &a.fit, &q);
    if (flagged_out(argv[0], &g[j], &q, a.keep_flagged)) continue;
    one_run_note(argv[0], &g[j], q.m);
    if (a.md)
      fprintf(out, "| %g | %g | %.4f | %.2g | %.2g | %.4f | %.2g | %zu | %.0f–%.0f | %s |\n",
              g[j].alpha, g[j].a_over_d, q.D_e, q.D_e_err, q.D_e_sys, q.ratio, q.ratio_err, q.m,
              q.cpd_start, q.cpd_end, q.flagged ? "inhomogeneous" : "");
    else
      fprintf(out, "%g\t%g\t%.6g\t%.3g\t%.6g\t%.3g\t%zu\t%.3g\t%.4g\t%.4g\t%s\n", g[j].alpha,
              g[j].a_over_d, q.D_e, q.D_e_err, q.ratio, q.ratio_err, q.m, q.D_e_sys, q.cpd_start,
              q.cpd_end, q.flagged ? "inhomogeneous" : "");
  }
  hd_cli_groups_free(db, fits, g, ng);
  return hd_cli_close(out, &a);
}

const hd_optspec haff_table2_spec = {
    .cmd = "table2",
    .opts = hd_cli_opts,
    .allowed = HD_OPT_RUN | HD_OPT_ALL | HD_OPT_FIT | HD_OPT_MD | HD_OPT_KCI,
    .npos_min = 1,
    .npos_max = 1,
    .pos = "one database argument",
    .head =
    "usage: haff table2 DB [--md] [--keep-flagged] [--k-ci ac|ols|runs] [--cpd-min-k X] [fit "
    "options] [-o FILE]\n"
    "Table II: K = E_tr/E_rot fitted as a0 + a1 tau (tau = cpd) by least squares on the\n"
    "homogeneous part of each dimer run, with 99% Student-t intervals, per (alpha, a/d).\n"
    "Columns: alpha a_over_d a0 a0_lo a0_hi a1 a1_lo a1_hi a0_sys a1_sys\n"
    "(*_sys: systematic errors, from the fits on the window's two halves and the correlated\n"
    "flow the state measures see; docs/analysis.md, \"Errors of K\")\n"};

int haff_table2_main(int argc, char **argv) {
  hd_cli_args a;
  int rc = hd_cli_parse(&haff_table2_spec, argc, argv, &a);
  if (rc) return rc < 0 ? 0 : rc;
  sqlite3 *db;
  hd_run_fit *fits;
  hd_group *g;
  size_t n, ng;
  if ((rc = hd_cli_groups(&a, argv[0], &db, &fits, &n, &g, &ng))) return rc;
  if (table_groups(argv[0], g, ng, 0) ==
      0) { /* K = E_tr/E_rot: a file without dimers is bad input */
    fprintf(stderr,
            "haff %s: no dimer run to fit (K = E_tr/E_rot needs rotation; dimers alone in a "
            "periodic box)\n",
            argv[0]);
    hd_cli_groups_free(db, fits, g, ng);
    return 2;
  }
  FILE *out = hd_cli_out(&a);
  if (!out) {
    hd_cli_groups_free(db, fits, g, ng);
    return 1;
  }
  if (a.md)
    fprintf(out, "| α | a/d | a0 | 99%% CI a0 | ±sys | a1 | 99%% CI a1 | ±sys |\n"
                 "|---|---|---|---|---|---|---|---|\n");
  else
    fprintf(out, "alpha\ta_over_d\ta0\ta0_lo\ta0_hi\ta1\ta1_lo\ta1_hi\ta0_sys\ta1_sys\n");
  int bad = 0;
  hd_error err;
  for (size_t j = 0; j < ng; j++) {
    if (!in_table(&g[j], 0)) continue;
    hd_group_fit q;
    hd_group_fit_do(fits, &g[j], &a.fit, &q);
    if (flagged_out(argv[0], &g[j], &q, a.keep_flagged)) continue;
    double r[6];
    if (hd_combine_k(fits, g[j].idx, g[j].n, a.kmode, a.fit.level, r, &err)) {
      fprintf(stderr, "haff %s: alpha %g a/d %g: %s\n", argv[0], g[j].alpha, g[j].a_over_d,
              err.msg);
      bad = 2;
      continue;
    }
    hd_k_sys ks;
    double a01[2] = {r[0], r[3]};
    hd_k_sys_do(fits, g[j].idx, g[j].n, a01, q.flow_excess, &ks);
    if (a.md)
      fprintf(out, "| %g | %g | %.4f | [%.4f, %.4f] | %.2g | %.3e | [%.3e, %.3e] | %.2g |\n",
              g[j].alpha, g[j].a_over_d, r[0], r[1], r[2], ks.sys[0], r[3], r[4], r[5], ks.sys[1]);
    else
      fprintf(out, "%g\t%g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.3g\t%.3g\n", g[j].alpha,
              g[j].a_over_d, r[0], r[1], r[2], r[3], r[4], r[5], ks.sys[0], ks.sys[1]);
  }
  hd_cli_groups_free(db, fits, g, ng);
  rc = hd_cli_close(out, &a);
  return rc ? rc : bad;
}
