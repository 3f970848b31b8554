/* hd_merge: see hd_merge.h for the contract. */
#include "hd_merge.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hd_db.h"
#include "hd_lock.h"
#include "hd_path.h"
#include "hd_stop.h"

static const char *const need_runs[] = {"runs", NULL};

/* HD_EIO "what: sqlite's message" for connection h, naming path. */
static int sql_fail(sqlite3 *h, const char *path, const char *what, hd_error *err) {
  return hd_error_set(err, HD_EIO, "%s: %s: %s", path, what, sqlite3_errmsg(h));
}

/* Prepares sql on h into *st; HD_OK, or sql_fail(path, what). */
static int prepare(sqlite3 *h, const char *sql, sqlite3_stmt **st, const char *path,
                   const char *what, hd_error *err) {
  if (sqlite3_prepare_v2(h, sql, -1, st, NULL) == SQLITE_OK) return HD_OK;
  return sql_fail(h, path, what, err);
}

/* Checks that path is a haff database that passes PRAGMA integrity_check. */
static int check_input(const char *path, hd_error *err) {
  sqlite3 *h;
  int rc = hd_db_open_read(path, 0, need_runs, &h, err);
  if (rc) return rc;
  sqlite3_busy_timeout(h, 10000);
  sqlite3_stmt *st;
  int version = -1; /* a schema from a newer haff: columns this one would drop unseen */
  if (sqlite3_prepare_v2(h, "PRAGMA user_version", -1, &st, NULL) == SQLITE_OK) {
    if (sqlite3_step(st) == SQLITE_ROW) version = sqlite3_column_int(st, 0);
    sqlite3_finalize(st);
  }
  if (version > HD_DB_SCHEMA_VERSION) {
    sqlite3_close(h);
    return hd_error_set(err, HD_EINPUT,
                        "%s: schema version %d is newer than this haff's (%d): merge it with a "
                        "newer haff",
                        path, version, HD_DB_SCHEMA_VERSION);
  }
  if (sqlite3_prepare_v2(h, "PRAGMA integrity_check", -1, &st, NULL) != SQLITE_OK) {
    rc = sql_fail(h, path, "integrity check", err);
  } else {
    int s = sqlite3_step(st);
    const char *v = s == SQLITE_ROW ? (const char *)sqlite3_column_text(st, 0) : NULL;
    if (s != SQLITE_ROW)
      rc = sql_fail(h, path, "integrity check", err);
    else if (!v || strcmp(v, "ok"))
      rc = hd_error_set(err, HD_EINPUT, "%s: fails PRAGMA integrity_check: %s", path,
                        v ? v : "(no answer)");
    sqlite3_finalize(st);
  }
  sqlite3_close(h);
  return rc;
}

int hd_merge_lock_held(const char *path, long long run) {
  char lk[PATH_MAX + 256];
  snprintf(lk, sizeof lk, "%s.lock", path);
  int fd = hd_lock_open(lk, 0);
  if (fd < 0) return 0;
  /* a read lock asked about: a write lock of anyone on the bytes asked conflicts with it;
   * start = len = 0: the whole file */
  hd_lock_who who;
  int held =
      hd_lock_holder(fd, run >= 0 ? (off_t)run : 0, run >= 0 ? 1 : 0, 0, &who) == 0 && who.pid != 0;
  close(fd);
  return held;
}

/* Fixed statements with no result rows (never text read from a file), path for the message. */
static int exec(sqlite3 *h, const char *path, const char *sql, const char *what, hd_error *err) {
  char *msg = NULL;
  if (sqlite3_exec(h, sql, NULL, NULL, &msg) != SQLITE_OK) {
    hd_error_set(err, HD_EIO, "%s: %s: %s", path, what, msg ? msg : sqlite3_errmsg(h));
    sqlite3_free(msg);
    return HD_EIO;
  }
  return HD_OK;
}

