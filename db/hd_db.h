/* hd_db: the SQLite log of runs (db/schema.sql is the documented schema, compiled in).
 * One file holds many runs.  Rows are inserted through prepared statements inside batch
 * transactions (WAL); a batch is committed every `batch_rows` rows and at every checkpoint,
 * so a killed process leaves whole batches only.  Indexes are built by hd_db_build_indexes.
 * Every SQLite failure (disk full, read-only file, I/O error, busy) is returned as HD_EIO with
 * the message "DBPATH: what failed: sqlite's message"; a failed batch is rolled back whole. */
#ifndef HD_DB_H
#define HD_DB_H

#include <stddef.h>
#include <stdint.h>

#include "hd_body.h"
#include "hd_error.h"

/* The schema version, stored in the file as PRAGMA user_version: 0 for the files made before it
 * was kept; 2 adds runs.cpd, the provenance and frames tables, the state measures of samples and
 * the views params and run_summary; 3 the species tables; 4 how each run was made
 * (runs.git_commit ... sweep_point), the view run_species and states.species; 5 stores per-species
 * energies in sample_species only: the table sample_rows, and samples a view of it with version
 * 4's columns (db/README.md lists them).  A file opened for writing (hd_db_open,
 * hd_db_open_existing) is brought up to it (hd_db_samples_convert); every version's file stays
 * readable (samples: a table up to 4, a view from 5, the same columns).  A writer refuses a file of
 * a newer version. */
#define HD_DB_SCHEMA_VERSION 5

typedef struct hd_db hd_db;
typedef struct sqlite3 sqlite3; /* the same typedef as <sqlite3.h> (C11 allows the repeat) */

/* The columns of `collisions` after `run`, in order: the one table that makes the struct
 * hd_collision_row, the INSERT statements and their binds (hd_db.c) and the CREATE TABLE of
 * db/schema.sql with its column comments (`make schema` writes it; tests/test_db.c checks it).
 * Adding a column is a row here and the code that fills the field (docs/architecture.md, "How
 * to add a collisions column").  X(name, ctype, bind, sqltype, scope, since, doc):
 *   ctype    the field's C type;  bind: how it is bound: INT64, INT, REAL (NaN -> NULL) or KIND
 *            (hd_coll_kind, hd_body.h, stored as its text);
 *   sqltype  the column's type and constraints in the CREATE TABLE;
 *   scope    HD_COLL_ALL: bound for every kind; HD_COLL_ROD: rod-rod rows only (NULL for the
 *            other kinds whatever the field holds, and not in the 2D insert);  HD_COLL_2D: NULL
 *            in rod-rod rows;
 *   since    the schema version that added it (0: in every file; a later one is added to the
 *            collisions of an older file with ALTER TABLE, old rows NULL, so it cannot be NOT
 *            NULL; bump HD_DB_SCHEMA_VERSION with it);
 *   doc      the field's meaning, the column's comment in db/schema.sql ("" for none). */
#define HD_COLLISION_COLUMNS(X)                                                                    \
  X(seq, int64_t, INT64, "INTEGER NOT NULL", HD_COLL_ALL, 0,                                       \
    "1, 2, ... within the run (all collisions count, logged or not)")                              \
  X(t, double, REAL, "REAL NOT NULL", HD_COLL_ALL, 0, "time")                                      \
  X(kind, hd_coll_kind, KIND, "TEXT NOT NULL", HD_COLL_ALL, 0, "collision kind (the list above)")  \
  X(i, int64_t, INT64, "INTEGER NOT NULL", HD_COLL_ALL, 0, "body (0-based)")                       \
  X(j, int64_t, INT64, "INTEGER NOT NULL", HD_COLL_ALL, 0, "body, or -1 - wall for a wall")        \
  X(disk_i, int, INT, "INTEGER", HD_COLL_ALL, 0, "the touching disk of i (0 for a disk)")          \
  X(disk_j, int, INT, "INTEGER", HD_COLL_ALL, 0, "the touching disk of j (-1 for a wall)")         \
  X(theta_i, double, REAL, "REAL", HD_COLL_ALL, 0, "contact angle of i (NULL when not defined)")   \
  X(theta_j, double, REAL, "REAL", HD_COLL_ALL, 0, "contact angle of j")                           \
  X(f, double, REAL, "REAL", HD_COLL_ALL, 0, "orientation factor mu_eff/m")                        \
  X(de, double, REAL, "REAL", HD_COLL_ALL, 0, "kinetic energy after minus before")                 \
  X(vn, double, REAL, "REAL", HD_COLL_ALL, 0, "normal relative velocity before (< 0)")             \
  X(eps, double, REAL, "REAL", HD_COLL_ROD, 0, "rods: coefficient of restitution drawn")           \
  X(e_tr, double, REAL, "REAL", HD_COLL_ROD, 0,                                                    \
    "rods: translational energy of the relative motion")                                           \
  X(tb_i, double, REAL, "REAL", HD_COLL_ROD, 0, "rods: bath temperature of i after the collision") \
  X(tb_j, double, REAL, "REAL", HD_COLL_ROD, 0, "rods: bath temperature of j after the collision")

