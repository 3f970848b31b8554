/* hd_db: the SQLite log of runs (see hd_db.h for the contract, db/schema.sql for the tables).
 *
 * Durability.  The file is in WAL mode with synchronous = NORMAL.  Every batch of rows is one
 * transaction; a WAL commit is atomic: the commit appends the batch's pages to the -wal file and
 * ends them with a commit frame, and a reader (or the recovery after a crash) only ever sees
 * frames up to the last complete commit frame.  A process killed with -9 (the OS still writes
 * what it was handed) therefore leaves the database with whole batches only, and it passes
 * `PRAGMA integrity_check`.  NORMAL skips the fsync at every commit (FULL would do it): a power
 * failure may lose the newest committed batches, but never leaves a half one.
 *
 * Errors.  Every SQLite failure is HD_EIO "DBPATH: what failed: sqlite's message".  A failure
 * inside a batch (an insert, the COMMIT, a checkpoint) rolls the whole batch back, so the file
 * holds whole batches only and stays sound; the rows of that batch are lost and the caller (the
 * run) stops with the error. */
#include "hd_db.h"

#include <math.h>
#include <sqlite3.h>
#include <stdlib.h>
#include <string.h>

extern const char hd_schema_sql[];

struct hd_db {
  sqlite3 *db;
  char *path;               /* as given, for messages */
  int readonly;             /* opened by hd_db_open_readonly */
  long batch_rows;          /* rows per batch transaction */
  long pending;             /* rows in the open batch */
  int in_tx;                /* a batch transaction is open */
  sqlite3_stmt *ins_run;    /* INSERT INTO runs */
  sqlite3_stmt *ins_coll;   /* INSERT INTO collisions */
  sqlite3_stmt *ins_sample; /* INSERT INTO samples */
  sqlite3_stmt *ins_state;  /* INSERT INTO states */
  sqlite3_stmt *ins_ckpt;   /* INSERT INTO checkpoints */
  sqlite3_stmt *del_ckpt;   /* DELETE older checkpoints of a run */
};

static const char *const coll_kind_names[] = {"dimer-dimer", "dimer-disk", "disk-disk",
                                              "dimer-wall",  "disk-wall",  "rod-rod"};

const char *hd_coll_kind_name(hd_coll_kind k) {
  if ((int)k < 0 || (size_t)k >= sizeof coll_kind_names / sizeof coll_kind_names[0]) return "?";
  return coll_kind_names[k];
}

const char *hd_db_kind_name(int kind) {
  switch (kind) {
  case 0:
    return "disk";
  case 1:
    return "dimer";
  case HD_DB_KIND_ROD:
    return "rod";
  default:
    return NULL;
  }
}

/* ---------------------------------------------------------------------------------------- */
/* errors */

/* Sets err to HD_EIO "path: what: sqlite's message" (the message of the last failed call). */
static int sql_error(hd_db *db, hd_error *err, const char *what) {
  return hd_error_set(err, HD_EIO, "%s: %s: %s", db->path, what, sqlite3_errmsg(db->db));
}

/* Rolls back whatever transaction is open and forgets the batch.  Keeps err as it is. */
static void rollback(hd_db *db) {
  if (!sqlite3_get_autocommit(db->db)) sqlite3_exec(db->db, "ROLLBACK", NULL, NULL, NULL);
  db->in_tx = 0;
  db->pending = 0;
}

/* A failure inside a batch: the message first (ROLLBACK would replace sqlite's message), then
 * the statement is reset and the whole batch rolled back. */
static int batch_fail(hd_db *db, sqlite3_stmt *st, hd_error *err, const char *what) {
  int rc = sql_error(db, err, what);
  if (st) sqlite3_reset(st);
  rollback(db);
  return rc;
}

static int check_db(hd_db *db, hd_error *err) {
  if (!db) return hd_error_set(err, HD_EIO, "database: not open");
  if (db->readonly)
    return hd_error_set(err, HD_EIO, "%s: write: the database was opened read-only", db->path);
  return HD_OK;
}

/* Binds a double, NaN as NULL. */
static int bind_real(sqlite3_stmt *st, int i, double v) {
  return isnan(v) ? sqlite3_bind_null(st, i) : sqlite3_bind_double(st, i, v);
}

