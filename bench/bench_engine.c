/* Benchmark of the engine: collisions per second against N, area fraction and logging.
 * usage: bench_engine KIND N ETA LOG [COLLISIONS (default max(2N, 2e6))]   KIND disk|dimer|trimer
 * (a linear trimer of touching unit disks, a named species: the general cluster code), LOG 0|1
 * (every collision to an SQLite file in $TMPDIR).  Prints one TSV line: kind n eta log collisions
 * seconds coll_per_s events_per_s stale_fraction cpu_ns_per_coll (the simulation thread's CPU
 * time of the timed loop per collision: on a loaded machine steadier than the wall clock).  Under
 * `valgrind --tool=callgrind
 * --instr-atstart=no` only the timed loop is counted (bench_callgrind.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "bench_callgrind.h"
#include "bench_util.h"
#include "hd_db.h"
#include "hd_model.h"
#include "hd_sim.h"

int main(int argc, char **argv) {
  if (argc < 5) {
    fprintf(stderr, "usage: bench_engine disk|dimer|trimer N ETA LOG [COLLISIONS]\n");
    return 2;
  }
  if (strcmp(argv[1], "dimer") && strcmp(argv[1], "disk") && strcmp(argv[1], "trimer")) {
    fprintf(stderr, "bench_engine: KIND = '%s': want disk, dimer or trimer\n", argv[1]);
    return 2;
  }
  int dimer = !strcmp(argv[1], "dimer"), trimer = !strcmp(argv[1], "trimer");
  long n, logl, ncoll;
  double eta;
  if (bench_arg_long("bench_engine", "N", argv[2], 2, 100000000, &n) ||
      bench_arg_double("bench_engine", "ETA", argv[3], 0.0, 0.9, &eta) ||
      bench_arg_long("bench_engine", "LOG", argv[4], 0, 1, &logl) ||
      (argc > 5 && bench_arg_long("bench_engine", "COLLISIONS", argv[5], 1, 1L << 62, &ncoll)))
    return 2;
  int log = (int)logl;
  if (argc <= 5) {
    ncoll = 2 * n;
    if (ncoll < 2000000) ncoll = 2000000;
  }
  hd_scene sc;
  memset(&sc, 0, sizeof sc);
  sc.dimer_d = sc.dimer_a = sc.dimer_m = 1.0;
  sc.disk_sigma = sc.disk_mass = 1.0;
  sc.dimer_alpha = sc.disk_alpha = sc.disk_alpha_dimer = sc.wall_alpha = 1.0;
  /* area of one body (a = d: two touching disks, pi / 2; a lens was once wrongly removed
   * here, which made the dimer rows 1.64 times denser than their label) */
  double area = dimer ? hd_dimer_area(1.0, 1.0) : trimer ? 3 * M_PI / 4 : M_PI / 4;
  if (dimer) {
    sc.n_dimers = n;
  } else if (trimer) {
    hd_scene_species *sp = &sc.named[sc.n_named++];
    snprintf(sp->name, sizeof sp->name, "trimer");
    sp->count = n;
    sp->ndisk = 3;
    for (int k = 0; k < 3; k++) sp->x[k] = k, sp->y[k] = 0, sp->d[k] = sp->m[k] = 1;
    sp->alpha = 1.0;
    for (int j = 0; j < 2; j++) sc.alpha_pair[2][j] = sc.alpha_pair[j][2] = 1.0;
  } else {
    sc.n_disks = n;
  }
  sc.box_x = sc.box_y = sqrt((double)n * area / eta);
  sc.seed = 1;
  sc.log_collisions = log ? HD_LOG_ALL : HD_LOG_NONE; /* as `haff run` with [log] collisions */
  sc.temperature = 1.0;
  sc.placement = !dimer && eta > 0.4 ? HD_PLACE_LATTICE : HD_PLACE_RANDOM;
  hd_sim *s;
  hd_error err;
  if (hd_sim_alloc(&s, &sc, &err)) {
    fprintf(stderr, "bench: %s\n", err.msg);
    return 1;
  }
  hd_db *db = NULL;
  int64_t run = 0;
  char path[256] = "";
  if (log) {
    const char *tmp = getenv("TMPDIR");
    snprintf(path, sizeof path, "%s/haff-bench-%d.db", tmp ? tmp : "/tmp", (int)getpid());
    if (hd_db_open(&db, path, &err) || hd_db_run_begin(db, "bench", 1, "bench", &run, &err)) {
      fprintf(stderr, "bench: %s\n", err.msg);
      return 1;
    }
  }
  /* the loop of `haff run`: the model interface (hd_model.h) turns events into rows */
  const hd_model_ops *ops = &hd_model_bodies2d;
  hd_collision_row row;
  /* warm up: 1 cpd melts the lattice and fills the caches */
  for (long k = 0; k < n / 2; k++) ops->next(s, INFINITY, &row, &err);
  int64_t e0 = s->c.events;
  double t0 = bench_now(), c0 = bench_cpu();
  BENCH_CG_START();
  for (long k = 1; k <= ncoll; k++) {
    if (ops->next(s, INFINITY, &row, &err)) {
      fprintf(stderr, "bench: %s\n", err.msg);
      return 1;
    }
    row.seq = k;
    if (db && hd_db_log_collision(db, run, &row, &err)) {
      fprintf(stderr, "bench: %s\n", err.msg);
      return 1;
    }
  }
  BENCH_CG_STOP();
  if (db && hd_db_commit(db, &err)) return 1;
  double dt = bench_now() - t0, dc = bench_cpu() - c0;
  printf("%s\t%ld\t%.2f\t%d\t%ld\t%.3f\t%.4g\t%.4g\t%.3f\t%.1f\n", argv[1], n, eta, log, ncoll, dt,
         (double)ncoll / dt, (double)(s->c.events - e0) / dt,
         (double)s->c.stale / (double)(s->c.events - e0), 1e9 * dc / (double)ncoll);
  if (db) {
    hd_db_close(db, &err);
    unlink(path);
    char w[300];
    snprintf(w, sizeof w, "%s-wal", path), unlink(w);
    snprintf(w, sizeof w, "%s-shm", path), unlink(w);
  }
  hd_sim_free(s);
  return 0;
}
