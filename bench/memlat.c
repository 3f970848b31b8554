/* The machine's memory latency, for bench/results.md: a random cyclic chain of 64-byte lines
 * through a buffer of MB megabytes (on transparent huge pages, as the engine's arrays are),
 * followed by CHAINS independent walkers at once.  One walker gives the latency of a load that
 * misses (L2, last-level cache or DRAM, by the size); many give the cost per line when that
 * many misses are in flight, which bounds what prefetching can hide.
 * usage: memlat MB CHAINS   prints "MB CHAINS ns_per_load" (TSV) */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <time.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include "bench_util.h"

enum { LINE = 8, MAX_CHAINS = 64 }; /* a line is 8 uint64_t */

int main(int argc, char **argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: memlat MB CHAINS\n");
    return 2;
  }
  long mbl, chl;
  if (bench_arg_long("memlat", "MB", argv[1], 1, 1L << 20, &mbl) ||
      bench_arg_long("memlat", "CHAINS", argv[2], 1, MAX_CHAINS, &chl))
    return 2;
  size_t mb = (size_t)mbl;
  int chains = (int)chl;
  size_t n = (mb << 20) / (LINE * sizeof(uint64_t)), bytes = n * LINE * sizeof(uint64_t);
  size_t huge = (size_t)2 << 20, alloc = (bytes + huge - 1) / huge * huge;
  uint64_t *a = aligned_alloc(huge, alloc);
  size_t *perm = malloc(n * sizeof *perm);
  gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
  if (!a || !perm || !r) {
    fprintf(stderr, "memlat: out of memory\n");
    return 1;
  }
  (void)madvise(a, alloc, MADV_HUGEPAGE);
  for (size_t i = 0; i < n; i++) perm[i] = i;
  gsl_rng_set(r, 1);
  gsl_ran_shuffle(r, perm, n, sizeof *perm);
  for (size_t i = 0; i < n; i++) a[perm[i] * LINE] = perm[(i + 1) % n] * LINE; /* one cycle */
  size_t p[MAX_CHAINS];
  for (int k = 0; k < chains; k++) p[k] = perm[(size_t)k * (n / (size_t)chains)] * LINE;
  long steps = 4000000 / chains;
  for (long s = 0; s < steps / 4; s++) /* warm up: pages faulted in, TLB filled */
    for (int k = 0; k < chains; k++) p[k] = a[p[k]];
  double t0 = bench_now();
  for (long s = 0; s < steps; s++)
    for (int k = 0; k < chains; k++) p[k] = a[p[k]];
  double dt = bench_now() - t0;
  size_t sink = 0;
  for (int k = 0; k < chains; k++) sink ^= p[k];
  if (sink == SIZE_MAX) puts("?"); /* uses the walk, which the compiler must then do */
  printf("%zu\t%d\t%.1f\n", mb, chains, 1e9 * dt / ((double)steps * chains));
  gsl_rng_free(r);
  free(perm);
  free(a);
  return 0;
}