/* ---------------------------------------------------------------------------------------- */
/* open / close */

static int prepare(hd_db *db, sqlite3_stmt **st, const char *sql, hd_error *err) {
  if (sqlite3_prepare_v2(db->db, sql, -1, st, NULL) != SQLITE_OK)
    return sql_error(db, err, "prepare statement");
  return HD_OK;
}

static void finalize_all(hd_db *db) {
  sqlite3_stmt **sts[] = {&db->ins_run,   &db->ins_coll, &db->ins_sample,
                          &db->ins_state, &db->ins_ckpt, &db->del_ckpt};
  for (size_t k = 0; k < sizeof sts / sizeof sts[0]; k++) {
    sqlite3_finalize(*sts[k]);
    *sts[k] = NULL;
  }
}

static void db_free(hd_db *db) {
  if (!db) return;
  finalize_all(db);
  sqlite3_close(db->db);
  free(db->path);
  free(db);
}

/* Allocates the handle and opens the file with flags. */
static int db_alloc_open(hd_db **out, const char *path, int flags, hd_error *err) {
  *out = NULL;
  if (!path || !*path) return hd_error_set(err, HD_EINPUT, "database: no path given");
  hd_db *db = calloc(1, sizeof *db);
  if (!db) return hd_error_set(err, HD_ENOMEM, "%s: out of memory", path);
  db->path = strdup(path);
  if (!db->path) {
    free(db);
    return hd_error_set(err, HD_ENOMEM, "%s: out of memory", path);
  }
  db->batch_rows = 10000;
  if (sqlite3_open_v2(path, &db->db, flags, NULL) != SQLITE_OK) {
    int rc = db->db ? sql_error(db, err, "open")
                    : hd_error_set(err, HD_ENOMEM, "%s: open: out of memory", path);
    db_free(db);
    return rc;
  }
  sqlite3_extended_result_codes(db->db, 1);
  sqlite3_busy_timeout(db->db, 10000); /* another writer: wait up to 10 s, then HD_EIO */
  *out = db;
  return HD_OK;
}

int hd_db_open(hd_db **out, const char *path, hd_error *err) {
  if (!out) return hd_error_set(err, HD_EINPUT, "hd_db_open: out is NULL");
  hd_db *db;
  int rc = db_alloc_open(&db, path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, err);
  if (rc) return rc;
  /* SQLite quietly falls back to read-only when the file is not writable; a run could then
   * not log anything, so say it now. */
  if (sqlite3_db_readonly(db->db, "main") == 1) {
    hd_error_set(err, HD_EIO, "%s: open: the database file is read-only (check its permissions)",
                 path);
    db_free(db);
    return HD_EIO;
  }
  /* WAL + NORMAL: see the top of this file for why a kill -9 still leaves whole batches. */
  if (sqlite3_exec(db->db, "PRAGMA journal_mode=WAL", NULL, NULL, NULL) != SQLITE_OK) {
    rc = sql_error(db, err, "set WAL mode");
  } else if (sqlite3_exec(db->db, "PRAGMA synchronous=NORMAL", NULL, NULL, NULL) != SQLITE_OK) {
    rc = sql_error(db, err, "set synchronous");
  } else if (sqlite3_exec(db->db, hd_schema_sql, NULL, NULL, NULL) != SQLITE_OK) {
    rc = sql_error(db, err, "apply schema");
  }
  if (!rc)
    rc = prepare(db, &db->ins_run,
                 "INSERT INTO runs (scene, seed, status, started, version) VALUES "
                 "(?1, ?2, 'running', strftime('%Y-%m-%dT%H:%M:%SZ','now'), ?3)",
                 err);
  if (!rc)
    rc = prepare(db, &db->ins_coll,
                 "INSERT INTO collisions (run, seq, t, kind, i, j, disk_i, disk_j, "
                 "theta_i, theta_j, f, de, vn, eps, e_tr, tb_i, tb_j) VALUES "
                 "(?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16, "
                 "?17)",
                 err);
  if (!rc)
    rc = prepare(db, &db->ins_sample,
                 "INSERT INTO samples (run, t, collisions, cpd, e_tr, e_rot, e_tr_dimer, "
                 "e_rot_dimer, e_tr_disk) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)",
                 err);
  if (!rc)
    rc = prepare(db, &db->ins_state,
                 "INSERT INTO states (run, label, t, cpd, body, kind, x, y, phi, vx, vy, "
                 "omega) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)",
                 err);
  if (!rc)
    rc = prepare(db, &db->ins_ckpt,
                 "INSERT INTO checkpoints (run, seq, t, blob) VALUES (?1, ?2, ?3, ?4)", err);
  if (!rc) rc = prepare(db, &db->del_ckpt, "DELETE FROM checkpoints WHERE run = ?1", err);
  if (rc) {
    db_free(db);
    return rc;
  }
  *out = db;
  return HD_OK;
}

