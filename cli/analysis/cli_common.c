/* cli_common: option parsing and shared plumbing of the analysis subcommands. */
#include "cli_common.h"
#include "haff.h"

#include "hd_db.h"

#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The options of the analysis subcommands: one table, each subcommand accepting the sets
 * (HD_OPT_*) of its spec's `allowed` (others: "does not apply here"). */
const hd_optdef hd_cli_opts[] = {
    HD_OPT_INT("run", 0, hd_cli_args, run, 0, INT64_MAX, HD_OPTF_ONCE, "ID",
               "one run (any status); default: every done/collapsed/interrupted run",
               .set = HD_OPT_RUN),
    HD_OPT_FLAG("all", 0, hd_cli_args, all, "every finished run (the default)", .set = HD_OPT_ALL),
    HD_OPT_FLAG("alpha-group", 0, hd_cli_args, group, "one line per (alpha, a/d) group",
                .set = HD_OPT_GROUP),
    HD_OPT_FLAG("by-species", 0, hd_cli_args, by_species,
                "one row per species of each ensemble of runs (same species, restitutions,\n"
                "box): T_i/T over the HCS window and Garzo-Dufty's value (docs/analysis.md)",
                .set = HD_OPT_SPECIES),
    HD_OPT_FLAG("md", 0, hd_cli_args, md, "a Markdown table instead of TSV", .set = HD_OPT_MD),
    HD_OPT_FLAG("keep-flagged", 0, hd_cli_args, keep_flagged,
                "keep the groups flagged inhomogeneous or short (left out by default)",
                .set = HD_OPT_MD),
    HD_OPT_ENUM("k-ci", 0, hd_cli_args, kmode, "ac|ols|runs", "ac|ols|runs",
                "ac [default]: runs combined by inverse-variance weights, each run's errors\n"
                "widened by its residuals' autocorrelation time (docs/analysis.md);\n"
                "ols: the same with plain OLS errors (the paper's test; too narrow);\n"
                "runs: mean over runs, t interval with runs-1 dof (needs >= 2 runs)",
                .set = HD_OPT_KCI),
    HD_OPT_DBL("cpd-min-k", 0, hd_cli_args, fit.cpd_min_k, 0, INFINITY, 0, "X",
               "skip the transient cpd < X [0]", .set = HD_OPT_KCI),
    HD_OPT_FLAG("no-detect", 0, hd_cli_args, fit.detect,
                "fit the whole run, not only the homogeneous part", .flags = HD_OPTF_CLEAR,
                .set = HD_OPT_FIT),
    HD_OPT_DBL("thr", 0, hd_cli_args, fit.homog.thr, 1e-6, INFINITY, 0, "X",
               "homogeneity: relative change of rate/sqrt(E) that ends it [0.1]",
               .set = HD_OPT_FIT),
    HD_OPT_DBL("min-coll", 0, hd_cli_args, fit.homog.min_coll, 1, INFINITY, 0, "N",
               "homogeneity: pair collisions per window [2000]", .set = HD_OPT_FIT),
    HD_OPT_DBL("cpd-max", 0, hd_cli_args, fit.cpd_max, 0, INFINITY, 0, "X",
               "fit only samples with cpd <= X (0: no limit, the default)", .set = HD_OPT_FIT),
    HD_OPT_DBL("cpd-skip", 0, hd_cli_args, fit.hcs.cpd_skip, 0, INFINITY, 0, "X",
               "HCS window: leave out the initial transient cpd < X [5]", .set = HD_OPT_FIT),
    HD_OPT_DBL("s-end", 0, hd_cli_args, fit.hcs.s_end, 1e-6, INFINITY, 0, "X",
               "HCS window: ends where a 5-cpd block's mean s_perp exceeds X [10]",
               .set = HD_OPT_FIT),
    HD_OPT_DBL("s-flag", 0, hd_cli_args, fit.s_flag, 1e-6, INFINITY, 0, "X",
               "flag a group 'inhomogeneous' when its window's mean s_perp exceeds X [2.5]",
               .set = HD_OPT_FIT),
    HD_OPT_DBL("min-window", 0, hd_cli_args, fit.min_window, 0, INFINITY, 0, "X",
               "... or when most of its runs left the HCS within X cpd [40]", .set = HD_OPT_FIT),
    HD_OPT_INT("block", 0, hd_cli_args, block, 1, LONG_MAX, 0, "N", "collisions per block [10000]",
               .set = HD_OPT_BLOCK),
    HD_OPT_FLAG("fmean", 0, hd_cli_args, fmean,
                "instead: one line 'run n f_mean f_err batches batch_size', <f> over\n"
                "the run with a batch-means standard error (batches of N, >= 20 of them)",
                .set = HD_OPT_BLOCK),
    HD_OPT_FLAG("stats", 0, hd_cli_args, stats,
                "instead: one line per snapshot and variable (vx, vy, omega, v2d):\n"
                "snap t cpd var n scale kurt a2 a2_err ks_d ks_p (docs/analysis.md)",
                .set = HD_OPT_STATS),
    HD_OPT_FLAG("pool", 0, hd_cli_args, pool,
                "one block instead: every snapshot of every finished run (or --run) of\n"
                "the first run's ensemble (haff-fit --alpha-group's group: species, alpha,\n"
                "a/d, N, density, roughness, shapes, walls) whose cpd is in the run's HCS\n"
                "window (haff-fit's\n"
                "window; fit options apply), pooled; extra column n (values per component)",
                .set = HD_OPT_STATS),
    HD_OPT_INT("bins", 0, hd_cli_args, bins, 1, 100000, 0, "B",
               "histogram bins [angles: 36 on (-pi, pi]; veldist: 40]", .set = HD_OPT_BINS),
    HD_OPT_DBL("range", 0, hd_cli_args, range, 1e-9, INFINITY, 0, "X", "histogram on [-X, X] [5]",
               .set = HD_OPT_STATS),
    HD_OPT_STR("label", 0, hd_cli_args, label, "L",
               "states label [velocities] (e.g. initial, final)", .set = HD_OPT_STATS),
    HD_OPT_STR("o", 'o', hd_cli_args, out, "FILE", "write to FILE instead of stdout (- is stdout)",
               .flags = HD_OPTF_SHORT | HD_OPTF_OUTPUT),
    {0}};

