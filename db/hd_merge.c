/* hd_merge: see hd_merge.h for the contract. */
#include "hd_merge.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hd_db.h"

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
  int fd = open(lk, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  struct flock fl;
  memset(&fl, 0, sizeof fl); /* l_start = l_len = 0: the whole file */
  fl.l_type = F_RDLCK;       /* a write lock of anyone on the bytes asked conflicts with it */
  fl.l_whence = SEEK_SET;
  if (run >= 0) fl.l_start = (off_t)run, fl.l_len = 1;
  int held = fcntl(fd, F_GETLK, &fl) == 0 && fl.l_type != F_UNLCK;
  close(fd);
  return held;
}

/* One statement with no result rows, path for the message. */
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
  if (sqlite3_open_v2(tmp, &dst, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, NULL) != SQLITE_OK) {
    rc = sql_fail(dst, tmp, "create", err);
  } else {
    sqlite3_backup *b = sqlite3_backup_init(dst, "main", src, "main");
    if (!b) {
      rc = sql_fail(dst, tmp, "copy the output database", err);
    } else {
      int s = sqlite3_backup_step(b, -1);
      sqlite3_backup_finish(b);
      if (s != SQLITE_DONE) rc = sql_fail(dst, tmp, "copy the output database", err);
    }
  }
  sqlite3_close(dst);
  sqlite3_close(src);
  return rc;
}

/* A growing string for SQL built from column names (identifiers quoted). */
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

/* Appends the rows of table t of the attached input s to main.t, with the column key (run, or
 * id for runs) shifted by temp.off; the columns both have.  Creates main.t from s's definition
 * when main lacks it. */
