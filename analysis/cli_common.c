/* cli_common: option parsing and shared plumbing of the analysis subcommands. */
#include "cli_common.h"

#include "hd_db.h"

#include <errno.h>
#include <getopt.h>
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static int parse_num(const char *cmd, const char *opt, const char *s, double lo, double *out) {
  char *end;
  errno = 0;
  double v = strtod(s, &end);
  if (end == s || *end || errno || !(v >= lo)) {
    fprintf(stderr, "haff %s: %s '%s': expected a number >= %g\n", cmd, opt, s, lo);
    return 2;
  }
  *out = v;
  return 0;
}

/* An integer option in [lo, hi]: whole digits only (no fraction, exponent or inf, which a cast
 * would truncate or make undefined); 2 after one line on stderr. */
static int parse_int(const char *cmd, const char *opt, const char *s, long long lo, long long hi,
                     long long *out) {
  char *end;
  errno = 0;
  long long v = strtoll(s, &end, 10);
  if (end == s || *end || errno || v < lo || v > hi) {
    fprintf(stderr, "haff %s: %s '%s': expected a whole number in [%lld, %lld]\n", cmd, opt, s, lo,
            hi);
    return 2;
  }
  *out = v;
  return 0;
}

int hd_cli_parse(int argc, char **argv, unsigned allowed, const char *usage, hd_cli_args *a) {
  memset(a, 0, sizeof *a);
  a->run = -1;
  a->fit = hd_fit_opts_defaults();
  a->block = 10000;
  a->bins = 0;
  a->label = "velocities";
  a->range = 5;
  a->kmode = HD_K_AC;
  const char *cmd = argv[0];
  static const struct option lo[] = {{"help", no_argument, 0, 'h'},
                                     {"run", required_argument, 0, 'r'},
                                     {"all", no_argument, 0, 'A'},
                                     {"no-detect", no_argument, 0, 'N'},
                                     {"thr", required_argument, 0, 'T'},
                                     {"min-coll", required_argument, 0, 'C'},
                                     {"cpd-max", required_argument, 0, 'X'},
                                     {"cpd-min-k", required_argument, 0, 'K'},
                                     {"md", no_argument, 0, 'M'},
                                     {"alpha-group", no_argument, 0, 'G'},
                                     {"block", required_argument, 0, 'b'},
                                     {"fmean", no_argument, 0, 'F'},
                                     {"bins", required_argument, 0, 'B'},
                                     {"stats", no_argument, 0, 'S'},
                                     {"label", required_argument, 0, 'L'},
                                     {"range", required_argument, 0, 'R'},
                                     {"k-ci", required_argument, 0, 'k'},
                                     {"cpd-skip", required_argument, 0, 'P'},
                                     {"s-end", required_argument, 0, 'E'},
                                     {"s-flag", required_argument, 0, 'Q'},
                                     {"min-window", required_argument, 0, 'W'},
                                     {"keep-flagged", no_argument, 0, 'Y'},
                                     {"pool", no_argument, 0, 'O'},
                                     {0, 0, 0, 0}};
  static const struct {
    int c;
    unsigned bit;
  } need[] = {{'r', HD_OPT_RUN},   {'A', HD_OPT_ALL},   {'N', HD_OPT_FIT},   {'T', HD_OPT_FIT},
              {'C', HD_OPT_FIT},   {'X', HD_OPT_FIT},   {'K', HD_OPT_KCI},   {'M', HD_OPT_MD},
              {'G', HD_OPT_GROUP}, {'b', HD_OPT_BLOCK}, {'F', HD_OPT_BLOCK}, {'B', HD_OPT_BINS},
              {'S', HD_OPT_STATS}, {'L', HD_OPT_STATS}, {'R', HD_OPT_STATS}, {'k', HD_OPT_KCI},
              {'P', HD_OPT_FIT},   {'E', HD_OPT_FIT},   {'Q', HD_OPT_FIT},   {'W', HD_OPT_FIT},
              {'Y', HD_OPT_MD},    {'O', HD_OPT_STATS}};
  optind = 0; /* full re-initialisation: the subcommands may run more than once per process */
  opterr = 0;
  int c, li;
  long long v;
  while ((c = getopt_long(argc, argv, "ho:", lo, &li)) != -1) {
    if (c == 'h') {
      printf("%s", usage);
      return -1;
    }
    if (c == '?') {
      char buf[8];
      fprintf(stderr, "haff %s: unknown option or missing value '%s' (see --help)\n", cmd,
              hd_opt_culprit(argv, lo, buf, sizeof buf));
      return 2;
    }
    for (size_t i = 0; i < sizeof need / sizeof need[0]; i++)
      if (need[i].c == c && !(allowed & need[i].bit)) {
        const char *name = "?";
        for (const struct option *o = lo; o->name; o++)
          if (o->val == c) name = o->name;
        fprintf(stderr, "haff %s: option '--%s' does not apply here (see --help)\n", cmd, name);
        return 2;
      }
    switch (c) {
    case 'o':
      a->out = optarg;
      break;
    case 'r':
      if (parse_int(cmd, "--run", optarg, 0, INT64_MAX, &v)) return 2;
      a->run = (int64_t)v;
      break;
    case 'A':
      a->all = 1;
      break;
    case 'N':
      a->fit.detect = 0;
      break;
    case 'T':
      if (parse_num(cmd, "--thr", optarg, 1e-6, &a->fit.homog.thr)) return 2;
      break;
    case 'C':
      if (parse_num(cmd, "--min-coll", optarg, 1, &a->fit.homog.min_coll)) return 2;
      break;
    case 'X':
      if (parse_num(cmd, "--cpd-max", optarg, 0, &a->fit.cpd_max)) return 2;
      break;
    case 'P':
      if (parse_num(cmd, "--cpd-skip", optarg, 0, &a->fit.hcs.cpd_skip)) return 2;
      break;
    case 'E':
      if (parse_num(cmd, "--s-end", optarg, 1e-6, &a->fit.hcs.s_end)) return 2;
      break;
    case 'Q':
      if (parse_num(cmd, "--s-flag", optarg, 1e-6, &a->fit.s_flag)) return 2;
      break;
    case 'W':
      if (parse_num(cmd, "--min-window", optarg, 0, &a->fit.min_window)) return 2;
      break;
    case 'Y':
      a->keep_flagged = 1;
      break;
    case 'O':
      a->pool = 1;
      break;
    case 'K':
      if (parse_num(cmd, "--cpd-min-k", optarg, 0, &a->fit.cpd_min_k)) return 2;
      break;
    case 'M':
      a->md = 1;
      break;
    case 'G':
      a->group = 1;
      break;
    case 'b':
      if (parse_int(cmd, "--block", optarg, 1, LONG_MAX, &v)) return 2;
      a->block = (long)v;
      break;
    case 'F':
      a->fmean = 1;
      break;
    case 'B':
      if (parse_int(cmd, "--bins", optarg, 1, 100000, &v)) return 2;
      a->bins = (int)v;
      break;
    case 'S':
      a->stats = 1;
      break;
    case 'L':
      a->label = optarg;
      break;
    case 'R':
      if (parse_num(cmd, "--range", optarg, 1e-9, &a->range)) return 2;
      break;
    case 'k':
      if (!strcmp(optarg, "ac"))
        a->kmode = HD_K_AC;
      else if (!strcmp(optarg, "ols"))
        a->kmode = HD_K_OLS;
      else if (!strcmp(optarg, "runs"))
        a->kmode = HD_K_RUNS;
      else {
        fprintf(stderr, "haff %s: --k-ci '%s': expected ac, ols or runs\n", cmd, optarg);
        return 2;
      }
      break;
    default:
      return 2;
    }
  }
  if (optind != argc - 1) {
    fprintf(stderr, "haff %s: expected one database argument (see --help)\n", cmd);
    return 2;
  }
  a->db = argv[optind];
  if (a->run >= 0 && a->all) {
    fprintf(stderr, "haff %s: --run and --all exclude each other\n", cmd);
    return 2;
  }
  return 0;
}