hd_cli_name hd_cli_group_name(const hd_group *g) {
  hd_cli_name n;
  if (isnan(g->alpha))
    snprintf(n.s, sizeof n.s, "alpha (several)");
  else
    snprintf(n.s, sizeof n.s, "alpha %g", g->alpha);
  if (!isnan(g->a_over_d)) {
    size_t l = strlen(n.s);
    snprintf(n.s + l, sizeof n.s - l, " a/d %g", g->a_over_d);
  }
  return n;
}

int hd_cli_parse(const hd_optspec *spec, int argc, char **argv, hd_cli_args *a) {
  memset(a, 0, sizeof *a);
  a->run = -1;
  a->fit = hd_fit_opts_defaults();
  a->block = 10000;
  a->bins = 0;
  a->label = "velocities";
  a->range = 5;
  a->kmode = HD_K_AC;
  hd_optres res;
  int rc = hd_opt_parse(spec, argc, argv, a, &res);
  if (rc) return rc;
  a->cmd = spec->cmd;
  a->db = res.pos[0];
  if (a->run >= 0 && a->all) {
    fprintf(stderr, "haff %s: --run and --all exclude each other\n", spec->cmd);
    return 2;
  }
  return 0;
}

FILE *hd_cli_out(const hd_cli_args *a) {
  if (!a->out || !strcmp(a->out, "-")) return stdout; /* -o -: the stream to stdout */
  FILE *f = haff_fopen_out(a->out);
  if (!f)
    fprintf(stderr, "haff %s: %s: cannot write: %s\n", a->cmd ? a->cmd : "", a->out,
            strerror(errno));
  return f;
}

int hd_cli_close(FILE *f, const hd_cli_args *a) {
  return haff_close_out(f, a->cmd, f == stdout ? NULL : a->out);
}

int hd_cli_fail(const char *cmd, const hd_error *err) {
  fprintf(stderr, "haff %s: %s\n", cmd, err->msg);
  return hd_exit_code(err->code);
}

