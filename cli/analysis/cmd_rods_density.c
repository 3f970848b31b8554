/* `haff rods-density`: rods Figs. 3, 4, 6 data, coarse-grained density and local energy. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_rods.h"
#include "cli_common.h" /* hd_cli_num */
#include "haff.h"

const hd_optspec hd_cmd_rods_density_spec = {
    HD_RCLI_SPEC("rods-density", HD_RCLI_RUN | HD_RCLI_BINS | HD_RCLI_T),
    .head =
        "usage: haff rods-density DB [--run ID] [--bins N] [--t T]\n"
        "Figs. 3, 4, 6 data: the coarse-grained density rho (rods per bin over the mean, N bins\n"
        "[100] on the ring) and the local kinetic energy per rod in each bin, for every snapshot\n"
        "(or the one nearest --t).  Columns t bin x rho e_local; a blank line after each\n"
        "snapshot (gnuplot pm3d).\n"};

/* The density and local energy of each snapshot (hd_rcli_series_fn). */
static int density(const char *cmd, const ropts *o, rrun *r, const double *ts, long nt) {
  long N = r->sc.n_rods;
  long *cnt = calloc((size_t)o->bins, sizeof *cnt);
  double *ek = calloc((size_t)o->bins, sizeof *ek);
  if (!cnt || !ek) {
    free(cnt), free(ek);
    return hd_rcli_oom(cmd);
  }
  printf("t\tbin\tx\trho\te_local\n");
  for (long k = 0; k < nt; k++) {
    rsnap s;
    if (hd_rcli_snapshot(cmd, r, ts[k], &s)) {
      free(cnt), free(ek);
      return 1;
    }
    memset(cnt, 0, (size_t)o->bins * sizeof *cnt);
    memset(ek, 0, (size_t)o->bins * sizeof *ek);
    for (long i = 0; i < N; i++) {
      long b = (long)(s.x[i] / (double)N * o->bins);
      if (b >= o->bins) b = o->bins - 1;
      if (b < 0) b = 0;
      cnt[b]++;
      ek[b] += 0.5 * hd_rcli_mass(&r->sc, i) * s.v[i] * s.v[i];
    }
    double mean = (double)N / o->bins;
    for (int b = 0; b < o->bins; b++)
      printf("%.10g\t%d\t%.6g\t%.6g\t%s\n", ts[k], b, (b + 0.5) * (double)N / o->bins,
             (double)cnt[b] / mean,
             hd_cli_num("%.6g", cnt[b] ? ek[b] / (double)cnt[b] : NAN, 0)); /* empty bin: empty */
    printf("\n");
    hd_rcli_snap_free(&s);
  }
  free(cnt), free(ek);
  return 0;
}

int hd_cmd_rods_density(int argc, char **argv) {
  return hd_rcli_main_series(&hd_cmd_rods_density_spec, argc, argv, 100, density);
}