int hd_db_open_readonly(hd_db **out, const char *path, hd_error *err) {
  if (!out) return hd_error_set(err, HD_EINPUT, "hd_db_open_readonly: out is NULL");
  hd_db *db;
  int rc = db_alloc_open(&db, path, SQLITE_OPEN_READONLY, err);
  if (rc) return rc;
  db->readonly = 1;
  /* Reading the schema now turns "not a database" into an error here, not later. */
  if (sqlite3_exec(db->db, "SELECT count(*) FROM sqlite_schema", NULL, NULL, NULL) != SQLITE_OK) {
    rc = sql_error(db, err, "open");
    db_free(db);
    return rc;
  }
  *out = db;
  return HD_OK;
}

int hd_db_close(hd_db *db, hd_error *err) {
  if (!db) return HD_OK;
  int rc = db->readonly ? HD_OK : hd_db_commit(db, err);
  finalize_all(db);
  if (sqlite3_close(db->db) != SQLITE_OK && !rc) {
    rc = sql_error(db, err, "close");
    sqlite3_close_v2(db->db); /* frees it once whatever holds it is gone */
  }
  free(db->path);
  free(db);
  return rc;
}

void hd_db_set_batch_rows(hd_db *db, long rows) {
  if (db) db->batch_rows = rows < 1 ? 1 : rows;
}

const char *hd_db_path(const hd_db *db) {
  return db ? db->path : "";
}

sqlite3 *hd_db_handle(hd_db *db) {
  return db ? db->db : NULL;
}

int hd_db_exec(hd_db *db, const char *sql, hd_error *err) {
  if (!db) return hd_error_set(err, HD_EIO, "database: not open");
  char *msg = NULL;
  if (sqlite3_exec(db->db, sql, NULL, NULL, &msg) != SQLITE_OK) {
    hd_error_set(err, HD_EIO, "%s: exec: %s", db->path, msg ? msg : sqlite3_errmsg(db->db));
    sqlite3_free(msg);
    /* A statement may have ended the batch's transaction (SQLite rolls back on some errors). */
    if (sqlite3_get_autocommit(db->db)) {
      db->in_tx = 0;
      db->pending = 0;
    }
    return HD_EIO;
  }
  if (db->in_tx && sqlite3_get_autocommit(db->db)) { /* the sql committed or rolled back */
    db->in_tx = 0;
    db->pending = 0;
  }
  return HD_OK;
}

/* ---------------------------------------------------------------------------------------- */
/* batches */

static int batch_begin(hd_db *db, hd_error *err) {
  if (db->in_tx) return HD_OK;
  /* IMMEDIATE takes the write lock now (waiting up to the busy timeout), not at the first
   * insert, so a busy database fails here with nothing written yet. */
  if (sqlite3_exec(db->db, "BEGIN IMMEDIATE", NULL, NULL, NULL) != SQLITE_OK)
    return batch_fail(db, NULL, err, "begin batch");
  db->in_tx = 1;
  db->pending = 0;
  return HD_OK;
}

