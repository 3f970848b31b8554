/* The rod figures (docs/rods.md): `haff rods-energy`, `rods-density`, `rods-phase`,
 * `rods-gofr`, `rods-veldist`, `rods-clusters` read a rods run from a database and write TSV;
 * `rods-collapse` scans (N, eps) of the constant model for inelastic collapse.  CLI code. */
#include <getopt.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>
#include <math.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hd_ana_cli.h"
#include "hd_anadb.h"
#include "hd_scene.h"
#include "hd_sim.h"
#include "rods.h"

/* Options shared by the DB readers. */
typedef struct ropts {
  const char *db;
  long run;     /* -1: newest rods run */
  int bins;     /* histogram bins */
  double t;     /* snapshot time wanted (nearest), NAN: every snapshot */
  double gap;   /* cluster finder: gap below which neighbours are in one cluster */
  long minsize; /* cluster finder: smallest cluster counted */
  double x;     /* rods-veldist: the cluster nearest x (NAN: the largest) */
  double range; /* rods-gofr: largest distance */
} ropts;

/* s is a finite number filling the whole string: *x. */
static int finite_number(const char *s, double *x) {
  char *e;
  *x = strtod(s, &e);
  return e != s && !*e && isfinite(*x);
}

/* s is a finite whole number (digits, or forms like 1e4 that are whole): *x. */
static int whole_number(const char *s, double *x) {
  return finite_number(s, x) && *x == floor(*x);
}

/* Prints why an option's value is refused and returns 2. */
static int bad_arg(const char *cmd, const char *opt, const char *val) {
  fprintf(stderr, "haff %s: %s '%s': out of range or not a number (see --help)\n", cmd, opt, val);
  return 2;
}

/* The comma-separated list s of option opt into v[0..max) (whole numbers when whole), each in
 * [lo, hi]: the count, or -1 after bad_arg (an empty item, as in 4,,8 or "", is one). */
static int parse_list(const char *cmd, const char *opt, const char *s, int whole, double lo,
                      double hi, double *v, int max) {
  char buf[512], *p = buf, *item;
  snprintf(buf, sizeof buf, "%s", s);
  int n = 0;
  while ((item = strsep(&p, ",")) != NULL) {
    if (n == max || !(whole ? whole_number(item, &v[n]) : finite_number(item, &v[n])) ||
        !(v[n] >= lo && v[n] <= hi)) {
      bad_arg(cmd, opt, *item ? item : s);
      return -1;
    }
    n++;
  }
  return n;
}

static int parse(int argc, char **argv, const char *usage, ropts *o) {
  static const struct option lo[] = {
      {"run", 1, 0, 'r'},   {"bins", 1, 0, 'b'},     {"t", 1, 0, 't'},
      {"gap", 1, 0, 'g'},   {"min-size", 1, 0, 'm'}, {"x", 1, 0, 'x'},
      {"range", 1, 0, 'R'}, {"help", 0, 0, 'h'},     {0, 0, 0, 0}};
  memset(o, 0, sizeof *o); /* --bins was read uninitialised: its defaults never applied */
  o->run = -1;
  o->t = NAN;
  o->x = NAN;
  o->gap = 0.1;
  o->minsize = 10;
  o->range = 50;
  optind = 1;
  int c, li = 0;
  opterr = 0; /* one line of ours for a bad option, not getopt's as well */
  while ((c = getopt_long(argc, argv, "h", lo, &li)) != -1) {
    double v;
    int ok = 1;
    switch (c) {
    case 'r':
      ok = whole_number(optarg, &v) && v >= 0 && v < 9e18;
      if (ok) o->run = (long)v;
      break;
    case 'b':
      ok = whole_number(optarg, &v) && v >= 1 && v <= 1e6;
      if (ok) o->bins = (int)v;
      break;
    case 't':
      ok = finite_number(optarg, &o->t);
      break;
    case 'g':
      ok = finite_number(optarg, &o->gap);
      break;
    case 'm':
      ok = whole_number(optarg, &v) && v >= 1 && v < 9e18;
      if (ok) o->minsize = (long)v;
      break;
    case 'x':
      ok = finite_number(optarg, &o->x);
      break;
    case 'R':
      ok = finite_number(optarg, &o->range);
      break;
    case 'h':
      fputs(usage, stdout);
      return -1;
    default: {
      char buf[8];
      fprintf(stderr, "haff %s: unknown option or missing value '%s' (see --help)\n", argv[0],
              hd_opt_culprit(argv, lo, buf, sizeof buf));
    }
      return 2;
    }
    if (!ok) {
      char opt[40];
      snprintf(opt, sizeof opt, "--%s", lo[li].name);
      return bad_arg(argv[0], opt, optarg);
    }
  }
  if (optind != argc - 1) {
    fprintf(stderr, "haff %s: expected one database (see --help)\n", argv[0]);
    return 2;
  }
  /* named one by one: each command reads some of them only */
  if (o->bins < 0 || o->gap <= 0 || o->range <= 0) {
    fprintf(stderr, "haff %s: %s must be > 0\n", argv[0],
            o->bins < 0   ? "--bins"
            : o->gap <= 0 ? "--gap"
                          : "--range");
    return 2;
  }
  o->db = argv[optind];
  return 0;
}

