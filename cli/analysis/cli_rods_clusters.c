/* `haff rods-clusters`: the clusters of every snapshot (count, largest, fraction in them). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_rods.h"
#include "haff.h"

const hd_optspec haff_rods_clusters_spec = {
    HD_OPT_SPEC("rods-clusters", hd_rcli_opts, HD_RCLI_RUN | HD_RCLI_GAP | HD_RCLI_MIN, 1, 1,
                "one database"),
    .head =
        "usage: haff rods-clusters DB [--run ID] [--gap G] [--min-size M]\n"
        "Clusters per snapshot (maximal runs of rods closer than G [0.1] to their neighbour, at\n"
        "least M [10] rods): columns t clusters largest in_clusters (fraction of rods in them).\n"};

int haff_rods_clusters_main(int argc, char **argv) {
  ropts o;
  rrun r;
  int rc = hd_rcli_start(&haff_rods_clusters_spec, argc, argv, 0, &o, &r);
  if (rc) return rc < 0 ? 0 : rc;
  long N = r.sc.n_rods;
  double *ts;
  long nt = hd_rcli_snap_times(&r, &ts);
  rclusters cl;
  if (hd_rcli_clusters_alloc(&cl, N)) {
    free(ts), hd_rcli_close(&r);
    return hd_rcli_oom(argv[0]);
  }
  const long *size = cl.size;
  printf("t\tclusters\tlargest\tin_clusters\n");
  for (long k = 0; k < nt; k++) {
    rsnap s;
    if (hd_rcli_snapshot(argv[0], &r, ts[k], &s)) {
      hd_rcli_clusters_free(&cl), free(ts), hd_rcli_close(&r);
      return 1;
    }
    long nc = hd_rcli_find_clusters(s.x, N, o.gap, &cl), big = 0, cnt = 0, in = 0;
    for (long c = 0; c < nc; c++)
      if (size[c] >= o.minsize) cnt++, in += size[c], big = size[c] > big ? size[c] : big;
    printf("%.10g\t%ld\t%ld\t%.6g\n", ts[k], cnt, big, (double)in / (double)N);
    hd_rcli_snap_free(&s);
  }
  hd_rcli_clusters_free(&cl), free(ts);
  return hd_rcli_close(&r);
}
