/* `haff angles`: contact-angle histograms per block of collisions (Fig. 5) and <f>. */
#include <gsl/gsl_histogram.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <stdlib.h>

#include "cli_common.h"
#include "haff.h"

const hd_optspec hd_cmd_angles_spec = {
    HD_CLI_SPEC("angles", HD_OPT_RUN | HD_OPT_BLOCK | HD_OPT_BINS),
    .help_for = (const char *const[]){"run", "the run (any status; required)", NULL},
    .head =
        "usage: haff angles DB --run ID [--block N] [--bins B] [--fmean] [-o FILE]\n"
        "Fig. 5: histogram of the contact angles theta (both bodies of every dimer-dimer\n"
        "collision, in (-pi, pi]) per block of N logged collisions, normalised to unit area.\n"
        "Columns: block first last theta density density_err   (first/last: collision numbers\n"
        "among the logged dimer-dimer collisions, 1-based; blocks separated by two blank lines,\n"
        "each headed by a line whose first field is its legend title; an incomplete last block\n"
        "is dropped)\n"};

int hd_cmd_angles(int argc, char **argv) {
  hd_cli_args a;
  sqlite3 *db;
  hd_run_info ri;
  int rc = hd_cli_one_run(&hd_cmd_angles_spec, argc, argv, &a, &db, &ri);
  if (rc) return rc < 0 ? 0 : rc;
  int bins = a.bins ? a.bins : 36;
  hd_error err;
  size_t n;
  double *ti, *tj, *f;
  if (hd_ana_dd_collisions(db, a.run, ri.named_dimers, &ti, &tj, &f, &n, &err)) {
    hd_ana_close(db);
    return hd_cli_fail(argv[0], &err);
  }
  hd_ana_close(db);
  if (n == 0) {
    free(ti), free(tj), free(f);
    if (ri.species == HD_KIND_BODY && ri.n > 0) /* the dimer-dimer rows of [dimers] only */
      fprintf(stderr,
              "haff %s: run %lld has named species (%s) and no logged dimer-dimer collisions: "
              "angles reads the collisions of [dimers], or of a gas of one named species of "
              "paper dimers (two equal disks); other bodies' contact angles are not Fig. 5's\n",
              argv[0], (long long)a.run, ri.label);
    else
      fprintf(stderr, "haff %s: run %lld has no logged dimer-dimer collisions\n", argv[0],
              (long long)a.run);
    return 2;
  }
  if (!a.fmean && n < (size_t)a.block) { /* before -o: no empty table for a plot to choke on */
    fprintf(stderr,
            "haff %s: run %lld has %zu dimer-dimer collisions, fewer than one block of %ld "
            "(--block)\n",
            argv[0], (long long)a.run, n, a.block);
    free(ti), free(tj), free(f);
    return 2;
  }
  FILE *out = hd_cli_out(&a);
  if (!out) {
    free(ti), free(tj), free(f);
    return 1;
  }
  if (a.fmean) {
    size_t bs = (size_t)a.block;
    if (n / bs < 20) bs = n / 20;
    if (bs < 1) {
      fprintf(stderr, "haff %s: %zu collisions are too few for batch means\n", argv[0], n);
      free(ti), free(tj), free(f), hd_cli_close(out, &a);
      return 2;
    }
    size_t nb = n / bs;
    double *bm = malloc(nb * sizeof *bm);
    for (size_t b = 0; bm && b < nb; b++) bm[b] = gsl_stats_mean(f + b * bs, 1, bs);
    double mean = gsl_stats_mean(f, 1, n);
    double se = bm ? gsl_stats_sd(bm, 1, nb) / sqrt((double)nb) : NAN;
    fprintf(out, "run\tn\tf_mean\tf_err\tbatches\tbatch_size\n%lld\t%zu\t%.8g\t%.3g\t%zu\t%zu\n",
            (long long)a.run, n, mean, se, nb, bs);
    free(bm);
  } else {
    gsl_histogram *h = gsl_histogram_alloc((size_t)bins);
    gsl_histogram_set_ranges_uniform(h, -M_PI, M_PI + 1e-12);
    size_t bs = (size_t)a.block, nb = n / bs;
    for (size_t b = 0; b < nb; b++) {
      gsl_histogram_reset(h);
      for (size_t i = b * bs; i < (b + 1) * bs; i++) {
        gsl_histogram_increment(h, ti[i]);
        gsl_histogram_increment(h, tj[i]);
      }
      double tot = gsl_histogram_sum(h), w = 2 * M_PI / bins;
      if (b) fprintf(out, "\n\n"); /* blank lines between blocks, none after the last */
      /* header: column 1's name is the block's legend title (gnuplot: title columnheader(1)) */
      fprintf(out, "collisions %zu-%zu\tfirst\tlast\ttheta\tdensity\tdensity_err\n", b * bs + 1,
              (b + 1) * bs);
      for (size_t k = 0; k < (size_t)bins; k++) {
        double lo, hi, c = gsl_histogram_get(h, k);
        gsl_histogram_get_range(h, k, &lo, &hi);
        fprintf(out, "%zu\t%zu\t%zu\t%.6g\t%.6g\t%.3g\n", b, b * bs + 1, (b + 1) * bs,
                0.5 * (lo + hi), c / (tot * w), sqrt(c) / (tot * w));
      }
    }
    gsl_histogram_free(h);
  }
  free(ti), free(tj), free(f);
  return hd_cli_close(out, &a);
}
