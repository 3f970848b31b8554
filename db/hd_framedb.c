/* hd_framedb: reading a run's frames back (hd_framedb.h). */
#include "hd_framedb.h"

#include <stdlib.h>
#include <string.h>

struct hd_framedb {
  sqlite3 *h;
  sqlite3_stmt *st;
};

static int sql_fail(sqlite3 *h, hd_error *err) {
  return hd_error_set(err, HD_EIO, "%s", sqlite3_errmsg(h));
}

int hd_framedb_run_read(sqlite3 *h, int64_t want, hd_framedb_run *r, hd_error *err) {
  memset(r, 0, sizeof *r);
  sqlite3_stmt *st = NULL;
  const char *sql = want > 0 ? "SELECT id, scene, box_x, box_y FROM runs WHERE id = ?1"
                             : "SELECT id, scene, box_x, box_y FROM runs ORDER BY id DESC LIMIT 1";
  if (sqlite3_prepare_v2(h, sql, -1, &st, NULL) != SQLITE_OK) return sql_fail(h, err);
  if (want > 0) sqlite3_bind_int64(st, 1, want);
  if (sqlite3_step(st) != SQLITE_ROW) {
    sqlite3_finalize(st);
    return hd_error_set(err, HD_EINPUT, "%s",
                        want > 0 ? "there is no such run" : "the database holds no run");
  }
  r->id = sqlite3_column_int64(st, 0);
  r->box_x = sqlite3_column_double(st, 2);
  r->box_y = sqlite3_column_double(st, 3);
  const char *scene = (const char *)sqlite3_column_text(st, 1);
  int rc = HD_OK;
  if (scene && !(r->scene = strdup(scene)))
    rc = hd_error_set(err, HD_ENOMEM, "out of memory for the scene of run %lld", (long long)r->id);
  sqlite3_finalize(st);
  return rc;
}

int hd_framedb_kinds(sqlite3 *h, int64_t run, int *kinds, long n, int dimer_kind, int disk_kind,
                     hd_error *err) {
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(h,
                         "SELECT body, kind FROM states WHERE run = ?1 AND label = 'initial' "
                         "AND t = (SELECT min(t) FROM states WHERE run = ?1 AND label = 'initial')",
                         -1, &st, NULL) != SQLITE_OK)
    return sql_fail(h, err);
  sqlite3_bind_int64(st, 1, run);
  while (sqlite3_step(st) == SQLITE_ROW) {
    long long b = sqlite3_column_int64(st, 0);
    const char *k = (const char *)sqlite3_column_text(st, 1);
    if (b >= 0 && b < n) kinds[b] = k && !strcmp(k, "dimer") ? dimer_kind : disk_kind;
  }
  sqlite3_finalize(st);
  return HD_OK;
}

int hd_framedb_open(sqlite3 *h, int64_t run, hd_framedb **out, hd_error *err) {
  *out = NULL;
  if (sqlite3_table_column_metadata(h, "main", "frames", "data", NULL, NULL, NULL, NULL, NULL) !=
      SQLITE_OK) /* a database from before the frames table */
    return hd_error_set(err, HD_EINPUT, "run %lld has no frames", (long long)run);
  hd_framedb *fr = calloc(1, sizeof *fr);
  if (!fr) return hd_error_set(err, HD_ENOMEM, "out of memory");
  fr->h = h;
  if (sqlite3_prepare_v2(h, "SELECT t, cpd, n, data FROM frames WHERE run = ?1 ORDER BY t, rowid",
                         -1, &fr->st, NULL) != SQLITE_OK) {
    free(fr);
    return sql_fail(h, err);
  }
  sqlite3_bind_int64(fr->st, 1, run);
  *out = fr;
  return HD_OK;
}

int hd_framedb_next(hd_framedb *fr, hd_framedb_frame *f, hd_error *err) {
  int s = sqlite3_step(fr->st);
  if (s == SQLITE_DONE) return 0;
  if (s != SQLITE_ROW) {
    sql_fail(fr->h, err);
    return -1;
  }
  f->t = sqlite3_column_double(fr->st, 0);
  f->cpd = sqlite3_column_double(fr->st, 1);
  f->n = (long)sqlite3_column_int64(fr->st, 2);
  f->data = sqlite3_column_blob(fr->st, 3);
  f->bytes = sqlite3_column_bytes(fr->st, 3);
  return 1;
}

void hd_framedb_close(hd_framedb *fr) {
  if (!fr) return;
  sqlite3_finalize(fr->st);
  free(fr);
}
