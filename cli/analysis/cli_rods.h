/* cli_rods: what the rod analyses share (cmd_rods_*.c, one file per subcommand; docs/rods.md):
 * their option table, opening a rods run of a database, its snapshots and the cluster finder.
 * CLI code: says what went wrong on stderr as "haff CMD: ...". */
#ifndef HD_CLI_RODS_H
#define HD_CLI_RODS_H

#include <sqlite3.h>

#include "hd_opt.h"
#include "hd_scene.h"

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

/* The options each rods subcommand reads (bits of hd_optspec.allowed); another is refused. */
enum {
  HD_RCLI_RUN = 1,   /* --run ID */
  HD_RCLI_BINS = 2,  /* --bins N */
  HD_RCLI_T = 4,     /* --t T */
  HD_RCLI_GAP = 8,   /* --gap G */
  HD_RCLI_MIN = 16,  /* --min-size M */
  HD_RCLI_X = 32,    /* --x X */
  HD_RCLI_RANGE = 64 /* --range X */
};

/* The options of the rods subcommands that read a database (dest: ropts). */
extern const hd_optdef hd_rcli_opts[];

/* The first fields of the hd_optspec of a rods subcommand that reads a database: its name CMD,
 * the options it reads (ALLOWED, of hd_rcli_opts) and its one positional argument. */
#define HD_RCLI_SPEC(CMD, ALLOWED) HD_OPT_SPEC(CMD, hd_rcli_opts, ALLOWED, 1, 1, "one database")

/* The run: its id and its scene (a [rods] scene). */
typedef struct rrun {
  sqlite3 *db;
  long id;
  hd_scene sc;
} rrun;

/* One snapshot: its time and x, v, T_B by body index (arrays of sc.n_rods, malloc'd). */
typedef struct rsnap {
  double t, *x, *v, *tb;
} rsnap;

/* Clusters of a snapshot: maximal runs of ring neighbours (in position order) closer than gap.
 * start[c], size[c]; order[] gets the rods sorted by x.  Arrays of n rods (clusters_alloc). */
typedef struct rclusters {
  long *order, *start, *size;
} rclusters;

/* The common start of the DB readers: parses the options by spec (bins: the --bins default, 0
 * for none) and opens the run.  Returns 0 to go on, -1 after --help (the caller returns 0),
 * else the exit code (nothing left open). */
int hd_rcli_start(const hd_optspec *spec, int argc, char **argv, int bins, ropts *o, rrun *r);

/* hd_rcli_start, then the snapshot nearest --t (or the last) into s.  Returns as
 * hd_rcli_start; 1 (run closed) when the run has no snapshots. */
int hd_rcli_start_at(const hd_optspec *spec, int argc, char **argv, int bins, ropts *o, rrun *r,
                     rsnap *s);

/* The work of a subcommand on one snapshot s of run r (rods-phase, -gofr, -veldist): prints
 * its table, returns the exit code (saying why on stderr when not 0). */
typedef int hd_rcli_at_fn(const char *cmd, const ropts *o, const rrun *r, const rsnap *s);

/* The main of such a subcommand: hd_rcli_start_at, fn, then the snapshot freed and the run
 * closed.  Returns the exit code (0 after --help). */
int hd_rcli_main_at(const hd_optspec *spec, int argc, char **argv, int bins, hd_rcli_at_fn *fn);

/* The work of a subcommand on snapshots of run r (rods-density, -clusters): ts[0..nt) their
 * times, ascending.  Prints its table, returns the exit code as hd_rcli_at_fn. */
typedef int hd_rcli_series_fn(const char *cmd, const ropts *o, rrun *r, const double *ts, long nt);

/* The main of such a subcommand: hd_rcli_start, the snapshot times (only the one nearest --t
 * when given), fn, then the times freed and the run closed.  Returns as hd_rcli_main_at. */
int hd_rcli_main_series(const hd_optspec *spec, int argc, char **argv, int bins,
                        hd_rcli_series_fn *fn);

/* Closes what hd_rcli_start opened; returns 0, the exit code of a command that got this far. */
int hd_rcli_close(rrun *r);

/* Snapshot times of the run (labels initial, velocities, final), ascending; malloc'd. */
long hd_rcli_snap_times(rrun *r, double **t);

/* The rods at snapshot time t into s (hd_rcli_snap_free).  Returns 0, or 1 after saying why on
 * stderr (nothing left allocated). */
int hd_rcli_snapshot(const char *cmd, rrun *r, double t, rsnap *s);

/* Frees the arrays of s. */
void hd_rcli_snap_free(rsnap *s);

/* The snapshot time nearest o->t (or the last) into *t.  Returns 0, or 1 after saying why. */
int hd_rcli_pick_time(const char *cmd, rrun *r, const ropts *o, double *t);

/* The mass of rod i (species alternate: 1 + gamma and 1 + 1/gamma). */
double hd_rcli_mass(const hd_scene *sc, long i);

/* Says that cmd ran out of memory; returns 1 (the exit code). */
int hd_rcli_oom(const char *cmd);

/* Allocates cl for n rods.  Returns 0, or 1 when out of memory (nothing left allocated). */
int hd_rcli_clusters_alloc(rclusters *cl, long n);

/* Frees what hd_rcli_clusters_alloc allocated. */
void hd_rcli_clusters_free(rclusters *cl);

/* Finds the clusters of x[0..n-1] (neighbours closer than gap) into cl; returns their count. */
long hd_rcli_find_clusters(const double *x, long n, double gap, rclusters *cl);

#endif