FILE *hd_cli_out(const hd_cli_args *a) {
  if (!a->out || !strcmp(a->out, "-")) return stdout; /* -o -: the stream to stdout */
  FILE *f = fopen(a->out, "w");
  if (!f) fprintf(stderr, "haff: %s: cannot write: %s\n", a->out, strerror(errno));
  return f;
}

int hd_cli_close(FILE *f, const hd_cli_args *a) {
  int bad = ferror(f);
  if (f != stdout)
    bad |= fclose(f);
  else
    bad |= fflush(f);
  if (bad) {
    fprintf(stderr, "haff: %s: write error\n", a->out && strcmp(a->out, "-") ? a->out : "stdout");
    return 1;
  }
  return 0;
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
    if (runs[i].species == HD_ANA_OTHER) continue;
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

int hd_cli_groups(const hd_cli_args *a, const char *cmd, sqlite3 **db, hd_run_fit **fits, size_t *n,
                  hd_group **g, size_t *ng) {
  int rc = hd_cli_fits(a, cmd, db, fits, n);
  if (rc) return rc;
  hd_error err;
  if (hd_group_runs(*fits, *n, g, ng, &err)) {
    free(*fits), *fits = NULL;
    hd_ana_close(*db), *db = NULL;
    return hd_cli_fail(cmd, &err);
  }
  hd_cli_groups_warn(cmd, *g, *ng);
  return 0;
}

void hd_cli_groups_warn(const char *cmd, const hd_group *g, size_t ng) {
  for (size_t j = 0; j < ng; j++)
    for (size_t k = 0; k < j; k++)
      if (hd_group_same_label(&g[j], &g[k])) {
        fprintf(stderr,
                "haff %s: warning: runs with alpha %g a/d %g differ in N, density, d or m (N %ld "
                "n %.6g and N %ld n %.6g): kept apart, as rows with the same alpha and a/d\n",
                cmd, g[j].alpha, g[j].a_over_d, g[k].nbodies, g[k].density, g[j].nbodies,
                g[j].density);
        break;
      }
}

void hd_cli_groups_free(sqlite3 *db, hd_run_fit *fits, hd_group *g, size_t ng) {
  free(fits), hd_groups_free(g, ng), hd_ana_close(db);
}

int hd_cli_one_run(int argc, char **argv, unsigned allowed, const char *usage, hd_cli_args *a,
                   sqlite3 **db, hd_run_info *info) {
  int rc = hd_cli_parse(argc, argv, allowed, usage, a);
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
