/* Benchmark of the rod ring's dense phase from a fixed checkpoint.
 * usage: bench_rods CKPT [COLLISIONS [N T0]]
 * The ring is that of scenes/rods-damped.ini (N = 1000 rods, gamma = 0.8, N_mod = 1000, damping
 * 0.01, tabulated eps, seed 1998).  When the file CKPT does not exist, the ring is run from t = 0
 * to T0 [3000] (its dense phase: ~3.3e7 collisions, ~25 s) and its state written there; then
 * the ring is restored from CKPT, the table's nodes below its grid are built (on first use in a
 * run, ~0.2 s each), COLLISIONS / 2 collisions of warm-up run, and COLLISIONS [4e6] collisions are
 * timed (between callgrind markers, bench_callgrind.h).  Prints one TSV line: n t_start collisions
 * seconds cpu_seconds coll_per_cpu_s */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_callgrind.h"
#include "bench_util.h"
#include "rods.h"

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: bench_rods CKPT [COLLISIONS [N T0]]\n");
    return 2;
  }
  long ncoll = 4000000, n = 1000;
  double t0 = 3000;
  if ((argc > 2 && bench_arg_long("bench_rods", "COLLISIONS", argv[2], 1, 1L << 62, &ncoll)) ||
      (argc > 3 && bench_arg_long("bench_rods", "N", argv[3], 2, 100000000, &n)) ||
      (argc > 4 && bench_arg_double("bench_rods", "T0", argv[4], 0, 1e12, &t0)))
    return 2;
  hd_rods_params p;
  hd_rods_params_default(&p);
  p.n = n;
  p.gamma = 0.8;
  p.nmod = 1000;
  p.damping = 0.01;
  p.table = 1;
  p.seed = 1998;
  hd_error err;
  hd_rods *r;
  hd_rods_event ev;
  FILE *f = fopen(argv[1], "rb");
  if (!f) {
    if (hd_rods_alloc(&r, &p, &err)) goto fail;
    int rc = HD_OK;
    while (rc == HD_OK) rc = hd_rods_next(r, t0, &ev, &err);
    if (rc != HD_SIM_STOPTIME) goto fail;
    void *blob;
    size_t nb;
    if (hd_rods_checkpoint(r, &blob, &nb, &err)) goto fail;
    f = fopen(argv[1], "wb");
    if (!f || fwrite(blob, 1, nb, f) != nb || fclose(f)) {
      fprintf(stderr, "bench_rods: cannot write %s\n", argv[1]);
      return 1;
    }
    free(blob);
    hd_rods_free(r);
    f = fopen(argv[1], "rb");
    if (!f) return 1;
  }
  fseek(f, 0, SEEK_END);
  long nb = ftell(f);
  rewind(f);
  void *blob = malloc((size_t)nb);
  if (!blob || fread(blob, 1, (size_t)nb, f) != (size_t)nb) return 1;
  fclose(f);
  if (hd_rods_alloc_restore(&r, &p, blob, (size_t)nb, &err)) goto fail;
  free(blob);
  /* every node below the table's grid built now (~1e9 instructions each), not in the timed
   * loop: one draw at each node's beta (the ring's RNG advances by these draws, the same in
   * every build) */
  for (int j = 1; j <= HD_RODS_LOW_NODES; j++)
    if (r->table) hd_rods_table_eps(r, r->table->beta_min * pow(10, -0.25 * j));
  for (long k = 0; k < ncoll / 2; k++)
    if (hd_rods_next(r, INFINITY, &ev, &err)) goto fail;
  double ts = r->t, w0 = bench_now(), c0 = bench_cpu();
  BENCH_CG_START();
  double check = 0; /* the sum of eps drawn: equal in builds meant to be exact */
  for (long k = 0; k < ncoll; k++) {
    if (hd_rods_next(r, INFINITY, &ev, &err)) goto fail;
    check += ev.eps;
  }
  BENCH_CG_STOP();
  double dt = bench_now() - w0, dc = bench_cpu() - c0;
  printf("%ld\t%.6g\t%ld\t%.3f\t%.3f\t%.4g\t%.17g\t%.17g\n", n, ts, ncoll, dt, dc,
         (double)ncoll / dc, r->t, check);
  hd_rods_free(r);
  return 0;
fail:
  fprintf(stderr, "bench_rods: %s\n", err.msg);
  return 1;
}
