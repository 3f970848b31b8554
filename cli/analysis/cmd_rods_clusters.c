/* `haff rods-clusters`: the clusters of every snapshot (count, largest, fraction in them). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_rods.h"
#include "haff.h"

const hd_optspec hd_cmd_rods_clusters_spec = {
    HD_RCLI_SPEC("rods-clusters", HD_RCLI_RUN | HD_RCLI_GAP | HD_RCLI_MIN),
    .head =
        "usage: haff rods-clusters DB [--run ID] [--gap G] [--min-size M]\n"
        "Clusters per snapshot (maximal runs of rods closer than G [0.1] to their neighbour, at\n"
        "least M [10] rods): columns t clusters largest in_clusters (fraction of rods in them).\n"};

/* The clusters of each snapshot (hd_rcli_series_fn). */
static int clusters(const char *cmd, const ropts *o, rrun *r, const double *ts, long nt) {
  long N = r->sc.n_rods;
  rclusters cl;
  if (hd_rcli_clusters_alloc(&cl, N)) return hd_rcli_oom(cmd);
  const long *size = cl.size;
  printf("t\tclusters\tlargest\tin_clusters\n");
  for (long k = 0; k < nt; k++) {
    rsnap s;
    if (hd_rcli_snapshot(cmd, r, ts[k], &s)) {
      hd_rcli_clusters_free(&cl);
      return 1;
    }
    long nc = hd_rcli_find_clusters(s.x, N, o->gap, &cl), big = 0, cnt = 0, in = 0;
    for (long c = 0; c < nc; c++)
      if (size[c] >= o->minsize) cnt++, in += size[c], big = size[c] > big ? size[c] : big;
    printf("%.10g\t%ld\t%ld\t%.6g\n", ts[k], cnt, big, (double)in / (double)N);
    hd_rcli_snap_free(&s);
  }
  hd_rcli_clusters_free(&cl);
  return 0;
}

int hd_cmd_rods_clusters(int argc, char **argv) {
  return hd_rcli_main_series(&hd_cmd_rods_clusters_spec, argc, argv, 0, clusters);
}