/* Copies OUT (an existing haff database) into the fresh file tmp with SQLite's backup API. */
static int copy_out(const char *out, const char *tmp, hd_error *err) {
  sqlite3 *src, *dst = NULL;
  int rc = hd_db_open_read(out, 0, need_runs, &src, err);
  if (rc) return rc;
  sqlite3_busy_timeout(src, 10000);
  char plain[PATH_MAX + 8];
  const char *name = hd_db_plain_name(tmp, plain, sizeof plain);
  if (!name ||
      sqlite3_open_v2(name, &dst, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, NULL) != SQLITE_OK) {
    rc = sql_fail(dst, tmp, "create", err);
  } else {
    sqlite3_backup *b = sqlite3_backup_init(dst, "main", src, "main");
    if (!b) {
      rc = sql_fail(dst, tmp, "copy the output database", err);
    } else {
      int s; /* 4096 pages at a time (16 MB), a stop asked for heard in between */
      while ((s = sqlite3_backup_step(b, 4096)) == SQLITE_OK && !hd_stop_requested) {
      }
      sqlite3_backup_finish(b);
      if (hd_stop_requested)
        rc = hd_error_set(err, HD_EINTR, "%s: interrupted by a signal: nothing merged", out);
      else if (s != SQLITE_DONE)
        rc = sql_fail(dst, tmp, "copy the output database", err);
    }
  }
  sqlite3_close(dst);
  sqlite3_close(src);
  return rc;
}

/* A growing string for the statements of copy_rows and copy_user (made of names checked before). */
typedef struct sbuf {
  char *s;
  size_t n, cap;
} sbuf;

static int sb_add(sbuf *b, const char *fmt, const char *arg) {
  int need = snprintf(NULL, 0, fmt, arg);
  if (b->n + (size_t)need + 1 > b->cap) {
    size_t cap = 2 * (b->n + (size_t)need + 1) + 256;
    char *p = realloc(b->s, cap);
    if (!p) return -1;
    b->s = p;
    b->cap = cap;
  }
  snprintf(b->s + b->n, b->cap - b->n, fmt, arg);
  b->n += (size_t)need;
  return 0;
}

/* Whether name is a plain SQL identifier (a letter or _, then letters, digits and _; at most
 * 64 bytes; not SQLite's own sqlite_*): the only names of a user's table or column that merge
 * writes into a statement, so that no name read from a file can change what it does. */
static int plain_identifier(const char *name) {
  size_t n = name ? strlen(name) : 0;
  if (n == 0 || n > 64 || !strncasecmp(name, "sqlite_", 7)) return 0;
  for (size_t k = 0; k < n; k++) {
    unsigned char c = (unsigned char)name[k];
    if (!(c == '_' || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
          (k && c >= '0' && c <= '9')))
      return 0;
  }
  return 1;
}

/* The names of haff's tables and their columns, from db/schema.sql (compiled in), in a
 * database in memory: the trusted side of every name merge puts in a statement. */
extern const char hd_schema_sql[];

static int open_schema(sqlite3 **mem, hd_error *err) {
  if (sqlite3_open_v2(":memory:", mem, SQLITE_OPEN_READWRITE, NULL) != SQLITE_OK ||
      sqlite3_exec(*mem, hd_schema_sql, NULL, NULL, NULL) != SQLITE_OK) {
    hd_error_set(err, HD_EIO, "merge: cannot read haff's own schema: %s",
                 *mem ? sqlite3_errmsg(*mem) : "out of memory");
    sqlite3_close(*mem);
    *mem = NULL;
    return HD_EIO;
  }
  return HD_OK;
}

/* Copies the rows of table t of the attached input s to main.t, the columns cols[0..n) (names
 * checked by the caller), the column key (run, or id for runs) shifted by temp.off: one fixed
 * statement with no value of the input in its text. */
static int copy_rows(sqlite3 *h, const char *tmp, const char *t, const char *key,
                     const char *const *cols, int n, hd_error *err) {
  if (n == 0) return HD_OK;
  sbuf sql = {0};
  int bad = sb_add(&sql, "INSERT INTO main.\"%s\" (", t);
  for (int k = 0; k < n; k++) bad |= sb_add(&sql, k ? ", \"%s\"" : "\"%s\"", cols[k]);
  bad |= sb_add(&sql, ") SELECT %s", "");
  for (int k = 0; k < n; k++) {
    bad |= sb_add(&sql, k ? ", " : "%s", "");
    bad |= sb_add(&sql, strcmp(cols[k], key) ? "s.\"%s\"" : "s.\"%s\" + (SELECT v FROM temp.off)",
                  cols[k]);
  }
  bad |= sb_add(&sql, " FROM s.\"%s\" AS s", t);
  int rc = HD_OK;
  sqlite3_stmt *st = NULL;
  if (bad) {
    rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", tmp);
  } else if (sqlite3_prepare_v2(h, sql.s, -1, &st, NULL) != SQLITE_OK) { /* one statement */
    rc = sql_fail(h, tmp, "copy rows", err);
  } else if (sqlite3_step(st) != SQLITE_DONE) {
    rc = sql_fail(h, tmp, "copy rows", err);
  }
  sqlite3_finalize(st);
  free(sql.s);
  return rc;
}

