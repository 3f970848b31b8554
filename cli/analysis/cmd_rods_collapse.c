/* `haff rods-collapse`: scans (N, eps) of the constant-eps ring for inelastic collapse, against
 * McNamara and Young's criterion. */
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h" /* hd_cli_num */
#include "haff.h"
#include "hd_opt.h"
#include "hd_sim.h"
#include "rods.h"

/* The options of rods-collapse. */
typedef struct copts {
  const char *nl, *el; /* --n, --eps: the lists */
  long seeds;          /* --seeds K */
  double cpd, gamma;   /* --cpd C, --gamma G */
} copts;

static const hd_optdef collapse_opts[] = {
    HD_OPT_STR("n", 0, copts, nl, "LIST", "ring sizes N, even, >= 2 [4,8,16,32,64,128]"),
    HD_OPT_STR("eps", 0, copts, el, "LIST",
               "coefficients of restitution in [0, 1) [0.3,0.5,0.7,0.8,0.9,0.95]"),
    HD_OPT_INT("seeds", 0, copts, seeds, 1, 10000000, HD_OPTF_EXP, "K",
               "rings per (N, eps), seeds 1..K [4]"),
    HD_OPT_DBL("cpd", 0, copts, cpd, 0, 1e10, HD_OPTF_GT, "C",
               "collisions per rod that a ring runs unless it collapses [2000]"),
    HD_OPT_DBL("gamma", 0, copts, gamma, 0, 1, HD_OPTF_GT, "G",
               "mass ratio of the alternating rods [1: equal masses]"),
    {0}};

/* One item of --n and of --eps (the one number parser reads each). */
static const hd_optdef n_item = {
    .name = "n", .kind = HD_ARG_INT, .ilo = 2, .ihi = 100000000, .flags = HD_OPTF_EXP};
static const hd_optdef eps_item = {
    .name = "eps", .kind = HD_ARG_DOUBLE, .lo = 0, .hi = 1, .flags = HD_OPTF_LT | HD_OPTF_FINITE};

/* The comma-separated list s of option d into v[0..max), each item read by hd_opt_number: the
 * count, or -1 after one line on stderr (an empty item, as in 4,,8 or "", names the list). */
static int parse_list(const char *cmd, const hd_optdef *d, const char *s, double *v, int max) {
  char buf[512], *p = buf, *item;
  snprintf(buf, sizeof buf, "%s", s);
  int n = 0;
  while ((item = strsep(&p, ",")) != NULL) {
    long long w;
    if (n == max) {
      fprintf(stderr, "haff %s: --%s '%s': more than %d values\n", cmd, d->name, s, max);
      return -1;
    }
    if (hd_opt_number(cmd, d, *item ? item : s, &v[n], &w)) return -1;
    if (d->kind == HD_ARG_INT) v[n] = (double)w;
    n++;
  }
  return n;
}

const hd_optspec hd_cmd_rods_collapse_spec = {
    HD_OPT_SPEC("rods-collapse", collapse_opts, 0, 0, 0, NULL),
    .head = "usage: haff rods-collapse [--n LIST] [--eps LIST] [--seeds K] [--cpd C] [--gamma G]\n"
            "Scans the constant-eps ring for inelastic collapse: for every N in LIST "
            "[4,8,16,32,64,128]\n"
            "and eps in LIST [0.3,0.5,0.7,0.8,0.9,0.95], K [4] rings (seeds 1..K) run to C [2000]\n"
            "collisions per rod (C <= 1e10) or collapse.  Columns N eps collapsed runs frac n_my\n"
            "(McNamara and Young's -ln(1-eps)/(1-eps)) my_predicts (1 if N > n_my)\n"
            "median_cpd_at_collapse.\n"
            "Masses alternate with ratio G [1: equal masses, as in McNamara and Young].\n"};

int hd_cmd_rods_collapse(int argc, char **argv) {
  copts o = {"4,8,16,32,64,128", "0.3,0.5,0.7,0.8,0.9,0.95", 4, 2000, 1};
  hd_optres res;
  int rc = hd_opt_parse(&hd_cmd_rods_collapse_spec, argc, argv, &o, &res);
  if (rc) return rc < 0 ? 0 : rc;
  const char *nl = o.nl, *el = o.el;
  long seeds = o.seeds;
  double cpd = o.cpd, gamma = o.gamma;
  /* both lists read and checked once, before any ring runs (N odd too: before the header) */
  double ns[256], epss[256];
  int nn = parse_list(argv[0], &n_item, nl, ns, 256),
      ne = nn < 0 ? -1 : parse_list(argv[0], &eps_item, el, epss, 256);
  if (nn < 0 || ne < 0) return 2;
  for (int k = 0; k < nn; k++)
    if (fmod(ns[k], 2) != 0) {
      fprintf(stderr,
              "haff %s: --n '%g': a ring holds an even number of rods (2 species alternate)\n",
              argv[0], ns[k]);
      return 2;
    }
  double *at = malloc((size_t)seeds * sizeof *at); /* cpd at collapse of every collapsed ring */
  if (!at) {
    fprintf(stderr, "haff %s: out of memory\n", argv[0]);
    return 1;
  }
  printf("N\teps\tcollapsed\truns\tfrac\tn_my\tmy_predicts\tmedian_cpd_at_collapse\n");
  for (int in = 0; in < nn; in++) {
    long N = (long)ns[in]; /* read as a number: "1e4" too, which atol read as 1 */
    for (int ie = 0; ie < ne; ie++) {
      double eps = epss[ie];
      long col = 0;
      for (long s = 1; s <= seeds; s++) {
        hd_rods_params p;
        hd_rods_params_default(&p);
        p.n = N, p.gamma = gamma, p.nmod = 1, p.model = HD_RODS_CONSTANT, p.eps = eps;
        p.seed = (unsigned long long)s;
        hd_rods *r;
        hd_error err;
        if (hd_rods_alloc(&r, &p, &err)) {
          fprintf(stderr, "haff %s: %s\n", argv[0], err.msg);
          free(at);
          return 2;
        }
        hd_rods_event ev;
        long nc = (long)(cpd * (double)N / 2);
        int rr = HD_OK;
        for (long k = 0; k < nc && rr == HD_OK; k++) rr = hd_rods_next(r, INFINITY, &ev, &err);
        if (rr == HD_ECOLLAPSE) {
          at[col++] = 2.0 * (double)r->collisions / (double)N;
        } else if (rr != HD_OK && rr != HD_SIM_IDLE) {
          /* HD_SIM_IDLE: a ring that cools for ever ran out of time (t near DBL_MAX, speeds
           * subnormal): not a collapse.  Anything else is an error */
          fprintf(stderr, "haff %s: N %ld eps %g seed %ld: %s\n", argv[0], N, eps, s, err.msg);
          hd_rods_free(r);
          free(at);
          return 1;
        }
        hd_rods_free(r);
      }
      gsl_sort(at, 1, (size_t)col);
      double nmy = hd_rods_my_ncrit(eps);
      printf("%ld\t%g\t%ld\t%ld\t%.3g\t%.4g\t%d\t%s\n", N, eps, col, seeds,
             (double)col / (double)seeds, nmy, (double)N > nmy,
             hd_cli_num("%.6g", col ? gsl_stats_median_from_sorted_data(at, 1, (size_t)col) : NAN,
                        0)); /* no collapse: empty, not nan */
      fflush(stdout);
    }
  }
  free(at);
  return 0;
}
