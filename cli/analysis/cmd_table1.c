/* `haff table1`: Table I, D_e and nu0_eff/nu0 per (alpha, a/d) from the fits of eq. (31). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "haff.h"
#include "hd_body.h"
#include "hd_enskog.h"
#include "hd_scene.h"
#include "rate.h"

/* The low-density theory of nu0_eff / nu0 at a/d (haff mc rate, docs/mc-rate.md): 10^6
 * configurations from seed 1 (standard error 0.12 %, ~1 s), once per a/d of the table; 1 exactly
 * for disks (a/d = 0).  NaN if it cannot be computed. */
static double rate_theory(double ad) {
  static double seen[64], val[64];
  static int n;
  for (int k = 0; k < n; k++)
    if (seen[k] == ad) return val[k];
  hd_shape sh;
  if (ad > 0)
    hd_shape_dimer(&sh, 1, ad, 1);
  else
    hd_shape_disk(&sh, 1, 2);
  hd_rate_opts o = {&sh, ad > 0 ? 1000000UL : 2UL, 0, 1};
  hd_rate_result r;
  hd_error err;
  double v = hd_rate_run(&o, &r, &err) == HD_OK ? r.ratio : NAN;
  if (n < 64) seen[n] = ad, val[n++] = v;
  return v;
}

const hd_optspec hd_cmd_table1_spec = {
    HD_CLI_SPEC("table1", HD_OPT_RUN | HD_OPT_ALL | HD_OPT_FIT | HD_OPT_MD),
    .head =
        "usage: haff table1 DB [--md] [--keep-flagged] [fit options] [-o FILE]\n"
        "Table I: D_e and nu0_eff/nu0 (nu0: Enskog eq. 29 for disks of diameter d, the body mass "
        "and\n"
        "density, at the initial translational temperature) per (alpha, a/d), mean +- standard "
        "error\n"
        "over the runs (empty when a group has one run).  a_over_d = 0: hard disks.\n"
        "Columns: alpha a_over_d D_e D_e_err ratio ratio_err runs D_e_sys cpd_start cpd_end flag\n"
        "N area_fraction nu_kt nu_kt_err rejected\n"
        "(ratio = nu0_eff/nu0, as in haff-fit: nu0 of eq. 29 with the number density of the\n"
        "bodies, sigma = d, the body mass (2m for a dimer), g(eta) at the reference disks'\n"
        "eta = pi n d^2/4, and the translational temperature at the window's start averaged\n"
        "over its samples; D_e_sys the systematic error, cpd_* the mean HCS window; N bodies,\n"
        "area_fraction the area they cover; nu_kt = ratio over its theory: the molecular-chaos\n"
        "rate of haff mc rate at a/d times g(area_fraction) / g(eta), 1 where theory and runs\n"
        "agree; groups flagged inhomogeneous, short or outliers are left out, with a note;\n"
        "flag rough (rough bodies: D_e a fit parameter, not eq. 31's) is kept, a caveat;\n"
        "rejected: runs left out as outliers, D_e more than 6 robust standard deviations from\n"
        "the group's median: near-collapse bursts, docs/analysis.md)\n"};

int hd_cmd_table1(int argc, char **argv) {
  hd_cli_args a;
  hd_cli_set s;
  FILE *out;
  int rc = hd_cli_table_start(&hd_cmd_table1_spec, argc, argv, 1,
                              "no run of one species in a periodic box to tabulate", &a, &s, &out);
  if (rc) return rc < 0 ? 0 : rc;
  if (a.md)
    fprintf(out, "| α | a/d | D_e | ±stat | ±sys | ν0_eff/ν0 | ±Δ | runs | cpd window | flag | N | "
                 "area fraction | ν0_eff/ν_kt | ±Δ | rejected |\n"
                 "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  else
    fprintf(out, "alpha\ta_over_d\tD_e\tD_e_err\tratio\tratio_err\truns\tD_e_sys\tcpd_start\t"
                 "cpd_end\tflag\tN\tarea_fraction\tnu_kt\tnu_kt_err\trejected\n");
  for (size_t j = 0; j < s.ng; j++) {
    if (!hd_cli_in_table(&s.g[j], 1)) continue;
    hd_group_fit q;
    hd_group_fit_do(s.fits, &s.g[j], &a.fit, &q);
    if (hd_cli_flagged_out(argv[0], &s.g[j], &q, a.keep_flagged)) continue;
    hd_cli_one_run_note(argv[0], &s.g[j], q.m);
    hd_cli_short_note(argv[0], &s.g[j], &q);
#define N(fmt, x) hd_cli_num(fmt, x, a.md)
    const hd_group *gj = &s.g[j];
    /* the area the bodies cover, and the theory of the ratio (docs/mc-rate.md) */
    double phi = gj->density * hd_dimer_area(gj->d, gj->a_over_d * gj->d);
    double eta = M_PI * gj->density * gj->d * gj->d / 4;
    double kt = rate_theory(gj->a_over_d) * hd_enskog_g2d(phi) / hd_enskog_g2d(eta);
    if (a.md)
      fprintf(
          out,
          "| %g | %g | %s | %s | %s | %s | %s | %zu | %.0f–%.0f | %s | %ld | %s | %s | %s | %zu "
          "|\n",
          gj->alpha, gj->a_over_d, N("%.4f", q.D_e), N("%.2g", q.D_e_err), N("%.2g", q.D_e_sys),
          N("%.4f", q.ratio), N("%.2g", q.ratio_err), q.m, q.cpd_start, q.cpd_end,
          hd_group_flag_name(q.flagged), gj->nbodies, N("%.3g", phi), N("%.4f", q.ratio / kt),
          N("%.2g", q.ratio_err / kt), q.n_rejected);
    else
      fprintf(out, "%g\t%g\t%s\t%s\t%s\t%s\t%zu\t%s\t%s\t%s\t%s\t%ld\t%s\t%s\t%s\t%zu\n", gj->alpha,
              gj->a_over_d, N("%.6g", q.D_e), N("%.3g", q.D_e_err), N("%.6g", q.ratio),
              N("%.3g", q.ratio_err), q.m, N("%.3g", q.D_e_sys), N("%.4g", q.cpd_start),
              N("%.4g", q.cpd_end), hd_group_flag_name(q.flagged), gj->nbodies, N("%.4g", phi),
              N("%.5g", q.ratio / kt), N("%.3g", q.ratio_err / kt), q.n_rejected);
#undef N
  }
  hd_cli_groups_free(&s);
  return hd_cli_close(out, &a);
}