/* Whether the attached input s has table t with column c (c NULL: the table). */
static int input_has(sqlite3 *h, const char *t, const char *c) {
  sqlite3_stmt *st;
  const char *sql = c ? "SELECT count(*) FROM pragma_table_info(?1, 's') WHERE name = ?2"
                      : "SELECT count(*) FROM s.sqlite_schema WHERE type = 'table' AND name = ?1";
  if (sqlite3_prepare_v2(h, sql, -1, &st, NULL) != SQLITE_OK) return 0;
  sqlite3_bind_text(st, 1, t, -1, SQLITE_STATIC);
  if (c) sqlite3_bind_text(st, 2, c, -1, SQLITE_STATIC);
  int has = sqlite3_step(st) == SQLITE_ROW && sqlite3_column_int(st, 0) > 0;
  sqlite3_finalize(st);
  return has;
}

/* Copies haff's table t (a name of db/schema.sql) of the input to main: the columns of haff's
 * schema (mem) that the input has (an older file lacks the later ones: NULL in OUT). */
static int copy_known(sqlite3 *h, sqlite3 *mem, const char *tmp, const char *t, const char *key,
                      hd_error *err) {
  if (!input_has(h, t, NULL)) return HD_OK; /* a file older than the table */
  sqlite3_stmt *st;
  if (sqlite3_prepare_v2(mem, "SELECT name FROM pragma_table_info(?1) ORDER BY cid", -1, &st,
                         NULL) != SQLITE_OK)
    return sql_fail(mem, tmp, "read haff's schema", err);
  sqlite3_bind_text(st, 1, t, -1, SQLITE_STATIC);
  char *cols[64];
  int n = 0, rc = HD_OK;
  while (n < 64 && sqlite3_step(st) == SQLITE_ROW) {
    const char *c = (const char *)sqlite3_column_text(st, 0);
    if (!input_has(h, t, c)) continue;
    if (!(cols[n] = strdup(c))) {
      rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", tmp);
      break;
    }
    n++;
  }
  sqlite3_finalize(st);
  if (!rc) rc = copy_rows(h, tmp, t, key, (const char *const *)cols, n, err);
  for (int k = 0; k < n; k++) free(cols[k]);
  return rc;
}

/* SQLite's affinity of a declared column type, as one of five fixed words (its rules: section
 * 3.1 of https://www.sqlite.org/datatype3.html). */
static const char *affinity(const char *decl) {
  char u[128];
  size_t k = 0;
  for (; decl && decl[k] && k + 1 < sizeof u; k++)
    u[k] = (char)((decl[k] >= 'a' && decl[k] <= 'z') ? decl[k] - 32 : decl[k]);
  u[k] = 0;
  if (strstr(u, "INT")) return "INTEGER";
  if (strstr(u, "CHAR") || strstr(u, "CLOB") || strstr(u, "TEXT")) return "TEXT";
  if (!u[0] || strstr(u, "BLOB")) return "BLOB";
  if (strstr(u, "REAL") || strstr(u, "FLOA") || strstr(u, "DOUB")) return "REAL";
  return "NUMERIC";
}

/* A user's table t of the input with a run column (plots/scripts/run.sh's plots_runs): its
 * name and columns must be plain identifiers (else HD_EINPUT: nothing merged); created in
 * main when missing, with the input's columns and their affinities (no constraint of the
 * input's definition is copied: its text is never run), and its rows copied with run shifted. */