int hd_db_commit(hd_db *db, hd_error *err) {
  if (!db) return hd_error_set(err, HD_EIO, "database: not open");
  if (!db->in_tx) return HD_OK;
  if (sqlite3_exec(db->db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK)
    return batch_fail(db, NULL, err, "commit batch");
  db->in_tx = 0;
  db->pending = 0;
  return HD_OK;
}

/* Steps a bound insert of the open batch; counts the row and commits a full batch. */
static int batch_step(hd_db *db, sqlite3_stmt *st, hd_error *err, const char *what) {
  if (sqlite3_step(st) != SQLITE_DONE) return batch_fail(db, st, err, what);
  sqlite3_reset(st);
  if (++db->pending >= db->batch_rows) return hd_db_commit(db, err);
  return HD_OK;
}

int hd_db_log_collision(hd_db *db, int64_t run, const hd_collision_row *r, hd_error *err) {
  int rc = check_db(db, err);
  if (rc || (rc = batch_begin(db, err))) return rc;
  sqlite3_stmt *st = db->ins_coll;
  sqlite3_bind_int64(st, 1, run);
  sqlite3_bind_int64(st, 2, r->seq);
  bind_real(st, 3, r->t);
  sqlite3_bind_text(st, 4, hd_coll_kind_name(r->kind), -1, SQLITE_STATIC);
  sqlite3_bind_int64(st, 5, r->i);
  sqlite3_bind_int64(st, 6, r->j);
  sqlite3_bind_int(st, 7, r->disk_i);
  sqlite3_bind_int(st, 8, r->disk_j);
  bind_real(st, 9, r->theta_i);
  bind_real(st, 10, r->theta_j);
  bind_real(st, 11, r->f);
  bind_real(st, 12, r->de);
  bind_real(st, 13, r->vn);
  int rod = r->kind == HD_CK_ROD_ROD;
  bind_real(st, 14, rod ? r->eps : NAN);
  bind_real(st, 15, rod ? r->e_tr : NAN);
  bind_real(st, 16, rod ? r->tb_i : NAN);
  bind_real(st, 17, rod ? r->tb_j : NAN);
  return batch_step(db, st, err, "insert collision");
}

int hd_db_log_sample(hd_db *db, int64_t run, const hd_sample_row *r, hd_error *err) {
  int rc = check_db(db, err);
  if (rc || (rc = batch_begin(db, err))) return rc;
  sqlite3_stmt *st = db->ins_sample;
  sqlite3_bind_int64(st, 1, run);
  bind_real(st, 2, r->t);
  sqlite3_bind_int64(st, 3, r->collisions);
  bind_real(st, 4, r->cpd);
  bind_real(st, 5, r->e_tr);
  bind_real(st, 6, r->e_rot);
  bind_real(st, 7, r->e_tr_dimer);
  bind_real(st, 8, r->e_rot_dimer);
  bind_real(st, 9, r->e_tr_disk);
  return batch_step(db, st, err, "insert sample");
}

int hd_db_log_state(hd_db *db, int64_t run, const char *label, const hd_state_rec *r,
                    hd_error *err) {
  int rc = check_db(db, err);
  if (rc) return rc;
  const char *kind = hd_db_kind_name(r->kind);
  if (!kind)
    return hd_error_set(err, HD_EINPUT, "%s: insert state: unknown body kind %d", db->path,
                        r->kind);
  if ((rc = batch_begin(db, err))) return rc;
  sqlite3_stmt *st = db->ins_state;
  sqlite3_bind_int64(st, 1, run);
  sqlite3_bind_text(st, 2, label, -1, SQLITE_TRANSIENT);
  bind_real(st, 3, r->t);
  bind_real(st, 4, r->cpd);
  sqlite3_bind_int64(st, 5, r->body);
  sqlite3_bind_text(st, 6, kind, -1, SQLITE_STATIC);
  bind_real(st, 7, r->x);
  bind_real(st, 8, r->y);
  bind_real(st, 9, r->phi);
  bind_real(st, 10, r->vx);
  bind_real(st, 11, r->vy);
  bind_real(st, 12, r->omega);
  return batch_step(db, st, err, "insert state");
}

/* ---------------------------------------------------------------------------------------- */
/* runs */

int hd_db_run_begin(hd_db *db, const char *scene_text, unsigned long long seed, const char *version,
                    int64_t *run, hd_error *err) {
  int rc = check_db(db, err);
  if (rc || (rc = hd_db_commit(db, err))) return rc;
  sqlite3_stmt *st = db->ins_run;
  sqlite3_bind_text(st, 1, scene_text ? scene_text : "", -1, SQLITE_TRANSIENT);
  /* runs.seed is a signed 64-bit integer: a seed >= 2^63 is stored as its two's complement
   * and read back exactly by hd_db_find_resumable. */
  sqlite3_bind_int64(st, 2, (sqlite3_int64)seed);
  sqlite3_bind_text(st, 3, version ? version : "", -1, SQLITE_TRANSIENT);
  if (sqlite3_step(st) != SQLITE_DONE) {
    rc = sql_error(db, err, "insert run");
    sqlite3_reset(st);
    return rc;
  }
  sqlite3_reset(st);
  if (run) *run = sqlite3_last_insert_rowid(db->db);
  return HD_OK;
}

/* Runs one UPDATE/DELETE statement sql with the run id bound to ?1 and the optional extra
 * parameters bound by `bind`, after committing the open batch. */
typedef void (*binder)(sqlite3_stmt *st, const void *ctx);

static int run_update(hd_db *db, int64_t run, const char *sql, binder bind, const void *ctx,
                      const char *what, int64_t *changes, hd_error *err) {
  int rc = check_db(db, err);
  if (rc || (rc = hd_db_commit(db, err))) return rc;
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(db->db, sql, -1, &st, NULL) != SQLITE_OK) return sql_error(db, err, what);
  sqlite3_bind_int64(st, 1, run);
  if (bind) bind(st, ctx);
  if (sqlite3_step(st) != SQLITE_DONE) rc = sql_error(db, err, what);
  if (changes) *changes = sqlite3_changes64(db->db);
  sqlite3_finalize(st);
  return rc;
}

