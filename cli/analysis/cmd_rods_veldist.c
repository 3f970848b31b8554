/* `haff rods-veldist`: rods Fig. 7 data, velocities of all rods and of a cluster. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_rods.h"
#include "cli_common.h" /* hd_cli_num */
#include "haff.h"

const hd_optspec hd_cmd_rods_veldist_spec = {
    HD_RCLI_SPEC("rods-veldist", HD_RCLI_RUN | HD_RCLI_T | HD_RCLI_BINS | HD_RCLI_GAP | HD_RCLI_X),
    .head =
        "usage: haff rods-veldist DB [--run ID] [--t T] [--bins N] [--gap G] [--x X]\n"
        "Fig. 7 data: histograms of w = sqrt(m_i) v_i (mass-scaled so that both species share one\n"
        "Maxwellian) for all rods and for one cluster (the largest, or the one nearest --x) at "
        "the\n"
        "snapshot nearest --t.  Clusters: maximal runs of rods whose neighbour distance is < G\n"
        "[0.1 mean spacings].  Columns w p_all p_cluster gauss_all gauss_cluster (Gaussians with\n"
        "the sample's mean and variance); header comments give the cluster and the moments.\n"};

/* The histograms of one snapshot (hd_rcli_at_fn). */
static int veldist(const char *cmd, const ropts *o, const rrun *r, const rsnap *s) {
  long N = r->sc.n_rods;
  rclusters cl;
  if (hd_rcli_clusters_alloc(&cl, N)) return hd_rcli_oom(cmd);
  const double *x = s->x, *v = s->v;
  const long *order = cl.order, *start = cl.start, *size = cl.size;
  long nc = hd_rcli_find_clusters(x, N, o->gap, &cl), pick = 0;
  for (long c = 0; c < nc; c++) {
    if (isnan(o->x)) {
      if (size[c] > size[pick]) pick = c;
    } else {
      double xc = x[order[(start[c] + size[c] / 2) % N]],
             xp = x[order[(start[pick] + size[pick] / 2) % N]];
      double dc = fabs(xc - o->x), dp = fabs(xp - o->x);
      if (size[c] >= o->minsize && (size[pick] < o->minsize || dc < dp)) pick = c;
    }
  }
  double *w = malloc((size_t)N * sizeof *w);
  double *ha = calloc((size_t)o->bins, sizeof *ha), *hc = calloc((size_t)o->bins, sizeof *hc);
  if (!w || !ha || !hc) {
    free(w), free(ha), free(hc), hd_rcli_clusters_free(&cl);
    return hd_rcli_oom(cmd);
  }
  double ma = 0, sa = 0, mc = 0, scl = 0, lo = INFINITY, hi = -INFINITY;
  for (long i = 0; i < N; i++) {
    w[i] = sqrt(hd_rcli_mass(&r->sc, i)) * v[i];
    ma += w[i], sa += w[i] * w[i];
    lo = fmin(lo, w[i]), hi = fmax(hi, w[i]);
  }
  ma /= (double)N, sa = sqrt(sa / (double)N - ma * ma);
  long ncl = size[pick];
  for (long m = 0; m < ncl; m++) {
    double y = w[order[(start[pick] + m) % N]];
    mc += y, scl += y * y;
  }
  mc /= (double)ncl, scl = sqrt(fmax(scl / (double)ncl - mc * mc, 0));
  double dw = (hi - lo) / o->bins;
  if (!(dw > 0)) dw = 1;
  for (long i = 0; i < N; i++) {
    long b = (long)((w[i] - lo) / dw);
    ha[b < o->bins ? b : o->bins - 1] += 1.0 / ((double)N * dw);
  }
  for (long m = 0; m < ncl; m++) {
    long b = (long)((w[order[(start[pick] + m) % N]] - lo) / dw);
    hc[b < o->bins ? b : o->bins - 1] += 1.0 / ((double)ncl * dw);
  }
  long nc2 = 0; /* clusters of 2 rods or more (rods-clusters --min-size 2); the rest are single */
  for (long c = 0; c < nc; c++) nc2 += size[c] >= 2;
  printf("# t = %.10g; %ld clusters of >= 2 rods and %ld single rods (gap < %g); cluster: %ld "
         "rods around x = %.6g\n",
         s->t, nc2, nc - nc2, o->gap, ncl, x[order[(start[pick] + ncl / 2) % N]]);
  printf("# all: mean %.6g sd %.6g; cluster: mean %.6g sd %.6g\n", ma, sa, mc, scl);
  printf("w\tp_all\tp_cluster\tgauss_all\tgauss_cluster\n");
  for (int b = 0; b < o->bins; b++) {
    double c = lo + (b + 0.5) * dw;
    double ga = sa > 0 ? exp(-0.5 * (c - ma) * (c - ma) / (sa * sa)) / (sa * sqrt(2 * M_PI)) : NAN;
    double gc =
        scl > 0 ? exp(-0.5 * (c - mc) * (c - mc) / (scl * scl)) / (scl * sqrt(2 * M_PI)) : NAN;
    printf("%.6g\t%.6g\t%.6g\t%s\t%s\n", c, ha[b], hc[b], hd_cli_num("%.6g", ga, 0),
           hd_cli_num("%.6g", gc, 0)); /* no cluster: empty, not nan */
  }
  free(w), free(ha), free(hc), hd_rcli_clusters_free(&cl);
  return 0;
}

int hd_cmd_rods_veldist(int argc, char **argv) {
  return hd_rcli_main_at(&hd_cmd_rods_veldist_spec, argc, argv, 40, veldist);
}
