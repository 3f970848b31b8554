/* `haff veldist`: scaled velocity distributions of the stored snapshots (Fig. 6). */
#include <gsl/gsl_histogram.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "haff.h"
#include "hd_velstats.h"

static void stat_line(FILE *out, size_t s, const hd_snapshot *sn, const char *var,
                      const hd_velstats *v) {
  /* a statistic the snapshot cannot give (too few bodies: hd_velstats) is empty, never nan */
  fprintf(out, "%zu\t%.8g\t%.6g\t%s\t%zu\t%s\t%s\t%s\t%s\t%s\t%s\n", s, sn->t, sn->cpd, var, v->n,
          hd_cli_num("%.6g", v->scale, 0), hd_cli_num("%.5f", v->kurt, 0),
          hd_cli_num("%.5f", v->a2, 0), hd_cli_num("%.3g", v->a2_err, 0),
          hd_cli_num("%.5f", v->ks_d, 0), hd_cli_num("%.3g", v->ks_p, 0));
}

/* Says on stderr why a run of named species (hd_run_info.species HD_KIND_BODY) is refused. */
static void refuse_shapes(const char *cmd, const hd_run_info *ri) {
  fprintf(stderr,
          "haff %s: run %lld has named species (%s): veldist reads one species, [dimers], "
          "[disks] or a gas of one named species of paper dimers (two equal disks); the states "
          "table holds every body's velocity (kind 'body')\n",
          cmd, (long long)ri->id, ri->label);
}

/* --pool: one histogram of the snapshots of every run (or --run) of the first run's ensemble whose
 * cpd lies in the run's HCS window (hd_run_fit_do: after the transient, before the end of
 * homogeneity), each scaled by its own s as in the per-snapshot blocks. */
static int veldist_pool(const hd_cli_args *a, const char *cmd) {
  sqlite3 *db;
  hd_run_fit *fits;
  size_t n;
  int rc = hd_cli_fits(a, cmd, &db, &fits, &n);
  if (rc) return rc;
  int bins = a->bins ? a->bins : 40, species = fits[0].info.species;
  if (species == HD_KIND_BODY) {
    refuse_shapes(cmd, &fits[0].info);
    free(fits);
    hd_ana_close(db);
    return 2;
  }
  gsl_histogram *h[3];
  for (int k = 0; k < 3; k++) {
    h[k] = gsl_histogram_alloc((size_t)bins);
    gsl_histogram_set_ranges_uniform(h[k], -a->range, a->range);
  }
  double nv = 0, nw = 0, c0 = INFINITY, c1 = -INFINITY;
  size_t runs = 0, snaps = 0, other = 0;
  hd_error err;
  /* the first run's ensemble only (hd_group_runs: species, alpha, a/d, N, density, roughness,
   * shapes, walls); runs of another alpha or roughness were pooled with it */
  hd_group *g = NULL;
  size_t ng = 0;
  if (hd_group_runs(fits, n, &g, &ng, &err)) rc = hd_cli_fail(cmd, &err);
  for (size_t r = 0; r < n && !rc; r++) {
    const hd_run_fit *f = &fits[r];
    int in = 0;
    for (size_t k = 0; k < g[0].n && !in; k++) in = g[0].idx[k] == r;
    if (!in) {
      other++;
      continue;
    }
    int dimers = species != HD_KIND_DISK;
    hd_snapshot *sn;
    size_t ns, used = 0;
    if (hd_ana_snapshots(db, f->info.id, a->label,
                         f->info.named_dimers ? "body"
                         : dimers             ? "dimer"
                                              : "disk",
                         &sn, &ns, &err)) {
      rc = hd_cli_fail(cmd, &err);
      break;
    }
    for (size_t s = 0; s < ns; s++) {
      hd_velstats vw, v2;
      if (isnan(sn[s].cpd) || sn[s].cpd < f->cpd_start || sn[s].cpd > f->cpd_end ||
          hd_velstats_2d(sn[s].vx, sn[s].vy, sn[s].n, &v2, &err))
        continue;
      int have_w = dimers && !hd_velstats_1d(sn[s].omega, sn[s].n, 0, &vw, &err);
      for (size_t i = 0; i < sn[s].n; i++) {
        gsl_histogram_increment(h[0], (sn[s].vx[i] - v2.mean_x) / v2.scale);
        gsl_histogram_increment(h[1], (sn[s].vy[i] - v2.mean_y) / v2.scale);
        if (have_w) gsl_histogram_increment(h[2], sn[s].omega[i] / vw.scale);
      }
      nv += (double)sn[s].n, nw += have_w ? (double)sn[s].n : 0;
      c0 = fmin(c0, sn[s].cpd), c1 = fmax(c1, sn[s].cpd);
      used++;
    }
    hd_snapshots_free(sn, ns);
    snaps += used, runs += used > 0;
  }
  hd_groups_free(g, ng);
  if (other)
    fprintf(stderr,
            "haff %s: note: --pool left out %zu run%s of another ensemble than the first run's "
            "(species, alpha, a/d, N, density, roughness, shapes or walls differ: haff-fit "
            "--alpha-group shows the groups)\n",
            cmd, other, other == 1 ? "" : "s");
  if (!rc && snaps == 0) {
    fprintf(stderr, "haff %s: --pool: no '%s' snapshot inside a run's HCS window\n", cmd, a->label);
    rc = 2;
  }
  FILE *out = rc ? NULL : hd_cli_out(a);
  if (!rc && !out) rc = 1;
  if (!rc) {
    double w = 2 * a->range / bins;
    /* one block, headed like the per-snapshot ones (its first field is the legend title) */
    fprintf(out,
            "pooled: %zu runs, %zu snapshots, cpd %.3g-%.3g\tcpd\tc\tp_vx\tp_vy\tp_omega\t"
            "gauss\tn\n",
            runs, snaps, c0, c1);
    for (size_t k = 0; k < (size_t)bins; k++) {
      double lo, hi;
      gsl_histogram_get_range(h[0], k, &lo, &hi);
      double c = 0.5 * (lo + hi);
      fprintf(out, "0\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.0f\n", 0.5 * (c0 + c1), c,
              gsl_histogram_get(h[0], k) / (nv * w), gsl_histogram_get(h[1], k) / (nv * w),
              nw > 0 ? gsl_histogram_get(h[2], k) / (nw * w) : NAN,
              exp(-0.5 * c * c) / sqrt(2 * M_PI), nv);
    }
    rc = hd_cli_close(out, a);
  }
  for (int k = 0; k < 3; k++) gsl_histogram_free(h[k]);
  free(fits);
  hd_ana_close(db);
  return rc;
}

