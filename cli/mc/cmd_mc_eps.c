/* `haff mc eps`: sample, study the convergence of, or tabulate p_beta(eps) (engine/rods/eps.h). */
#include <errno.h>
#include <gsl/gsl_randist.h>
#include <gsl/gsl_sort.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "eps.h"
#include "haff.h"
#include "hd_db.h"
#include "hd_epsdb.h"
#include "hd_opt.h"

/* The options of `haff mc eps`. */
typedef struct eopts {
  double gamma, beta, beta2, bmin, bmax; /* --gamma (NAN: not given), --beta, --beta2 (NAN: B) */
  long n, seed, adapt, nbeta, nu;        /* --samples (-1: the mode's default), --adapt (-1) */
  int conv, tab;                         /* --convergence, --tabulate */
  const char *dump, *dbpath;             /* --dump FILE, --db DB */
  hd_eps_opts o;                         /* --step, --richardson, --refine */
} eopts;

#define NUM(N, F, M, H)                                                                            \
  HD_OPT_DBL(N, 0, eopts, F, -INFINITY, INFINITY, 0, M, H) /* nan refused, inf allowed */
static const hd_optdef eps_opts[] = {
    NUM("gamma", gamma, "G", "length ratio l1/l2 > 0 (required)"),
    NUM("beta", beta, "B",
        "E_tr/T_B, T_B the mean bath temperature (paper's rule) [1]; inf = cold"),
    NUM("beta2", beta2, "B2", "unequal baths: B = E_tr/T_B(rod 1), B2 = E_tr/T_B(rod 2)"),
    HD_OPT_INT("samples", 0, eopts, n, 1, LONG_MAX, 0, "N",
               "samples [10000] (per beta node with --tabulate [2000])"),
    HD_OPT_INT("seed", 0, eopts, seed, 0, LONG_MAX, 0, "K", "RNG seed (mt19937) [1]"),
    NUM("step", o.step, "H", "grid step in tau at beta >= 1 [0.01]"),
    NUM("refine", o.refine, "H",
        "refine the steps near the running maximum down to H, 0 = plain grid (tables and "
        "--convergence: the plain grid) [0.01/128]"),
    HD_OPT_INT("adapt", 0, eopts, adapt, 1, INT_MAX, 0, "A",
               "step reduced down to H/A at beta < 1 (power of 2) [16]"),
    HD_OPT_FLAG("richardson", 0, eopts, o.richardson,
                "per-path Richardson extrapolation (4x finer grid)"),
    HD_OPT_STR("dump", 0, eopts, dump, "FILE",
               "write the samples, one per line (-: to stdout, the summary to stderr)",
               .flags = HD_OPTF_OUTPUT),
    HD_OPT_FLAG("convergence", 0, eopts, conv,
                "bias against the step: TSV of mean eps at steps H..H/64 on coupled\n"
                "paths, and the detailed-balance yardsticks <beta(eps^2-1)> and\n"
                "<ln eps> with beta ~ Exp(1) (both 0 exactly)"),
    HD_OPT_FLAG("tabulate", 0, eopts, tab,
                "build inverse-CDF tables on a log beta grid and store them in --db;\n"
                "prints the table's KS distance and mean error against direct sampling"),
    HD_OPT_PATH("db", 0, eopts, dbpath, HD_OPTF_NOT_STDOUT | HD_OPTF_OUTPUT | HD_OPTF_DB, "DB",
                "the database of --tabulate"),
    NUM("beta-min", bmin, "B0", "table grid: smallest beta [1e-3]"),
    NUM("beta-max", bmax, "B1", "table grid: largest beta [1e3]"),
    HD_OPT_INT("nbeta", 0, eopts, nbeta, INT_MIN, INT_MAX, 0, "K", "table grid: beta nodes [25]"),
    HD_OPT_INT("nu", 0, eopts, nu, INT_MIN, INT_MAX, 0, "M", "table grid: entries per table [129]"),
    {0}};
#undef NUM

const hd_optspec hd_cmd_mc_eps_spec = {
    HD_OPT_SPEC("mc eps", eps_opts, 0, 0, 0, NULL),
    .head = "usage: haff mc eps --gamma G [--beta B] [--beta2 B2] [--samples N] [--seed K]\n"
            "                   [--step H] [--adapt A] [--richardson] [--refine H] [--dump FILE]\n"
            "       haff mc eps --gamma G [--beta B] --convergence [--samples N] [--step H]\n"
            "       haff mc eps --gamma G --tabulate --db DB [--beta-min B0] [--beta-max B1]\n"
            "                   [--nbeta K] [--nu M] [--samples N] [--step H]\n\n"
            "Samples the rods' stochastic coefficient of restitution eps (Aspelmeier et al. 1998,\n"
            "eqs. 13-14, hard-core limit) for length ratio G = l1/l2 and beta = E_tr/T_B.\n"
            "Prints TSV: gamma beta eps_mean eps_stderr eps_sd samples seconds.\n\n"};