static int copy_table(sqlite3 *h, const char *tmp, const char *t, const char *key, hd_error *err) {
  sqlite3_stmt *st;
  int rc = HD_OK;
  /* the table in OUT, made as the input has it when missing (a user's table) */
  if ((rc = prepare(h,
                    "SELECT (SELECT count(*) FROM main.sqlite_schema WHERE type = 'table' "
                    "AND name = ?1), (SELECT sql FROM s.sqlite_schema WHERE type = 'table' "
                    "AND name = ?1)",
                    &st, tmp, "read the schema", err)))
    return rc;
  sqlite3_bind_text(st, 1, t, -1, SQLITE_STATIC);
  if (sqlite3_step(st) == SQLITE_ROW && sqlite3_column_int(st, 0) == 0) {
    const char *def = (const char *)sqlite3_column_text(st, 1);
    if (def) rc = exec(h, tmp, def, "create a table of the input", err);
  }
  sqlite3_finalize(st);
  if (rc) return rc;
  if ((rc = prepare(h,
                    "SELECT m.name FROM pragma_table_info(?1, 'main') m JOIN "
                    "pragma_table_info(?1, 's') i ON i.name = m.name ORDER BY m.cid",
                    &st, tmp, "read the columns", err)))
    return rc;
  sqlite3_bind_text(st, 1, t, -1, SQLITE_STATIC);
  sbuf cols = {0}, exprs = {0};
  int bad = 0, first = 1;
  while (!bad && sqlite3_step(st) == SQLITE_ROW) {
    const char *c = (const char *)sqlite3_column_text(st, 0);
    bad |= sb_add(&cols, first ? "\"%s\"" : ", \"%s\"", c);
    bad |= sb_add(&exprs, first ? "%s" : ", %s", "");
    bad |= sb_add(&exprs, strcmp(c, key) ? "s.\"%s\"" : "s.\"%s\" + (SELECT v FROM temp.off)", c);
    first = 0;
  }
  sqlite3_finalize(st);
  sbuf sql = {0};
  if (!bad && !first) {
    bad |= sb_add(&sql, "INSERT INTO main.\"%s\" (", t);
    bad |= sb_add(&sql, "%s) SELECT ", cols.s);
    bad |= sb_add(&sql, "%s FROM s.", exprs.s);
    bad |= sb_add(&sql, "\"%s\" AS s", t);
  }
  if (bad)
    rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", tmp);
  else if (!first)
    rc = exec(h, tmp, sql.s, "copy rows", err);
  free(cols.s);
  free(exprs.s);
  free(sql.s);
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
  if (!rc) rc = copy_table(h, tmp, "runs", "id", err);
  if (!rc) *runs += sqlite3_changes(h);
  /* every table of the input with a run column, but provenance (below) */
  if (!rc)
    rc = prepare(h,
                 "SELECT name FROM s.sqlite_schema t WHERE type = 'table' AND name "
                 "NOT IN ('runs', 'provenance') AND name NOT LIKE 'sqlite_%' AND "
                 "EXISTS (SELECT 1 FROM pragma_table_info(t.name, 's') WHERE "
                 "name = 'run') ORDER BY name",
                 &st, shown, "list tables", err);
  if (!rc) {
    char **names = NULL;
    int n = 0;
    while (rc == HD_OK && sqlite3_step(st) == SQLITE_ROW) {
      char **p = realloc(names, (size_t)(n + 1) * sizeof *p);
      char *name = strdup((const char *)sqlite3_column_text(st, 0));
      if (!p || !name) {
        free(p ? NULL : name);
        if (p) names = p;
        rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", tmp);
        break;
      }
      names = p;
      names[n++] = name;
    }
    sqlite3_finalize(st);
    for (int k = 0; k < n; k++) {
      if (!rc) rc = copy_table(h, tmp, names[k], "run", err);
      free(names[k]);
    }
    free(names);
  }
  if (rc) return rc;
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

int hd_db_merge(const char *out, const char *const *in, int n_in, int64_t *runs, hd_error *err) {
  int64_t nruns = 0;
  if (runs) *runs = 0;
  if (!out || !*out) return hd_error_set(err, HD_EINPUT, "merge: no output database given");
  if (n_in < 1) return hd_error_set(err, HD_EINPUT, "merge: no input databases given");
  struct stat so;
  int out_exists = stat(out, &so) == 0;
  if (out_exists && S_ISDIR(so.st_mode))
    return hd_error_set(err, HD_EINPUT, "%s: is a directory, not a database file", out);
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
    if (!rc && out_exists && so.st_dev == ids[k].st_dev && so.st_ino == ids[k].st_ino)
      rc = hd_error_set(err, HD_EINPUT, "%s: is the output database too: nothing merged", in[k]);
  }
  free(ids);
  for (int k = 0; k < n_in && !rc; k++) rc = check_input(in[k], err);
  if (!rc && out_exists && hd_merge_lock_held(out, -1))
    rc = hd_error_set(err, HD_EINPUT,
                      "%s: a run is writing to it (%s.lock is held): merge when it has ended", out,
                      out);
  if (!rc && out_exists) rc = check_input(out, err);
  if (rc) return rc;

  char tmp[PATH_MAX];
  if (snprintf(tmp, sizeof tmp, "%s.merge-%ld.tmp", out, (long)getpid()) >= (int)sizeof tmp)
    return hd_error_set(err, HD_EINPUT, "%s: path too long", out);
  remove_tmp(tmp);
  if (out_exists) rc = copy_out(out, tmp, err);
  hd_db *db = NULL;
  if (!rc) rc = hd_db_open(&db, tmp, err); /* the schema, brought to this haff's version */
  sqlite3 *h = db ? hd_db_handle(db) : NULL;
  if (!rc)
    rc =
        exec(h, tmp, "PRAGMA synchronous = OFF; CREATE TEMP TABLE off (v INTEGER)", "prepare", err);
  for (int k = 0; k < n_in && !rc; k++) {
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(h, "ATTACH ?1 AS s", -1, &st, NULL) != SQLITE_OK)
      rc = sql_fail(h, tmp, "attach", err);
    if (!rc) {
      sqlite3_bind_text(st, 1, in[k], -1, SQLITE_STATIC);
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
    if (sqlite3_open_v2(tmp, &h, SQLITE_OPEN_READWRITE, NULL) != SQLITE_OK)
      rc = sql_fail(h, tmp, "reopen", err);
    else
      rc = exec(h, tmp, "PRAGMA journal_mode = DELETE", "end the write-ahead log", err);
    sqlite3_close(h);
  }
  if (!rc) rc = sync_file(tmp, err);
  if (!rc && rename(tmp, out) != 0)
    rc = hd_error_set(err, HD_EIO, "%s: rename to %s: %s", tmp, out, strerror(errno));
  if (rc) {
    remove_tmp(tmp);
    return rc;
  }
  if (runs) *runs = nruns;
  return HD_OK;
}
