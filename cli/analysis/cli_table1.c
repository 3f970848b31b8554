/* `haff table1`: Table I, D_e and nu0_eff/nu0 per (alpha, a/d) from the fits of eq. (31). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "haff.h"

const hd_optspec haff_table1_spec = {
    HD_CLI_SPEC("table1", HD_OPT_RUN | HD_OPT_ALL | HD_OPT_FIT | HD_OPT_MD),
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
  hd_cli_set s;
  FILE *out;
  int rc = hd_cli_table_start(&haff_table1_spec, argc, argv, 1,
                              "no run of one species in a periodic box to tabulate", &a, &s, &out);
  if (rc) return rc < 0 ? 0 : rc;
  if (a.md)
    fprintf(out, "| α | a/d | D_e | ±stat | ±sys | ν0_eff/ν0 | ±Δ | runs | cpd window | flag |\n"
                 "|---|---|---|---|---|---|---|---|---|---|\n");
  else
    fprintf(out, "alpha\ta_over_d\tD_e\tD_e_err\tratio\tratio_err\truns\tD_e_sys\tcpd_start\t"
                 "cpd_end\tflag\n");
  for (size_t j = 0; j < s.ng; j++) {
    if (!hd_cli_in_table(&s.g[j], 1)) continue;
    hd_group_fit q;
    hd_group_fit_do(s.fits, &s.g[j], &a.fit, &q);
    if (hd_cli_flagged_out(argv[0], &s.g[j], &q, a.keep_flagged)) continue;
    hd_cli_one_run_note(argv[0], &s.g[j], q.m);
    hd_cli_short_note(argv[0], &s.g[j], &q);
#define N(fmt, x) hd_cli_num(fmt, x, a.md)
    if (a.md)
      fprintf(out, "| %g | %g | %s | %s | %s | %s | %s | %zu | %.0f–%.0f | %s |\n", s.g[j].alpha,
              s.g[j].a_over_d, N("%.4f", q.D_e), N("%.2g", q.D_e_err), N("%.2g", q.D_e_sys),
              N("%.4f", q.ratio), N("%.2g", q.ratio_err), q.m, q.cpd_start, q.cpd_end,
              hd_group_flag_name(q.flagged));
    else
      fprintf(out, "%g\t%g\t%s\t%s\t%s\t%s\t%zu\t%s\t%s\t%s\t%s\n", s.g[j].alpha, s.g[j].a_over_d,
              N("%.6g", q.D_e), N("%.3g", q.D_e_err), N("%.6g", q.ratio), N("%.3g", q.ratio_err),
              q.m, N("%.3g", q.D_e_sys), N("%.4g", q.cpd_start), N("%.4g", q.cpd_end),
              hd_group_flag_name(q.flagged));
#undef N
  }
  hd_cli_groups_free(&s);
  return hd_cli_close(out, &a);
}
