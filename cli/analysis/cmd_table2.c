/* `haff table2`: Table II, K = E_tr/E_rot = a0 + a1 tau per (alpha, a/d), with 99% intervals. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "haff.h"

const hd_optspec hd_cmd_table2_spec = {
    HD_CLI_SPEC("table2", HD_OPT_RUN | HD_OPT_ALL | HD_OPT_FIT | HD_OPT_MD | HD_OPT_KCI),
    .head =
        "usage: haff table2 DB [--md] [--keep-flagged] [--k-ci ac|ols|runs] [--cpd-min-k X] [fit "
        "options] [-o FILE]\n"
        "Table II: K = E_tr/E_rot fitted as a0 + a1 tau (tau = cpd) by least squares on the\n"
        "homogeneous part of each dimer run, with 99% Student-t intervals, per (alpha, a/d).\n"
        "Columns: alpha a_over_d a0 a0_lo a0_hi a1 a1_lo a1_hi a0_sys a1_sys\n"
        "(*_sys: systematic errors, from the fits on the window's two halves and the correlated\n"
        "flow the state measures see; docs/analysis.md, \"Errors of K\"; empty when not\n"
        "measured.  Runs that table1 rejects as near-collapse outliers are left out of K too)\n"};

int hd_cmd_table2(int argc, char **argv) {
  hd_cli_args a;
  hd_cli_set s;
  FILE *out;
  int rc = hd_cli_table_start(
      &hd_cmd_table2_spec, argc, argv, 0,
      "no dimer run to fit (K = E_tr/E_rot needs rotation; dimers alone in a periodic box)", &a, &s,
      &out);
  if (rc) return rc < 0 ? 0 : rc;
  if (a.md)
    fprintf(out, "| α | a/d | a0 | 99%% CI a0 | ±sys | a1 | 99%% CI a1 | ±sys |\n"
                 "|---|---|---|---|---|---|---|---|\n");
  else
    fprintf(out, "alpha\ta_over_d\ta0\ta0_lo\ta0_hi\ta1\ta1_lo\ta1_hi\ta0_sys\ta1_sys\n");
  int bad = 0;
  hd_error err;
  for (size_t j = 0; j < s.ng; j++) {
    if (!hd_cli_in_table(&s.g[j], 0)) continue;
    hd_group_fit q;
    hd_group_fit_do(s.fits, &s.g[j], &a.fit, &q);
    if (hd_cli_flagged_out(argv[0], &s.g[j], &q, a.keep_flagged)) continue;
    /* K without the runs the outlier rule rejected (a near-collapse burst is not in the HCS:
     * hd_group_outliers); a short window is eq. (31)'s limit, not the linear K fit's */
    size_t *use = malloc((s.g[j].n ? s.g[j].n : 1) * sizeof *use), nu = 0;
    unsigned char *rk = malloc(s.g[j].n ? s.g[j].n : 1);
    if (!use || !rk) {
      free(use), free(rk), hd_cli_groups_free(&s), hd_cli_close(out, &a);
      fprintf(stderr, "haff %s: out of memory\n", argv[0]);
      return 1;
    }
    hd_group_outliers(s.fits, &s.g[j], &a.fit, rk, NULL);
    for (size_t k = 0; k < s.g[j].n; k++)
      if (!rk[k]) use[nu++] = s.g[j].idx[k];
    free(rk);
    double r[6];
    if (hd_combine_k(s.fits, use, nu, a.kmode, a.fit.level, r, &err)) {
      free(use);
      fprintf(stderr, "haff %s: %s: %s\n", argv[0], hd_cli_group_name(&s.g[j]).s, err.msg);
      bad = 2;
      continue;
    }
    hd_k_sys ks;
    double a01[2] = {r[0], r[3]};
    hd_k_sys_do(s.fits, use, nu, a01, q.flow_resolved, &ks);
    free(use);
#define N(fmt, x) hd_cli_num(fmt, x, a.md)
    if (a.md)
      fprintf(out, "| %g | %g | %.4f | [%.4f, %.4f] | %s | %.3e | [%.3e, %.3e] | %s |\n",
              s.g[j].alpha, s.g[j].a_over_d, r[0], r[1], r[2], N("%.2g", ks.sys[0]), r[3], r[4],
              r[5], N("%.2g", ks.sys[1]));
    else
      fprintf(out, "%g\t%g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%s\t%s\n", s.g[j].alpha,
              s.g[j].a_over_d, r[0], r[1], r[2], r[3], r[4], r[5], N("%.3g", ks.sys[0]),
              N("%.3g", ks.sys[1]));
#undef N
  }
  hd_cli_groups_free(&s);
  rc = hd_cli_close(out, &a);
  return rc ? rc : bad;
}