static int copy_user(sqlite3 *h, const char *tmp, const char *shown, const char *t, hd_error *err) {
  if (!plain_identifier(t))
    return hd_error_set(err, HD_EINPUT,
                        "%s: a table with a run column whose name is not a plain identifier "
                        "(letters, digits, _): not a haff database to merge; nothing merged",
                        shown);
  sqlite3_stmt *st;
  if (prepare(h,
              "SELECT i.name, i.type, (SELECT count(*) FROM pragma_table_info(?1, 'main') m "
              "WHERE m.name = i.name) FROM pragma_table_info(?1, 's') i ORDER BY i.cid",
              &st, shown, "read the columns", err))
    return HD_EIO;
  sqlite3_bind_text(st, 1, t, -1, SQLITE_STATIC);
  char *cols[64];
  int n = 0, rc = HD_OK;
  sbuf def = {0};
  int main_has = 0;
  {
    sqlite3_stmt *q;
    if (sqlite3_prepare_v2(h,
                           "SELECT count(*) FROM main.sqlite_schema WHERE type = 'table' AND "
                           "name = ?1",
                           -1, &q, NULL) == SQLITE_OK) {
      sqlite3_bind_text(q, 1, t, -1, SQLITE_STATIC);
      main_has = sqlite3_step(q) == SQLITE_ROW && sqlite3_column_int(q, 0) > 0;
      sqlite3_finalize(q);
    }
  }
  int bad = main_has ? 0 : sb_add(&def, "CREATE TABLE main.\"%s\" (", t);
  while (!rc && sqlite3_step(st) == SQLITE_ROW) {
    const char *c = (const char *)sqlite3_column_text(st, 0);
    const char *type = (const char *)sqlite3_column_text(st, 1);
    int in_main = sqlite3_column_int(st, 2) > 0;
    if (!plain_identifier(c)) {
      rc = hd_error_set(err, HD_EINPUT,
                        "%s: table %s has a column whose name is not a plain identifier "
                        "(letters, digits, _): nothing merged",
                        shown, t);
      break;
    }
    if (n == 64) {
      rc = hd_error_set(err, HD_EINPUT, "%s: table %s has more than 64 columns: nothing merged",
                        shown, t);
      break;
    }
    if (!main_has) {
      bad |= sb_add(&def, n ? ", \"%s\"" : "\"%s\"", c);
      bad |= sb_add(&def, " %s", affinity(type));
    } else if (!in_main) {
      continue; /* OUT's table lacks it */
    }
    if (!(cols[n] = strdup(c)))
      bad = 1;
    else
      n++;
  }
  sqlite3_finalize(st);
  if (!rc && bad) rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", tmp);
  if (!rc && !main_has) {
    bad |= sb_add(&def, ")%s", "");
    if (bad)
      rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", tmp);
    else if (sqlite3_prepare_v2(h, def.s, -1, &st, NULL) != SQLITE_OK)
      rc = sql_fail(h, tmp, "create a table of the input", err);
    else {
      if (sqlite3_step(st) != SQLITE_DONE)
        rc = sql_fail(h, tmp, "create a table of the input", err);
      sqlite3_finalize(st);
    }
  }
  free(def.s);
  if (!rc) rc = copy_rows(h, tmp, t, "run", (const char *const *)cols, n, err);
  for (int k = 0; k < n; k++) free(cols[k]);
  return rc;
}

/* The input's tables with a run column that are not haff's (mem: haff's schema), in *names
 * (malloc'd, *n of them); HD_OK or HD_ENOMEM / HD_EIO. */
static int user_tables(sqlite3 *h, sqlite3 *mem, const char *tmp, const char *shown, char ***names,
                       int *n, hd_error *err) {
  *names = NULL, *n = 0;
  sqlite3_stmt *st, *known;
  if (prepare(h,
              "SELECT name FROM s.sqlite_schema t WHERE type = 'table' AND EXISTS (SELECT 1 FROM "
              "pragma_table_info(t.name, 's') WHERE name = 'run') ORDER BY name",
              &st, shown, "list tables", err))
    return HD_EIO;
  if (sqlite3_prepare_v2(mem, "SELECT count(*) FROM sqlite_schema WHERE name = ?1", -1, &known,
                         NULL) != SQLITE_OK) {
    sqlite3_finalize(st);
    return sql_fail(mem, tmp, "read haff's schema", err);
  }
  int rc = HD_OK;
  while (!rc && sqlite3_step(st) == SQLITE_ROW) {
    const char *t = (const char *)sqlite3_column_text(st, 0);
    sqlite3_bind_text(known, 1, t, -1, SQLITE_TRANSIENT);
    int ours = sqlite3_step(known) == SQLITE_ROW && sqlite3_column_int(known, 0) > 0;
    sqlite3_reset(known);
    if (ours) continue;
    char **p = realloc(*names, (size_t)(*n + 1) * sizeof *p);
    char *name = p ? strdup(t) : NULL;
    if (p) *names = p;
    if (!name) {
      rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", tmp);
      break;
    }
    (*names)[(*n)++] = name;
  }
  sqlite3_finalize(st);
  sqlite3_finalize(known);
  return rc;
}