/* The scope of a collisions column (HD_COLLISION_COLUMNS). */
enum { HD_COLL_ALL, HD_COLL_ROD, HD_COLL_2D };

/* One row of `collisions`: a field per column of HD_COLLISION_COLUMNS, in its order, meaning
 * what its doc says (build it with designated initialisers).  NaN doubles are stored as NULL. */
typedef struct hd_collision_row {
#define HD_COLL_FIELD(name, ctype, bind, sqltype, scope, since, doc) ctype name;
  HD_COLLISION_COLUMNS(HD_COLL_FIELD)
#undef HD_COLL_FIELD
} hd_collision_row;

/* The CREATE TABLE statement of `collisions` that HD_COLLISION_COLUMNS gives, as db/schema.sql
 * holds it (from "CREATE TABLE" to ");\n"), malloc'd; NULL when out of memory. */
char *hd_db_collisions_create_sql(void);

/* One row of `sample_rows` (energies per body, all species; each species' own: a
 * hd_species_sample, hd_db_log_species_sample). */
typedef struct hd_sample_row {
  double t;
  int64_t collisions; /* pair collisions so far (walls not counted) */
  double cpd;         /* 2 * collisions / N */
  double e_tr, e_rot; /* translational and rotational kinetic energy per body */
  /* state measures (hd_sim.h, hd_state_measures; NaN -> NULL, e.g. for rods): */
  double flow_frac, flow_chaos, count_var, s_rho, s_perp, s_par;
} hd_sample_row;

/* One row of `states`. */
typedef struct hd_state_rec {
  double t;
  int64_t body;
  int kind; /* an hd_kind (hd_body.h), stored as states.kind text (hd_kind_name) */
  double x, y, phi, vx, vy, omega;
  double cpd;  /* collisions per particle at t (states.cpd); NaN is stored as NULL */
  int species; /* the body's species.idx (states.species, schema version 4): 0 [dimers], 1
                * [disks], 2.. each [species NAME]; stored as NULL for a rod (kind 2) */
} hd_state_rec;

/* One row of `species` (schema version 3). */
typedef struct hd_species_rec {
  int idx;           /* engine species index */
  const char *name;  /* "dimer", "disk" or the section's NAME */
  const char *disks; /* "x y d m; ..." (schema.sql) */
  int64_t count;     /* bodies */
  double mass;       /* total mass of a body */
  double inertia;    /* its moment of inertia about the centre of mass */
} hd_species_rec;

/* One row of `sample_species` (schema version 3). */
typedef struct hd_species_sample {
  double t;     /* the samples row's t */
  int species;  /* species.idx */
  double e_tr;  /* translational energy per body of the species */
  double e_rot; /* rotational energy per body of the species */
} hd_species_sample;

/* Brings the rows of a table `samples` of schema version 0 to 4 in schema src of connection h
 * ("main" or an attached "s"; a name of the caller's, never read from a file) into main's
 * version 5 tables: every row to main.sample_rows (the columns it has; those it lacks NULL), and
 * each dimer-disk mixture value of its columns e_tr_dimer, e_rot_dimer, e_tr_disk that src's
 * sample_species has no row for (run, t, species) to main.sample_species (species 0: e_tr_dimer,
 * e_rot_dimer; 1: e_tr_disk, e_rot 0).  run_off: an SQL expression added to run ("0", or merge's
 * run shift).  Nothing when src's samples is not a table (version 5: the view).  The caller holds
 * the transaction and drops the old table.  HD_OK, or HD_EIO / HD_ENOMEM naming path. */
int hd_db_samples_convert(sqlite3 *h, const char *src, const char *run_off, const char *path,
                          hd_error *err);

/* The status for an SQLite result code (primary or extended) of a failed call: HD_EINPUT for a
 * damaged or foreign file (SQLITE_CORRUPT "malformed", SQLITE_NOTADB: bad input, exit 2),
 * HD_ENOMEM for SQLITE_NOMEM, else HD_EIO. */
int hd_db_status_of(int sqlite_code);