/* The run: its id and its scene (a [rods] scene). */
typedef struct rrun {
  sqlite3 *db;
  long id;
  hd_scene sc;
} rrun;

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

/* Closes what open_run opened; returns 0, the exit code of a command that got this far. */
static int close_run(rrun *r) {
  hd_scene_free(&r->sc);
  hd_ana_close(r->db);
  return 0;
}

/* The common start of the DB readers: parses the options (bins: the --bins default, 0 for none)
 * and opens the run.  Returns 0 to go on, -1 after --help (the caller returns 0), else the exit
 * code (nothing left open). */
static int start(int argc, char **argv, const char *usage, int bins, ropts *o, rrun *r) {
  int rc = parse(argc, argv, usage, o);
  if (rc) return rc;
  if (o->bins == 0) o->bins = bins;
  return open_run(argv[0], o, r);
}

/* Snapshot times of the run (labels initial, velocities, final), ascending; malloc'd. */
static long snap_times(rrun *r, double **t) {
  return hd_ana_rods_times(r->db, r->id, t);
}

/* One snapshot: its time and x, v, T_B by body index (arrays of sc.n_rods, malloc'd). */
typedef struct rsnap {
  double t, *x, *v, *tb;
} rsnap;

static void snap_free(rsnap *s) {
  free(s->x), free(s->v), free(s->tb);
  s->x = s->v = s->tb = NULL;
}

/* Says that cmd ran out of memory; returns 1 (the exit code). */
static int out_of_memory(const char *cmd) {
  fprintf(stderr, "haff %s: out of memory\n", cmd);
  return 1;
}

/* The rods at snapshot time t into s (snap_free).  Returns 0, or 1 after saying why on stderr
 * (nothing left allocated). */
static int snapshot(const char *cmd, rrun *r, double t, rsnap *s) {
  long n = r->sc.n_rods;
  s->t = t;
  s->x = calloc((size_t)n, sizeof(double));
  s->v = calloc((size_t)n, sizeof(double));
  s->tb = calloc((size_t)n, sizeof(double));
  if (!s->x || !s->v || !s->tb) {
    snap_free(s);
    return out_of_memory(cmd);
  }
  hd_error err;
  if (hd_ana_rods_snapshot(r->db, r->id, t, n, s->x, s->v, s->tb, &err)) {
    fprintf(stderr, "haff %s: cannot read the states of run %ld: %s\n", cmd, r->id, err.msg);
    snap_free(s);
    return 1;
  }
  return 0;
}

static double mass(const hd_scene *sc, long i) {
  return i % 2 ? 1 + 1 / sc->rod_gamma : 1 + sc->rod_gamma;
}

/* The snapshot nearest o->t (or the last). */
static int pick_time(const char *cmd, rrun *r, const ropts *o, double *t) {
  double *ts;
  long n = snap_times(r, &ts);
  if (n <= 0) {
    fprintf(stderr, "haff %s: run %ld has no rod snapshots ([log] velocities_at)\n", cmd, r->id);
    free(ts);
    return 1;
  }
  long best = n - 1;
  if (!isnan(o->t))
    for (long k = 0; k < n; k++)
      if (fabs(ts[k] - o->t) < fabs(ts[best] - o->t)) best = k;
  *t = ts[best];
  free(ts);
  return 0;
}