typedef struct status_args {
  const char *status;
  int64_t events;
  double wall;
} status_args;

static void bind_status(sqlite3_stmt *st, const void *ctx) {
  const status_args *a = ctx;
  sqlite3_bind_text(st, 2, a->status, -1, SQLITE_STATIC);
  sqlite3_bind_int64(st, 3, a->events);
  bind_real(st, 4, a->wall);
}

int hd_db_run_status(hd_db *db, int64_t run, const char *status, int64_t events,
                     double wall_seconds, hd_error *err) {
  static const char *const ok[] = {"running", "done", "interrupted", "collapsed", "failed"};
  int known = 0;
  for (size_t k = 0; status && k < sizeof ok / sizeof ok[0]; k++) known |= !strcmp(status, ok[k]);
  if (!known)
    return hd_error_set(err, HD_EINPUT,
                        "%s: run status '%s' is not one of running, done, "
                        "interrupted, collapsed, failed",
                        db ? db->path : "database", status ? status : "(null)");
  status_args a = {status, events, wall_seconds};
  int64_t n = 0;
  int rc = run_update(db, run,
                      "UPDATE runs SET status = ?2, events = ?3, wall_seconds = coalesce(?4, 0), "
                      "finished = CASE WHEN ?2 = 'running' THEN NULL "
                      "ELSE strftime('%Y-%m-%dT%H:%M:%SZ','now') END WHERE id = ?1",
                      bind_status, &a, "set run status", &n, err);
  if (!rc && n == 0)
    return hd_error_set(err, HD_EINPUT, "%s: set run status: no run %lld", db->path,
                        (long long)run);
  return rc;
}

static void bind_message(sqlite3_stmt *st, const void *ctx) {
  if (ctx)
    sqlite3_bind_text(st, 2, ctx, -1, SQLITE_STATIC);
  else
    sqlite3_bind_null(st, 2);
}

int hd_db_run_message(hd_db *db, int64_t run, const char *msg, hd_error *err) {
  int64_t n = 0;
  int rc = run_update(db, run, "UPDATE runs SET message = ?2 WHERE id = ?1", bind_message, msg,
                      "set run message", &n, err);
  if (!rc && n == 0)
    return hd_error_set(err, HD_EINPUT, "%s: set run message: no run %lld", db->path,
                        (long long)run);
  return rc;
}

static void bind_box(sqlite3_stmt *st, const void *ctx) {
  const double *b = ctx;
  bind_real(st, 2, b[0]);
  bind_real(st, 3, b[1]);
}