/* Opens (creating if needed) the database at path, applies the schema, sets WAL.  The path is
 * a plain file name (hd_db_plain_name).  Returns HD_OK, HD_EINPUT (path is a directory, a file
 * that is not an SQLite database, or a database that is not haff's: it has tables but none of
 * haff's, or one of haff's tables without a column of haff's; such a file is left byte for
 * byte as it was) or HD_EIO with err set. */
int hd_db_open(hd_db **out, const char *path, hd_error *err);

/* The name under which SQLite opens the file PATH as a plain file name: PATH itself when it is
 * absolute, else "./PATH" (in buf of size bytes).  SQLite gives a name of its own meaning to
 * ":memory:" (a database in memory), "" (a temporary one) and, with URIs enabled as Debian's
 * build has them, "file:..." (a URI: "file:x.db?mode=memory"); "./" makes each an ordinary file
 * in the current folder.  NULL when it does not fit in buf. */
const char *hd_db_plain_name(const char *path, char *buf, size_t size);

/* HD_EINPUT with err set when PATH is a directory or another file that is not a regular one
 * (a FIFO, a device: SQLite would fail on it with "disk I/O error" or hang), or does not exist
 * and must_exist; else HD_OK (a missing path is a new database to hd_db_open). */
int hd_db_check_path(const char *path, int must_exist, hd_error *err);

/* As hd_db_open, for a file that must be a haff database already (`haff resume`): HD_EINPUT
 * when it is missing, a directory, not an SQLite file or has no runs table, found before
 * anything is written (hd_db_open would add haff's tables to any file). */
int hd_db_open_existing(hd_db **out, const char *path, hd_error *err);

/* Opens PATH, which must hold every table of tables (NULL-terminated names), for reading into
 * *h (sqlite3_open_v2 flags, e.g. SQLITE_OPEN_NOMUTEX): read-write with PRAGMA query_only when
 * the file may be written, so that the last reader to close removes the -wal and -shm files
 * SQLite makes beside a database in WAL mode (a read-only connection leaves them); read-only
 * when it is write-protected; as immutable in a read-only folder or file system, where no -shm
 * can be made (not when PATH-wal holds rows, which immutable would leave out).  HD_OK; else *h
 * NULL and HD_EINPUT (missing, a directory, not an SQLite file, a table missing: not a haff
 * database), HD_EIO or HD_ENOMEM with err set. */
int hd_db_open_read(const char *path, int flags, const char *const *tables, sqlite3 **h,
                    hd_error *err);

/* Closes a connection of hd_db_open_read (NULL allowed), so that a reader above the store
 * does not call SQLite itself. */
void hd_db_close_read(sqlite3 *h);

/* Opens an existing database read-only (for analysis and export): no schema is applied and
 * every write fails with HD_EIO.  In a read-only folder or file system (no -shm can be made)
 * it reads the file as immutable.  Returns HD_OK, HD_EINPUT (missing, a directory, not an
 * SQLite file, or no runs table: not a haff database) or HD_EIO with err set. */
int hd_db_open_readonly(hd_db **out, const char *path, hd_error *err);

/* Commits any open batch and closes. NULL is allowed. Returns HD_OK or HD_EIO. */
int hd_db_close(hd_db *db, hd_error *err);

/* Rows per batch transaction [10000]; rows < 1 is taken as 1. */
void hd_db_set_batch_rows(hd_db *db, long rows);

/* The path the database was opened with (for messages). */
const char *hd_db_path(const hd_db *db);

/* Inserts a runs row with status 'running' and returns its id in *run.  The row is left in
 * the open batch: other connections see it once it is committed (hd_db_commit, or any call
 * below that commits first), so that the caller can first take a lock named by the id
 * (hd_run.c: a resume never finds a new run before its process holds the run's lock). */
int hd_db_run_begin(hd_db *db, const char *scene_text, unsigned long long seed, const char *version,
                    int64_t *run, hd_error *err);

/* Sets status ('running','done','interrupted','collapsed','failed'), events, wall_seconds and
 * (for a final status) finished; commits the open batch first.  'done' and 'collapsed' also
 * delete the run's checkpoint: such a run cannot be resumed. */
int hd_db_run_status(hd_db *db, int64_t run, const char *status, int64_t events,
                     double wall_seconds, hd_error *err);

/* Stores a message for run (why it ended when not 'done': collapse details, an error); NULL
 * clears it.  Commits the open batch first. */
int hd_db_run_message(hd_db *db, int64_t run, const char *msg, hd_error *err);

/* Stores the box edges Lx, Ly of run in runs.box_x, runs.box_y (read by `haff export xyz`).
 * Commits the open batch first. */
