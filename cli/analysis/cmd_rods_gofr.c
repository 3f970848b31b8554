/* `haff rods-gofr`: rods Fig. 8 data, the pair correlation g(x) at a time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_rods.h"
#include "haff.h"

const hd_optspec hd_cmd_rods_gofr_spec = {
    HD_RCLI_SPEC("rods-gofr", HD_RCLI_RUN | HD_RCLI_T | HD_RCLI_BINS | HD_RCLI_RANGE),
    .head =
        "usage: haff rods-gofr DB [--run ID] [--t T] [--bins N] [--range X]\n"
        "Fig. 8 data: g(x) = 1/(N-1) sum_{i!=j} delta(x - |x_i - x_j|) (ring distance), "
        "normalised\n"
        "so that uniformly placed rods give 1, on N bins [200] of [0, X] [50], at the snapshot\n"
        "nearest --t.  Columns x g.\n"};

/* The table of one snapshot (hd_rcli_at_fn). */
static int gofr(const char *cmd, const ropts *o, const rrun *r, const rsnap *s) {
  const double *x = s->x;
  long N = r->sc.n_rods;
  double L = (double)N, dx = o->range / o->bins;
  double *h = calloc((size_t)o->bins, sizeof *h);
  if (!h) return hd_rcli_oom(cmd);
  for (long i = 0; i < N; i++)
    for (long j = i + 1; j < N; j++) {
      double d = fabs(x[i] - x[j]);
      if (d > L / 2) d = L - d;
      double q = d / dx; /* compared as a double: a tiny --range makes it past a long */
      if (q < o->bins) h[(long)q] += 2;
    }
  printf("# t = %.10g\nx\tg\n", s->t);
  for (int b = 0; b < o->bins; b++) /* uniform: N (N-1) 2 dx / L ordered pairs per bin */
    printf("%.6g\t%.6g\n", (b + 0.5) * dx, h[b] / ((double)N * (double)(N - 1) * 2 * dx / L));
  free(h);
  return 0;
}

int hd_cmd_rods_gofr(int argc, char **argv) {
  return hd_rcli_main_at(&hd_cmd_rods_gofr_spec, argc, argv, 200, gofr);
}