/* start(), then the snapshot nearest --t (or the last) into s.  Returns as start(); 1 (run
 * closed) when the run has no snapshots. */
static int start_at(int argc, char **argv, const char *usage, int bins, ropts *o, rrun *r,
                    rsnap *s) {
  int rc = start(argc, argv, usage, bins, o, r);
  if (rc) return rc;
  double t;
  if (pick_time(argv[0], r, o, &t) || snapshot(argv[0], r, t, s)) {
    close_run(r);
    return 1;
  }
  return 0;
}

/* ---- rods-energy ------------------------------------------------------------------------------
 */

int haff_rods_energy_main(int argc, char **argv) {
  static const char usage[] =
      "usage: haff rods-energy DB [--run ID]\n"
      "Figs. 1, 2, 9-11 data: per sample of a rods run (newest by default) the columns\n"
      "  t collisions cpd e_kin e_bath e_kin_over_e0 e_mode e_kin_stat coll_ideal coll_eq35\n"
      "e_kin, e_bath per rod; e_mode = e_bath / nmod (energy per vibrational mode);\n"
      "e_kin_stat = the equipartition value (docs/rods.md); coll_ideal and coll_eq35: the\n"
      "stationary collision count rate*t from the 1D ideal gas and from the paper's eq. (35).\n";
  ropts o;
  rrun r;
  int rc = start(argc, argv, usage, 0, &o, &r);
  if (rc) return rc < 0 ? 0 : rc;
  const hd_scene *sc = &r.sc;
  long N = sc->n_rods, nmod = sc->rod_nmod;
  double e0 = 0.5 * sc->rod_temperature; /* E_kin(0) per rod */
  double es = hd_rods_ekin_stat(N, nmod, e0 * (double)N) / (double)N;
  double rate_i = hd_rods_rate_ideal(N, 2 * es * (double)N / (double)(N - 1));
  double rate_35 = hd_rods_rate_eq35(N, nmod) * sqrt(sc->rod_temperature);
  hd_series ser;
  hd_error err;
  if (hd_ana_samples(r.db, r.id, &ser, &err)) {
    fprintf(stderr, "haff %s: cannot read the samples of run %ld: %s\n", argv[0], r.id, err.msg);
    close_run(&r);
    return 1;
  }
  printf("# run %ld: N=%ld gamma=%g nmod=%ld model=%s damping=%g\n", r.id, N, sc->rod_gamma, nmod,
         sc->rod_model ? "constant" : "stochastic", sc->rod_damping);
  printf("t\tcollisions\tcpd\te_kin\te_bath\te_kin_over_e0\te_mode\te_kin_stat\tcoll_ideal\t"
         "coll_eq35\n");
  for (size_t k = 0; k < ser.n; k++) {
    double t = ser.t[k];
    double ek = ser.e_tr[k], eb = ser.e_rot[k];
    printf("%.10g\t%lld\t%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%.8g\t%.8g\n", t,
           (long long)ser.coll[k], ser.cpd[k], ek, eb, ek / e0, eb / (double)nmod, es, rate_i * t,
           rate_35 * t);
  }
  hd_series_free(&ser);
  return close_run(&r);
}

/* ---- rods-density -----------------------------------------------------------------------------
 */

