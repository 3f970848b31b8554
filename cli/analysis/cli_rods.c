/* cli_rods: the plumbing the rod analyses share (cli_rods.h). */
#include "cli_rods.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_anadb.h"

/* Every option of the DB readers; each subcommand's spec says which it reads. */
const hd_optdef hd_rcli_opts[] = {
    HD_OPT_INT("run", 0, ropts, run, 0, 8999999999999999999LL, HD_OPTF_EXP | HD_OPTF_ONCE, "ID",
               "the run [the newest rods run of DB]", .set = HD_RCLI_RUN),
    HD_OPT_DBL("t", 0, ropts, t, -INFINITY, INFINITY, HD_OPTF_FINITE, "T",
               "the snapshot nearest time T [the last; rods-density: every one]", .set = HD_RCLI_T),
    HD_OPT_INT("bins", 0, ropts, bins, 1, 1000000, HD_OPTF_EXP, "N",
               "histogram bins [rods-density 100, rods-gofr 200, rods-veldist 40]",
               .set = HD_RCLI_BINS),
    HD_OPT_DBL("range", 0, ropts, range, -INFINITY, INFINITY, HD_OPTF_FINITE, "X",
               "g(x) on distances [0, X], X > 0 [50]", .set = HD_RCLI_RANGE),
    HD_OPT_DBL("gap", 0, ropts, gap, -INFINITY, INFINITY, HD_OPTF_FINITE, "G",
               "cluster finder: neighbours closer than G > 0 are in one cluster [0.1]",
               .set = HD_RCLI_GAP),
    HD_OPT_INT("min-size", 0, ropts, minsize, 1, 8999999999999999999LL, HD_OPTF_EXP, "M",
               "smallest cluster counted [10]", .set = HD_RCLI_MIN),
    HD_OPT_DBL("x", 0, ropts, x, -INFINITY, INFINITY, HD_OPTF_FINITE, "X",
               "the cluster nearest position X [the largest]", .set = HD_RCLI_X),
    {0}};

static int parse(const hd_optspec *spec, int argc, char **argv, ropts *o) {
  memset(o, 0, sizeof *o); /* --bins was read uninitialised: its defaults never applied */
  o->run = -1;
  o->t = NAN;
  o->x = NAN;
  o->gap = 0.1;
  o->minsize = 10;
  o->range = 50;
  hd_optres res;
  int rc = hd_opt_parse(spec, argc, argv, o, &res);
  if (rc) return rc;
  /* named one by one: each command reads some of them only */
  if (o->bins < 0 || o->gap <= 0 || o->range <= 0) {
    fprintf(stderr, "haff %s: %s must be > 0\n", argv[0],
            o->bins < 0   ? "--bins"
            : o->gap <= 0 ? "--gap"
                          : "--range");
    return 2;
  }
  o->db = res.pos[0];
  return 0;
}

static int open_run(const char *cmd, const ropts *o, rrun *r) {
  memset(r, 0, sizeof *r);
  hd_error err;
  hd_error_clear(&err);
  if (hd_ana_open(&r->db, o->db, &err)) { /* a missing file or not a haff database: exit 2 */
    fprintf(stderr, "haff %s: %s\n", cmd, err.msg);
    return hd_exit_code(err.code);
  }
  int64_t id;
  char *scene;
  int rc = hd_ana_rods_run(r->db, o->run, &id, &scene, &err);
  if (rc == HD_EIO || rc == HD_ENOMEM) {
    fprintf(stderr, "haff %s: %s: %s%s\n", cmd, o->db, rc == HD_EIO ? "not a haff database: " : "",
            err.msg);
    hd_ana_close(r->db);
    return rc == HD_EIO ? 2 : 1;
  }
  if (rc == HD_OK) {
    r->id = (long)id;
    rc = 2;
    if (hd_scene_load_string(&r->sc, scene, "runs.scene", NULL, 0, &err) == HD_OK &&
        r->sc.n_rods > 0)
      rc = 0;
    else
      fprintf(stderr, "haff %s: %s: run %ld is not a rods run\n", cmd, o->db, r->id);
  } else {
    rc = 2;
    fprintf(stderr, "haff %s: %s: no rods run%s\n", cmd, o->db, o->run >= 0 ? " with that id" : "");
  }
  free(scene);
  if (rc) {
    hd_scene_free(&r->sc);
    hd_ana_close(r->db);
  }
  return rc;
}