int hd_cli_fits(const hd_cli_args *a, const char *cmd, sqlite3 **db, hd_run_fit **fits, size_t *n) {
  hd_error err;
  hd_error_clear(&err);
  *fits = NULL, *n = 0;
  if (hd_ana_open(db, a->db, &err)) return hd_cli_fail(cmd, &err);
  hd_run_info *runs;
  size_t nr;
  if (hd_ana_runs(*db, a->run, &runs, &nr, &err)) {
    hd_ana_close(*db), *db = NULL;
    return hd_cli_fail(cmd, &err);
  }
  if (nr == 0) {
    free(runs);
    hd_ana_close(*db), *db = NULL;
    fprintf(stderr, "haff %s: %s: no finished runs\n", cmd, a->db);
    return 2;
  }
  *fits = calloc(nr, sizeof **fits);
  if (!*fits) {
    free(runs);
    hd_ana_close(*db), *db = NULL;
    fprintf(stderr, "haff %s: out of memory\n", cmd);
    return 1;
  }
  size_t m = 0;
  for (size_t i = 0; i < nr; i++) {
    if (runs[i].species == HD_KIND_ROD) continue;
    int rc = hd_run_fit_do(*db, &runs[i], &a->fit, &(*fits)[m], &err);
    /* skip short runs in an ensemble, say so; not a damaged database (SQLite's "malformed",
     * bad input too, for the whole file) */
    if (rc == HD_EINPUT && a->run < 0 && hd_ana_status(*db) != HD_EINPUT) {
      fprintf(stderr, "haff %s: skipping: %s\n", cmd, err.msg);
      continue;
    }
    if (rc) {
      free(runs), free(*fits), *fits = NULL;
      hd_ana_close(*db), *db = NULL;
      return hd_cli_fail(cmd, &err);
    }
    if ((*fits)[m].why[0])
      fprintf(stderr, "haff %s: run %lld: %s\n", cmd, (long long)runs[i].id, (*fits)[m].why);
    m++;
  }
  free(runs);
  *n = m;
  size_t cnt[3] = {0, 0, 0};
  for (size_t i = 0; i < m; i++) cnt[(*fits)[i].window]++;
  if (m && a->fit.detect)
    fprintf(
        stderr,
        "haff %s: note: HCS windows: %zu stored with the runs (runs.hcs_*), %zu computed now%s\n",
        cmd, cnt[HD_WINDOW_STORED], cnt[HD_WINDOW_COMPUTED],
        cnt[HD_WINDOW_COMPUTED] == 0 ? ""
        : hd_hcs_opts_default(&a->fit.homog, &a->fit.hcs)
            ? " (no stored window: a file from before, or a run that has not ended)"
            : " (detection options other than the defaults)");
  if (m == 0) {
    free(*fits), *fits = NULL;
    hd_ana_close(*db), *db = NULL;
    fprintf(stderr, "haff %s: no run with dimers or disks and enough samples\n", cmd);
    return 2;
  }
  return 0;
}

int hd_cli_groups(const hd_optspec *spec, int argc, char **argv, hd_cli_args *a, hd_cli_set *s) {
  memset(s, 0, sizeof *s);
  int rc = hd_cli_parse(spec, argc, argv, a);
  if (rc) return rc;
  const char *cmd = spec->cmd;
  rc = hd_cli_fits(a, cmd, &s->db, &s->fits, &s->n);
  if (rc) return rc;
  hd_error err;
  if (hd_group_runs(s->fits, s->n, &s->g, &s->ng, &err)) {
    free(s->fits), s->fits = NULL;
    hd_ana_close(s->db), s->db = NULL;
    return hd_cli_fail(cmd, &err);
  }
  hd_cli_groups_warn(cmd, s->g, s->ng);
  return 0;
}

