/* cli_species: the per-species analysis of mixtures, `--by-species` (hd_species). */
#include "cli_species.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_grid.h"
#include "hd_species.h"

/* What both commands read: the runs' fits and their ensembles. */
typedef struct loaded {
  sqlite3 *db;
  hd_run_fit *fits;
  hd_species_group *g; /* ng ensembles (hd_species_groups) */
  size_t ng;
} loaded;

/* hd_cli_fits, then the ensembles (hd_species_groups).  Exit code; on 0 *l is the caller's to
 * free with unload. */
static int load(const hd_cli_args *a, const char *cmd, loaded *l) {
  size_t n;
  int rc = hd_cli_fits(a, cmd, &l->db, &l->fits, &n);
  if (rc) return rc;
  hd_error err;
  if (hd_species_groups(l->db, l->fits, n, &l->g, &l->ng, &err)) {
    free(l->fits), hd_ana_close(l->db);
    return hd_cli_fail(cmd, &err);
  }
  if (l->ng == 0) {
    free(l->fits), hd_ana_close(l->db), hd_species_groups_free(l->g, l->ng);
    fprintf(stderr, "haff %s: no run with species (rods have none)\n", cmd);
    return 2;
  }
  for (size_t j = 0; j < l->ng; j++) {
    const hd_species_group *q = &l->g[j];
    if (q->used == 0)
      fprintf(stderr, "haff %s: run %lld and its ensemble: no per-species samples in the window\n",
              cmd, (long long)l->fits[q->idx[0]].info.id);
  }
  return 0;
}

static void unload(loaded *l) {
  hd_species_groups_free(l->g, l->ng), free(l->fits), hd_ana_close(l->db);
}

int hd_cli_species_fit(const hd_cli_args *a, const char *cmd) {
  loaded l;
  int rc = load(a, cmd, &l);
  if (rc) return rc;
  const hd_run_fit *fits = l.fits;
  const hd_species_group *g = l.g;
  size_t ng = l.ng;
  FILE *out = hd_cli_out(a);
  if (out) {
    fprintf(out, "group\trun\truns\tspecies\tN\tT_ratio\tT_ratio_err\terr_from\tT_ratio_theory\t"
                 "K\tK_err\tmass\tsigma\talpha\tcpd_start\tcpd_end\n");
    for (size_t j = 0; j < ng; j++) {
      const hd_species_group *q = &g[j];
      if (q->why[0])
        fprintf(stderr, "haff %s: group %zu: no T_ratio_theory: %s\n", cmd, j + 1, q->why);
      for (int i = 0; i < q->mix.k; i++) {
        const hd_species_row *w = &q->row[i];
        const hd_ana_sp *p = &q->mix.sp[i];
#define N(fmt, x) hd_cli_num(fmt, x, 0)
        fprintf(out, "%zu\t%lld\t%zu\t%s\t%ld\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n", j + 1,
                (long long)fits[q->idx[0]].info.id, q->used, p->name, p->count,
                N("%.6g", w->T_ratio), N("%.3g", w->T_ratio_err),
                q->used == 0  ? ""
                : q->err_runs ? "runs"
                              : "blocks",
                N("%.6g", w->T_ratio_theory), N("%.6g", w->K), N("%.3g", w->K_err),
                N("%.6g", p->mass), N("%.6g", p->sigma), N("%g", q->mix.alpha[i * q->mix.k + i]),
                N("%.4g", q->cpd_start), N("%.4g", q->cpd_end));
#undef N
      }
    }
    rc = hd_cli_close(out, a);
  } else {
    rc = 1;
  }
  size_t used = 0;
  for (size_t j = 0; j < ng; j++) used += g[j].used;
  unload(&l);
  if (!rc && used == 0) {
    fprintf(stderr, "haff %s: no run had per-species samples in its window\n", cmd);
    return 2;
  }
  return rc;
}

/* One run's per-species series with the cpd of each frame (NaN where samples has no row at
 * that t) and whether the frame is in the run's window. */
typedef struct run_series {
  hd_ana_spseries s;
  double *cpd;
} run_series;

static int read_run(sqlite3 *db, const hd_run_fit *f, const hd_ana_mix *mix, run_series *r,
                    hd_error *err) {
  memset(r, 0, sizeof *r);
  int rc = hd_ana_spseries_read(db, f->info.id, mix, &r->s, err);
  if (rc) return rc;
  hd_series smp;
  if ((rc = hd_ana_samples(db, f->info.id, &smp, err))) return hd_ana_spseries_free(&r->s), rc;
  r->cpd = malloc((r->s.n ? r->s.n : 1) * sizeof *r->cpd);
  if (!r->cpd) rc = hd_error_set(err, HD_ENOMEM, "out of memory");
  for (size_t i = 0, q = 0; !rc && i < r->s.n; i++) { /* both by t */
    while (q < smp.n && smp.t[q] < r->s.t[i]) q++;
    r->cpd[i] = q < smp.n && smp.t[q] == r->s.t[i] ? smp.cpd[q] : NAN;
  }
  hd_series_free(&smp);
  if (rc) hd_ana_spseries_free(&r->s), free(r->cpd), r->cpd = NULL;
  return rc;
}