int haff_rods_density_main(int argc, char **argv) {
  static const char usage[] =
      "usage: haff rods-density DB [--run ID] [--bins N] [--t T]\n"
      "Figs. 3, 4, 6 data: the coarse-grained density rho (rods per bin over the mean, N bins\n"
      "[100] on the ring) and the local kinetic energy per rod in each bin, for every snapshot\n"
      "(or the one nearest --t).  Columns t bin x rho e_local; a blank line after each\n"
      "snapshot (gnuplot pm3d).\n";
  ropts o;
  rrun r;
  int rc = start(argc, argv, usage, 100, &o, &r);
  if (rc) return rc < 0 ? 0 : rc;
  long N = r.sc.n_rods;
  double *ts;
  long nt = snap_times(&r, &ts);
  if (!isnan(o.t)) {
    double t;
    if (pick_time(argv[0], &r, &o, &t)) { /* it says why */
      free(ts);
      close_run(&r);
      return 1;
    }
    ts[0] = t, nt = 1;
  }
  long *cnt = calloc((size_t)o.bins, sizeof *cnt);
  double *ek = calloc((size_t)o.bins, sizeof *ek);
  if (!cnt || !ek) {
    free(cnt), free(ek), free(ts), close_run(&r);
    return out_of_memory(argv[0]);
  }
  printf("t\tbin\tx\trho\te_local\n");
  for (long k = 0; k < nt; k++) {
    rsnap s;
    if (snapshot(argv[0], &r, ts[k], &s)) {
      free(cnt), free(ek), free(ts), close_run(&r);
      return 1;
    }
    memset(cnt, 0, (size_t)o.bins * sizeof *cnt);
    memset(ek, 0, (size_t)o.bins * sizeof *ek);
    for (long i = 0; i < N; i++) {
      long b = (long)(s.x[i] / (double)N * o.bins);
      if (b >= o.bins) b = o.bins - 1;
      if (b < 0) b = 0;
      cnt[b]++;
      ek[b] += 0.5 * mass(&r.sc, i) * s.v[i] * s.v[i];
    }
    double mean = (double)N / o.bins;
    for (int b = 0; b < o.bins; b++)
      printf("%.10g\t%d\t%.6g\t%.6g\t%.6g\n", ts[k], b, (b + 0.5) * (double)N / o.bins,
             (double)cnt[b] / mean, cnt[b] ? ek[b] / (double)cnt[b] : NAN);
    printf("\n");
    snap_free(&s);
  }
  free(cnt), free(ek), free(ts);
  return close_run(&r);
}

/* ---- rods-phase -------------------------------------------------------------------------------
 */

int haff_rods_phase_main(int argc, char **argv) {
  static const char usage[] =
      "usage: haff rods-phase DB [--run ID] [--t T]\n"
      "Fig. 5 data: phase space of the snapshot nearest --t (default the last): columns\n"
      "body x v tb (bath temperature).\n";
  ropts o;
  rrun r;
  rsnap s;
  int rc = start_at(argc, argv, usage, 0, &o, &r, &s);
  if (rc) return rc < 0 ? 0 : rc;
  printf("# t = %.10g\nbody\tx\tv\ttb\n", s.t);
  for (long i = 0; i < r.sc.n_rods; i++)
    printf("%ld\t%.8g\t%.8g\t%.6g\n", i, s.x[i], s.v[i], s.tb[i]);
  snap_free(&s);
  return close_run(&r);
}

/* ---- rods-gofr --------------------------------------------------------------------------------
 */

int haff_rods_gofr_main(int argc, char **argv) {
  static const char usage[] =
      "usage: haff rods-gofr DB [--run ID] [--t T] [--bins N] [--range X]\n"
      "Fig. 8 data: g(x) = 1/(N-1) sum_{i!=j} delta(x - |x_i - x_j|) (ring distance), normalised\n"
      "so that uniformly placed rods give 1, on N bins [200] of [0, X] [50], at the snapshot\n"
      "nearest --t.  Columns x g.\n";
  ropts o;
  rrun r;
  rsnap s;
  int rc = start_at(argc, argv, usage, 200, &o, &r, &s);
  if (rc) return rc < 0 ? 0 : rc;
  const double *x = s.x;
  long N = r.sc.n_rods;
  double L = (double)N, dx = o.range / o.bins;
  double *h = calloc((size_t)o.bins, sizeof *h);
  if (!h) {
    snap_free(&s), close_run(&r);
    return out_of_memory(argv[0]);
  }
  for (long i = 0; i < N; i++)
    for (long j = i + 1; j < N; j++) {
      double d = fabs(x[i] - x[j]);
      if (d > L / 2) d = L - d;
      double q = d / dx; /* compared as a double: a tiny --range makes it past a long */
      if (q < o.bins) h[(long)q] += 2;
    }
  printf("# t = %.10g\nx\tg\n", s.t);
  for (int b = 0; b < o.bins; b++) /* uniform: N (N-1) 2 dx / L ordered pairs per bin */
    printf("%.6g\t%.6g\n", (b + 0.5) * dx, h[b] / ((double)N * (double)(N - 1) * 2 * dx / L));
  free(h), snap_free(&s);
  return close_run(&r);
}

/* ---- clusters ---------------------------------------------------------------------------------
 */

/* Clusters of a snapshot: maximal runs of ring neighbours (in position order) closer than gap.
 * start[c], size[c]; order[] gets the rods sorted by x.  Arrays of n rods (clusters_alloc). */