int hd_cli_table_start(const hd_optspec *spec, int argc, char **argv, int with_disks,
                       const char *none, hd_cli_args *a, hd_cli_set *s, FILE **out) {
  int rc = hd_cli_groups(spec, argc, argv, a, s);
  if (rc) return rc;
  if (hd_cli_table_groups(spec->cmd, s->g, s->ng, with_disks) == 0) { /* bad input */
    fprintf(stderr, "haff %s: %s\n", spec->cmd, none);
    hd_cli_groups_free(s);
    return 2;
  }
  if (!(*out = hd_cli_out(a))) {
    hd_cli_groups_free(s);
    return 1;
  }
  return 0;
}

void hd_cli_groups_warn(const char *cmd, const hd_group *g, size_t ng) {
  for (size_t j = 0; j < ng; j++)
    for (size_t k = 0; k < j; k++)
      if (hd_group_same_label(&g[j], &g[k])) {
        char what[160];
        hd_group_differ(&g[k], &g[j], what, sizeof what);
        fprintf(stderr,
                "haff %s: warning: runs with %s differ in %s (N %ld n %.6g%s and N "
                "%ld n %.6g%s): kept apart, as rows with the same alpha and a/d\n",
                cmd, hd_cli_group_name(&g[j]).s, what, g[k].nbodies, g[k].density,
                g[k].rough ? ", rough" : "", g[j].nbodies, g[j].density,
                g[j].rough ? ", rough" : "");
        break;
      }
  for (size_t j = 0; j < ng; j++)
    if (g[j].rough)
      fprintf(stderr,
              "haff %s: note: %s %s N %ld: rough bodies (tangential restitution "
              "beta > -1): eq. (31) is Haff's law of smooth bodies, so their D_e is a fit "
              "parameter, not eq. (31)'s (flag rough; docs/analysis.md, \"Rough bodies\")\n",
              cmd, g[j].label, hd_cli_group_name(&g[j]).s, g[j].nbodies);
}

void hd_cli_groups_free(hd_cli_set *s) {
  free(s->fits), hd_groups_free(s->g, s->ng), hd_ana_close(s->db);
  memset(s, 0, sizeof *s);
}

int hd_cli_one_run(const hd_optspec *spec, int argc, char **argv, hd_cli_args *a, sqlite3 **db,
                   hd_run_info *info) {
  int rc = hd_cli_parse(spec, argc, argv, a);
  if (rc) return rc;
  if (a->run < 0) {
    fprintf(stderr, "haff %s: --run ID is required\n", argv[0]);
    return 2;
  }
  hd_error err;
  if (hd_ana_open(db, a->db, &err)) return hd_cli_fail(argv[0], &err);
  hd_run_info *ri;
  size_t nr;
  if (hd_ana_runs(*db, a->run, &ri, &nr, &err)) {
    hd_ana_close(*db), *db = NULL;
    return hd_cli_fail(argv[0], &err);
  }
  *info = ri[0];
  free(ri);
  return 0;
}

const char *hd_cli_window_name(int window) {
  return window == HD_WINDOW_STORED     ? "stored"
         : window == HD_WINDOW_COMPUTED ? "computed"
                                        : "whole";
}

/* Whether group g is in the papers' tables: one species in a periodic box, dimers (and disks
 * when with_disks: Table I's reference; Table II's K needs rotation). */
int hd_cli_in_table(const hd_group *g, int with_disks) {
  return !g->walls && ((g->species == HD_KIND_DIMER && !g->mixture) ||
                       (with_disks && g->species == HD_KIND_DISK));
}

/* How many of the groups g[0..ng) are in the table; says on stderr which are left out for not
 * being the papers' case (a mixture, walls) and where they are fitted. */
size_t hd_cli_table_groups(const char *cmd, const hd_group *g, size_t ng, int with_disks) {
  size_t in = 0;
  for (size_t j = 0; j < ng; j++) {
    if (hd_cli_in_table(&g[j], with_disks))
      in++;
    else if (g[j].species != HD_KIND_DISK || g[j].walls) /* not the disks table2 has no use for */
      fprintf(stderr,
              "haff %s: note: left out %zu run%s of %s (%s): %s; haff-fit "
              "--alpha-group fits them\n",
              cmd, g[j].n, g[j].n == 1 ? "" : "s", g[j].label, hd_cli_group_name(&g[j]).s,
              g[j].walls     ? "the table is for a periodic box, these have walls"
              : g[j].mixture ? "the table is for one species, these are a mixture"
              : g[j].species == HD_KIND_BODY
                  ? "the table is for dimers (of [dimers], or a gas of one named species of two "
                    "equal disks) and disks, these are other bodies or a mixture"
                  : "the table is for one species in a periodic box");
  }
  return in;
}