int hd_db_run_box(hd_db *db, int64_t run, double lx, double ly, hd_error *err);

/* Stores run's homogeneous cooling state window in runs.hcs_cpd_start, hcs_cpd_end, hcs_end
 * ('none', 's_perp' or 'rate': what ended it), hcs_s_perp and hcs_flow_excess (means over the
 * state measures' window), found by hd_hcs_window_find with the default options on the samples
 * the run has logged (all of them, over every resume); NULL with fewer than 3 samples.  hd_run
 * calls it when a run ends (done, collapsed, interrupted); the analyses use it when their
 * detection options are the defaults (docs/analysis.md, "The stored window").  Commits the open
 * batch first. */
int hd_db_run_hcs(hd_db *db, int64_t run, hd_error *err);

/* Stores how far run has got: runs.events and runs.cpd (collisions per particle reached);
 * commits the open batch first (hd_run calls it at every commit it forces, about once a
 * second, so that a running run's row says how far it is). */
int hd_db_run_progress(hd_db *db, int64_t run, int64_t events, double cpd, hd_error *err);

/* Records where run is made in the provenance table: host name and Slurm job and array task
 * ids (NULL or "" for none; source stays NULL: made here).  Commits the open batch first. */
int hd_db_run_origin(hd_db *db, int64_t run, const char *host, const char *slurm_job,
                     const char *slurm_task, hd_error *err);

/* How a run was made (schema version 4), for hd_db_run_provenance.  Text NULL or "": NULL. */
typedef struct hd_run_prov {
  const char *git_commit;  /* the commit haff was built from, or "unknown" */
  int git_dirty;           /* 1 the tree differed from it, 0 it did not, -1 unknown (NULL) */
  const char *compiler;    /* the compiler's version line */
  const char *cflags;      /* the build's flags */
  const char *command;     /* the command line that began the run */
  const char *sweep_point; /* "DIR point K: SETS" for a point of haff sweep, else NULL */
} hd_run_prov;

/* Stores p in run's runs.git_commit, git_dirty, compiler, cflags, command and sweep_point.
 * Commits the open batch first.  HD_OK, HD_EIO. */
int hd_db_run_provenance(hd_db *db, int64_t run, const hd_run_prov *p, hd_error *err);

/* The first run of db with this scene text (runs.scene) and seed, if any. */
typedef struct hd_same_run {
  int64_t run;     /* its id, 0: none */
  char status[16]; /* its status */
  char commit[48]; /* its git_commit, 'unknown' when not known (NULL, or a file before v4) */
} hd_same_run;

/* Looks in db (open for writing or read-only) for a run of the same scene text and seed, so
 * that `haff run` does not repeat one by mistake; same->run 0 when there is none.  HD_OK,
 * HD_EIO. */
int hd_db_find_same_run(hd_db *db, const char *scene_text, unsigned long long seed,
                        hd_same_run *same, hd_error *err);

/* Builds the indexes (after a run): collisions(run,seq), collisions(run,kind),
 * sample_rows(run,t) (named samples_run_t), states(run,label,t), checkpoints(run).  Commits the
 * open batch first. */
int hd_db_build_indexes(hd_db *db, hd_error *err);

/* Buffered inserts into the open batch (a batch is opened on demand). */
int hd_db_log_collision(hd_db *db, int64_t run, const hd_collision_row *r, hd_error *err);
int hd_db_log_sample(hd_db *db, int64_t run, const hd_sample_row *r, hd_error *err);
/* A sample_species row (buffered like the samples). */
int hd_db_log_species_sample(hd_db *db, int64_t run, const hd_species_sample *r, hd_error *err);
/* A species row of run (after the rows logged before it, in the open batch). */
int hd_db_log_species(hd_db *db, int64_t run, const hd_species_rec *r, hd_error *err);
/* `label`: 'initial', 'final', 'checkpoint', 'velocities' (snapshots at [log] velocities_at). */
int hd_db_log_state(hd_db *db, int64_t run, const char *label, const hd_state_rec *r,
                    hd_error *err);

/* Inserts a frames row of run at time t / cpd: n bodies packed in data (size bytes, the
 * layout of db/schema.sql, HD_FRAME_BODY_BYTES per body), in the open batch after every row
 * logged before it.  HD_EINPUT when size exceeds SQLite's limit per value. */
int hd_db_log_frame(hd_db *db, int64_t run, double t, double cpd, int64_t n, const void *data,
                    size_t size, hd_error *err);

/* The bytes of frame data stored for run so far (sum of length(data)), in *bytes. */
int hd_db_frames_bytes(hd_db *db, int64_t run, int64_t *bytes, hd_error *err);