/* The blocks of group q (one per species), the first one's separator after `first`: the runs
 * averaged at matching cpd (hd_cli_grid: on the finest run's cpd values over the range every
 * run covers; cmd_energy.c's rule: t linear in cpd, the energies linear in ln E). */
static int write_group(FILE *out, const char *cmd, sqlite3 *db, const hd_run_fit *fits,
                       const hd_species_group *q, size_t gi, int *first, hd_error *err) {
  size_t n = q->n, k = (size_t)q->mix.k;
  run_series *r = calloc(n ? n : 1, sizeof *r);
  const double **x = calloc(n ? n : 1, sizeof *x);
  size_t *nx = calloc(n ? n : 1, sizeof *nx), *hint = calloc(n ? n : 1, sizeof *hint);
  double *et = malloc((k ? k : 1) * sizeof *et);
  hd_cli_grid g = {0};
  int rc = HD_OK, empty = 0;
  if (!r || !x || !nx || !hint || !et) rc = hd_error_set(err, HD_ENOMEM, "out of memory");
  for (size_t i = 0; i < n && !rc; i++) {
    rc = read_run(db, &fits[q->idx[i]], &q->mix, &r[i], err);
    if (!rc) x[i] = r[i].cpd, nx[i] = r[i].s.n, empty |= r[i].s.n == 0;
  }
  if (!rc && n > 0 && !empty) rc = hd_cli_grid_make(x, nx, n, &g, err);
  if (!rc && n > 0 && !empty) {
    long N = 0;
    for (size_t j = 0; j < k; j++) N += q->mix.sp[j].count;
    if (g.longest > g.hi)
      fprintf(stderr,
              "haff %s: note: group %zu: averaged up to cpd %g, where its shortest run ends "
              "(the longest goes on to cpd %g)\n",
              cmd, gi + 1, g.hi, g.longest);
    for (size_t j = 0; j < k; j++) {
      const hd_ana_sp *p = &q->mix.sp[j];
      if (!*first) fprintf(out, "\n\n");
      *first = 0;
      fprintf(out, "# group=%zu run=%lld runs=%zu species=%s N=%ld T_ratio_theory=%s cpd_end=%.8g",
              gi + 1, (long long)fits[q->idx[0]].info.id, n, p->name, p->count,
              hd_cli_num("%.6g", q->row[j].T_ratio_theory, 0), g.hi);
      if (g.longest > g.hi) fprintf(out, " truncated_from=%.8g", g.longest);
      fprintf(out, "\n%s (%zu runs)\tcpd\te_tr\te_rot\tT_ratio\tK\thcs\n", p->name, n);
      for (size_t i = 0; i < n; i++) hint[i] = 0;
      for (size_t f = 0; f < g.n; f++) {
        double c = g.cpd[f], t = 0, etj = 0, er = 0, tr = 0;
        int in = 1;
        for (size_t i = 0; i < n; i++) {
          const hd_ana_spseries *s = &r[i].s;
          const hd_run_fit *fi = &fits[q->idx[i]];
          size_t h = hint[i], h2;
          double Tm = 0;
          t += hd_cli_interp(x[i], s->t, 1, nx[i], c, 0, &h);
          for (size_t l = 0; l < k; l++) {
            h2 = hint[i];
            et[l] = hd_cli_interp(x[i], s->e_tr + l, k, nx[i], c, 1, &h2);
            Tm += (double)q->mix.sp[l].count / (double)N * et[l];
          }
          h2 = hint[i];
          er += hd_cli_interp(x[i], s->e_rot + j, k, nx[i], c, 1, &h2);
          hint[i] = h;
          etj += et[j], tr += et[j] / Tm;
          in &= c >= fi->cpd_start && c <= fi->cpd_end;
        }
        double m = (double)n;
        fprintf(out, "%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%s\t%d\n", t / m, c, etj / m, er / m, tr / m,
                hd_cli_num("%.8g", p->rotates && er > 0 ? etj / er : NAN, 0), in);
      }
    }
  }
  for (size_t i = 0; r && i < n; i++) hd_ana_spseries_free(&r[i].s), free(r[i].cpd);
  hd_cli_grid_free(&g);
  free(r), free(x), free(nx), free(hint), free(et);
  return rc;
}

int hd_cli_species_energy(const hd_cli_args *a, const char *cmd) {
  loaded l;
  int rc = load(a, cmd, &l);
  if (rc) return rc;
  FILE *out = hd_cli_out(a);
  hd_error err;
  int first = 1;
  rc = out ? 0 : 1;
  for (size_t j = 0; out && j < l.ng && !rc; j++)
    if (write_group(out, cmd, l.db, l.fits, &l.g[j], j, &first, &err)) rc = hd_cli_fail(cmd, &err);
  if (out) {
    int c = hd_cli_close(out, a);
    if (!rc) rc = c;
  }
  unload(&l);
  return rc;
}