int hd_rcli_close(rrun *r) {
  hd_scene_free(&r->sc);
  hd_ana_close(r->db);
  return 0;
}

int hd_rcli_start(const hd_optspec *spec, int argc, char **argv, int bins, ropts *o, rrun *r) {
  int rc = parse(spec, argc, argv, o);
  if (rc) return rc;
  if (o->bins == 0) o->bins = bins;
  return open_run(argv[0], o, r);
}

/* Snapshot times of the run (labels initial, velocities, final), ascending; malloc'd. */
long hd_rcli_snap_times(rrun *r, double **t) {
  return hd_ana_rods_times(r->db, r->id, t);
}

void hd_rcli_snap_free(rsnap *s) {
  free(s->x), free(s->v), free(s->tb);
  s->x = s->v = s->tb = NULL;
}

/* Says that cmd ran out of memory; returns 1 (the exit code). */
int hd_rcli_oom(const char *cmd) {
  fprintf(stderr, "haff %s: out of memory\n", cmd);
  return 1;
}

/* The rods at snapshot time t into s (snap_free).  Returns 0, or 1 after saying why on stderr
 * (nothing left allocated). */
int hd_rcli_snapshot(const char *cmd, rrun *r, double t, rsnap *s) {
  long n = r->sc.n_rods;
  s->t = t;
  s->x = calloc((size_t)n, sizeof(double));
  s->v = calloc((size_t)n, sizeof(double));
  s->tb = calloc((size_t)n, sizeof(double));
  if (!s->x || !s->v || !s->tb) {
    hd_rcli_snap_free(s);
    return hd_rcli_oom(cmd);
  }
  hd_error err;
  if (hd_ana_rods_snapshot(r->db, r->id, t, n, s->x, s->v, s->tb, &err)) {
    fprintf(stderr, "haff %s: cannot read the states of run %ld: %s\n", cmd, r->id, err.msg);
    hd_rcli_snap_free(s);
    return 1;
  }
  return 0;
}

double hd_rcli_mass(const hd_scene *sc, long i) {
  return i % 2 ? 1 + 1 / sc->rod_gamma : 1 + sc->rod_gamma;
}

/* The snapshot nearest o->t (or the last). */
int hd_rcli_pick_time(const char *cmd, rrun *r, const ropts *o, double *t) {
  double *ts;
  long n = hd_rcli_snap_times(r, &ts);
  if (n <= 0) {
    fprintf(stderr, "haff %s: run %ld has no rod snapshots ([log] velocities_at)\n", cmd, r->id);
    free(ts);
    return 1;
  }
  long best = n - 1;
  if (!isnan(o->t))
    for (long k = 0; k < n; k++)
      if (fabs(ts[k] - o->t) < fabs(ts[best] - o->t)) best = k;
  /* --t between or past the snapshots: say which one is read (it was in the header only) */
  if (!isnan(o->t) && fabs(ts[best] - o->t) > 1e-9 * fmax(1, fabs(o->t)))
    fprintf(stderr,
            "haff %s: note: run %ld has no snapshot at t = %g: the nearest, t = %.6g, is read "
            "(its %ld snapshots: t = %.6g to %.6g)\n",
            cmd, r->id, o->t, ts[best], n, ts[0], ts[n - 1]);
  *t = ts[best];
  free(ts);
  return 0;
}