/* Commits the open batch, if any. */
int hd_db_commit(hd_db *db, hd_error *err);

/* Writes a checkpoint (an opaque engine blob, exact) for run at collision seq / time t in the
 * same transaction as the rows logged so far, then commits.  Older checkpoints of the run are
 * deleted. */
int hd_db_checkpoint_save(hd_db *db, int64_t run, int64_t seq, double t, const void *blob, size_t n,
                          hd_error *err);

/* Loads the newest checkpoint of run: *blob malloc'd (free()), *seq and *t as saved.
 * HD_EINPUT if the run has none. */
int hd_db_checkpoint_load(hd_db *db, int64_t run, void **blob, size_t *n, int64_t *seq, double *t,
                          hd_error *err);

/* *unstarted = 1 when run is 'running' and has no checkpoint: its process ended in its set-up,
 * before the first checkpoint (killed in its first milliseconds), and nothing of it can be
 * continued; else 0 (also when there is no such run).  HD_OK or HD_EIO. */
int hd_db_run_unstarted(hd_db *db, int64_t run, int *unstarted, hd_error *err);

/* A table of db/schema.sql that holds rows of runs (a `run` column), in the one list that
 * truncation (hd_db_truncate_after), deletion (hd_db_run_delete) and merge (db/hd_merge.c)
 * use. */
typedef struct hd_run_table {
  const char *name;     /* the table */
  const char *truncate; /* the DELETE of the rows a resumed run writes again (?1 run, ?2 the
                         * checkpoint's seq, ?3 its t), NULL when its rows are kept */
} hd_run_table;

/* The per-run tables, ending with an entry whose name is NULL (runs itself not included). */
const hd_run_table *hd_db_run_tables(void);

/* Deletes run and its rows in every per-run table, in one transaction.  HD_EINPUT when there
 * is no such run.  Commits the open batch first. */
int hd_db_run_delete(hd_db *db, int64_t run, hd_error *err);

/* Deletes the rows a resumed run will write again, in every per-run table
 * (hd_db_run_tables): collisions with seq > seq, sample_rows,
 * frames, sample_species and states with t > t; and the run's 'checkpoint' and 'final' states
 * (where it stopped: it goes on, and writes its final state again); species too when t < 0 (a
 * run begun again from its set-up, t = -inf, writes them again). */
int hd_db_truncate_after(hd_db *db, int64_t run, int64_t seq, double t, hd_error *err);

/* The id of the newest run that has a checkpoint and whose status is 'interrupted', 'failed'
 * (disk full: resumable once there is room) or 'running' (a killed process), or that is
 * 'running' without a checkpoint (killed in its set-up: hd_db_run_unstarted); HD_EINPUT if
 * none.  *scene_text malloc'd, *seed its seed.  want_run <= 0 picks the newest such run;
 * want_run > 0 asks for that run, and a run that does not exist or has ended ('done',
 * 'collapsed') is HD_EINPUT with a message that says so. */
int hd_db_find_resumable(hd_db *db, int64_t want_run, int64_t *run, char **scene_text,
                         unsigned long long *seed, hd_error *err);

/* The ids of every run that hd_db_find_resumable would take (status 'running', 'interrupted'
 * or 'failed' with a checkpoint, and 'running' without one: killed in its set-up, run again
 * from the start), oldest first: *ids malloc'd (free(); NULL when *n is 0). */
int hd_db_list_resumable(hd_db *db, int64_t **ids, size_t *n, hd_error *err);

/* The SQLite handle, for analysis code that reads with its own statements.  Owned by db. */
sqlite3 *hd_db_handle(hd_db *db);

/* The newest run of the database at path (a sweep's point): opens it for reading (waiting up
 * to 10 s for a writer), and gives its id in *run (0 when the file has no run), its status in
 * status (size bytes; "" when none) and in *resumable whether it has a checkpoint.  HD_OK, or
 * the status of hd_db_open_read, or HD_EIO when the runs cannot be read. */
int hd_db_newest_run(const char *path, int64_t *run, char *status, size_t size, int *resumable,
                     hd_error *err);

/* The species of a run (idx order, the order of the bodies' numbers) as the engine's shapes
 * (hd_shape_cluster of the stored disks), with their counts, from the species table of the
 * database open on h: at most max of them into shape[], count[]; *n their number, 0 for a run
 * or file without a species table (before schema version 3).  HD_OK, or HD_EINPUT for a row
 * that is not a shape (its message names the run and idx), HD_EIO. */
int hd_db_read_species(sqlite3 *h, int64_t run, hd_shape *shape, int64_t *count, int max, int *n,
                       hd_error *err);

#endif