static double seconds_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Mean, stderr, sd of x[0..n). */
static void moments(const double *x, long n, double *mean, double *se, double *sd) {
  double m = 0, v = 0;
  for (long i = 0; i < n; i++) m += x[i];
  m /= (double)n;
  for (long i = 0; i < n; i++) v += (x[i] - m) * (x[i] - m);
  v = n > 1 ? v / (double)(n - 1) : 0;
  *mean = m;
  *sd = sqrt(v);
  *se = sqrt(v / (double)n);
}

/* The convergence study (docs/mc-eps.md, "Bias against the step"). */
static int convergence(double gamma, double beta, double beta2, long n, double step, gsl_rng *rng) {
  enum { NS = 7 };
  hd_eps_opts o;
  hd_eps_opts_default(&o);
  o.step = step;
  o.adapt = 64;
  hd_eps_sampler *s;
  hd_error err;
  o.refine = 0; /* the study solves plain grids at several strides */
  if (hd_eps_sampler_alloc(&s, gamma, &o, &err)) {
    fprintf(stderr, "haff mc eps: %s\n", err.msg);
    return 2;
  }
  const int strides[NS] = {64, 32, 16, 8, 4, 2, 1};
  double out[NS];
  double *e = malloc(sizeof(double) * (size_t)n * NS);
  double *d1 = malloc(sizeof(double) * (size_t)n * NS),
         *d2 = malloc(sizeof(double) * (size_t)n * NS);
  double *col = malloc(sizeof(double) * (size_t)n);
  if (!e || !d1 || !d2 || !col) {
    fprintf(stderr, "haff mc eps: out of memory\n");
    free(e);
    free(d1);
    free(d2);
    free(col);
    hd_eps_sampler_free(s);
    return 1;
  }
  for (long i = 0; i < n; i++) {
    hd_eps_sample_strides(s, beta, beta2, strides, NS, out, rng);
    for (int m = 0; m < NS; m++) e[m * n + i] = out[m];
    double b = gsl_ran_exponential(rng, 1.0); /* detailed-balance yardsticks */
    hd_eps_sample_strides(s, b, b, strides, NS, out, rng);
    for (int m = 0; m < NS; m++) {
      d1[m * n + i] = b * (out[m] * out[m] - 1.0);
      d2[m * n + i] = log(out[m]);
    }
  }
  printf("scheme\tstep\teps_mean\teps_sd\tbias_vs_finest\tbias_stderr\tdb_energy\tdb_energy_se"
         "\tdb_log\tdb_log_se\tus_per_sample\n");
  double h0 = hd_eps_sampler_step(s) / 64.0;
  for (int pass = 0; pass < 2; pass++)
    for (int m = 0; m < NS; m++) {
      if (pass == 1 && m + 2 >= NS) break;
      double mean, se, sd, bm, bse, bsd, em, ese, lm, lse;
      /* plain grid at stride m, or Richardson 2 eps(stride/4) - eps(stride) */
      for (long i = 0; i < n; i++)
        col[i] = pass == 0 ? e[m * n + i] : fmax(0, 2 * e[(m + 2) * n + i] - e[m * n + i]);
      moments(col, n, &mean, &se, &sd);
      for (long i = 0; i < n; i++) col[i] -= e[(NS - 1) * n + i];
      moments(col, n, &bm, &bse, &bsd);
      for (long i = 0; i < n; i++)
        col[i] = pass == 0 ? d1[m * n + i] : 2 * d1[(m + 2) * n + i] - d1[m * n + i];
      moments(col, n, &em, &ese, &bsd);
      for (long i = 0; i < n; i++)
        col[i] = pass == 0 ? d2[m * n + i] : 2 * d2[(m + 2) * n + i] - d2[m * n + i];
      moments(col, n, &lm, &lse, &bsd);
      /* cost: time the plain sampler at this step on a fresh sampler */
      hd_eps_opts oc;
      hd_eps_opts_default(&oc);
      oc.step = h0 * strides[m];
      oc.adapt = 1;
      oc.richardson = pass;
      oc.refine = 0; /* the plain grid, as the rows */
      hd_eps_sampler *sc;
      double us = NAN;
      if (hd_eps_sampler_alloc(&sc, gamma, &oc, &err) == HD_OK) {
        long nt = n < 2000 ? n : 2000;
        double t0 = seconds_now();
        for (long i = 0; i < nt; i++) hd_eps_sample2(sc, beta, beta2, rng);
        us = (seconds_now() - t0) / (double)nt * 1e6;
        hd_eps_sampler_free(sc);
      }
      printf("%s\t%.6g\t%.6f\t%.6f\t%.6f\t%.6f\t%.5f\t%.5f\t%.5f\t%.5f\t%.2f\n",
             pass ? "richardson" : "grid", h0 * strides[m], mean, sd, bm, bse, em, ese, lm, lse,
             us);
    }
  free(e);
  free(d1);
  free(d2);
  free(col);
  hd_eps_sampler_free(s);
  return 0;
}

