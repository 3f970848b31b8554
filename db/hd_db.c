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
#include "hd_homog.h"
#include "hd_walck.h"

#include <errno.h>
#include <math.h>
#include <sqlite3.h>
#include <stdlib.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

extern const char hd_schema_sql[];

#define HD_DB_NBUF 8 /* buffers in the ring between the producer and the writer thread */

struct hd_db {
  sqlite3 *db;
  char *path;                 /* as given, for messages */
  int readonly;               /* opened by hd_db_open_readonly */
  long batch_rows;            /* rows per batch transaction */
  long pending;               /* rows in the open batch */
  int in_tx;                  /* a batch transaction is open */
  sqlite3_stmt *ins_run;      /* INSERT INTO runs */
  sqlite3_stmt *ins_coll;     /* INSERT INTO collisions */
  sqlite3_stmt *ins_sample;   /* INSERT INTO sample_rows */
  sqlite3_stmt *ins_spsample; /* INSERT INTO sample_species */
  sqlite3_stmt *ins_state;    /* INSERT INTO states */
  sqlite3_stmt *ins_ckpt;     /* INSERT INTO checkpoints */
  sqlite3_stmt *del_ckpt;     /* DELETE older checkpoints of a run */
  sqlite3_stmt *ins_coll_k;   /* INSERT INTO collisions, HD_DB_GROUP rows at once */
  sqlite3_stmt *ins_coll2_k;  /* the same without the rod columns (left NULL): 2D collisions */
  /* The writer thread (see "asynchronous rows" below). */
  int writer_on; /* the thread has been started */
  pthread_t writer;
  pthread_mutex_t mu;
  pthread_cond_t cv;
  struct rec *buf[HD_DB_NBUF]; /* ring of row buffers: the queued ones, then the fill one */
  int nrows[HD_DB_NBUF];       /* rows in each queued buffer */
  int qhead;                   /* the oldest queued buffer (the one the writer writes) */
  int nq;                      /* buffers queued for the writer, the one it writes included */
  int fill;                    /* the buffer the producer fills: (qhead + nq) % HD_DB_NBUF */
  int nfill;                   /* rows in it */
  hd_walck *walck; /* the log checkpointer, started with the writer (NULL if it could not be) */
  int quit;        /* the writer must end */
  int werr;        /* first error of the writer (hd_status), HD_OK if none */
  hd_error werror; /* its message */
};

/* A row waiting for the writer thread. */
typedef struct rec {
  int type; /* REC_COLLISION, REC_SAMPLE, REC_STATE, REC_SPECIES_SAMPLE */
  int64_t run;
  const char *label; /* states: a string literal ('initial', ...) */
  union {
    hd_collision_row c;
    hd_sample_row s;
    hd_state_rec st;
    hd_species_sample sp;
  } u;
} rec;
enum { REC_COLLISION, REC_SAMPLE, REC_STATE, REC_SPECIES_SAMPLE };

static int drain(hd_db *db, hd_error *err);
static void writer_stop(hd_db *db);
#define HD_DB_QCAP 4096 /* rows per buffer handed to the writer */
#define HD_DB_GROUP 32  /* collisions per multi-row INSERT */

/* The columns of `collisions` (HD_COLLISION_COLUMNS, hd_db.h) as data. */
static const struct coll_col {
  const char *name, *sqltype, *doc;
  int scope, since;
} coll_cols[] = {
#define COLL_COL(name, ctype, bind, sqltype, scope, since, doc) {#name, sqltype, doc, scope, since},
    HD_COLLISION_COLUMNS(COLL_COL)
#undef COLL_COL
};
#define COLL_NCOL (sizeof coll_cols / sizeof *coll_cols)

/* ---------------------------------------------------------------------------------------- */
/* errors */

int hd_db_status_of(int sqlite_code) {
  int primary = sqlite_code & 0xff;
  if (primary == SQLITE_CORRUPT || primary == SQLITE_NOTADB) return HD_EINPUT;
  return primary == SQLITE_NOMEM ? HD_ENOMEM : HD_EIO;
}

/* Sets err to "path: what: sqlite's message" (the message of the last failed call), HD_EIO or
 * as hd_db_status_of says (a malformed file is bad input). */
