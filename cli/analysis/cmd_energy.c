/* `haff energy`: energy and collision count against time for Figs. 2 and 3. */
#include <math.h>
#include <stdlib.h>

#include "cli_common.h"
#include "cli_species.h"
#include "haff.h"

/* Writes one block: the sample-by-sample mean over the runs of group grp (truncated to the
 * shortest) with the Haff and eq. (31) curves of the mean fitted D_e and nu0 (of the runs whose
 * window is not short and that the outlier rule of o keeps). */
static int write_block(FILE *out, sqlite3 *db, const hd_run_fit *fits, const hd_group *grp,
                       const hd_fit_opts *o, int first, hd_error *err) {
  const size_t *idx = grp->idx, m = grp->n;
  hd_series *s = calloc(m, sizeof *s);
  unsigned char *rej = malloc(m ? m : 1);
  if (!s || !rej) {
    free(s), free(rej);
    return hd_error_set(err, HD_ENOMEM, "out of memory");
  }
  hd_group_outliers(fits, grp, o, rej, NULL); /* their D_e is left out as in table1 */
  int rc = HD_OK;
  size_t len = (size_t)-1, homog = (size_t)-1, nfit = 0, nshort = 0, i0 = 0;
  double De = 0, nu = 0;
  for (size_t k = 0; k < m && rc == HD_OK; k++) {
    const hd_run_fit *f = &fits[idx[k]];
    rc = hd_ana_samples(db, f->info.id, &s[k], err);
    if (rc) break;
    if (s[k].n < len) len = s[k].n;
    if (f->n_used < homog) homog = f->n_used;
    if (f->n_start > i0) i0 = f->n_start; /* the latest window start of the runs */
    if (f->haff_ok && !f->short_window && !rej[k]) De += f->haff.D_e, nu += f->haff.nu0, nfit++;
    nshort += f->short_window != 0;
  }
  if (rc == HD_OK) {
    const hd_run_info *ri = &fits[idx[0]].info;
    double al = ri->alpha, c = 1 - al * al;
    De = nfit ? De / (double)nfit : NAN;
    nu = nfit ? nu / (double)nfit : NAN;
    if (!first) fprintf(out, "\n\n"); /* blank lines between blocks, none after the last */
    /* a run whose window is too short for eq. (31) (hd_run_fit.short_window) is left out of
     * D_e and nu0_eff; none left: they are empty and the block says flag=short */
    fprintf(out, "# %s alpha=%g a_over_d=%g runs=%zu D_e=%s nu0_eff=%s%s\n", ri->label, al,
            ri->a_over_d, m, hd_cli_num("%.6g", De, 0), hd_cli_num("%.6g", nu, 0),
            nfit == 0 && nshort ? " flag=short" : "");
    /* header: column 1's name is the block's legend title (gnuplot: title columnheader(1)) */
    if (ri->species == HD_KIND_DIMER && !ri->mixture &&
        !ri->walls) /* the papers' case: the legend as before */
      fprintf(out, "alpha=%g a/d=%g (%zu runs)", al, ri->a_over_d, m);
    else if (ri->species == HD_KIND_DISK && !ri->walls)
      fprintf(out, "disks alpha=%g (%zu runs)", al, m);
    else
      fprintf(out, "%s alpha=%g a/d=%g (%zu runs)", ri->label, al, ri->a_over_d, m);
    fprintf(out, "\tcpd\tE\tE_over_E0\te_tr\te_rot\tx\tnu0t\thaff_E_over_E0\tx_eq31\thomog\n");
    double E0 = 0;
    for (size_t k = 0; k < m; k++) E0 += s[k].e_tr[0] + s[k].e_rot[0];
    E0 /= (double)m;
    /* the fits start at the window's first sample i0 (t counted from there): the curves too */
    double ts = 0, cs = 0, Es = 0;
    if (i0 >= len) i0 = len ? len - 1 : 0;
    for (size_t k = 0; k < m && len; k++)
      ts += s[k].t[i0], cs += s[k].cpd[i0], Es += s[k].e_tr[i0] + s[k].e_rot[i0];
    ts /= (double)m, cs /= (double)m, Es /= (double)m;
    for (size_t i = 0; i < len; i++) {
      double t = 0, cpd = 0, et = 0, er = 0;
      for (size_t k = 0; k < m; k++)
        t += s[k].t[i], cpd += s[k].cpd[i], et += s[k].e_tr[i], er += s[k].e_rot[i];
      t /= (double)m, cpd /= (double)m, et /= (double)m, er /= (double)m;
      double g = c / (2 * De), u = 1 + g * nu * (t - ts), haff = Es / E0 / (u * u);
      double xeq = c * (cs + hd_haff_tau(t - ts, al, De, nu));
      if (c == 0) haff = 1;
      fprintf(out, "%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%s\t%s\t%s\t%d\n", t, cpd, et + er,
              (et + er) / E0, et, er, c * cpd, hd_cli_num("%.8g", nu * t, 0),
              hd_cli_num("%.8g", haff, 0), hd_cli_num("%.8g", xeq, 0), i >= i0 && i < homog);
    }
  }
  for (size_t k = 0; k < m; k++) hd_series_free(&s[k]);
  free(s), free(rej);
  return rc;
}

const hd_optspec hd_cmd_energy_spec = {
    HD_CLI_SPEC("energy", HD_OPT_RUN | HD_OPT_ALL | HD_OPT_FIT | HD_OPT_SPECIES),
    .head =
        "usage: haff energy DB [--run ID | --all] [--by-species] [fit options] [-o FILE]\n"
        "Energy per body and collisions per particle against time, for Figs. 2 and 3: one block\n"
        "per run (--run) or per (alpha, a/d) group averaged sample by sample (--all, default),\n"
        "blocks separated by two blank lines, each headed by '# species alpha=.. a_over_d=.. ...'\n"
        "and a header line whose first field is the block's legend title (column 1 holds t).\n"
        "Columns: t cpd E E_over_E0 e_tr e_rot x=(1-alpha^2)cpd nu0t=nu0_eff*t\n"
        "         haff_E_over_E0=(E_s/E0)/(1+gamma nu0 (t-t_s))^2 x_eq31=(1-alpha^2)(cpd_s+eq.(31) "
        "at\n"
        "         t-t_s) homog (1 if fitted); t_s, cpd_s, E_s: the HCS window's start (nu0: "
        "there)\n"
        "--by-species: instead, per ensemble of runs of the same species (haff-fit --by-species)\n"
        "one block per species, '# group=G run=ID runs=R species=NAME N=.. T_ratio_theory=..',\n"
        "averaged over the runs sample by sample: t cpd e_tr e_rot T_ratio=e_tr/T K=e_tr/e_rot\n"
        "hcs (1 inside every run's HCS window); T = sum_j x_j e_tr_j\n"};

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
    if (write_block(out, s.db, s.fits, &s.g[j], &a.fit, j == 0, &err))
      rc = hd_cli_fail(argv[0], &err);
  hd_cli_groups_free(&s);
  if (out) {
    int c = hd_cli_close(out, &a);
    if (!rc) rc = c;
  }
  return rc;
}