int hd_db_run_box(hd_db *db, int64_t run, double lx, double ly, hd_error *err) {
  double b[2] = {lx, ly};
  int64_t n = 0;
  int rc = run_update(db, run, "UPDATE runs SET box_x = ?2, box_y = ?3 WHERE id = ?1", bind_box, b,
                      "set run box", &n, err);
  if (!rc && n == 0)
    return hd_error_set(err, HD_EINPUT, "%s: set run box: no run %lld", db->path, (long long)run);
  return rc;
}

int hd_db_build_indexes(hd_db *db, hd_error *err) {
  int rc = check_db(db, err);
  if (rc || (rc = hd_db_commit(db, err))) return rc;
  static const char sql[] =
      "CREATE INDEX IF NOT EXISTS collisions_run_seq ON collisions(run, seq);"
      "CREATE INDEX IF NOT EXISTS collisions_run_kind ON collisions(run, kind);"
      "CREATE INDEX IF NOT EXISTS samples_run_t ON samples(run, t);"
      "CREATE INDEX IF NOT EXISTS states_run_label_t ON states(run, label, t);"
      "CREATE INDEX IF NOT EXISTS checkpoints_run ON checkpoints(run);";
  if (sqlite3_exec(db->db, sql, NULL, NULL, NULL) != SQLITE_OK)
    return sql_error(db, err, "build indexes");
  return HD_OK;
}

/* ---------------------------------------------------------------------------------------- */
/* checkpoints and resume */

int hd_db_checkpoint_save(hd_db *db, int64_t run, int64_t seq, double t, const void *blob, size_t n,
                          hd_error *err) {
  int rc = check_db(db, err);
  if (rc || (rc = batch_begin(db, err))) return rc;
  sqlite3_stmt *st = db->del_ckpt;
  sqlite3_bind_int64(st, 1, run);
  if (sqlite3_step(st) != SQLITE_DONE) return batch_fail(db, st, err, "delete old checkpoint");
  sqlite3_reset(st);
  st = db->ins_ckpt;
  sqlite3_bind_int64(st, 1, run);
  sqlite3_bind_int64(st, 2, seq);
  bind_real(st, 3, t);
  /* An empty blob must still be a blob (NOT NULL): zeroblob(0). */
  if (n == 0 || !blob)
    sqlite3_bind_zeroblob(st, 4, 0);
  else
    sqlite3_bind_blob64(st, 4, blob, (sqlite3_uint64)n, SQLITE_STATIC);
  if (sqlite3_step(st) != SQLITE_DONE) return batch_fail(db, st, err, "insert checkpoint");
  sqlite3_reset(st);
  sqlite3_clear_bindings(st); /* do not keep a pointer to the caller's blob */
  return hd_db_commit(db, err);
}

int hd_db_checkpoint_load(hd_db *db, int64_t run, void **blob, size_t *n, int64_t *seq, double *t,
                          hd_error *err) {
  if (!db) return hd_error_set(err, HD_EIO, "database: not open");
  *blob = NULL;
  *n = 0;
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(db->db,
                         "SELECT seq, t, blob FROM checkpoints WHERE run = ?1 "
                         "ORDER BY seq DESC, rowid DESC LIMIT 1",
                         -1, &st, NULL) != SQLITE_OK)
    return sql_error(db, err, "load checkpoint");
  sqlite3_bind_int64(st, 1, run);
  int rc = HD_OK, s = sqlite3_step(st);
  if (s == SQLITE_ROW) {
    const void *b = sqlite3_column_blob(st, 2);
    int len = sqlite3_column_bytes(st, 2);
    void *copy = malloc(len > 0 ? (size_t)len : 1);
    if (!copy) {
      rc = hd_error_set(err, HD_ENOMEM, "%s: load checkpoint: out of memory", db->path);
    } else {
      if (len > 0) memcpy(copy, b, (size_t)len);
      *blob = copy;
      *n = (size_t)len;
      if (seq) *seq = sqlite3_column_int64(st, 0);
      if (t) *t = sqlite3_column_double(st, 1);
    }
  } else if (s == SQLITE_DONE) {
    rc = hd_error_set(err, HD_EINPUT, "%s: run %lld has no checkpoint", db->path, (long long)run);
  } else {
    rc = sql_error(db, err, "load checkpoint");
  }
  sqlite3_finalize(st);
  return rc;
}