typedef struct rclusters {
  long *order, *start, *size;
} rclusters;

static void clusters_free(rclusters *cl) {
  free(cl->order), free(cl->start), free(cl->size);
  cl->order = cl->start = cl->size = NULL;
}

/* Returns 0, or 1 when out of memory (nothing left allocated). */
static int clusters_alloc(rclusters *cl, long n) {
  cl->order = malloc((size_t)n * sizeof *cl->order);
  cl->start = malloc((size_t)n * sizeof *cl->start);
  cl->size = malloc((size_t)n * sizeof *cl->size);
  if (cl->order && cl->start && cl->size) return 0;
  clusters_free(cl);
  return 1;
}

static long *g_sort_x;
static int by_x(const void *a, const void *b) {
  double xa = ((const double *)g_sort_x)[*(const long *)a],
         xb = ((const double *)g_sort_x)[*(const long *)b];
  return (xa > xb) - (xa < xb);
}
/* Finds the clusters of x[0..n-1] into cl; returns their count. */
static long find_clusters(const double *x, long n, double gap, rclusters *cl) {
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

int haff_rods_veldist_main(int argc, char **argv) {
  static const char usage[] =
      "usage: haff rods-veldist DB [--run ID] [--t T] [--bins N] [--gap G] [--x X]\n"
      "Fig. 7 data: histograms of w = sqrt(m_i) v_i (mass-scaled so that both species share one\n"
      "Maxwellian) for all rods and for one cluster (the largest, or the one nearest --x) at the\n"
      "snapshot nearest --t.  Clusters: maximal runs of rods whose neighbour distance is < G\n"
      "[0.1 mean spacings].  Columns w p_all p_cluster gauss_all gauss_cluster (Gaussians with\n"
      "the sample's mean and variance); header comments give the cluster and the moments.\n";
  ropts o;
  rrun r;
  rsnap s;
  int rc = start_at(argc, argv, usage, 40, &o, &r, &s);
  if (rc) return rc < 0 ? 0 : rc;
  long N = r.sc.n_rods;
  rclusters cl;
  if (clusters_alloc(&cl, N)) {
    snap_free(&s), close_run(&r);
    return out_of_memory(argv[0]);
  }
  const double *x = s.x, *v = s.v;
  const long *order = cl.order, *start = cl.start, *size = cl.size;
  long nc = find_clusters(x, N, o.gap, &cl), pick = 0;
  for (long c = 0; c < nc; c++) {
    if (isnan(o.x)) {
      if (size[c] > size[pick]) pick = c;
    } else {
      double xc = x[order[(start[c] + size[c] / 2) % N]],
             xp = x[order[(start[pick] + size[pick] / 2) % N]];
      double dc = fabs(xc - o.x), dp = fabs(xp - o.x);
      if (size[c] >= o.minsize && (size[pick] < o.minsize || dc < dp)) pick = c;
    }
  }
  double *w = malloc((size_t)N * sizeof *w);
  double *ha = calloc((size_t)o.bins, sizeof *ha), *hc = calloc((size_t)o.bins, sizeof *hc);
  if (!w || !ha || !hc) {
    free(w), free(ha), free(hc), clusters_free(&cl), snap_free(&s), close_run(&r);
    return out_of_memory(argv[0]);
  }
  double ma = 0, sa = 0, mc = 0, scl = 0, lo = INFINITY, hi = -INFINITY;
  for (long i = 0; i < N; i++) {
    w[i] = sqrt(mass(&r.sc, i)) * v[i];
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
  double dw = (hi - lo) / o.bins;
  if (!(dw > 0)) dw = 1;
  for (long i = 0; i < N; i++) {
    long b = (long)((w[i] - lo) / dw);
    ha[b < o.bins ? b : o.bins - 1] += 1.0 / ((double)N * dw);
  }
  for (long m = 0; m < ncl; m++) {
    long b = (long)((w[order[(start[pick] + m) % N]] - lo) / dw);
    hc[b < o.bins ? b : o.bins - 1] += 1.0 / ((double)ncl * dw);
  }
  printf("# t = %.10g; %ld clusters (gap < %g); cluster: %ld rods around x = %.6g\n", s.t, nc,
         o.gap, ncl, x[order[(start[pick] + ncl / 2) % N]]);
  printf("# all: mean %.6g sd %.6g; cluster: mean %.6g sd %.6g\n", ma, sa, mc, scl);
  printf("w\tp_all\tp_cluster\tgauss_all\tgauss_cluster\n");
  for (int b = 0; b < o.bins; b++) {
    double c = lo + (b + 0.5) * dw;
    double ga = exp(-0.5 * (c - ma) * (c - ma) / (sa * sa)) / (sa * sqrt(2 * M_PI));
    double gc =
        scl > 0 ? exp(-0.5 * (c - mc) * (c - mc) / (scl * scl)) / (scl * sqrt(2 * M_PI)) : NAN;
    printf("%.6g\t%.6g\t%.6g\t%.6g\t%.6g\n", c, ha[b], hc[b], ga, gc);
  }
  free(w), free(ha), free(hc), clusters_free(&cl), snap_free(&s);
  return close_run(&r);
}

int haff_rods_clusters_main(int argc, char **argv) {
  static const char usage[] =
      "usage: haff rods-clusters DB [--run ID] [--gap G] [--min-size M]\n"
      "Clusters per snapshot (maximal runs of rods closer than G [0.1] to their neighbour, at\n"
      "least M [10] rods): columns t clusters largest in_clusters (fraction of rods in them).\n";
  ropts o;
  rrun r;
  int rc = start(argc, argv, usage, 0, &o, &r);
  if (rc) return rc < 0 ? 0 : rc;
  long N = r.sc.n_rods;
  double *ts;
  long nt = snap_times(&r, &ts);
  rclusters cl;
  if (clusters_alloc(&cl, N)) {
    free(ts), close_run(&r);
    return out_of_memory(argv[0]);
  }
  const long *size = cl.size;
  printf("t\tclusters\tlargest\tin_clusters\n");
  for (long k = 0; k < nt; k++) {
    rsnap s;
    if (snapshot(argv[0], &r, ts[k], &s)) {
      clusters_free(&cl), free(ts), close_run(&r);
      return 1;
    }
    long nc = find_clusters(s.x, N, o.gap, &cl), big = 0, cnt = 0, in = 0;
    for (long c = 0; c < nc; c++)
      if (size[c] >= o.minsize) cnt++, in += size[c], big = size[c] > big ? size[c] : big;
    printf("%.10g\t%ld\t%ld\t%.6g\n", ts[k], cnt, big, (double)in / (double)N);
    snap_free(&s);
  }
  clusters_free(&cl), free(ts);
  return close_run(&r);
}

/* ---- rods-collapse ----------------------------------------------------------------------------
 */

int haff_rods_collapse_main(int argc, char **argv) {
  static const char usage[] =
      "usage: haff rods-collapse [--n LIST] [--eps LIST] [--seeds K] [--cpd C] [--gamma G]\n"
      "Scans the constant-eps ring for inelastic collapse: for every N in LIST [4,8,16,32,64,128]\n"
      "and eps in LIST [0.3,0.5,0.7,0.8,0.9,0.95], K [4] rings (seeds 1..K) run to C [2000]\n"
      "collisions per rod (C <= 1e10) or collapse.  Columns N eps collapsed runs frac n_my\n"
      "(McNamara and Young's -ln(1-eps)/(1-eps)) my_predicts (1 if N > n_my)\n"
      "median_cpd_at_collapse.\n"
      "Masses alternate with ratio G [1: equal masses, as in McNamara and Young].\n";
  const char *nl = "4,8,16,32,64,128", *el = "0.3,0.5,0.7,0.8,0.9,0.95";
  long seeds = 4;
  double cpd = 2000, gamma = 1;
  static const struct option lo[] = {{"n", 1, 0, 'n'},   {"eps", 1, 0, 'e'},   {"seeds", 1, 0, 's'},
                                     {"cpd", 1, 0, 'c'}, {"gamma", 1, 0, 'g'}, {"help", 0, 0, 'h'},
                                     {0, 0, 0, 0}};
  optind = 1;
  int c;
  double x;
  opterr = 0;
  while ((c = getopt_long(argc, argv, "h", lo, NULL)) != -1) {
    switch (c) {
    case 'n':
      nl = optarg;
      break;
    case 'e':
      el = optarg;
      break;
    case 's':
      if (!whole_number(optarg, &x) || x < 1 || x > 1e7) return bad_arg(argv[0], "--seeds", optarg);
      seeds = (long)x;
      break;
    case 'c':
      /* at most 1e10: the collision count cpd N / 2 must be a long for 1e8 rods (1e300 gave
       * LONG_MIN, no ring ran and every eps read as "0 collapsed") */
      if (!finite_number(optarg, &x) || !(x > 0 && x <= 1e10))
        return bad_arg(argv[0], "--cpd", optarg);
      cpd = x;
      break;
    case 'g':
      if (!finite_number(optarg, &x) || !(x > 0 && x <= 1))
        return bad_arg(argv[0], "--gamma", optarg);
      gamma = x;
      break;
    case 'h':
      fputs(usage, stdout);
      return 0;
    default: {
      char buf[8];
      fprintf(stderr, "haff %s: unknown option or missing value '%s' (see --help)\n", argv[0],
              hd_opt_culprit(argv, lo, buf, sizeof buf));
    }
      return 2;
    }
  }
  if (optind != argc) {
    fprintf(stderr, "haff %s: unexpected argument '%s' (see --help)\n", argv[0], argv[optind]);
    return 2;
  }
  /* both lists read and checked once, before any ring runs (N odd too: before the header) */
  double ns[256], epss[256];
  int nn = parse_list(argv[0], "--n", nl, 1, 2, 1e8, ns, 256),
      ne = nn < 0 ? -1 : parse_list(argv[0], "--eps", el, 0, 0, nextafter(1, 0), epss, 256);
  if (nn < 0 || ne < 0) return 2;
  for (int k = 0; k < nn; k++)
    if (fmod(ns[k], 2) != 0) {
      fprintf(stderr,
              "haff %s: --n '%g': a ring holds an even number of rods (2 species alternate)\n",
              argv[0], ns[k]);
      return 2;
    }
  double *at = malloc((size_t)seeds * sizeof *at); /* cpd at collapse of every collapsed ring */
  if (!at) {
    fprintf(stderr, "haff %s: out of memory\n", argv[0]);
    return 1;
  }
  printf("N\teps\tcollapsed\truns\tfrac\tn_my\tmy_predicts\tmedian_cpd_at_collapse\n");
  for (int in = 0; in < nn; in++) {
    long N = (long)ns[in]; /* read as a number: "1e4" too, which atol read as 1 */
    for (int ie = 0; ie < ne; ie++) {
      double eps = epss[ie];
      long col = 0;
      for (long s = 1; s <= seeds; s++) {
        hd_rods_params p;
        hd_rods_params_default(&p);
        p.n = N, p.gamma = gamma, p.nmod = 1, p.model = HD_RODS_CONSTANT, p.eps = eps;
        p.seed = (unsigned long long)s;
        hd_rods *r;
        hd_error err;
        if (hd_rods_alloc(&r, &p, &err)) {
          fprintf(stderr, "haff %s: %s\n", argv[0], err.msg);
          free(at);
          return 2;
        }
        hd_rods_event ev;
        long nc = (long)(cpd * (double)N / 2);
        int rr = HD_OK;
        for (long k = 0; k < nc && rr == HD_OK; k++) rr = hd_rods_next(r, INFINITY, &ev, &err);
        if (rr == HD_ECOLLAPSE) {
          at[col++] = 2.0 * (double)r->collisions / (double)N;
        } else if (rr != HD_OK && rr != HD_SIM_IDLE) {
          /* HD_SIM_IDLE: a ring that cools for ever ran out of time (t near DBL_MAX, speeds
           * subnormal): not a collapse.  Anything else is an error */
          fprintf(stderr, "haff %s: N %ld eps %g seed %ld: %s\n", argv[0], N, eps, s, err.msg);
          hd_rods_free(r);
          free(at);
          return 1;
        }
        hd_rods_free(r);
      }
      gsl_sort(at, 1, (size_t)col);
      double nmy = hd_rods_my_ncrit(eps);
      printf("%ld\t%g\t%ld\t%ld\t%.3g\t%.4g\t%d\t%.6g\n", N, eps, col, seeds,
             (double)col / (double)seeds, nmy, (double)N > nmy,
             col ? gsl_stats_median_from_sorted_data(at, 1, (size_t)col) : NAN);
      fflush(stdout);
    }
  }
  free(at);
  return 0;
}