const hd_optspec hd_cmd_veldist_spec = {
    HD_CLI_SPEC("veldist", HD_OPT_RUN | HD_OPT_BINS | HD_OPT_STATS | HD_OPT_FIT),
    .help_for =
        (const char *const[]){"run",
                              "the run (any status); required, except with --pool (default: every\n"
                              "finished run)",
                              NULL},
    .head =
        "usage: haff veldist DB --run ID [--stats] [--bins B] [--range X] [--label L] [-o FILE]\n"
        "       haff veldist DB --pool [--run ID] [--bins B] [--range X] [--label L] [-o FILE]\n"
        "Fig. 6: histograms of the scaled velocities c = (v - <v>)/s of every snapshot (label\n"
        "'velocities', taken at [log] velocities_at), s the snapshot's own per-component rms\n"
        "(vx, vy: sqrt(<|V-<V>|^2>/2); omega: sqrt(<omega^2>), not centred), so that a Maxwellian\n"
        "gives the standard normal.  One block per snapshot, two blank lines between, each headed\n"
        "by a line whose first field is its legend title 'cpd=X'.\n"
        "Columns: snap cpd c p_vx p_vy p_omega gauss   (p_omega NaN for disks)\n"};

int hd_cmd_veldist(int argc, char **argv) {
  hd_cli_args a;
  sqlite3 *db;
  hd_run_info ri;
  int rc = hd_cli_parse(&hd_cmd_veldist_spec, argc, argv, &a);
  if (rc) return rc < 0 ? 0 : rc;
  if (a.pool) {
    if (a.stats) {
      fprintf(stderr, "haff %s: --pool and --stats exclude each other\n", argv[0]);
      return 2;
    }
    return veldist_pool(&a, argv[0]);
  }
  rc = hd_cli_one_run(&hd_cmd_veldist_spec, argc, argv, &a, &db, &ri);
  if (rc) return rc < 0 ? 0 : rc;
  if (ri.species == HD_KIND_ROD) {
    hd_ana_close(db);
    fprintf(stderr, "haff %s: run %lld is a rods run: see haff rods-veldist\n", argv[0],
            (long long)a.run);
    return 2;
  }
  if (ri.species == HD_KIND_BODY) {
    hd_ana_close(db);
    refuse_shapes(argv[0], &ri);
    return 2;
  }
  int bins = a.bins ? a.bins : 40;
  hd_error err;
  size_t ns;
  hd_snapshot *sn;
  int dimers = ri.species != HD_KIND_DISK;
  rc = hd_ana_snapshots(db, a.run, a.label,
                        ri.named_dimers ? "body"
                        : dimers        ? "dimer"
                                        : "disk",
                        &sn, &ns, &err);
  hd_ana_close(db);
  if (rc) return hd_cli_fail(argv[0], &err);
  if (ns == 0) {
    fprintf(stderr, "haff %s: run %lld has no '%s' snapshots\n", argv[0], (long long)a.run,
            a.label);
    return 2;
  }
  FILE *out = hd_cli_out(&a);
  if (!out) {
    hd_snapshots_free(sn, ns);
    return 1;
  }
  gsl_histogram *h[3];
  for (int k = 0; k < 3; k++) {
    h[k] = gsl_histogram_alloc((size_t)bins);
    gsl_histogram_set_ranges_uniform(h[k], -a.range, a.range);
  }
  if (a.stats) fprintf(out, "snap\tt\tcpd\tvar\tn\tscale\tkurt\ta2\ta2_err\tks_d\tks_p\n");
  for (size_t s = 0; s < ns && !rc; s++) {
    hd_velstats vx, vy, vw, v2;
    int have_w = dimers;
    if (hd_velstats_1d(sn[s].vx, sn[s].n, 1, &vx, &err) ||
        hd_velstats_1d(sn[s].vy, sn[s].n, 1, &vy, &err) ||
        hd_velstats_2d(sn[s].vx, sn[s].vy, sn[s].n, &v2, &err)) {
      rc = hd_cli_fail(argv[0], &err);
      break;
    }
    if (have_w && hd_velstats_1d(sn[s].omega, sn[s].n, 0, &vw, &err)) have_w = 0;
    if (a.stats) {
      stat_line(out, s, &sn[s], "vx", &vx);
      stat_line(out, s, &sn[s], "vy", &vy);
      if (have_w) stat_line(out, s, &sn[s], "omega", &vw);
      stat_line(out, s, &sn[s], "v2d", &v2);
      continue;
    }
    double sc = v2.scale; /* one per-component scale for both components */
    for (int k = 0; k < 3; k++) gsl_histogram_reset(h[k]);
    for (size_t i = 0; i < sn[s].n; i++) {
      gsl_histogram_increment(h[0], (sn[s].vx[i] - v2.mean_x) / sc);
      gsl_histogram_increment(h[1], (sn[s].vy[i] - v2.mean_y) / sc);
      if (have_w) gsl_histogram_increment(h[2], sn[s].omega[i] / vw.scale);
    }
    double w = 2 * a.range / bins, dn = (double)sn[s].n;
    if (s) fprintf(out, "\n\n"); /* blank lines between blocks, none after the last */
    /* header: column 1's name is the block's legend title (gnuplot: title columnheader(1)) */
    fprintf(out, "cpd=%.4g\tcpd\tc\tp_vx\tp_vy\tp_omega\tgauss\n", sn[s].cpd);
    for (size_t k = 0; k < (size_t)bins; k++) {
      double lo, hi;
      gsl_histogram_get_range(h[0], k, &lo, &hi);
      double c = 0.5 * (lo + hi);
      fprintf(out, "%zu\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\n", s, sn[s].cpd, c,
              gsl_histogram_get(h[0], k) / (dn * w), gsl_histogram_get(h[1], k) / (dn * w),
              have_w ? gsl_histogram_get(h[2], k) / (dn * w) : NAN,
              exp(-0.5 * c * c) / sqrt(2 * M_PI));
    }
  }
  for (int k = 0; k < 3; k++) gsl_histogram_free(h[k]);
  hd_snapshots_free(sn, ns);
  int c = hd_cli_close(out, &a);
  return rc ? rc : c;
}