/* Appends every run of input path (attached as s) to main; *runs counts them. */
static int merge_one(sqlite3 *h, const char *tmp, const char *path, const char *shown,
                     const char *out, int64_t *runs, hd_error *err) {
  sqlite3_stmt *st;
  int rc = HD_OK;
  /* a run already present: the same identity, scene text, seed and commit (runs.git_commit;
   * 'unknown' for NULL and for an input from before schema version 4, which has no column) */
  int s_commit = 0;
  if (sqlite3_prepare_v2(h,
                         "SELECT count(*) FROM pragma_table_info('runs', 's') WHERE name = "
                         "'git_commit'",
                         -1, &st, NULL) == SQLITE_OK) {
    if (sqlite3_step(st) == SQLITE_ROW) s_commit = sqlite3_column_int(st, 0);
    sqlite3_finalize(st);
  }
  if ((rc = prepare(h,
                    s_commit ? "SELECT s.id, m.id, s.seed FROM s.runs s JOIN main.runs m ON "
                               "m.scene = s.scene AND m.seed = s.seed AND coalesce(m.git_commit, "
                               "'unknown') = coalesce(s.git_commit, 'unknown') "
                               "ORDER BY s.id LIMIT 1"
                             : "SELECT s.id, m.id, s.seed FROM s.runs s JOIN main.runs m ON "
                               "m.scene = s.scene AND m.seed = s.seed AND coalesce(m.git_commit, "
                               "'unknown') = 'unknown' ORDER BY s.id LIMIT 1",
                    &st, shown, "compare runs", err)))
    return rc;
  if (sqlite3_step(st) == SQLITE_ROW)
    rc = hd_error_set(err, HD_EINPUT,
                      "%s: run %lld (seed %lld) is already in %s as run %lld (the same scene, "
                      "seed and commit): nothing merged",
                      shown, (long long)sqlite3_column_int64(st, 0),
                      (long long)sqlite3_column_int64(st, 2), out,
                      (long long)sqlite3_column_int64(st, 1));
  sqlite3_finalize(st);
  if (rc) return rc;
  rc = exec(h, tmp,
            "DELETE FROM temp.off; INSERT INTO temp.off SELECT coalesce(max(id), 0) FROM main.runs",
            "number the runs", err);
  sqlite3 *mem = NULL;
  if (!rc) rc = open_schema(&mem, err);
  if (!rc) rc = copy_known(h, mem, tmp, "runs", "id", err);
  if (!rc) *runs += sqlite3_changes(h);
  /* haff's tables with a run column (the one list, db/hd_db.c), but provenance (below) */
  for (const hd_run_table *k = hd_db_run_tables(); !rc && k->name; k++)
    if (strcmp(k->name, "provenance")) rc = copy_known(h, mem, tmp, k->name, "run", err);
  /* an input of schema version 0 to 4: its table samples (not the view of version 5) into
   * sample_rows and, for the per-species columns sample_species lacks, sample_species */
  if (!rc) rc = hd_db_samples_convert(h, "s", "(SELECT v FROM temp.off)", shown, err);
  /* and a user's tables with a run column, their names checked */
  char **names = NULL;
  int n = 0;
  if (!rc) rc = user_tables(h, mem, tmp, shown, &names, &n, err);
  for (int k = 0; k < n; k++) {
    if (!rc) rc = copy_user(h, tmp, shown, names[k], err);
    free(names[k]);
  }
  free(names);
  sqlite3_close(mem);
  /* provenance: carried over, with the file and id it came from (kept when already set: a run
   * merged twice names the file it was made in); an older input's runs get a row too */
  int has_prov = 0;
  if (sqlite3_prepare_v2(h,
                         "SELECT count(*) FROM s.sqlite_schema WHERE type = 'table' AND name = "
                         "'provenance'",
                         -1, &st, NULL) == SQLITE_OK) {
    if (sqlite3_step(st) == SQLITE_ROW) has_prov = sqlite3_column_int(st, 0);
    sqlite3_finalize(st);
  }
  char abs[PATH_MAX];
  const char *src = realpath(path, abs) ? abs : path;
  const char *sql_prov =
      "INSERT INTO main.provenance (run, host, slurm_job, slurm_task, source, source_run, merged) "
      "SELECT p.run + (SELECT v FROM temp.off), p.host, p.slurm_job, p.slurm_task, "
      "coalesce(p.source, ?1), coalesce(p.source_run, p.run), "
      "coalesce(p.merged, strftime('%Y-%m-%dT%H:%M:%SZ','now')) FROM s.provenance p "
      "WHERE p.run IN (SELECT id FROM s.runs)";
  const char *sql_rest =
      has_prov ? "INSERT INTO main.provenance (run, source, source_run, merged) SELECT "
                 "r.id + (SELECT v FROM temp.off), ?1, r.id, strftime('%Y-%m-%dT%H:%M:%SZ','now') "
                 "FROM s.runs r WHERE r.id NOT IN (SELECT run FROM s.provenance)"
               : "INSERT INTO main.provenance (run, source, source_run, merged) SELECT "
                 "r.id + (SELECT v FROM temp.off), ?1, r.id, strftime('%Y-%m-%dT%H:%M:%SZ','now') "
                 "FROM s.runs r";
  for (int k = has_prov ? 0 : 1; k < 2 && !rc; k++) {
    if (sqlite3_prepare_v2(h, k ? sql_rest : sql_prov, -1, &st, NULL) != SQLITE_OK)
      return sql_fail(h, shown, "copy provenance", err);
    sqlite3_bind_text(st, 1, src, -1, SQLITE_TRANSIENT);
    if (sqlite3_step(st) != SQLITE_DONE) rc = sql_fail(h, shown, "copy provenance", err);
    sqlite3_finalize(st);
  }
  return rc;
}