typedef struct trunc_args {
  int64_t seq;
  double t;
} trunc_args;

static void bind_seq(sqlite3_stmt *st, const void *ctx) {
  sqlite3_bind_int64(st, 2, ((const trunc_args *)ctx)->seq);
}

static void bind_t(sqlite3_stmt *st, const void *ctx) {
  sqlite3_bind_double(st, 2, ((const trunc_args *)ctx)->t);
}

int hd_db_truncate_after(hd_db *db, int64_t run, int64_t seq, double t, hd_error *err) {
  trunc_args a = {seq, t};
  int rc = check_db(db, err);
  if (rc || (rc = hd_db_commit(db, err))) return rc;
  /* One transaction: either every table is truncated or none. */
  if (sqlite3_exec(db->db, "BEGIN IMMEDIATE", NULL, NULL, NULL) != SQLITE_OK)
    return sql_error(db, err, "truncate: begin");
  rc = run_update(db, run, "DELETE FROM collisions WHERE run = ?1 AND seq > ?2", bind_seq, &a,
                  "truncate collisions", NULL, err);
  if (!rc)
    rc = run_update(db, run, "DELETE FROM samples WHERE run = ?1 AND t > ?2", bind_t, &a,
                    "truncate samples", NULL, err);
  if (!rc)
    rc = run_update(db, run,
                    "DELETE FROM states WHERE run = ?1 AND t > ?2 "
                    "AND label <> 'checkpoint'",
                    bind_t, &a, "truncate states", NULL, err);
  if (!rc && sqlite3_exec(db->db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK)
    rc = sql_error(db, err, "truncate: commit");
  if (rc) rollback(db);
  return rc;
}

int hd_db_find_resumable(hd_db *db, int64_t want_run, int64_t *run, char **scene_text,
                         unsigned long long *seed, hd_error *err) {
  if (!db) return hd_error_set(err, HD_EIO, "database: not open");
  if (scene_text) *scene_text = NULL;
  sqlite3_stmt *st = NULL;
  const char *sql = want_run > 0
                        ? "SELECT id, status, scene, seed FROM runs WHERE id = ?1"
                        : "SELECT id, status, scene, seed FROM runs "
                          "WHERE status IN ('running','interrupted','failed') ORDER BY id DESC "
                          "LIMIT 1";
  if (sqlite3_prepare_v2(db->db, sql, -1, &st, NULL) != SQLITE_OK)
    return sql_error(db, err, "find resumable run");
  if (want_run > 0) sqlite3_bind_int64(st, 1, want_run);
  int rc = HD_OK, s = sqlite3_step(st);
  if (s == SQLITE_ROW) {
    const char *status = (const char *)sqlite3_column_text(st, 1);
    if (!status ||
        (strcmp(status, "running") && strcmp(status, "interrupted") && strcmp(status, "failed"))) {
      rc = hd_error_set(err, HD_EINPUT,
                        "%s: run %lld is %s: only an interrupted, failed (disk "
                        "full, I/O) or killed ('running') run can be resumed; a collapsed run "
                        "keeps its state at the collapse in `states` and `checkpoints`",
                        db->path, (long long)want_run, status ? status : "(no status)");
    } else {
      const char *scene = (const char *)sqlite3_column_text(st, 2);
      if (scene_text) {
        *scene_text = strdup(scene ? scene : "");
        if (!*scene_text) rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", db->path);
      }
      if (!rc) {
        if (run) *run = sqlite3_column_int64(st, 0);
        if (seed) *seed = (unsigned long long)sqlite3_column_int64(st, 3);
      }
    }
  } else if (s == SQLITE_DONE) {
    if (want_run > 0)
      rc = hd_error_set(err, HD_EINPUT, "%s: there is no run %lld", db->path, (long long)want_run);
    else
      rc = hd_error_set(err, HD_EINPUT, "%s: no interrupted run to resume", db->path);
  } else {
    rc = sql_error(db, err, "find resumable run");
  }
  sqlite3_finalize(st);
  return rc;
}