int hd_rcli_start_at(const hd_optspec *spec, int argc, char **argv, int bins, ropts *o, rrun *r,
                     rsnap *s) {
  int rc = hd_rcli_start(spec, argc, argv, bins, o, r);
  if (rc) return rc;
  double t;
  if (hd_rcli_pick_time(argv[0], r, o, &t) || hd_rcli_snapshot(argv[0], r, t, s)) {
    hd_rcli_close(r);
    return 1;
  }
  return 0;
}

int hd_rcli_main_at(const hd_optspec *spec, int argc, char **argv, int bins, hd_rcli_at_fn *fn) {
  ropts o;
  rrun r;
  rsnap s;
  int rc = hd_rcli_start_at(spec, argc, argv, bins, &o, &r, &s);
  if (rc) return rc < 0 ? 0 : rc;
  rc = fn(argv[0], &o, &r, &s);
  hd_rcli_snap_free(&s);
  hd_rcli_close(&r);
  return rc;
}

int hd_rcli_main_series(const hd_optspec *spec, int argc, char **argv, int bins,
                        hd_rcli_series_fn *fn) {
  ropts o;
  rrun r;
  int rc = hd_rcli_start(spec, argc, argv, bins, &o, &r);
  if (rc) return rc < 0 ? 0 : rc;
  double *ts;
  long nt = hd_rcli_snap_times(&r, &ts);
  if (!isnan(o.t)) {
    double t;
    if (hd_rcli_pick_time(argv[0], &r, &o, &t)) { /* it says why */
      free(ts);
      hd_rcli_close(&r);
      return 1;
    }
    ts[0] = t, nt = 1;
  }
  rc = fn(argv[0], &o, &r, ts, nt);
  free(ts);
  hd_rcli_close(&r);
  return rc;
}

void hd_rcli_clusters_free(rclusters *cl) {
  free(cl->order), free(cl->start), free(cl->size);
  cl->order = cl->start = cl->size = NULL;
}

/* Returns 0, or 1 when out of memory (nothing left allocated). */
int hd_rcli_clusters_alloc(rclusters *cl, long n) {
  cl->order = malloc((size_t)n * sizeof *cl->order);
  cl->start = malloc((size_t)n * sizeof *cl->start);
  cl->size = malloc((size_t)n * sizeof *cl->size);
  if (cl->order && cl->start && cl->size) return 0;
  hd_rcli_clusters_free(cl);
  return 1;
}

static long *g_sort_x;
static int by_x(const void *a, const void *b) {
  double xa = ((const double *)g_sort_x)[*(const long *)a],
         xb = ((const double *)g_sort_x)[*(const long *)b];
  return (xa > xb) - (xa < xb);
}
/* Finds the clusters of x[0..n-1] into cl; returns their count. */
long hd_rcli_find_clusters(const double *x, long n, double gap, rclusters *cl) {
  long *order = cl->order, *start = cl->start, *size = cl->size;
  for (long i = 0; i < n; i++) order[i] = i;
  g_sort_x = (long *)(void *)x;
  qsort(order, (size_t)n, sizeof *order, by_x);
  /* start after the largest hole, so that no cluster wraps */
  long k0 = 0;
  double big = -1;
  for (long k = 0; k < n; k++) {
    double d = x[order[(k + 1) % n]] - x[order[k]];
    if (d < 0) d += (double)n;
    if (d > big) big = d, k0 = (k + 1) % n;
  }
  long nc = 0;
  for (long m = 0; m < n; m++) {
    long k = (k0 + m) % n;
    double d = m == 0 ? INFINITY : x[order[k]] - x[order[(k + n - 1) % n]];
    if (d < 0) d += (double)n;
    if (d >= gap) {
      start[nc] = m;
      size[nc++] = 0;
    }
    size[nc - 1]++;
  }
  for (long c = 0; c < nc; c++) start[c] = (k0 + start[c]) % n;
  return nc;
}