/* Removes tmp and the files SQLite may have left beside it. */
static void remove_tmp(const char *tmp) {
  char p[PATH_MAX + 8];
  unlink(tmp);
  snprintf(p, sizeof p, "%s-wal", tmp);
  unlink(p);
  snprintf(p, sizeof p, "%s-shm", tmp);
  unlink(p);
  snprintf(p, sizeof p, "%s-journal", tmp);
  unlink(p);
}

/* Flushes file path to the disk (before it is renamed into place). */
static int sync_file(const char *path, hd_error *err) {
  int fd = open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0 || fsync(fd) != 0) {
    int e = errno;
    if (fd >= 0) close(fd);
    return hd_error_set(err, HD_EIO, "%s: sync: %s", path, strerror(e));
  }
  close(fd);
  return HD_OK;
}

/* Whether SQLite, or a reader of haff's command lines, gives name a meaning other than the
 * file of that name: "-" (stdin, stdout), ":memory:" and "" (databases in memory), "file:..." (a
 * URI).  Such a name is refused as OUT; "./NAME" is the file. */
static const char *special_name(const char *name) {
  if (!strcmp(name, "-")) return "stands for stdin or stdout, not a database file";
  if (!strcmp(name, ":memory:")) return "names SQLite's database in memory, not a file";
  if (!strncmp(name, "file:", 5)) return "reads as an SQLite URI, not a file name";
  return NULL;
}

/* SIGINT and SIGTERM during a merge: the stop flag, which the merge polls (progress handler,
 * backup steps), so that it fails and removes its temporary file; a second signal acts as
 * the default (SA_RESETHAND). */
static void on_signal(int sig) {
  (void)sig;
  hd_stop_requested = 1;
}

/* SQLite's progress handler: a non-zero answer interrupts the statement. */
static int stop_asked(void *arg) {
  (void)arg;
  return hd_stop_requested != 0;
}

/* What OUT and its log look like (existence, inode, size, modification time), to tell at the
 * end whether another process changed OUT while the merge was built from its copy. */
typedef struct out_look {
  int exists[2];
  struct stat st[2];
} out_look;

static void look_at(const char *out, out_look *l) {
  char wal[PATH_MAX + 8];
  snprintf(wal, sizeof wal, "%s-wal", out);
  const char *p[2] = {out, wal};
  memset(l, 0, sizeof *l);
  for (int k = 0; k < 2; k++) l->exists[k] = stat(p[k], &l->st[k]) == 0;
}

static int same_look(const out_look *a, const out_look *b) {
  for (int k = 0; k < 2; k++) {
    if (a->exists[k] != b->exists[k]) return 0;
    if (!a->exists[k]) continue;
    const struct stat *x = &a->st[k], *y = &b->st[k];
    if (x->st_ino != y->st_ino || x->st_dev != y->st_dev || x->st_size != y->st_size ||
        x->st_mtim.tv_sec != y->st_mtim.tv_sec || x->st_mtim.tv_nsec != y->st_mtim.tv_nsec)
      return 0;
  }
  return 1;
}

