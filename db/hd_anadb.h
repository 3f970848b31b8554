/* hd_anadb: read-only access of the analysis programs to a haff database (db/schema.sql),
 * through the sqlite3 C API: runs with the scene parameters they need, the `samples` series,
 * `states` snapshots and dimer-dimer collision angles. */
#ifndef HD_ANADB_H
#define HD_ANADB_H

#include <sqlite3.h>
#include <stddef.h>
#include <stdint.h>

#include "hd_body.h"
#include "hd_error.h"

/* Length of hd_run_info.label (and hd_group.label), the terminating NUL included. */
#define HD_ANA_LABEL_MAX 96

/* The label in tables of what a run is analysed as (hd_run_info.species, .mixture): dimers,
 * disks, dimers+disks (a mixture), shapes (named species: hd_run_info.label names them) or
 * other (rods), with +walls when the box has walls. */
const char *hd_ana_species_name(int kind, int mixture, int walls);

/* One run and the scene parameters the analysis needs (parsed from runs.scene). */
typedef struct hd_run_info {
  int64_t id;
  char status[16]; /* runs.status */
  unsigned long long seed;
  int species;      /* the kind the run is analysed as (hd_kind): HD_KIND_BODY if a [species NAME]
                       section has count > 0 (the gas as a whole: every body, whatever its shape;
                       HD_KIND_DIMER for named_dimers below),
                       else HD_KIND_DIMER if [dimers] count > 0 (with mixture set if [disks]
                       count > 0 too: the whole gas, with the dimers' a, d), else HD_KIND_DISK
                       if [disks] count > 0, else HD_KIND_ROD (a rods run, or no bodies) */
  int named_dimers; /* 1: the gas is one [species NAME] of paper dimers (two equal disks, as
                       `shape = dimer A`), which runs bit for bit as [dimers]: analysed as dimers
                       (HD_KIND_DIMER, its a, d, m, alpha, beta, q; label "shapes:NAME"), its
                       states rows of kind 'body', its collisions 'body-body' */
  int mixture;      /* 1: HD_KIND_DIMER of a [dimers]-[disks] mixture (N, density: every
                       body's; its alpha: NaN when the three restitutions differ; no Enskog
                       reference: mass NaN) */
  int walls;        /* [walls] sides given: not the periodic box of the papers */
  char label[HD_ANA_LABEL_MAX]; /* what tables print: hd_ana_species_name, or for HD_KIND_BODY
                                   "shapes:" and the present species' names joined by '+' in
                                   scene order ("shapes:dimers+tri"), then "+walls" if walls */
  int rotates;                  /* 1 if some body has more than one disk (E_rot and K exist) */
  long n;       /* bodies of that species (HD_KIND_BODY and a mixture: of every species) */
  double alpha; /* its restitution with itself ([dimers] or [disks] alpha, default 1);
                   HD_KIND_BODY and a mixture: the one restitution of every pair of
                   present species, NaN when they differ (eq. 31 has no single alpha
                   then) */
  double alpha_lo, alpha_hi; /* the smallest and largest restitution of a pair of present
                                species (alpha_lo = alpha_hi = alpha for one species) */
  double a, d;          /* bond length and disk diameter (disks: a = 0, d = sigma; HD_KIND_BODY:
                           0 and NaN) */
  double m;             /* disk mass ([dimers] m or [disks] mass, default 1; shapes: NaN) */
  double mass;          /* body mass: 2 m for a dimer, m for a disk (shapes: NaN, so no Enskog
                           nu0 reference) */
  double a_over_d;      /* a / d (0 for disks, NaN for shapes) */
  double beta, q;       /* rough bodies (issue 29): that species' tangential restitution with
                           itself and its disks' q ([dimers] or [disks] beta, q: -1, 0 when
                           smooth; NaN for shapes and rods) */
  int rough;            /* 1 when a pair of present species, or a body and the walls, collide
                           with a tangential restitution beta > -1 (issue 29): eq. (31) is Haff's
                           law of smooth bodies, and its D_e does not describe them */
  double wall_alpha;    /* [walls] alpha (NaN without walls) */
  uint64_t shape_key;   /* a hash of the present species in engine order: counts, every disk's
                           place about its body's centre of mass, diameter and mass (not their
                           names: the label has them) */
  uint64_t coll_key;    /* a hash of the normal restitutions: every pair of present species'
                           alpha, the walls' sides and alpha */
  uint64_t rough_key;   /* a hash of the roughness: every pair's beta, each species' q, the walls'
                           beta */
  double box_x, box_y;  /* the box: runs.box_x/box_y (the engine's), else the scene's: [system]
                           box, or derived from area_fraction as the loader does (0: none) */
  double area_fraction; /* [system] area_fraction (0 if absent) */
  double density;       /* n / area of this species (area = the box above; NaN without one) */
  double eta_disk;      /* pi n d^2 / 4: area fraction of the reference disks (eq. 30) */
  int hcs_stored;       /* 1 if runs.hcs_cpd_start/end are set (hd_db_run_hcs), else 0 */
  double hcs_cpd_start, hcs_cpd_end;  /* the stored HCS window (NaN when not stored) */
  int hcs_end;                        /* runs.hcs_end as HD_HCS_END_* (hd_homog.h) */
  double hcs_s_perp, hcs_flow_excess; /* runs.hcs_s_perp, hcs_flow_excess (NaN when NULL) */
} hd_run_info;