/* KS distance between the sorted sample x and the table's CDF at beta (u found by bisection). */
static double ks_table(const hd_eps_table *t, double beta, const double *x, long n) {
  double d = 0;
  for (long i = 0; i < n; i++) {
    double lo = 0, hi = 1;
    for (int it = 0; it < 40; it++) {
      double mid = 0.5 * (lo + hi);
      if (hd_eps_table_quantile(t, beta, mid) <= x[i])
        lo = mid;
      else
        hi = mid;
    }
    double a = fabs(lo - (double)i / (double)n), b = fabs(lo - (double)(i + 1) / (double)n);
    d = fmax(d, fmax(a, b));
  }
  return d;
}

static int tabulate(hd_eps_sampler *s, const char *dbpath, double bmin, double bmax, int nbeta,
                    int nu, long n, unsigned long seed, gsl_rng *rng) {
  hd_error err;
  hd_eps_table *t;
  if (hd_eps_table_build(&t, s, bmin, bmax, nbeta, nu, n, rng, &err)) {
    fprintf(stderr, "haff mc eps: %s\n", err.msg);
    return hd_exit_code(err.code);
  }
  /* opened as a run's writer opens it: a plain file name (not ":memory:" nor a URI), WAL, the
   * busy timeout of a run's writer (a run writing the file made it fail at once with "database
   * is locked"), and no table added to a database that is not haff's */
  hd_db *db = NULL;
  int64_t id = 0;
  int rc = hd_db_open(&db, dbpath, &err);
  if (!rc) rc = hd_eps_table_save(t, hd_db_handle(db), seed, &id, &err);
  hd_error e2;
  int crc = hd_db_close(db, &e2);
  if (!rc && crc) rc = crc, err = e2;
  if (rc) {
    fprintf(stderr, "haff mc eps: %s\n", err.msg);
    hd_eps_table_free(t);
    return hd_exit_code(rc);
  }
  fprintf(stderr, "eps table %lld: gamma %g, %d x %d, %ld samples per node, %.1f s\n",
          (long long)id, t->gamma, t->nbeta, t->nu, t->samples, t->seconds);
  /* the table's error at off-node betas (geometric midpoints) against fresh direct samples */
  printf("table\tbeta\tks\tks_noise\tmean_direct\tmean_table\tmean_err\tmean_err_se\n");
  double *x = malloc(sizeof(double) * (size_t)n);
  if (!x) {
    hd_eps_table_free(t);
    return 1;
  }
  double lr = log(bmax / bmin) / (nbeta - 1);
  for (int k = 0; k + 1 < nbeta; k += (nbeta > 6 ? (nbeta - 1) / 6 : 1)) {
    double b = bmin * exp(lr * (k + 0.5));
    for (long i = 0; i < n; i++) x[i] = hd_eps_sample(s, b, rng);
    gsl_sort(x, 1, (size_t)n);
    double ks = ks_table(t, b, x, n);
    double md = 0, mt = 0, vd = 0;
    for (long i = 0; i < n; i++) {
      md += x[i];
      vd += x[i] * x[i];
      mt += hd_eps_table_quantile(t, b, ((double)i + 0.5) / (double)n);
    }
    md /= (double)n;
    mt /= (double)n;
    vd = vd / (double)n - md * md;
    printf("%lld\t%.6g\t%.4f\t%.4f\t%.5f\t%.5f\t%.5f\t%.5f\n", (long long)id, b, ks,
           1.36 * sqrt(2.0 / (double)n), md, mt, mt - md, sqrt(2 * vd / (double)n));
  }
  free(x);
  hd_eps_table_free(t);
  return 0;
}

/* Draws n samples of eps with s at (beta, beta2), writes them to dump (a file, "-" for stdout,
 * or NULL), and prints the summary row.  Returns the exit code. */
