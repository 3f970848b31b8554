/* `haff energy`: energy and collision count against time for Figs. 2 and 3. */
#include <math.h>
#include <stdlib.h>

#include "cli_common.h"
#include "cli_grid.h"
#include "cli_species.h"
#include "haff.h"

/* The mean over the group's runs s[0..m) of each series at cpd c (t, e_tr, e_rot; hints: one
 * per run, see hd_cli_interp).  t is interpolated linearly in cpd, the energies linearly in
 * ln E (exact for Haff's law, whose ln E is linear in cpd; hd_cli_interp). */
static void mean_at(const hd_series *s, size_t m, double c, size_t *hint, double *t, double *et,
                    double *er) {
  *t = *et = *er = 0;
  for (size_t k = 0; k < m; k++) {
    size_t h = hint[k], h2 = hint[k]; /* the three series of a run share their cpd */
    *t += hd_cli_interp(s[k].cpd, s[k].t, 1, s[k].n, c, 0, &h);
    *et += hd_cli_interp(s[k].cpd, s[k].e_tr, 1, s[k].n, c, 1, &h2);
    h2 = hint[k];
    *er += hd_cli_interp(s[k].cpd, s[k].e_rot, 1, s[k].n, c, 1, &h2);
    hint[k] = h;
  }
  *t /= (double)m, *et /= (double)m, *er /= (double)m;
}

/* Writes one block: the mean over the runs of group grp at matching cpd (hd_cli_grid: on the
 * finest run's cpd values, over the cpd range every run covers; the longer runs are cut there,
 * and the header and a note say so) with the Haff and eq. (31) curves of the mean fitted D_e
 * and nu0 (of the runs whose window is not short and that the outlier rule of o keeps). */
static int write_block(FILE *out, const char *cmd, sqlite3 *db, const hd_run_fit *fits,
                       const hd_group *grp, const hd_fit_opts *o, int first, hd_error *err) {
  const size_t *idx = grp->idx, m = grp->n;
  hd_series *s = calloc(m, sizeof *s);
  unsigned char *rej = malloc(m ? m : 1);
  const double **x = calloc(m ? m : 1, sizeof *x);
  size_t *n = calloc(m ? m : 1, sizeof *n), *hint = calloc(m ? m : 1, sizeof *hint);
  hd_cli_grid g = {0};
  if (!s || !rej || !x || !n || !hint) {
    free(s), free(rej), free(x), free(n), free(hint);
    return hd_error_set(err, HD_ENOMEM, "out of memory");
  }
  hd_group_outliers(fits, grp, o, rej, NULL); /* their D_e is left out as in table1 */
  int rc = HD_OK;
  size_t nfit = 0, nshort = 0;
  double De = 0, nu = 0, cs = -INFINITY, ce = INFINITY;
  for (size_t k = 0; k < m && rc == HD_OK; k++) {
    const hd_run_fit *f = &fits[idx[k]];
    rc = hd_ana_samples(db, f->info.id, &s[k], err);
    if (rc) break;
    x[k] = s[k].cpd, n[k] = s[k].n;
    cs = fmax(cs, f->cpd_start); /* the latest window start of the runs */
    ce = fmin(ce, f->cpd_end);   /* the earliest window end */
    if (f->haff_ok && !f->short_window && !rej[k]) De += f->haff.D_e, nu += f->haff.nu0, nfit++;
    nshort += f->short_window != 0;
  }
  if (rc == HD_OK) rc = hd_cli_grid_make(x, n, m, &g, err);
  if (rc == HD_OK) {
    const hd_run_info *ri = &fits[idx[0]].info;
    double al = ri->alpha, c = 1 - al * al;
    De = nfit ? De / (double)nfit : NAN;
    nu = nfit ? nu / (double)nfit : NAN;
    if (g.longest > g.hi)
      fprintf(stderr,
              "haff %s: note: %s alpha=%g a_over_d=%g: averaged up to cpd %g, where its shortest "
              "run ends (the longest goes on to cpd %g)\n",
              cmd, ri->label, al, ri->a_over_d, g.hi, g.longest);
    if (!first) fprintf(out, "\n\n"); /* blank lines between blocks, none after the last */
    /* a run whose window is too short for eq. (31) (hd_run_fit.short_window) is left out of
     * D_e and nu0_eff; none left: they are empty and the block says flag=short.  cpd_end: the
     * last cpd every run reaches (the block's end); truncated_from: the longest run's last
     * cpd, when it goes on past cpd_end */
    fprintf(out, "# %s alpha=%g a_over_d=%g runs=%zu D_e=%s nu0_eff=%s%s cpd_end=%.8g", ri->label,
            al, ri->a_over_d, m, hd_cli_num("%.6g", De, 0), hd_cli_num("%.6g", nu, 0),
            nfit == 0 && nshort ? " flag=short" : "", g.hi);
    if (g.longest > g.hi) fprintf(out, " truncated_from=%.8g", g.longest);
    fprintf(out, "\n");
    /* header: column 1's name is the block's legend title (gnuplot: title columnheader(1)) */
    if (ri->species == HD_KIND_DIMER && !ri->mixture &&
        !ri->walls) /* the papers' case: the legend as before */
      fprintf(out, "alpha=%g a/d=%g (%zu runs)", al, ri->a_over_d, m);
    else if (ri->species == HD_KIND_DISK && !ri->walls)
      fprintf(out, "disks alpha=%g (%zu runs)", al, m);
    else
      fprintf(out, "%s alpha=%g a/d=%g (%zu runs)", ri->label, al, ri->a_over_d, m);
    fprintf(out, "\tcpd\tE\tE_over_E0\te_tr\te_rot\tx\tnu0t\thaff_E_over_E0\tx_eq31\thomog\n");
    double E0, ts, Es, et, er;
    mean_at(s, m, g.cpd[0], hint, &ts, &et, &er);
    E0 = et + er;
    /* the fits start at the latest window start cs (t counted from there): the curves too */
    if (!(cs >= g.cpd[0])) cs = g.cpd[0];
    if (cs > g.hi) cs = g.hi;
    for (size_t k = 0; k < m; k++) hint[k] = 0;
    mean_at(s, m, cs, hint, &ts, &et, &er);
    Es = et + er;
    for (size_t k = 0; k < m; k++) hint[k] = 0;
    for (size_t i = 0; i < g.n; i++) {
      double t, cpd = g.cpd[i];
      mean_at(s, m, cpd, hint, &t, &et, &er);
      double gam = c / (2 * De), u = 1 + gam * nu * (t - ts), haff = Es / E0 / (u * u);
      double xeq = c * (cs + hd_haff_tau(t - ts, al, De, nu));
      if (c == 0) haff = 1;
      fprintf(out, "%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%s\t%s\t%s\t%d\n", t, cpd, et + er,
              (et + er) / E0, et, er, c * cpd, hd_cli_num("%.8g", nu * t, 0),
              hd_cli_num("%.8g", haff, 0), hd_cli_num("%.8g", xeq, 0), cpd >= cs && cpd <= ce);
    }
  }
  for (size_t k = 0; k < m; k++) hd_series_free(&s[k]);
  hd_cli_grid_free(&g);
  free(s), free(rej), free(x), free(n), free(hint);
  return rc;
}