static int sql_error(hd_db *db, hd_error *err, const char *what) {
  return hd_error_set(err, hd_db_status_of(sqlite3_errcode(db->db)), "%s: %s: %s", db->path, what,
                      sqlite3_errmsg(db->db));
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

/* Prepares "INSERT INTO collisions (run, ...) VALUES (?,...),..." for `rows` rows of every
 * column of HD_COLLISION_COLUMNS, or (twod) of those but the rod-rod ones (left NULL), the
 * parameters numbered in order (bind_collision). */
static int prepare_coll(hd_db *db, sqlite3_stmt **st, int rows, int twod, hd_error *err) {
  sqlite3_str *q = sqlite3_str_new(db->db);
  int ncol = 1;
  sqlite3_str_appendall(q, "INSERT INTO collisions (run");
  for (size_t c = 0; c < COLL_NCOL; c++)
    if (!twod || coll_cols[c].scope != HD_COLL_ROD) {
      sqlite3_str_appendf(q, ", %s", coll_cols[c].name);
      ncol++;
    }
  sqlite3_str_appendall(q, ") VALUES ");
  for (int k = 0; k < rows; k++)
    for (int c = 0; c < ncol; c++)
      sqlite3_str_appendall(q, c ? (c == ncol - 1 ? ",?)" : ",?") : (k ? ",(?" : "(?"));
  char *sql = sqlite3_str_finish(q);
  if (!sql) return hd_error_set(err, HD_ENOMEM, "%s: out of memory", db->path);
  int rc = prepare(db, st, sql, err);
  sqlite3_free(sql);
  return rc;
}

static void finalize_all(hd_db *db) {
  sqlite3_stmt **sts[] = {&db->ins_run,    &db->ins_coll,    &db->ins_sample,
                          &db->ins_state,  &db->ins_ckpt,    &db->del_ckpt,
                          &db->ins_coll_k, &db->ins_coll2_k, &db->ins_spsample};
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

/* Allocates the handle for path, not yet open. */
static int db_alloc(hd_db **out, const char *path, hd_error *err) {
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
  *out = db;
  return HD_OK;
}

/* The error of a connection h to path that failed at `what`: HD_EINPUT when the file is not an
 * SQLite database ("not a haff database": bad input, exit 2), else HD_EIO with SQLite's
 * message; HD_ENOMEM when h could not even be made. */
static int open_error(sqlite3 *h, const char *path, const char *what, hd_error *err) {
  if (!h) return hd_error_set(err, HD_ENOMEM, "%s: open: out of memory", path);
  if ((sqlite3_errcode(h) & 0xff) == SQLITE_NOTADB)
    return hd_error_set(err, HD_EINPUT, "%s: not a haff database (%s)", path, sqlite3_errmsg(h));
  return hd_error_set(err, hd_db_status_of(sqlite3_errcode(h)), "%s: %s: %s", path, what,
                      sqlite3_errmsg(h));
}

static int tables_missing(sqlite3 *h, const char *const *tables, const char **missing);

/* The columns that later schema versions added to tables that older files already have
 * (CREATE TABLE IF NOT EXISTS cannot add them): schema_apply adds each one that is missing
 * with ALTER TABLE, and not_haffs does not ask an older haff file for them.  Tables and views
 * that are new in a version need no entry here: db/schema.sql creates them IF NOT EXISTS. */
static const struct {
  const char *table, *column, *decl;
} added_columns[] = {
    {"runs", "cpd", "REAL"},          /* 2: the cpd reached, updated at each commit */
    {"samples", "flow_frac", "REAL"}, /* 2: the state measures (docs/analysis.md) */
    {"samples", "flow_chaos", "REAL"},
    {"samples", "count_var", "REAL"},
    {"samples", "s_rho", "REAL"},
    {"samples", "s_perp", "REAL"},
    {"samples", "s_par", "REAL"},
    {"runs", "hcs_cpd_start", "REAL"}, /* 2: the run's HCS window (hd_db_run_hcs) */
    {"runs", "hcs_cpd_end", "REAL"},
    {"runs", "hcs_end", "TEXT"},
    {"runs", "hcs_s_perp", "REAL"},
    {"runs", "hcs_flow_excess", "REAL"},
    {"runs", "git_commit", "TEXT"}, /* 4: how the run was made (hd_db_run_provenance) */
    {"runs", "git_dirty", "INTEGER"},
    {"runs", "compiler", "TEXT"},
    {"runs", "cflags", "TEXT"},
    {"runs", "command", "TEXT"},
    {"runs", "sweep_point", "TEXT"},
    {"states", "species", "INTEGER"}, /* 4: the body's species.idx (NULL for rods) */
};

/* The k-th column that a later schema version added to a table older files have: those of
 * added_columns, then the collisions columns of HD_COLLISION_COLUMNS with a `since`.  Sets
 * *table, *column and *decl and returns 1; returns 0 past the last. */
static int added_at(size_t k, const char **table, const char **column, const char **decl) {
  size_t na = sizeof added_columns / sizeof *added_columns;
  if (k < na) {
    *table = added_columns[k].table, *column = added_columns[k].column;
    *decl = added_columns[k].decl;
    return 1;
  }
  for (size_t c = 0; c < COLL_NCOL; c++)
    if (coll_cols[c].since > 0 && k == na++) {
      *table = "collisions", *column = coll_cols[c].name, *decl = coll_cols[c].sqltype;
      return 1;
    }
  return 0;
}

char *hd_db_collisions_create_sql(void) {
  sqlite3_str *q = sqlite3_str_new(NULL);
  sqlite3_str_appendall(q, "CREATE TABLE IF NOT EXISTS collisions (\n"
                           "  run     INTEGER NOT NULL REFERENCES runs(id),\n");
  for (size_t c = 0; c < COLL_NCOL; c++) {
    const struct coll_col *k = &coll_cols[c];
    int len = sqlite3_str_length(q);
    sqlite3_str_appendf(q, "  %-7s %s%s", k->name, k->sqltype, c + 1 < COLL_NCOL ? "," : "");
    if (*k->doc) { /* the comments from the 31st character of the line (db/schema.sql) */
      int w = sqlite3_str_length(q) - len;
      sqlite3_str_appendchar(q, w < 29 ? 30 - w : 1, ' ');
      sqlite3_str_appendf(q, "-- %s", k->doc);
    }
    sqlite3_str_appendchar(q, 1, '\n');
  }
  sqlite3_str_appendall(q, ");\n");
  char *sql = sqlite3_str_finish(q), *out = sql ? strdup(sql) : NULL;
  sqlite3_free(sql);
  return out;
}

/* Whether table.column is one that a later schema version added (added_at: an older haff file
 * may lack it). */
static int added_column(const char *table, const char *column) {
  const char *t, *c, *d;
  for (size_t k = 0; added_at(k, &t, &c, &d); k++)
    if (!strcmp(t, table) && !strcmp(c, column)) return 1;
  return 0;
}

/* Whether haff may write its tables into the database open on h: 0 when it has no table (a new
 * or empty file), or when it has one of haff's tables at least and each of haff's tables that
 * it has holds every column of haff's (db/schema.sql, read from a schema applied in memory); 1
 * with why (size bytes) set when not: a file of another program, or a table of haff's name
 * that is not haff's (haff added its seven tables to any SQLite file, and left them behind
 * when a `runs` table of another shape then failed); -1 when the schema cannot be read (not a
 * database: SQLite's error is on h).  Nothing is written. */
static int not_haffs(sqlite3 *h, char *why, size_t size) {
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(h,
                         "SELECT name FROM sqlite_schema WHERE type = 'table' AND name NOT LIKE "
                         "'sqlite\\_%' ESCAPE '\\' ORDER BY name",
                         -1, &st, NULL) != SQLITE_OK)
    return -1;
  sqlite3 *mem = NULL; /* haff's own tables, in memory */
  sqlite3_stmt *cols = NULL, *has = NULL;
  int rc = 0, ours = 0, others = 0, s;
  char other[64] = "";
  if (sqlite3_open_v2(":memory:", &mem, SQLITE_OPEN_READWRITE, NULL) != SQLITE_OK ||
      sqlite3_exec(mem, hd_schema_sql, NULL, NULL, NULL) != SQLITE_OK ||
      sqlite3_prepare_v2(mem, "SELECT p.name FROM pragma_table_info(?1) p", -1, &cols, NULL) !=
          SQLITE_OK ||
      sqlite3_prepare_v2(h, "SELECT count(*) FROM pragma_table_info(?1) WHERE name = ?2", -1, &has,
                         NULL) != SQLITE_OK) {
    rc = 1;
    snprintf(why, size, "cannot read haff's own schema");
  }
  while (!rc && (s = sqlite3_step(st)) == SQLITE_ROW) {
    const char *table = (const char *)sqlite3_column_text(st, 0);
    sqlite3_bind_text(cols, 1, table, -1, SQLITE_TRANSIENT);
    int ncol = 0;
    while (!rc && sqlite3_step(cols) == SQLITE_ROW) {
      ncol++;
      const char *col = (const char *)sqlite3_column_text(cols, 0);
      sqlite3_bind_text(has, 1, table, -1, SQLITE_TRANSIENT);
      sqlite3_bind_text(has, 2, col, -1, SQLITE_TRANSIENT);
      if (sqlite3_step(has) != SQLITE_ROW) {
        rc = -1;
      } else if (sqlite3_column_int(has, 0) == 0 && !added_column(table, col)) {
        rc = 1;
        snprintf(why, size, "its table %.64s has no column %.64s: it is not haff's", table, col);
      }
      sqlite3_reset(has);
    }
    sqlite3_reset(cols);
    if (ncol)
      ours++;
    else if (!others++)
      snprintf(other, sizeof other, "%.60s", table);
  }
  if (!rc && s != SQLITE_DONE) rc = -1;
  if (!rc && others && !ours) {
    rc = 1;
    snprintf(why, size, "it holds tables of another program (%s%s) and none of haff's", other,
             others > 1 ? ", ..." : "");
  }
  sqlite3_finalize(st);
  sqlite3_finalize(cols);
  sqlite3_finalize(has);
  sqlite3_close(mem);
  return rc;
}

/* The integer that sql (one row, one column) gives, or -1 on error. */
static int query_int(sqlite3 *h, const char *sql) {
  sqlite3_stmt *st;
  if (sqlite3_prepare_v2(h, sql, -1, &st, NULL) != SQLITE_OK) return -1;
  int v = sqlite3_step(st) == SQLITE_ROW ? sqlite3_column_int(st, 0) : -1;
  sqlite3_finalize(st);
  return v;
}

/* Whether the table exists and lacks the column: 1, 0, or -1 on error (a fixed statement,
 * the names bound). */
static int column_missing(sqlite3 *h, const char *table, const char *column) {
  sqlite3_stmt *st;
  if (sqlite3_prepare_v2(h,
                         "SELECT (SELECT count(*) FROM sqlite_schema WHERE type = 'table' AND "
                         "name = ?1) AND NOT (SELECT count(*) FROM pragma_table_info(?1) WHERE "
                         "name = ?2)",
                         -1, &st, NULL) != SQLITE_OK)
    return -1;
  sqlite3_bind_text(st, 1, table, -1, SQLITE_STATIC);
  sqlite3_bind_text(st, 2, column, -1, SQLITE_STATIC);
  int v = sqlite3_step(st) == SQLITE_ROW ? sqlite3_column_int(st, 0) : -1;
  sqlite3_finalize(st);
  return v;
}

/* 1 when schema src (a name of this program: "main", "s") has a table (c NULL) or a column c of
 * table t, 0 when not, -1 on failure. */
static int schema_has(sqlite3 *h, const char *src, const char *t, const char *c) {
  sqlite3_stmt *st;
  char sql[160];
  if (c)
    snprintf(sql, sizeof sql, "SELECT count(*) FROM pragma_table_info(?1, '%s') WHERE name = ?2",
             src);
  else
    snprintf(sql, sizeof sql,
             "SELECT count(*) FROM \"%s\".sqlite_schema WHERE type = 'table' AND name = ?1", src);
  if (sqlite3_prepare_v2(h, sql, -1, &st, NULL) != SQLITE_OK) return -1;
  sqlite3_bind_text(st, 1, t, -1, SQLITE_STATIC);
  if (c) sqlite3_bind_text(st, 2, c, -1, SQLITE_STATIC);
  int v = sqlite3_step(st) == SQLITE_ROW ? sqlite3_column_int(st, 0) > 0 : -1;
  sqlite3_finalize(st);
  return v;
}

/* Runs the statement made of q (sqlite3_str, finished and freed here) on h. */
static int exec_str(sqlite3 *h, sqlite3_str *q, const char *path, hd_error *err) {
  char *sql = sqlite3_str_finish(q);
  if (!sql) return hd_error_set(err, HD_ENOMEM, "%s: out of memory", path);
  int ok = sqlite3_exec(h, sql, NULL, NULL, NULL) == SQLITE_OK;
  sqlite3_free(sql);
  if (ok) return HD_OK;
  return hd_error_set(err, hd_db_status_of(sqlite3_errcode(h)),
                      "%s: convert the samples table of an older schema version: %s", path,
                      sqlite3_errmsg(h));
}

int hd_db_samples_convert(sqlite3 *h, const char *src, const char *run_off, const char *path,
                          hd_error *err) {
  int old = schema_has(h, src, "samples", NULL);
  if (old <= 0) /* version 5 (samples is the view), or no samples at all */
    return old < 0 ? hd_error_set(err, hd_db_status_of(sqlite3_errcode(h)),
                                  "%s: read the schema: %s", path, sqlite3_errmsg(h))
                   : HD_OK;
  /* the columns of sample_rows, each from the old table when it has it (else NULL: a file of
   * version 0 read by merge lacks the state measures) */
  sqlite3_stmt *st;
  if (sqlite3_prepare_v2(h,
                         "SELECT name FROM pragma_table_info('sample_rows', 'main') ORDER BY cid",
                         -1, &st, NULL) != SQLITE_OK)
    return hd_error_set(err, HD_EIO, "%s: read the schema: %s", path, sqlite3_errmsg(h));
  sqlite3_str *cols = sqlite3_str_new(h), *vals = sqlite3_str_new(h);
  int rc = HD_OK, k = 0;
  while (!rc && sqlite3_step(st) == SQLITE_ROW) {
    const char *c = (const char *)sqlite3_column_text(st, 0); /* haff's own names */
    int has = schema_has(h, src, "samples", c);
    if (has < 0) rc = hd_error_set(err, HD_EIO, "%s: read the schema: %s", path, sqlite3_errmsg(h));
    sqlite3_str_appendf(cols, "%s\"%w\"", k ? ", " : "", c); /* %w: quoted as a name */
    if (!strcmp(c, "run"))
      sqlite3_str_appendf(vals, "%sold.run + %s", k ? ", " : "", run_off);
    else
      sqlite3_str_appendf(vals, has > 0 ? "%sold.\"%w\"" : "%sNULL", k ? ", " : "", c);
    k++;
  }
  sqlite3_finalize(st);
  char *cs = sqlite3_str_finish(cols), *vs = sqlite3_str_finish(vals);
  if (!rc && (!cs || !vs)) rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", path);
  if (!rc) {
    sqlite3_str *q = sqlite3_str_new(h);
    sqlite3_str_appendf(q,
                        "INSERT INTO main.sample_rows (%s) SELECT %s FROM \"%s\".samples AS old "
                        "ORDER BY old.rowid",
                        cs, vs, src);
    rc = exec_str(h, q, path, err);
  }
  sqlite3_free(cs);
  sqlite3_free(vs);
  /* the per-species columns, where sample_species has no row of that species at that t (files
   * before version 3 have no sample_species; from 3 on it has every species) */
  int pk = 1, ss = rc ? 0 : schema_has(h, src, "sample_species", NULL);
  static const char *const pcols[] = {"e_tr_dimer", "e_rot_dimer", "e_tr_disk"};
  for (int j = 0; j < 3 && !rc; j++) pk &= schema_has(h, src, "samples", pcols[j]) == 1;
  if (!rc && ss < 0)
    rc = hd_error_set(err, HD_EIO, "%s: read the schema: %s", path, sqlite3_errmsg(h));
  if (!rc && pk) {
    sqlite3_str *q = sqlite3_str_new(h);
    for (int sp = 0; sp < 2; sp++) {
      sqlite3_str_appendf(q,
                          "%s SELECT old.run + %s, old.t, %d, %s FROM \"%s\".samples AS old "
                          "WHERE %s",
                          sp ? " UNION ALL"
                             : "INSERT INTO main.sample_species (run, t, species, "
                               "e_tr, e_rot)",
                          run_off, sp, sp ? "old.e_tr_disk, 0" : "old.e_tr_dimer, old.e_rot_dimer",
                          src,
                          sp ? "old.e_tr_disk IS NOT NULL"
                             : "old.e_tr_dimer IS NOT NULL AND old.e_rot_dimer IS NOT NULL");
      if (ss)
        sqlite3_str_appendf(q,
                            " AND NOT EXISTS (SELECT 1 FROM \"%s\".sample_species AS x WHERE "
                            "x.run = old.run AND x.t = old.t AND x.species = %d)",
                            src, sp);
    }
    sqlite3_str_appendall(q, " ORDER BY 1, 2, 3");
    rc = exec_str(h, q, path, err);
  }
  return rc;
}

/* The views that a writer remakes from db/schema.sql (the tables they read never change with
 * them), in one statement. */
static const char drop_views[] = "DROP VIEW IF EXISTS params; DROP VIEW IF EXISTS run_summary; "
                                 "DROP VIEW IF EXISTS run_species;";

/* Whether the file open on h holds the views of drop_views as db/schema.sql defines them
 * (compared with the schema applied in memory by their text, which SQLite stores as written):
 * 0 yes, 1 when one differs or is missing (a file written by a build whose view differed, such
 * as run_summary's NULL area_fraction of a one-species run given a box), -1
 * when a schema cannot be read.  Nothing is written. */
static int views_stale(sqlite3 *h) {
  static const char q[] = "SELECT name, sql FROM sqlite_schema WHERE type = 'view' AND name IN "
                          "('params', 'run_summary', 'run_species') ORDER BY name";
  sqlite3 *mem = NULL;
  sqlite3_stmt *a = NULL, *b = NULL;
  int rc = -1;
  if (sqlite3_open_v2(":memory:", &mem, SQLITE_OPEN_READWRITE, NULL) == SQLITE_OK &&
      sqlite3_exec(mem, hd_schema_sql, NULL, NULL, NULL) == SQLITE_OK &&
      sqlite3_prepare_v2(mem, q, -1, &a, NULL) == SQLITE_OK &&
      sqlite3_prepare_v2(h, q, -1, &b, NULL) == SQLITE_OK) {
    for (rc = 0; !rc;) {
      int sa = sqlite3_step(a), sb = sqlite3_step(b);
      if (sa == SQLITE_DONE && sb == SQLITE_DONE) break; /* the same views */
      if (sa != SQLITE_ROW || sb != SQLITE_ROW) {        /* one lacks a view, or an error */
        int ok = (sa == SQLITE_ROW || sa == SQLITE_DONE) && (sb == SQLITE_ROW || sb == SQLITE_DONE);
        rc = ok ? 1 : -1;
        break;
      }
      for (int c = 0; c < 2 && !rc; c++) {
        const char *x = (const char *)sqlite3_column_text(a, c);
        const char *y = (const char *)sqlite3_column_text(b, c);
        rc = !x || !y || strcmp(x, y) ? 1 : 0;
      }
    }
  }
  sqlite3_finalize(a);
  sqlite3_finalize(b);
  sqlite3_close(mem);
  return rc;
}

/* Applies db/schema.sql (every statement IF NOT EXISTS) and brings a file of an older schema
 * version (PRAGMA user_version below HD_DB_SCHEMA_VERSION; 0 for files made before it was
 * kept) up to this one, under the write lock so that two processes upgrading at once end the
 * same: the columns of added_at that its tables lack are added (old rows read NULL), the
 * views are dropped to be made again as this version defines them, and the version is
 * stamped; so is a file of this version that lacks some of them (made by an earlier build of
 * it, before runs.hcs_* were added).  A file of this version whose views params, run_summary,
 * run_species differ from db/schema.sql's (views_stale: an earlier build's, e.g. before
 * run_summary's area_fraction of one species in a box given was fixed) gets them made again.
 * Additive up to version 4; version 5 replaces the table samples by sample_rows, sample_species
 * rows and the view samples of the same columns (hd_db_samples_convert), so that queries of samples
 * read the file as before (a haff of version 4 or older refuses it).  A file of a newer version is
 * refused (HD_EINPUT): this haff does not know its columns. */
static int schema_apply(hd_db *db, hd_error *err) {
  int v = query_int(db->db, "PRAGMA user_version");
  if (v < 0) return sql_error(db, err, "read the schema version");
  if (v > HD_DB_SCHEMA_VERSION)
    return hd_error_set(err, HD_EINPUT,
                        "%s: schema version %d is newer than this haff's (%d): use a newer haff",
                        db->path, v, HD_DB_SCHEMA_VERSION);
  int missing = 0; /* a file of this version from a build before the last added columns */
  const char *table, *column, *decl;
  for (size_t k = 0; v == HD_DB_SCHEMA_VERSION && added_at(k, &table, &column, &decl); k++) {
    int m = column_missing(db->db, table, column);
    if (m < 0) return sql_error(db, err, "read the schema");
    missing |= m;
  }
  if (v == HD_DB_SCHEMA_VERSION && !missing) {
    if (sqlite3_exec(db->db, hd_schema_sql, NULL, NULL, NULL) != SQLITE_OK)
      return sql_error(db, err, "apply schema");
    /* a view of an earlier build of this version: made again, under the write lock */
    int stale = views_stale(db->db);
    if (stale < 0) return sql_error(db, err, "read the schema");
    if (stale && (sqlite3_exec(db->db, "BEGIN IMMEDIATE", NULL, NULL, NULL) != SQLITE_OK ||
                  sqlite3_exec(db->db, drop_views, NULL, NULL, NULL) != SQLITE_OK ||
                  sqlite3_exec(db->db, hd_schema_sql, NULL, NULL, NULL) != SQLITE_OK ||
                  sqlite3_exec(db->db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK)) {
      int rc = sql_error(db, err, "remake the views");
      sqlite3_exec(db->db, "ROLLBACK", NULL, NULL, NULL);
      return rc;
    }
    return HD_OK;
  }
  if (sqlite3_exec(db->db, "BEGIN IMMEDIATE", NULL, NULL, NULL) != SQLITE_OK)
    return sql_error(db, err, "upgrade the schema");
  int rc = HD_OK;
  for (size_t k = 0; !rc && added_at(k, &table, &column, &decl); k++) {
    int m = column_missing(db->db, table, column);
    char sql[256];
    /* names of added_at, this program's constants (a name cannot be a bound parameter) */
    snprintf(sql, sizeof sql, "ALTER TABLE %s ADD COLUMN %s %s", table, column, decl);
    if (m < 0 || (m && sqlite3_exec(db->db, sql, NULL, NULL, NULL) != SQLITE_OK))
      rc = sql_error(db, err, "upgrade the schema");
  }
  char set[64];
  snprintf(set, sizeof set, "PRAGMA user_version = %d", HD_DB_SCHEMA_VERSION);
  if (!rc && (sqlite3_exec(db->db, drop_views, NULL, NULL, NULL) != SQLITE_OK ||
              sqlite3_exec(db->db, hd_schema_sql, NULL, NULL, NULL) != SQLITE_OK))
    rc = sql_error(db, err, "upgrade the schema");
  /* 5: the table samples of an older file becomes sample_rows and sample_species rows, then
   * the view samples (the schema again: the view was not made beside the table) */
  int old = rc ? 0 : schema_has(db->db, "main", "samples", NULL);
  if (old < 0) rc = sql_error(db, err, "upgrade the schema");
  if (!rc && old && (rc = hd_db_samples_convert(db->db, "main", "0", db->path, err)) == HD_OK &&
      (sqlite3_exec(db->db, "DROP TABLE main.samples", NULL, NULL, NULL) != SQLITE_OK ||
       sqlite3_exec(db->db, hd_schema_sql, NULL, NULL, NULL) != SQLITE_OK))
    rc = sql_error(db, err, "upgrade the schema");
  if (!rc && sqlite3_exec(db->db, set, NULL, NULL, NULL) != SQLITE_OK)
    rc = sql_error(db, err, "upgrade the schema");
  if (!rc && sqlite3_exec(db->db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK)
    rc = sql_error(db, err, "upgrade the schema");
  if (rc) sqlite3_exec(db->db, "ROLLBACK", NULL, NULL, NULL);
  return rc;
  return HD_OK;
}

/* hd_db_open (existing 0: created if missing) and hd_db_open_existing (1: must be a haff
 * database already, checked before anything is written). */
static int open_rw(hd_db **out, const char *path, int existing, hd_error *err) {
  if (!out) return hd_error_set(err, HD_EINPUT, "hd_db_open: out is NULL");
  *out = NULL;
  hd_db *db;
  int rc = hd_db_check_path(path, existing, err);
  if (rc || (rc = db_alloc(&db, path, err))) return rc;
  /* NOMUTEX: SQLite's per-call locking (17 % of a logged run) is not needed: the connection is
   * used by one thread at a time, the writer between hand-offs and the caller only after
   * drain(), and the hand-off (mu, cv) orders their accesses. */
  int flags = SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX | (existing ? 0 : SQLITE_OPEN_CREATE);
  static const char *const runs[] = {"runs", NULL};
  const char *none = NULL;
  int missing = 0, foreign = 0;
  char plain[4200], why[200];
  const char *name = hd_db_plain_name(path, plain, sizeof plain);
  if (!name) {
    db_free(db);
    return hd_error_set(err, HD_EINPUT, "%.200s...: path too long", path);
  }
  /* checked before anything is written: not even the switch to WAL touches a file of someone
   * else's */
  int opened = sqlite3_open_v2(name, &db->db, flags, NULL) == SQLITE_OK;
  if (opened) {
    sqlite3_extended_result_codes(db->db, 1);
    sqlite3_busy_timeout(db->db, 10000); /* another writer: wait up to 10 s, then HD_EIO */
  }
  if (!opened || (foreign = not_haffs(db->db, why, sizeof why)) < 0 ||
      (existing && !foreign && (missing = tables_missing(db->db, runs, &none)) < 0)) {
    /* a write-protected file in a read-only folder cannot be read either (no -shm) */
    rc =
        opened && sqlite3_db_readonly(db->db, "main") == 1
            ? hd_error_set(err, HD_EIO,
                           "%s: open: the database file is read-only (check its permissions)", path)
            : open_error(db->db, path, "open", err);
    db_free(db);
    return rc;
  }
  if (foreign || missing) {
    db_free(db);
    if (foreign) return hd_error_set(err, HD_EINPUT, "%s: not a haff database: %s", path, why);
    return hd_error_set(err, HD_EINPUT, "%s: not a haff database (no %s table)", path, none);
  }
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
    rc = open_error(db->db, path, "set WAL mode", err);
  } else if (sqlite3_exec(db->db, "PRAGMA synchronous=NORMAL", NULL, NULL, NULL) != SQLITE_OK) {
    rc = sql_error(db, err, "set synchronous");
  } else {
    rc = schema_apply(db, err);
  }
  if (!rc)
    rc = prepare(db, &db->ins_run,
                 "INSERT INTO runs (scene, seed, status, started, version) VALUES "
                 "(?1, ?2, 'running', strftime('%Y-%m-%dT%H:%M:%SZ','now'), ?3)",
                 err);
  if (!rc) rc = prepare_coll(db, &db->ins_coll, 1, 0, err);
  if (!rc) /* the same, HD_DB_GROUP rows per statement */
    rc = prepare_coll(db, &db->ins_coll_k, HD_DB_GROUP, 0, err);
  if (!rc) /* 2D collisions: the rod columns are left to their default, NULL */
    rc = prepare_coll(db, &db->ins_coll2_k, HD_DB_GROUP, 1, err);
  if (!rc)
    rc = prepare(db, &db->ins_sample,
                 "INSERT INTO sample_rows (run, t, collisions, cpd, e_tr, e_rot, flow_frac, "
                 "flow_chaos, count_var, s_rho, s_perp, s_par) VALUES (?1, ?2, ?3, ?4, ?5, ?6, "
                 "?7, ?8, ?9, ?10, ?11, ?12)",
                 err);
  if (!rc)
    rc = prepare(db, &db->ins_spsample,
                 "INSERT INTO sample_species (run, t, species, e_tr, e_rot) VALUES (?1, ?2, ?3, "
                 "?4, ?5)",
                 err);
  if (!rc)
    rc = prepare(db, &db->ins_state,
                 "INSERT INTO states (run, label, t, cpd, body, kind, x, y, phi, vx, vy, "
                 "omega, species) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, "
                 "?13)",
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

int hd_db_open(hd_db **out, const char *path, hd_error *err) {
  return open_rw(out, path, 0, err);
}

int hd_db_open_existing(hd_db **out, const char *path, hd_error *err) {
  return open_rw(out, path, 1, err);
}

/* Writes into buf the URI "file:PATH?immutable=1" (PATH percent-encoded where a URI needs it);
 * 0, or -1 when it does not fit in size bytes or when PATH-wal holds rows (which immutable would
 * not read). */
static int uri_immutable(const char *path, char *buf, size_t size) {
  static const char hex[] = "0123456789ABCDEF";
  /* immutable reads the main file only: not when a log holds rows not yet copied into it (a
   * killed run's PATH-wal), which it would silently leave out */
  char wal[4200];
  struct stat st;
  snprintf(wal, sizeof wal, "%s-wal", path);
  if (stat(wal, &st) == 0 && st.st_size > 0) return -1;
  size_t k = (size_t)snprintf(buf, size, "file:");
  char plain[4200]; /* "file::memory:" would be a database in memory */
  const char *name = hd_db_plain_name(path, plain, sizeof plain);
  if (!name) return -1;
  for (const unsigned char *p = (const unsigned char *)name; *p && k + 4 < size; p++) {
    if (*p == '%' || *p == '?' || *p == '#' || *p <= ' ' || *p >= 0x7f) {
      buf[k++] = '%', buf[k++] = hex[*p >> 4], buf[k++] = hex[*p & 15];
    } else {
      buf[k++] = (char)*p;
    }
  }
  if (k + 12 >= size) return -1;
  snprintf(buf + k, size - k, "?immutable=1");
  return 0;
}

/* Opens PATH (which must exist) for reading, as sqlite3_open_v2 with flags: read-write when
 * the file may be written, with PRAGMA query_only (no statement can change it), so that the
 * last reader to close removes the -wal and -shm files that SQLite makes for a database in WAL
 * mode (a read-only connection leaves them beside it for good); read-only when the file is
 * write-protected.  Returns SQLite's code; *h as sqlite3_open_v2 leaves it. */
static int open_reader(const char *path, sqlite3 **h, int flags) {
  /* READWRITE opens a write-protected file read-only by itself; without CREATE a missing file
   * is SQLITE_CANTOPEN, as with READONLY */
  char plain[4200];
  const char *name = hd_db_plain_name(path, plain, sizeof plain);
  if (!name) return SQLITE_CANTOPEN;
  int rc = sqlite3_open_v2(name, h, flags | SQLITE_OPEN_READWRITE, NULL);
  if (rc == SQLITE_OK) rc = sqlite3_exec(*h, "PRAGMA query_only = 1", NULL, NULL, NULL);
  return rc;
}

/* After reading the schema through *h failed: if it failed because SQLite cannot make the
 * log's index (-shm) in a read-only folder or file system, replaces *h by a connection that
 * reads PATH as immutable (opened with flags | READONLY) and returns 1; not when PATH-wal holds
 * rows, which immutable would leave out.  Else 0 (*h, closed and reopened or not, is for the
 * caller's error message and sqlite3_close). */
static int reopen_immutable(const char *path, sqlite3 **h, int flags) {
  int code = *h ? sqlite3_errcode(*h) & 0xff : SQLITE_NOMEM; /* primary code of an extended one */
  char uri[8300];
  if ((code != SQLITE_CANTOPEN && code != SQLITE_READONLY) || uri_immutable(path, uri, sizeof uri))
    return 0;
  sqlite3_close(*h);
  *h = NULL;
  return sqlite3_open_v2(uri, h, flags | SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, NULL) == SQLITE_OK;
}

const char *hd_db_plain_name(const char *path, char *buf, size_t size) {
  if (path[0] == '/') return path;
  int k = snprintf(buf, size, "./%s", path);
  return k >= 0 && (size_t)k < size ? buf : NULL;
}

int hd_db_check_path(const char *path, int must_exist, hd_error *err) {
  struct stat st;
  if (stat(path, &st) != 0) {
    if (errno != ENOENT) /* a folder on the way that cannot be searched, say */
      return hd_error_set(err, HD_EINPUT, "%s: %s", path, strerror(errno));
    if (!must_exist) return HD_OK;
    return hd_error_set(err, HD_EINPUT, "%s: no such database", path);
  }
  if (S_ISDIR(st.st_mode))
    return hd_error_set(err, HD_EINPUT, "%s: is a directory, not a database file", path);
  if (!S_ISREG(st.st_mode))
    return hd_error_set(err, HD_EINPUT,
                        "%s: not a regular file (a FIFO or a device), not a database", path);
  return HD_OK;
}

/* Whether h holds every table of tables (NULL-terminated names): 0; 1 with *missing the first
 * it lacks; -1 when its schema cannot be read (not a database, or no -shm can be made). */
static int tables_missing(sqlite3 *h, const char *const *tables, const char **missing) {
  sqlite3_stmt *st;
  /* samples is a view from schema version 5 on, a table before */
  if (sqlite3_prepare_v2(h,
                         "SELECT count(*) FROM sqlite_schema WHERE type IN ('table', 'view') AND "
                         "name = ?1",
                         -1, &st, NULL) != SQLITE_OK)
    return -1;
  int rc = 0;
  for (const char *const *t = tables; *t && !rc; t++) {
    sqlite3_bind_text(st, 1, *t, -1, SQLITE_STATIC);
    if (sqlite3_step(st) != SQLITE_ROW)
      rc = -1;
    else if (sqlite3_column_int(st, 0) == 0)
      rc = 1, *missing = *t;
    sqlite3_reset(st);
  }
  sqlite3_finalize(st);
  return rc;
}

int hd_db_open_read(const char *path, int flags, const char *const *tables, sqlite3 **h,
                    hd_error *err) {
  *h = NULL;
  int rc = hd_db_check_path(path, 1, err);
  if (rc) return rc;
  const char *none = NULL;
  int missing = open_reader(path, h, flags) == SQLITE_OK ? tables_missing(*h, tables, &none) : -1;
  if (missing < 0 && reopen_immutable(path, h, flags)) /* a read-only folder */
    missing = tables_missing(*h, tables, &none);
  if (missing) {
    rc = missing < 0
             ? open_error(*h, path, "open", err)
             : hd_error_set(err, HD_EINPUT, "%s: not a haff database (no %s table)", path, none);
    sqlite3_close(*h);
    *h = NULL;
    return rc;
  }
  sqlite3_extended_result_codes(*h, 1);
  return HD_OK;
}

void hd_db_close_read(sqlite3 *h) {
  sqlite3_close(h);
}

int hd_db_open_readonly(hd_db **out, const char *path, hd_error *err) {
  if (!out) return hd_error_set(err, HD_EINPUT, "hd_db_open_readonly: out is NULL");
  *out = NULL;
  hd_db *db;
  static const char *const runs[] = {"runs", NULL};
  int rc = db_alloc(&db, path, err);
  if (!rc) rc = hd_db_open_read(path, SQLITE_OPEN_NOMUTEX, runs, &db->db, err);
  if (rc) {
    db_free(db);
    return rc;
  }
  sqlite3_busy_timeout(db->db, 10000);
  db->readonly = 1;
  *out = db;
  return HD_OK;
}

int hd_db_close(hd_db *db, hd_error *err) {
  if (!db) return HD_OK;
  int rc = db->readonly ? HD_OK : hd_db_commit(db, err);
  writer_stop(db);
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
  if (db) drain(db, NULL); /* rows logged before keep the old batch size */
  if (db) db->batch_rows = rows < 1 ? 1 : rows;
}

const char *hd_db_path(const hd_db *db) {
  return db ? db->path : "";
}

sqlite3 *hd_db_handle(hd_db *db) {
  if (db) drain(db, NULL); /* the caller sees every row logged so far */
  return db ? db->db : NULL;
}

/* ---------------------------------------------------------------------------------------- */
/* batches */

static int hd_db_commit_now(hd_db *db, hd_error *err);

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

/* Commits the open batch (the caller's thread when the writer is idle, or the writer). */
static int hd_db_commit_now(hd_db *db, hd_error *err) {
  if (!db->in_tx) return HD_OK;
  if (sqlite3_exec(db->db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK)
    return batch_fail(db, NULL, err, "commit batch");
  db->in_tx = 0;
  db->pending = 0;
  return HD_OK;
}

int hd_db_commit(hd_db *db, hd_error *err) {
  if (!db) return hd_error_set(err, HD_EIO, "database: not open");
  int rc = drain(db, err);
  return rc ? rc : hd_db_commit_now(db, err);
}

/* Steps a bound insert of the open batch; counts the row and commits a full batch. */
static int batch_step(hd_db *db, sqlite3_stmt *st, hd_error *err, const char *what) {
  if (sqlite3_step(st) != SQLITE_DONE) return batch_fail(db, st, err, what);
  sqlite3_reset(st);
  if (++db->pending >= db->batch_rows) return hd_db_commit_now(db, err);
  return HD_OK;
}

/* Binds value v at parameter i of st, or NULL when !keep (the bind kinds of
 * HD_COLLISION_COLUMNS). */
static void bind_INT64(sqlite3_stmt *st, int i, int64_t v, int keep) {
  keep ? sqlite3_bind_int64(st, i, v) : sqlite3_bind_null(st, i);
}
static void bind_INT(sqlite3_stmt *st, int i, int v, int keep) {
  keep ? sqlite3_bind_int(st, i, v) : sqlite3_bind_null(st, i);
}
static void bind_REAL(sqlite3_stmt *st, int i, double v, int keep) {
  bind_real(st, i, keep ? v : NAN);
}
static void bind_KIND(sqlite3_stmt *st, int i, hd_coll_kind v, int keep) {
  keep ? sqlite3_bind_text(st, i, hd_coll_kind_name(v), -1, SQLITE_STATIC)
       : sqlite3_bind_null(st, i);
}

/* Binds run and collision row r at parameters base+1, base+2, ... of st, in the order of
 * prepare_coll (twod: without the rod-rod columns); a column of another scope than r's kind is
 * bound NULL.  Returns the number of parameters bound. */
static inline int bind_collision(sqlite3_stmt *st, int base, int64_t run, const hd_collision_row *r,
                                 int twod) {
  int p = base, rod = r->kind == hd_coll_kind_of(HD_KIND_ROD, HD_KIND_ROD);
  sqlite3_bind_int64(st, ++p, run);
#define COLL_BIND(name, ctype, bind, sqltype, scope, since, doc)                                   \
  if (!twod || (scope) != HD_COLL_ROD)                                                             \
    bind_##bind(st, ++p, r->name, (scope) == HD_COLL_ALL || ((scope) == HD_COLL_ROD) == rod);
  HD_COLLISION_COLUMNS(COLL_BIND)
#undef COLL_BIND
  return p - base;
}

static int put_collision(hd_db *db, int64_t run, const hd_collision_row *r, hd_error *err) {
  int rc = batch_begin(db, err);
  if (rc) return rc;
  bind_collision(db->ins_coll, 0, run, r, 0);
  return batch_step(db, db->ins_coll, err, "insert collision");
}

/* HD_DB_GROUP collisions in one statement; the caller checked that they fit the open batch. */
static int put_collision_group(hd_db *db, const rec *g, hd_error *err) {
  int rc = batch_begin(db, err);
  if (rc) return rc;
  int rods = 0;
  for (int k = 0; k < HD_DB_GROUP; k++)
    rods |= g[k].u.c.kind == hd_coll_kind_of(HD_KIND_ROD, HD_KIND_ROD);
  sqlite3_stmt *st = rods ? db->ins_coll_k : db->ins_coll2_k;
  if (rods) /* (two loops: bind_collision is specialised for each) */
    for (int k = 0, base = 0; k < HD_DB_GROUP; k++)
      base += bind_collision(st, base, g[k].run, &g[k].u.c, 0);
  else
    for (int k = 0, base = 0; k < HD_DB_GROUP; k++)
      base += bind_collision(st, base, g[k].run, &g[k].u.c, 1);
  if (sqlite3_step(st) != SQLITE_DONE) return batch_fail(db, st, err, "insert collisions");
  sqlite3_reset(st);
  db->pending += HD_DB_GROUP;
  if (db->pending >= db->batch_rows) return hd_db_commit_now(db, err);
  return HD_OK;
}

static int put_sample(hd_db *db, int64_t run, const hd_sample_row *r, hd_error *err) {
  int rc = batch_begin(db, err);
  if (rc) return rc;
  sqlite3_stmt *st = db->ins_sample;
  sqlite3_bind_int64(st, 1, run);
  bind_real(st, 2, r->t);
  sqlite3_bind_int64(st, 3, r->collisions);
  bind_real(st, 4, r->cpd);
  bind_real(st, 5, r->e_tr);
  bind_real(st, 6, r->e_rot);
  bind_real(st, 7, r->flow_frac);
  bind_real(st, 8, r->flow_chaos);
  bind_real(st, 9, r->count_var);
  bind_real(st, 10, r->s_rho);
  bind_real(st, 11, r->s_perp);
  bind_real(st, 12, r->s_par);
  return batch_step(db, st, err, "insert sample");
}

static int put_species_sample(hd_db *db, int64_t run, const hd_species_sample *r, hd_error *err) {
  int rc = batch_begin(db, err);
  if (rc) return rc;
  sqlite3_stmt *st = db->ins_spsample;
  sqlite3_bind_int64(st, 1, run);
  bind_real(st, 2, r->t);
  sqlite3_bind_int(st, 3, r->species);
  bind_real(st, 4, r->e_tr);
  bind_real(st, 5, r->e_rot);
  return batch_step(db, st, err, "insert species sample");
}

static int put_state(hd_db *db, int64_t run, const char *label, const hd_state_rec *r,
                     hd_error *err) {
  int rc = batch_begin(db, err);
  if (rc) return rc;
  sqlite3_stmt *st = db->ins_state;
  sqlite3_bind_int64(st, 1, run);
  sqlite3_bind_text(st, 2, label, -1, SQLITE_STATIC);
  bind_real(st, 3, r->t);
  bind_real(st, 4, r->cpd);
  sqlite3_bind_int64(st, 5, r->body);
  sqlite3_bind_text(st, 6, hd_kind_name(r->kind), -1, SQLITE_STATIC);
  bind_real(st, 7, r->x);
  bind_real(st, 8, r->y);
  bind_real(st, 9, r->phi);
  bind_real(st, 10, r->vx);
  bind_real(st, 11, r->vy);
  bind_real(st, 12, r->omega);
  if (r->kind == HD_KIND_ROD || r->species < 0)
    sqlite3_bind_null(st, 13);
  else
    sqlite3_bind_int(st, 13, r->species);
  return batch_step(db, st, err, "insert state");
}

/* ---------------------------------------------------------------------------------------- */
/* asynchronous rows
 * The log_* calls only copy their row into a buffer; a writer thread inserts the buffers into
 * the open batch transaction (collisions HD_DB_GROUP at a time), committing every batch_rows
 * rows exactly as a synchronous writer would: a batch is still one transaction, so a killed
 * process leaves whole batches only.  Every other call first drains the buffers (waits for the
 * writer to be idle), so checkpoints, commits and status changes see every row logged before
 * them.  An error of the writer is returned by the next log_* or draining call. */

/* Writes n rows (writer thread, or the caller's thread once the writer is idle). */
static int write_rows(hd_db *db, const rec *r, int n, hd_error *err) {
  int rc = HD_OK;
  for (int k = 0; k < n && !rc;) {
    if (r[k].type == REC_COLLISION && k + HD_DB_GROUP <= n &&
        r[k + HD_DB_GROUP - 1].type == REC_COLLISION &&
        db->pending + HD_DB_GROUP <= db->batch_rows) {
      int all = 1;
      for (int q = k + 1; q < k + HD_DB_GROUP - 1 && all; q++) all = r[q].type == REC_COLLISION;
      if (all) {
        rc = put_collision_group(db, r + k, err);
        k += HD_DB_GROUP;
        continue;
      }
    }
    if (r[k].type == REC_COLLISION)
      rc = put_collision(db, r[k].run, &r[k].u.c, err);
    else if (r[k].type == REC_SAMPLE)
      rc = put_sample(db, r[k].run, &r[k].u.s, err);
    else if (r[k].type == REC_SPECIES_SAMPLE)
      rc = put_species_sample(db, r[k].run, &r[k].u.sp, err);
    else
      rc = put_state(db, r[k].run, r[k].label, &r[k].u.st, err);
    k++;
  }
  return rc;
}

static void *writer_main(void *arg) {
  hd_db *db = arg;
  sigset_t all;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, NULL); /* signals are for the simulation's thread */
  pthread_mutex_lock(&db->mu);
  for (;;) {
    while (!db->nq && !db->quit) pthread_cond_wait(&db->cv, &db->mu);
    if (!db->nq) break;
    rec *w = db->buf[db->qhead];
    int n = db->nrows[db->qhead], failed = db->werr;
    pthread_mutex_unlock(&db->mu);
    hd_error e;
    hd_error_clear(&e);
    int rc = failed ? HD_OK : write_rows(db, w, n, &e);
    pthread_mutex_lock(&db->mu);
    if (rc && !db->werr) {
      db->werror = e;
      __atomic_store_n(&db->werr, rc, __ATOMIC_RELEASE);
    }
    db->qhead = (db->qhead + 1) % HD_DB_NBUF;
    db->nq--;
    pthread_cond_broadcast(&db->cv);
  }
  pthread_mutex_unlock(&db->mu);
  return NULL;
}

/* Hands the fill buffer to the writer (waiting for it to finish the previous one). */
static int handoff(hd_db *db, hd_error *err) {
  if (!db->writer_on) {
    for (int b = 0; b < HD_DB_NBUF; b++)
      if (!db->buf[b] && !(db->buf[b] = malloc(sizeof(rec) * HD_DB_QCAP)))
        return hd_error_set(err, HD_ENOMEM, "%s: out of memory for the row buffer", db->path);
    if (pthread_mutex_init(&db->mu, NULL) || pthread_cond_init(&db->cv, NULL) ||
        pthread_create(&db->writer, NULL, writer_main, db))
      return hd_error_set(err, HD_ENOMEM, "%s: cannot start the writer thread", db->path);
    db->writer_on = 1;
    /* checkpoints off the writer's path: an optimisation, so without it SQLite's automatic
     * checkpoints stay on and nothing is lost */
    hd_error ignored;
    hd_walck_start(&db->walck, db->db, db->path, &ignored);
  }
  if (db->nfill == 0) return HD_OK;
  pthread_mutex_lock(&db->mu);
  while (db->nq == HD_DB_NBUF - 1) pthread_cond_wait(&db->cv, &db->mu);
  db->nrows[db->fill] = db->nfill;
  if (db->nq++ == 0) pthread_cond_broadcast(&db->cv); /* the writer was idle */
  pthread_mutex_unlock(&db->mu);
  db->fill = (db->fill + 1) % HD_DB_NBUF;
  db->nfill = 0;
  return HD_OK;
}

/* Waits until every logged row is written; returns the writer's first error, if any, once:
 * the rows after it were dropped, the database stays usable (to record the run's status). */
static int drain(hd_db *db, hd_error *err) {
  if (!db) return HD_OK;
  int rc = handoff(db, err);
  if (rc || !db->writer_on) return rc;
  pthread_mutex_lock(&db->mu);
  while (db->nq) pthread_cond_wait(&db->cv, &db->mu);
  rc = db->werr;
  if (rc && err) *err = db->werror;
  db->werr = HD_OK;
  pthread_mutex_unlock(&db->mu);
  return rc;
}

/* Stops the writer (after drain). */
static void writer_stop(hd_db *db) {
  if (db->writer_on) {
    pthread_mutex_lock(&db->mu);
    db->quit = 1;
    pthread_cond_broadcast(&db->cv);
    pthread_mutex_unlock(&db->mu);
    pthread_join(db->writer, NULL);
    hd_walck_stop(db->walck);
    db->walck = NULL;
    pthread_mutex_destroy(&db->mu);
    pthread_cond_destroy(&db->cv);
    db->writer_on = 0;
  }
  for (int b = 0; b < HD_DB_NBUF; b++) {
    free(db->buf[b]);
    db->buf[b] = NULL;
  }
}

/* A slot for one more row, handing a full buffer over first. */
static rec *slot(hd_db *db, hd_error *err, int *rc) {
  if (__atomic_load_n(&db->werr, __ATOMIC_ACQUIRE)) { /* reported once the writer is idle */
    *rc = drain(db, err);
    return NULL;
  }
  if ((!db->writer_on || db->nfill == HD_DB_QCAP) && (*rc = handoff(db, err))) return NULL;
  return &db->buf[db->fill][db->nfill++];
}

int hd_db_log_collision(hd_db *db, int64_t run, const hd_collision_row *r, hd_error *err) {
  int rc = check_db(db, err);
  if (rc) return rc;
  rec *q = slot(db, err, &rc);
  if (!q) return rc;
  q->type = REC_COLLISION;
  q->run = run;
  q->u.c = *r;
  return HD_OK;
}

int hd_db_log_sample(hd_db *db, int64_t run, const hd_sample_row *r, hd_error *err) {
  int rc = check_db(db, err);
  if (rc) return rc;
  rec *q = slot(db, err, &rc);
  if (!q) return rc;
  q->type = REC_SAMPLE;
  q->run = run;
  q->u.s = *r;
  return HD_OK;
}

int hd_db_log_species_sample(hd_db *db, int64_t run, const hd_species_sample *r, hd_error *err) {
  int rc = check_db(db, err);
  if (rc) return rc;
  rec *q = slot(db, err, &rc);
  if (!q) return rc;
  q->type = REC_SPECIES_SAMPLE;
  q->run = run;
  q->u.sp = *r;
  return HD_OK;
}

int hd_db_log_species(hd_db *db, int64_t run, const hd_species_rec *r, hd_error *err) {
  int rc = check_db(db, err);
  if (rc) return rc;
  /* after the rows logged before it, in the open batch (a few rows per run: no writer ring) */
  if ((rc = drain(db, err)) || (rc = batch_begin(db, err))) return rc;
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(db->db,
                         "INSERT INTO species (run, idx, name, disks, count, mass, inertia) "
                         "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)",
                         -1, &st, NULL) != SQLITE_OK)
    return batch_fail(db, NULL, err, "insert species");
  sqlite3_bind_int64(st, 1, run);
  sqlite3_bind_int(st, 2, r->idx);
  sqlite3_bind_text(st, 3, r->name, -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(st, 4, r->disks, -1, SQLITE_TRANSIENT);
  sqlite3_bind_int64(st, 5, r->count);
  bind_real(st, 6, r->mass);
  bind_real(st, 7, r->inertia);
  rc = sqlite3_step(st) == SQLITE_DONE ? HD_OK : batch_fail(db, st, err, "insert species");
  sqlite3_finalize(st);
  if (!rc && ++db->pending >= db->batch_rows) rc = hd_db_commit_now(db, err);
  return rc;
}

/* Labels of states rows: the rows keep a pointer, so they must be these literals. */
static const char *state_label(const char *label) {
  static const char *const known[] = {"initial", "final", "checkpoint", "velocities"};
  for (size_t k = 0; k < sizeof known / sizeof known[0]; k++)
    if (!strcmp(label, known[k])) return known[k];
  return NULL;
}

int hd_db_log_state(hd_db *db, int64_t run, const char *label, const hd_state_rec *r,
                    hd_error *err) {
  int rc = check_db(db, err);
  if (rc) return rc;
  if (!hd_kind_name(r->kind))
    return hd_error_set(err, HD_EINPUT, "%s: insert state: unknown body kind %d", db->path,
                        r->kind);
  const char *lab = label ? state_label(label) : NULL;
  if (!lab)
    return hd_error_set(err, HD_EINPUT, "%s: insert state: unknown label '%s'", db->path,
                        label ? label : "(null)");
  rec *q = slot(db, err, &rc);
  if (!q) return rc;
  q->type = REC_STATE;
  q->run = run;
  q->label = lab;
  q->u.st = *r;
  return HD_OK;
}

/* ---------------------------------------------------------------------------------------- */
/* runs */

int hd_db_run_begin(hd_db *db, const char *scene_text, unsigned long long seed, const char *version,
                    int64_t *run, hd_error *err) {
  int rc = check_db(db, err);
  /* in a batch of its own, left open: the row is seen by others once the caller commits */
  if (rc || (rc = hd_db_commit(db, err)) || (rc = batch_begin(db, err))) return rc;
  sqlite3_stmt *st = db->ins_run;
  sqlite3_bind_text(st, 1, scene_text ? scene_text : "", -1, SQLITE_TRANSIENT);
  /* runs.seed is a signed 64-bit integer: a seed >= 2^63 is stored as its two's complement
   * and read back exactly by hd_db_find_resumable. */
  sqlite3_bind_int64(st, 2, (sqlite3_int64)seed);
  sqlite3_bind_text(st, 3, version ? version : "", -1, SQLITE_TRANSIENT);
  if (sqlite3_step(st) != SQLITE_DONE) return batch_fail(db, st, err, "insert run");
  sqlite3_reset(st); /* not counted in the batch's rows: batches stay whole batch_rows of logs */
  if (run) *run = sqlite3_last_insert_rowid(db->db);
  return HD_OK;
}

int hd_db_run_unstarted(hd_db *db, int64_t run, int *unstarted, hd_error *err) {
  if (!db) return hd_error_set(err, HD_EIO, "database: not open");
  *unstarted = 0;
  int rc = drain(db, err);
  if (rc) return rc;
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(db->db,
                         "SELECT status = 'running' AND NOT EXISTS (SELECT 1 FROM checkpoints c "
                         "WHERE c.run = runs.id) FROM runs WHERE id = ?1",
                         -1, &st, NULL) != SQLITE_OK)
    return sql_error(db, err, "look for the checkpoint");
  sqlite3_bind_int64(st, 1, run);
  int s = sqlite3_step(st);
  if (s == SQLITE_ROW)
    *unstarted = sqlite3_column_int(st, 0);
  else if (s != SQLITE_DONE)
    rc = sql_error(db, err, "look for the checkpoint");
  sqlite3_finalize(st);
  return rc;
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
  if (!rc && (!strcmp(status, "done") || !strcmp(status, "collapsed"))) {
    /* an ended run cannot be resumed: its checkpoint (~150 bytes per body) goes, and its pages
     * take the rows of the runs that follow (auto_vacuum, which would give them back to the
     * file system, cost 3 % of a logged run's speed; VACUUM does it on demand) */
    rc = run_update(db, run, "DELETE FROM checkpoints WHERE run = ?1", NULL, NULL,
                    "delete the checkpoint of an ended run", NULL, err);
  }
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

static void bind_progress(sqlite3_stmt *st, const void *ctx) {
  const double *p = ctx;
  sqlite3_bind_int64(st, 2, (sqlite3_int64)p[0]);
  bind_real(st, 3, p[1]);
}

int hd_db_run_progress(hd_db *db, int64_t run, int64_t events, double cpd, hd_error *err) {
  double p[2] = {(double)events, cpd};
  return run_update(db, run, "UPDATE runs SET events = ?2, cpd = ?3 WHERE id = ?1", bind_progress,
                    p, "set run progress", NULL, err);
}

static void bind_hcs(sqlite3_stmt *st, const void *ctx) {
  const double *v = ctx; /* cpd_start, cpd_end, end code (-1: NULL), s_perp, flow_excess */
  static const char *const ends[] = {"none", "s_perp", "rate"};
  bind_real(st, 2, v[0]);
  bind_real(st, 3, v[1]);
  if (v[2] >= 0 && v[2] < 3)
    sqlite3_bind_text(st, 4, ends[(int)v[2]], -1, SQLITE_STATIC);
  else
    sqlite3_bind_null(st, 4);
  bind_real(st, 5, v[3]);
  bind_real(st, 6, v[4]);
}

int hd_db_run_hcs(hd_db *db, int64_t run, hd_error *err) {
  int rc = check_db(db, err);
  if (rc || (rc = hd_db_commit(db, err))) return rc;
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(db->db,
                         "SELECT t, collisions, cpd, e_tr + e_rot, s_perp, flow_frac, flow_chaos "
                         "FROM samples WHERE run = ?1 ORDER BY t",
                         -1, &st, NULL) != SQLITE_OK)
    return sql_error(db, err, "read the samples for the HCS window");
  sqlite3_bind_int64(st, 1, run);
  size_t n = 0, cap = 0;
  double *v = NULL; /* 7 columns per sample */
  int s;
  while ((s = sqlite3_step(st)) == SQLITE_ROW) {
    if (n == cap) {
      cap = cap ? 2 * cap : 256;
      double *nv = realloc(v, cap * 7 * sizeof *nv);
      if (!nv) {
        free(v), sqlite3_finalize(st);
        return hd_error_set(err, HD_ENOMEM, "HCS window: out of memory");
      }
      v = nv;
    }
    for (int c = 0; c < 7; c++)
      v[7 * n + (size_t)c] =
          sqlite3_column_type(st, c) == SQLITE_NULL ? NAN : sqlite3_column_double(st, c);
    n++;
  }
  sqlite3_finalize(st);
  if (s != SQLITE_DONE) {
    free(v);
    return sql_error(db, err, "read the samples for the HCS window");
  }
  double row[5] = {NAN, NAN, -1, NAN, NAN}; /* fewer than 3 samples: NULL, nothing to fit */
  if (n >= 3) {
    double *a = malloc(7 * n * sizeof *a);
    if (!a) {
      free(v);
      return hd_error_set(err, HD_ENOMEM, "HCS window: out of memory");
    }
    for (size_t i = 0; i < n; i++)
      for (size_t c = 0; c < 7; c++) a[c * n + i] = v[7 * i + c];
    hd_homog_opts ho = hd_homog_defaults();
    hd_hcs_opts hc = hd_hcs_defaults();
    hd_hcs_window w;
    hd_error e2;
    if (hd_hcs_window_find(a, a + n, a + 3 * n, a + 2 * n, a + 4 * n, a + 5 * n, a + 6 * n, n, &ho,
                           &hc, &w, &e2) == HD_OK) {
      row[0] = a[2 * n + w.n_start], row[1] = a[2 * n + w.n_end - 1], row[2] = w.end;
      if (w.hcs_ok && w.hcs.have) row[3] = w.hcs.s_perp, row[4] = w.hcs.flow_excess;
    }
    free(a);
  }
  free(v);
  return run_update(db, run,
                    "UPDATE runs SET hcs_cpd_start = ?2, hcs_cpd_end = ?3, hcs_end = ?4, "
                    "hcs_s_perp = ?5, hcs_flow_excess = ?6 WHERE id = ?1",
                    bind_hcs, row, "store the HCS window", NULL, err);
}

static void bind_origin(sqlite3_stmt *st, const void *ctx) {
  const char *const *v = ctx;
  for (int k = 0; k < 3; k++)
    if (v[k] && v[k][0])
      sqlite3_bind_text(st, k + 2, v[k], -1, SQLITE_STATIC);
    else
      sqlite3_bind_null(st, k + 2);
}

int hd_db_run_origin(hd_db *db, int64_t run, const char *host, const char *slurm_job,
                     const char *slurm_task, hd_error *err) {
  const char *v[3] = {host, slurm_job, slurm_task};
  return run_update(db, run,
                    "INSERT OR REPLACE INTO provenance (run, host, slurm_job, slurm_task) "
                    "VALUES (?1, ?2, ?3, ?4)",
                    bind_origin, v, "record where the run is made", NULL, err);
}

/* Binds text v to parameter k of st, NULL for NULL or "". */
static void bind_text_or_null(sqlite3_stmt *st, int k, const char *v) {
  if (v && v[0])
    sqlite3_bind_text(st, k, v, -1, SQLITE_STATIC);
  else
    sqlite3_bind_null(st, k);
}

static void bind_prov(sqlite3_stmt *st, const void *ctx) {
  const hd_run_prov *p = ctx;
  bind_text_or_null(st, 2, p->git_commit);
  if (p->git_dirty == 0 || p->git_dirty == 1)
    sqlite3_bind_int(st, 3, p->git_dirty);
  else
    sqlite3_bind_null(st, 3);
  bind_text_or_null(st, 4, p->compiler);
  bind_text_or_null(st, 5, p->cflags);
  bind_text_or_null(st, 6, p->command);
  bind_text_or_null(st, 7, p->sweep_point);
}

int hd_db_run_provenance(hd_db *db, int64_t run, const hd_run_prov *p, hd_error *err) {
  if (!p) return hd_error_set(err, HD_EINPUT, "hd_db_run_provenance: no provenance given");
  return run_update(db, run,
                    "UPDATE runs SET git_commit = ?2, git_dirty = ?3, compiler = ?4, cflags = ?5, "
                    "command = ?6, sweep_point = ?7 WHERE id = ?1",
                    bind_prov, p, "record how the run is made", NULL, err);
}

int hd_db_find_same_run(hd_db *db, const char *scene_text, unsigned long long seed,
                        hd_same_run *same, hd_error *err) {
  if (!db) return hd_error_set(err, HD_EIO, "database: not open");
  memset(same, 0, sizeof *same);
  int rc = drain(db, err);
  if (rc) return rc;
  int has_commit = !column_missing(db->db, "runs", "git_commit");
  sqlite3_stmt *st = NULL;
  const char *sql = has_commit ? "SELECT id, status, coalesce(git_commit, 'unknown') FROM runs "
                                 "WHERE scene = ?1 AND seed = ?2 ORDER BY id LIMIT 1"
                               : "SELECT id, status, 'unknown' FROM runs "
                                 "WHERE scene = ?1 AND seed = ?2 ORDER BY id LIMIT 1";
  if (sqlite3_prepare_v2(db->db, sql, -1, &st, NULL) != SQLITE_OK)
    return sql_error(db, err, "look for the same run");
  sqlite3_bind_text(st, 1, scene_text ? scene_text : "", -1, SQLITE_STATIC);
  sqlite3_bind_int64(st, 2, (sqlite3_int64)seed);
  int s = sqlite3_step(st);
  if (s == SQLITE_ROW) {
    same->run = sqlite3_column_int64(st, 0);
    snprintf(same->status, sizeof same->status, "%s", (const char *)sqlite3_column_text(st, 1));
    snprintf(same->commit, sizeof same->commit, "%s", (const char *)sqlite3_column_text(st, 2));
  } else if (s != SQLITE_DONE) {
    rc = sql_error(db, err, "look for the same run");
  }
  sqlite3_finalize(st);
  return rc;
}

int hd_db_build_indexes(hd_db *db, hd_error *err) {
  int rc = check_db(db, err);
  if (rc || (rc = hd_db_commit(db, err))) return rc;
  static const char sql[] =
      "CREATE INDEX IF NOT EXISTS collisions_run_seq ON collisions(run, seq);"
      "CREATE INDEX IF NOT EXISTS collisions_run_kind ON collisions(run, kind);"
      "CREATE INDEX IF NOT EXISTS samples_run_t ON sample_rows(run, t);"
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
  if (rc) return rc;
  int lim = sqlite3_limit(db->db, SQLITE_LIMIT_LENGTH, -1);
  if (n > (size_t)lim) /* ~149 bytes per disk: above ~6.7e6 bodies */
    return hd_error_set(err, HD_EINPUT,
                        "%s: a checkpoint of this run takes %zu bytes, more than SQLite's limit "
                        "of %d per value: fewer bodies (at most ~%d million) can be checkpointed",
                        db->path, n, lim, (int)(lim / 150 / 1000000));
  if ((rc = drain(db, err)) || (rc = batch_begin(db, err))) return rc;
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

int hd_db_log_frame(hd_db *db, int64_t run, double t, double cpd, int64_t n, const void *data,
                    size_t size, hd_error *err) {
  int rc = check_db(db, err);
  if (rc) return rc;
  if (size > (size_t)sqlite3_limit(db->db, SQLITE_LIMIT_LENGTH, -1))
    return hd_error_set(err, HD_EINPUT,
                        "%s: a frame of %lld bodies takes %zu bytes, more than SQLite's limit "
                        "per value: frames cannot be stored for this many bodies",
                        db->path, (long long)n, size);
  /* after the rows logged before it, in the open batch (frames are rare: no writer ring) */
  if ((rc = drain(db, err)) || (rc = batch_begin(db, err))) return rc;
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(db->db,
                         "INSERT INTO frames (run, t, cpd, n, data) VALUES (?1, ?2, ?3, "
                         "?4, ?5)",
                         -1, &st, NULL) != SQLITE_OK)
    return batch_fail(db, NULL, err, "insert frame");
  sqlite3_bind_int64(st, 1, run);
  bind_real(st, 2, t);
  bind_real(st, 3, cpd);
  sqlite3_bind_int64(st, 4, n);
  sqlite3_bind_blob64(st, 5, data, (sqlite3_uint64)size, SQLITE_STATIC);
  rc = sqlite3_step(st) == SQLITE_DONE ? HD_OK : batch_fail(db, st, err, "insert frame");
  sqlite3_finalize(st);
  if (!rc && ++db->pending >= db->batch_rows) rc = hd_db_commit_now(db, err);
  return rc;
}

int hd_db_frames_bytes(hd_db *db, int64_t run, int64_t *bytes, hd_error *err) {
  int rc = check_db(db, err);
  if (rc || (rc = drain(db, err))) return rc;
  sqlite3_stmt *st = NULL;
  *bytes = 0;
  if (sqlite3_prepare_v2(db->db, "SELECT coalesce(sum(length(data)), 0) FROM frames WHERE run = ?1",
                         -1, &st, NULL) != SQLITE_OK)
    return sql_error(db, err, "count frames");
  sqlite3_bind_int64(st, 1, run);
  if (sqlite3_step(st) == SQLITE_ROW)
    *bytes = sqlite3_column_int64(st, 0);
  else
    rc = sql_error(db, err, "count frames");
  sqlite3_finalize(st);
  return rc;
}

int hd_db_checkpoint_load(hd_db *db, int64_t run, void **blob, size_t *n, int64_t *seq, double *t,
                          hd_error *err) {
  if (!db) return hd_error_set(err, HD_EIO, "database: not open");
  *blob = NULL;
  int drc = drain(db, err);
  if (drc) return drc;
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

/* The one list of the tables of db/schema.sql that hold rows of a run (a `run` column; runs
 * itself, keyed by id, is not in it), that truncation, deletion (hd_db_run_delete) and merge
 * (db/hd_merge.c) all use; tests/test_harden.c fails when a table of the schema with a run
 * column is missing here.  truncate: the rows a resumed run writes again (?1 the run, ?2 the
 * checkpoint's seq, ?3 its t; -inf for a run begun again from its set-up), NULL for rows kept:
 * the checkpoint resumed from, and provenance. */
static const hd_run_table run_tables[] = {
    {"provenance", NULL},
    {"collisions", "DELETE FROM collisions WHERE run = ?1 AND seq > ?2"},
    {"sample_rows", "DELETE FROM sample_rows WHERE run = ?1 AND t > ?3"},
    {"sample_species", "DELETE FROM sample_species WHERE run = ?1 AND t > ?3"},
    /* written once, at the start (t = 0): again only by a run begun again from its set-up */
    {"species", "DELETE FROM species WHERE run = ?1 AND ?3 < 0"},
    {"states", "DELETE FROM states WHERE run = ?1 AND (t > ?3 OR label IN ('checkpoint', "
               "'final'))"},
    {"frames", "DELETE FROM frames WHERE run = ?1 AND t > ?3"},
    {"checkpoints", NULL},
    {NULL, NULL}};

const hd_run_table *hd_db_run_tables(void) {
  return run_tables;
}

typedef struct trunc_args {
  int64_t seq;
  double t;
} trunc_args;

static void bind_trunc(sqlite3_stmt *st, const void *ctx) {
  sqlite3_bind_int64(st, 2, ((const trunc_args *)ctx)->seq);
  sqlite3_bind_double(st, 3, ((const trunc_args *)ctx)->t);
}

int hd_db_truncate_after(hd_db *db, int64_t run, int64_t seq, double t, hd_error *err) {
  trunc_args a = {seq, t};
  int rc = check_db(db, err);
  if (rc || (rc = hd_db_commit(db, err))) return rc;
  /* One transaction: either every table is truncated or none. */
  if (sqlite3_exec(db->db, "BEGIN IMMEDIATE", NULL, NULL, NULL) != SQLITE_OK)
    return sql_error(db, err, "truncate: begin");
  for (const hd_run_table *k = run_tables; !rc && k->name; k++) {
    char what[64];
    snprintf(what, sizeof what, "truncate %s", k->name);
    if (k->truncate) rc = run_update(db, run, k->truncate, bind_trunc, &a, what, NULL, err);
  }
  if (!rc && sqlite3_exec(db->db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK)
    rc = sql_error(db, err, "truncate: commit");
  if (rc) rollback(db);
  return rc;
}

int hd_db_run_delete(hd_db *db, int64_t run, hd_error *err) {
  int rc = check_db(db, err);
  if (rc || (rc = hd_db_commit(db, err))) return rc;
  if (sqlite3_exec(db->db, "BEGIN IMMEDIATE", NULL, NULL, NULL) != SQLITE_OK)
    return sql_error(db, err, "delete run: begin");
  for (const hd_run_table *k = run_tables; !rc && k->name; k++) {
    char sql[96], what[64];
    snprintf(sql, sizeof sql, "DELETE FROM %s WHERE run = ?1", k->name); /* the list's name */
    snprintf(what, sizeof what, "delete the run's %s", k->name);
    rc = run_update(db, run, sql, NULL, NULL, what, NULL, err);
  }
  int64_t n = 0;
  if (!rc)
    rc = run_update(db, run, "DELETE FROM runs WHERE id = ?1", NULL, NULL, "delete run", &n, err);
  if (!rc && n == 0)
    rc = hd_error_set(err, HD_EINPUT, "%s: delete run: no run %lld", db->path, (long long)run);
  if (!rc && sqlite3_exec(db->db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK)
    rc = sql_error(db, err, "delete run: commit");
  if (rc) rollback(db);
  return rc;
}

int hd_db_list_resumable(hd_db *db, int64_t **ids, size_t *n, hd_error *err) {
  *ids = NULL;
  *n = 0;
  if (!db) return hd_error_set(err, HD_EIO, "database: not open");
  int rc = drain(db, err);
  if (rc) return rc;
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(db->db,
                         "SELECT id FROM runs WHERE status IN "
                         "('running','interrupted','failed') AND (EXISTS (SELECT 1 FROM "
                         "checkpoints c WHERE c.run = runs.id) OR status = 'running') "
                         "ORDER BY id",
                         -1, &st, NULL) != SQLITE_OK)
    return sql_error(db, err, "list resumable runs");
  size_t cap = 0;
  int s;
  while ((s = sqlite3_step(st)) == SQLITE_ROW) {
    if (*n == cap) {
      cap = cap ? 2 * cap : 16;
      int64_t *p = realloc(*ids, cap * sizeof *p);
      if (!p) {
        rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", db->path);
        break;
      }
      *ids = p;
    }
    (*ids)[(*n)++] = sqlite3_column_int64(st, 0);
  }
  if (!rc && s != SQLITE_DONE) rc = sql_error(db, err, "list resumable runs");
  sqlite3_finalize(st);
  if (rc) {
    free(*ids);
    *ids = NULL;
    *n = 0;
  }
  return rc;
}

int hd_db_find_resumable(hd_db *db, int64_t want_run, int64_t *run, char **scene_text,
                         unsigned long long *seed, hd_error *err) {
  if (!db) return hd_error_set(err, HD_EIO, "database: not open");
  if (scene_text) *scene_text = NULL;
  int drc = drain(db, err);
  if (drc) return drc;
  sqlite3_stmt *st = NULL;
  const char *sql = want_run > 0
                        ? "SELECT id, status, scene, seed FROM runs WHERE id = ?1"
                        : "SELECT id, status, scene, seed FROM runs "
                          "WHERE status IN ('running','interrupted','failed') AND (EXISTS "
                          "(SELECT 1 FROM checkpoints c WHERE c.run = runs.id) OR status = "
                          "'running') ORDER BY id DESC LIMIT 1";
  /* a run that failed in its set-up has no checkpoint; one left 'running' without it was
   * killed in its set-up, and is run again from the start */
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
                        "keeps its state at the collapse in `states` (label 'checkpoint')",
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

int hd_db_newest_run(const char *path, int64_t *run, char *status, size_t size, int *resumable,
                     hd_error *err) {
  *run = 0;
  status[0] = '\0';
  *resumable = 0;
  static const char *const need[] = {"runs", NULL};
  sqlite3 *h;
  int rc = hd_db_open_read(path, 0, need, &h, err);
  if (rc) return rc;
  sqlite3_busy_timeout(h, 10000);
  sqlite3_stmt *q;
  if (sqlite3_prepare_v2(h,
                         "SELECT id, status, EXISTS (SELECT 1 FROM checkpoints c WHERE c.run = "
                         "runs.id) FROM runs ORDER BY id DESC LIMIT 1",
                         -1, &q, NULL) == SQLITE_OK) {
    if (sqlite3_step(q) == SQLITE_ROW) {
      *run = sqlite3_column_int64(q, 0);
      snprintf(status, size, "%s", (const char *)sqlite3_column_text(q, 1));
      *resumable = sqlite3_column_int(q, 2);
    }
    sqlite3_finalize(q);
  } else {
    rc = hd_error_set(err, HD_EIO, "%s: read runs: %s", path, sqlite3_errmsg(h));
  }
  sqlite3_close(h);
  return rc;
}

int hd_db_read_species(sqlite3 *h, int64_t run, hd_shape *shape, int64_t *count, int max, int *n,
                       hd_error *err) {
  *n = 0;
  if (sqlite3_table_column_metadata(h, "main", "species", "disks", NULL, NULL, NULL, NULL, NULL) !=
      SQLITE_OK)
    return HD_OK; /* a file from before schema version 3 */
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(h, "SELECT idx, disks, count FROM species WHERE run = ?1 ORDER BY idx", -1,
                         &st, NULL) != SQLITE_OK)
    return hd_error_set(err, HD_EIO, "read species: %s", sqlite3_errmsg(h));
  sqlite3_bind_int64(st, 1, run);
  int s, rc = HD_OK;
  while (!rc && (s = sqlite3_step(st)) == SQLITE_ROW) {
    int idx = sqlite3_column_int(st, 0), k = 0;
    const char *p = (const char *)sqlite3_column_text(st, 1);
    double x[HD_MAX_BODY_DISKS], y[HD_MAX_BODY_DISKS], d[HD_MAX_BODY_DISKS], m[HD_MAX_BODY_DISKS];
    while (p && *p && k < HD_MAX_BODY_DISKS) {
      int used = 0;
      if (sscanf(p, " %lf %lf %lf %lf%n", &x[k], &y[k], &d[k], &m[k], &used) != 4) break;
      k++;
      p += used;
      while (*p == ' ' || *p == ';') p++;
    }
    if (*n == max || (p && *p) || hd_shape_cluster(&shape[*n], k, x, y, d, m, 1))
      rc = hd_error_set(err, HD_EINPUT, "run %lld: species %d: its disks are not a shape",
                        (long long)run, idx);
    else
      count[(*n)++] = sqlite3_column_int64(st, 2);
  }
  if (!rc && s != SQLITE_DONE)
    rc = hd_error_set(err, HD_EIO, "read species: %s", sqlite3_errmsg(h));
  sqlite3_finalize(st);
  return rc;
}