static int sample(hd_eps_sampler *s, double gamma, double beta, double beta2, long n,
                  const char *dump, gsl_rng *rng) {
  double *x = malloc(sizeof(double) * (size_t)n);
  if (!x) {
    fprintf(stderr, "haff mc eps: out of memory\n");
    return 1;
  }
  int rc = 0;
  double t0 = seconds_now();
  for (long i = 0; i < n; i++) x[i] = hd_eps_sample2(s, beta, beta2, rng);
  double sec = seconds_now() - t0;
  /* --dump -: the samples are the stream on stdout, and the summary goes to stderr */
  int dump_stdout = dump && !strcmp(dump, "-");
  FILE *summary = dump_stdout ? stderr : stdout;
  if (dump) {
    FILE *f = dump_stdout ? stdout : fopen(dump, "w");
    if (!f) {
      fprintf(stderr, "haff mc eps: cannot write %s\n", dump);
      rc = 1;
    } else {
      for (long i = 0; i < n; i++) fprintf(f, "%.10g\n", x[i]);
      if (dump_stdout ? fflush(f) != 0 || ferror(f) : fclose(f) != 0) {
        fprintf(stderr, "haff mc eps: error writing %s\n", dump);
        rc = 1;
      }
    }
  }
  double mean, se, sd;
  moments(x, n, &mean, &se, &sd);
  fprintf(summary, "gamma\tbeta\teps_mean\teps_stderr\teps_sd\tsamples\tseconds\n");
  fprintf(summary, "%g\t%g\t%.6f\t%.6f\t%.6f\t%ld\t%.3f\n", gamma, beta, mean, se, sd, n, sec);
  hd_eps_stats st;
  hd_eps_sampler_stats(s, &st);
  if (st.truncated || st.clamped)
    fprintf(stderr, "haff mc eps: %ld collisions cut at max_tau, %ld Richardson values clamped\n",
            st.truncated, st.clamped);
  free(x);
  return rc;
}

/* The checks between options: --gamma required, the options the mode does not read refused
 * (--tabulate --beta 5 ran with no word of the beta).  Returns 0 or 2 after one line. */
static int eps_check(const hd_optres *res, const eopts *e) {
  if (isnan(e->gamma)) {
    fprintf(stderr, "haff mc eps: --gamma is required (see --help)\n");
    return 2;
  }
  if (e->tab)
    return hd_opt_refuse(&hd_cmd_mc_eps_spec, res, NULL, "beta beta2 dump convergence refine",
                         "with --tabulate");
  if (e->conv)
    return hd_opt_refuse(&hd_cmd_mc_eps_spec, res, NULL,
                         "dump adapt richardson refine db beta-min beta-max nbeta nu",
                         "with --convergence");
  return hd_opt_refuse(&hd_cmd_mc_eps_spec, res, NULL, "db beta-min beta-max nbeta nu",
                       "without --tabulate");
}

int hd_cmd_mc_eps(int argc, char **argv) {
  eopts e = {.gamma = NAN,
             .beta = 1,
             .beta2 = NAN,
             .bmin = 1e-3,
             .bmax = 1e3,
             .n = -1,
             .seed = 1,
             .adapt = -1,
             .nbeta = 25,
             .nu = 129};
  hd_eps_opts_default(&e.o);
  hd_optres res;
  int rc = hd_opt_parse(&hd_cmd_mc_eps_spec, argc, argv, &e, &res);
  if (rc) return rc < 0 ? 0 : rc;
  if ((rc = eps_check(&res, &e))) return rc;
  double gamma = e.gamma, beta = e.beta, beta2 = e.beta2, bmin = e.bmin, bmax = e.bmax;
  long n = e.n, seed = e.seed, nbeta = e.nbeta, nu = e.nu, adapt = e.adapt;
  int conv = e.conv, tab = e.tab;
  const char *dump = e.dump, *dbpath = e.dbpath;
  hd_eps_opts o = e.o;
  if (isnan(beta2)) beta2 = beta;
  if (!(beta > 0) || !(beta2 > 0)) {
    fprintf(stderr, "haff mc eps: --beta and --beta2 must be > 0\n");
    return 2;
  }
  if (tab && !dbpath) {
    fprintf(stderr, "haff mc eps: --tabulate needs --db DB\n");
    return 2;
  }
  if (adapt >= 0) o.adapt = (int)adapt;
  if (n < 0) n = tab ? 2000 : 10000;
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  if (!rng) return 1;
  gsl_rng_set(rng, (unsigned long)seed);
  if (conv) {
    rc = convergence(gamma, beta, beta2, n, o.step, rng);
    gsl_rng_free(rng);
    return rc;
  }
  hd_eps_sampler *s;
  hd_error err;
  if (tab) o.refine = 0; /* tables: the plain grid, as the ring's (docs/mc-eps.md 2b) */
  if (hd_eps_sampler_alloc(&s, gamma, &o, &err)) {
    fprintf(stderr, "haff mc eps: %s\n", err.msg);
    gsl_rng_free(rng);
    return hd_exit_code(err.code);
  }
  if (tab) {
    rc = tabulate(s, dbpath, bmin, bmax, (int)nbeta, (int)nu, n, (unsigned long)seed, rng);
    hd_eps_sampler_free(s);
    gsl_rng_free(rng);
    return rc;
  }
  rc = sample(s, gamma, beta, beta2, n, dump, rng);
  hd_eps_sampler_free(s);
  gsl_rng_free(rng);
  return rc;
}