/* The merge proper, after the signals are set: see hd_db_merge. */
static int merge(const char *out, const char *const *in, int n_in, int64_t *runs, hd_error *err) {
  int64_t nruns = 0;
  const char *why = special_name(out);
  if (why)
    return hd_error_set(err, HD_EINPUT,
                        "%s: %s (give ./%s for a file of that name): nothing merged", out, why,
                        out);
  struct stat so;
  int out_exists = stat(out, &so) == 0;
  if (out_exists && S_ISDIR(so.st_mode))
    return hd_error_set(err, HD_EINPUT, "%s: is a directory, not a database file", out);
  /* the rename at the end replaces a name: through a symbolic link, the file it leads to (not
   * the link); a file of more names (hard links) would be replaced under this one only */
  struct stat sl;
  char real[PATH_MAX];
  if (lstat(out, &sl) == 0 && S_ISLNK(sl.st_mode)) {
    if (!out_exists || !realpath(out, real))
      return hd_error_set(err, HD_EINPUT,
                          "%s: a symbolic link to no file: give the database's own name", out);
    out = real;
  }
  if (out_exists && so.st_nlink > 1)
    return hd_error_set(err, HD_EINPUT,
                        "%s: has %ld hard links: the merge would replace it under this name only; "
                        "nothing merged",
                        out, (long)so.st_nlink);
  /* each file once: the same file (by device and inode, whatever the path) given twice */
  struct stat *ids = calloc((size_t)n_in, sizeof *ids);
  if (!ids) return hd_error_set(err, HD_ENOMEM, "merge: out of memory");
  int rc = HD_OK;
  for (int k = 0; k < n_in && !rc; k++) {
    rc = hd_db_check_path(in[k], 1, err);
    if (!rc && stat(in[k], &ids[k]) != 0)
      rc = hd_error_set(err, HD_EINPUT, "%s: %s", in[k], strerror(errno));
    for (int j = 0; j < k && !rc; j++)
      if (ids[j].st_dev == ids[k].st_dev && ids[j].st_ino == ids[k].st_ino)
        rc = hd_error_set(err, HD_EINPUT, "%s: given twice (also as %s): nothing merged", in[k],
                          in[j]);
    if (!rc && hd_path_overwrites(out, in[k])) /* the same file, or its SQLite log */
      rc = hd_error_set(err, HD_EINPUT, "%s: is the output database too: nothing merged", in[k]);
  }
  free(ids);
  for (int k = 0; k < n_in && !rc; k++)
    if (hd_merge_lock_held(in[k], -1)) /* its running run would be copied half-way */
      rc = hd_error_set(err, HD_EINPUT,
                        "%s: a run is writing to it (%s.lock is held): merge it when it has "
                        "ended; nothing merged",
                        in[k], in[k]);
  if (!rc && out_exists && !(so.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)))
    rc = hd_error_set(err, HD_EINPUT,
                      "%s: is write-protected (mode %03o): nothing merged (chmod u+w to merge "
                      "into it)",
                      out, (unsigned)(so.st_mode & 0777));
  for (int k = 0; k < n_in && !rc; k++) rc = check_input(in[k], err);
  if (!rc && out_exists && hd_merge_lock_held(out, -1))
    rc = hd_error_set(err, HD_EINPUT,
                      "%s: a run is writing to it (%s.lock is held): merge when it has ended", out,
                      out);
  if (!rc && out_exists) rc = check_input(out, err);
  if (rc) return rc;

  char tmp[PATH_MAX], plain[PATH_MAX + 8];
  const char *tmp_name = NULL; /* tmp as SQLite opens a plain file */
  if (snprintf(tmp, sizeof tmp, "%s.merge-%ld.tmp", out, (long)getpid()) >= (int)sizeof tmp ||
      !(tmp_name = hd_db_plain_name(tmp, plain, sizeof plain)))
    return hd_error_set(err, HD_EINPUT, "%s: path too long", out);
  remove_tmp(tmp);
  out_look before, after;
  look_at(out, &before);
  if (out_exists) rc = copy_out(out, tmp, err);
  hd_db *db = NULL;
  if (!rc) rc = hd_db_open(&db, tmp, err); /* the schema, brought to this haff's version */
  sqlite3 *h = db ? hd_db_handle(db) : NULL;
  if (h) sqlite3_progress_handler(h, 10000, stop_asked, NULL);
  if (!rc)
    rc =
        exec(h, tmp, "PRAGMA synchronous = OFF; CREATE TEMP TABLE off (v INTEGER)", "prepare", err);
  for (int k = 0; k < n_in && !rc; k++) {
    sqlite3_stmt *st;
    char buf[PATH_MAX + 8];
    const char *name = hd_db_plain_name(in[k], buf, sizeof buf); /* ":memory:": ./:memory: */
    if (!name)
      rc = hd_error_set(err, HD_EINPUT, "%s: path too long", in[k]);
    else if (sqlite3_prepare_v2(h, "ATTACH ?1 AS s", -1, &st, NULL) != SQLITE_OK)
      rc = sql_fail(h, tmp, "attach", err);
    if (!rc) {
      sqlite3_bind_text(st, 1, name, -1, SQLITE_STATIC);
      if (sqlite3_step(st) != SQLITE_DONE) rc = sql_fail(h, in[k], "attach", err);
      sqlite3_finalize(st);
    }
    if (rc) break;
    rc = exec(h, tmp, "BEGIN IMMEDIATE", "begin", err);
    if (!rc) rc = merge_one(h, tmp, in[k], in[k], out, &nruns, err);
    if (!rc) rc = exec(h, tmp, "COMMIT", "commit", err);
    if (rc) sqlite3_exec(h, "ROLLBACK", NULL, NULL, NULL);
    int drc = exec(h, tmp, "DETACH s", "detach", rc ? NULL : err);
    if (!rc) rc = drc;
  }
  if (!rc) rc = hd_db_build_indexes(db, err);
  hd_error e2;
  int crc = hd_db_close(db, &e2);
  if (!rc && crc) *err = e2, rc = crc;
  if (!rc) { /* one self-contained file to rename: the log copied back and removed */
    if (sqlite3_open_v2(tmp_name, &h, SQLITE_OPEN_READWRITE, NULL) != SQLITE_OK)
      rc = sql_fail(h, tmp, "reopen", err);
    else
      rc = exec(h, tmp, "PRAGMA journal_mode = DELETE", "end the write-ahead log", err);
    sqlite3_close(h);
  }
  if (!rc && out_exists && chmod(tmp, so.st_mode & 07777) != 0) /* OUT keeps its mode */
    rc = hd_error_set(err, HD_EIO, "%s: chmod: %s", tmp, strerror(errno));
  if (!rc) rc = sync_file(tmp, err);
  if (!rc && hd_stop_requested) /* a signal between two statements */
    rc = hd_error_set(err, HD_EINTR, "%s: interrupted by a signal: nothing merged", out);
  /* another merge or a run that wrote OUT meanwhile: its rows would be lost by the rename */
  if (!rc) look_at(out, &after);
  if (!rc && !same_look(&before, &after))
    rc = hd_error_set(err, HD_EINPUT,
                      "%s: changed while the merge was made (another merge or a run writing to "
                      "it): nothing merged; merge again",
                      out);
  if (!rc && !out_exists && renameat2(AT_FDCWD, tmp, AT_FDCWD, out, RENAME_NOREPLACE) != 0)
    rc =
        hd_error_set(err, errno == EEXIST ? HD_EINPUT : HD_EIO, "%s: rename to %s: %s%s", tmp, out,
                     strerror(errno),
                     errno == EEXIST ? " (made by another process meanwhile): nothing merged" : "");
  if (!rc && out_exists && rename(tmp, out) != 0)
    rc = hd_error_set(err, HD_EIO, "%s: rename to %s: %s", tmp, out, strerror(errno));
  if (rc) {
    if (hd_stop_requested && rc != HD_EINTR) /* SQLite's "interrupted", said plainly */
      rc = hd_error_set(err, HD_EINTR, "%s: interrupted by a signal: nothing merged", out);
    remove_tmp(tmp);
    return rc;
  }
  if (runs) *runs = nruns;
  return HD_OK;
}

int hd_db_merge(const char *out, const char *const *in, int n_in, int64_t *runs, hd_error *err) {
  if (runs) *runs = 0;
  if (!out || !*out) return hd_error_set(err, HD_EINPUT, "merge: no output database given");
  if (n_in < 1) return hd_error_set(err, HD_EINPUT, "merge: no input databases given");
  struct sigaction sa, old_int, old_term;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sa.sa_flags = SA_RESETHAND;
  sigemptyset(&sa.sa_mask);
  hd_stop_requested = 0;
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);
  int rc = merge(out, in, n_in, runs, err);
  sigaction(SIGINT, &old_int, NULL);
  sigaction(SIGTERM, &old_term, NULL);
  hd_stop_requested = 0;
  return rc;
}