const hd_optspec hd_cmd_energy_spec = {
    HD_CLI_SPEC("energy", HD_OPT_RUN | HD_OPT_ALL | HD_OPT_FIT | HD_OPT_SPECIES),
    .head =
        "usage: haff energy DB [--run ID | --all] [--by-species] [fit options] [-o FILE]\n"
        "Energy per body and collisions per particle against time, for Figs. 2 and 3: one block\n"
        "per run (--run) or per (alpha, a/d) group (--all, default), the runs averaged at\n"
        "matching cpd: on the cpd values of the run sampled most often, over the cpd range that\n"
        "every run covers (t interpolated linearly in cpd, energies linearly in ln E), so a\n"
        "group is cut where its shortest run ends: the block's '#' line ends with cpd_end=\n"
        "and, when a longer run was cut, truncated_from= (its end), and a note says so.\n"
        "Blocks are separated by two blank lines, each headed by '# species alpha=.. a_over_d=..\n"
        "...' and a header line whose first field is the block's legend title (column 1: t).\n"
        "Columns: t cpd E E_over_E0 e_tr e_rot x=(1-alpha^2)cpd nu0t=nu0_eff*t\n"
        "         haff_E_over_E0=(E_s/E0)/(1+gamma nu0 (t-t_s))^2 x_eq31=(1-alpha^2)(cpd_s+eq.(31) "
        "at\n"
        "         t-t_s) homog (1 if fitted); t_s, cpd_s, E_s: the HCS window's start (nu0: "
        "there)\n"
        "--by-species: instead, per ensemble of runs of the same species (haff-fit --by-species)\n"
        "one block per species, '# group=G run=ID runs=R species=NAME N=.. T_ratio_theory=..',\n"
        "averaged over the runs at matching cpd as above: t cpd e_tr e_rot T_ratio=e_tr/T\n"
        "K=e_tr/e_rot hcs (1 inside every run's HCS window); T = sum_j x_j e_tr_j\n"};

int hd_cmd_energy(int argc, char **argv) {
  hd_cli_args a;
  int rc = hd_cli_parse(&hd_cmd_energy_spec, argc, argv, &a);
  if (rc) return rc < 0 ? 0 : rc;
  if (a.by_species) return hd_cli_species_energy(&a, argv[0]);
  hd_cli_set s;
  rc = hd_cli_groups(&hd_cmd_energy_spec, argc, argv, &a, &s);
  if (rc) return rc < 0 ? 0 : rc;
  hd_error err;
  FILE *out = hd_cli_out(&a);
  rc = out ? 0 : 1;
  for (size_t j = 0; out && j < s.ng && !rc; j++)
    if (write_block(out, argv[0], s.db, s.fits, &s.g[j], &a.fit, j == 0, &err))
      rc = hd_cli_fail(argv[0], &err);
  hd_cli_groups_free(&s);
  if (out) {
    int c = hd_cli_close(out, &a);
    if (!rc) rc = c;
  }
  return rc;
}