/* Opens path for reading (hd_db_open_read: nothing is written) and checks that the tables runs
 * and samples exist.  HD_OK, or HD_EINPUT / HD_EIO / HD_ENOMEM with err set and *db NULL. */
int hd_ana_open(sqlite3 **db, const char *path, hd_error *err);

/* Parses a stored scene text into ri (everything but id, status, seed) with the engine's loader
 * (hd_scene_read_stored: its keys, defaults and body areas).  HD_EINPUT, with the loader's
 * "runs.scene:LINE: [section] key = value: why", for a text it refuses. */
int hd_ana_parse_scene(const char *text, hd_run_info *ri, hd_error *err);

/* Whether runs a and b ran the same bodies and collision rule (their shape_key, coll_key and
 * rough_key equal; box and seed aside): 1 or 0. */
int hd_ana_same_physics(const hd_run_info *a, const hd_run_info *b);

/* The runs to analyse: want >= 0 gives that run (any status; HD_EINPUT if absent), want < 0
 * every run with status done, collapsed or interrupted, by id.  *runs malloc'd (free()). */
int hd_ana_runs(sqlite3 *db, int64_t want, hd_run_info **runs, size_t *n, hd_error *err);

/* The `samples` series of one run, ordered by t (arrays malloc'd; hd_series_free). */
typedef struct hd_series {
  size_t n;
  double *t, *coll, *cpd, *e_tr, *e_rot;
  /* state measures (db/schema.sql, samples; NaN when NULL or in a file of schema < 2) */
  double *s_perp, *flow_frac, *flow_chaos;
} hd_series;
int hd_ana_samples(sqlite3 *db, int64_t run, hd_series *s, hd_error *err);
void hd_series_free(hd_series *s);

/* One snapshot of body velocities (rows of `states` with one label and one t). */
typedef struct hd_snapshot {
  double t, cpd; /* cpd NaN when NULL */
  size_t n;      /* bodies of the analysed species in it */
  double *vx, *vy, *omega;
} hd_snapshot;

/* Every snapshot of run with the given label, by t, keeping rows whose kind is `kind`
 * ("dimer" or "disk").  *snaps malloc'd; free with hd_snapshots_free. */
int hd_ana_snapshots(sqlite3 *db, int64_t run, const char *label, const char *kind,
                     hd_snapshot **snaps, size_t *n, hd_error *err);
void hd_snapshots_free(hd_snapshot *snaps, size_t n);

/* Dimer-dimer collisions of one run by seq: theta_i, theta_j, f (malloc'd arrays; NULL
 * angles are skipped); body: the rows of kind 'body-body' instead (a run of named dimers,
 * hd_run_info.named_dimers).  HD_OK with *n = 0 when there are none. */
int hd_ana_dd_collisions(sqlite3 *db, int64_t run, int body, double **theta_i, double **theta_j,
                         double **f, size_t *n, hd_error *err);

/* Closes a database of hd_ana_open (NULL allowed). */
void hd_ana_close(sqlite3 *db);

/* The status (hd_db_status_of) of the last failure on db: HD_EINPUT for a damaged file. */
int hd_ana_status(sqlite3 *db);

/* ---- the rod paper's analyses (cli/analysis/cli_rods*.c) ---- */

/* The rods run to analyse: want >= 0 gives that run, want < 0 the newest run whose scene has a
 * [rods] section; *id, and its scene text in *scene (malloc'd, free(); NULL when none).  HD_OK;
 * HD_EINPUT with err.msg "" when there is no such run; HD_EIO with SQLite's message when the
 * runs cannot be read; HD_ENOMEM. */
int hd_ana_rods_run(sqlite3 *db, int64_t want, int64_t *id, char **scene, hd_error *err);

/* The times of the run's rod snapshots (states of kind 'rod' labelled initial, velocities or
 * final), ascending, into *t (malloc'd, free()): their count (the ones read before running out
 * of memory), or -1 when they cannot be read. */
long hd_ana_rods_times(sqlite3 *db, int64_t run, double **t);

/* The rods of the run's snapshot at time t: for each body b < n in it, x[b], v[b] (states.vx)
 * and its bath temperature tb[b] (states.omega); other entries are left as they are.  HD_OK,
 * or HD_EIO with SQLite's message. */
int hd_ana_rods_snapshot(sqlite3 *db, int64_t run, double t, long n, double *x, double *v,
                         double *tb, hd_error *err);

#endif