/* Whether a table leaves group g out for being flagged inhomogeneous (not with keep); says so on
 * stderr, and that a group without state measures could not be checked. */
int hd_cli_flagged_out(const char *cmd, const hd_group *g, const hd_group_fit *q, int keep) {
  if (!q->measured)
    fprintf(stderr,
            "haff %s: note: %s: no state measures in its samples (logged before "
            "schema 2): its homogeneity is not checked and D_e_sys has no box term\n",
            cmd, hd_cli_group_name(g).s);
  if (!(q->flagged & ~HD_FLAG_ROUGH) || keep) return 0; /* rough: a caveat, kept */
  if (q->flagged & HD_FLAG_INHOMOG)
    fprintf(stderr,
            "haff %s: note: left out %s N %ld: inhomogeneous (window mean s_perp "
            "%.3g, %zu of %zu runs left the HCS early); --keep-flagged keeps it\n",
            cmd, hd_cli_group_name(g).s, g->nbodies, q->s_perp, q->ended, q->m);
  else if (q->flagged & HD_FLAG_SHORT)
    fprintf(stderr,
            "haff %s: note: left out %s N %ld: short (%zu of %zu runs have a window "
            "too short for eq. (31)); --keep-flagged keeps it\n",
            cmd, hd_cli_group_name(g).s, g->nbodies, q->n_short, q->n_short + q->m);
  else
    fprintf(stderr,
            "haff %s: note: left out %s N %ld: outliers (%zu of %zu runs rejected, "
            "more than %g of them: the box's bursts are not rare); --keep-flagged keeps it\n",
            cmd, hd_cli_group_name(g).s, g->nbodies, q->n_rejected, q->n_rejected + q->m,
            HD_FIT_REJECT_FLAG);
  return 1;
}

/* Says on stderr why a group fitted from one run has no error (hd_ensemble_mean). */
void hd_cli_one_run_note(const char *cmd, const hd_group *g, size_t m) {
  if (m == 1)
    fprintf(stderr,
            "haff %s: note: %s: one fitted run, so its errors are empty (an ensemble "
            "error needs >= 2 runs; the fit's formal error, haff-fit's *_fit_err, is several times "
            "smaller than the scatter between runs)\n",
            cmd, hd_cli_group_name(g).s);
}

void hd_cli_short_note(const char *cmd, const hd_group *g, const hd_group_fit *q) {
  if (q->n_rejected)
    fprintf(stderr,
            "haff %s: note: %s N %ld: rejected %zu run%s whose D_e is more than %g "
            "robust standard deviations from the group's median (near-collapse bursts; "
            "haff-fit flags them `outlier`, docs/analysis.md \"Outlier runs\")%s\n",
            cmd, hd_cli_group_name(g).s, g->nbodies, q->n_rejected, q->n_rejected == 1 ? "" : "s",
            HD_FIT_REJECT_Z,
            q->flagged & HD_FLAG_OUTLIERS ? ": the group is flagged outliers" : "");
  if (q->n_short)
    fprintf(stderr,
            "haff %s: note: %s N %ld: left out %zu run%s whose window is too short "
            "for eq. (31) (< %d samples, or ln(E_start/E_end) < %g)%s\n",
            cmd, hd_cli_group_name(g).s, g->nbodies, q->n_short, q->n_short == 1 ? "" : "s",
            HD_FIT_MIN_SAMPLES, HD_FIT_MIN_DECAY,
            q->flagged & HD_FLAG_SHORT ? ": the group is flagged short" : "");
}

const char *hd_cli_num(const char *fmt, double x, int md) {
  static char buf[64][40];
  static unsigned k;
  char *b = buf[k++ % 64];
  if (isnan(x)) return md ? "—" : "";
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
  snprintf(b, sizeof buf[0], fmt, x);
#pragma GCC diagnostic pop
  return b;
}
