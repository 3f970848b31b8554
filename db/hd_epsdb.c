/* hd_epsdb: the eps tables (engine/rods/eps.h) in the run database, tables eps_tables and
 * eps_table_points of db/schema.sql. */
#include "hd_epsdb.h"

#include <math.h>

extern const char hd_schema_sql[]; /* db/schema.sql, compiled in by the Makefile */

static int db_fail(sqlite3 *db, hd_error *err, const char *what) {
  return hd_error_set(err, HD_EIO, "eps table: %s: %s", what, sqlite3_errmsg(db));
}

int hd_eps_table_save(const hd_eps_table *t, sqlite3 *db, unsigned long seed, int64_t *id,
                      hd_error *err) {
  char *msg = NULL;
  if (sqlite3_exec(db, hd_schema_sql, NULL, NULL, &msg) != SQLITE_OK) {
    int rc = hd_error_set(err, HD_EIO, "eps table: schema: %s", msg ? msg : "?");
    sqlite3_free(msg);
    return rc;
  }
  if (sqlite3_exec(db, "BEGIN IMMEDIATE", NULL, NULL, NULL) != SQLITE_OK)
    return db_fail(db, err, "begin");
  sqlite3_stmt *st = NULL;
  int ok =
      sqlite3_prepare_v2(db,
                         "INSERT INTO eps_tables (gamma, gamma_eff, nbeta, nu, beta_min, "
                         "beta_max, samples, step, adapt, richardson, seed, seconds, created)"
                         " VALUES (?,?,?,?,?,?,?,?,?,?,?,?,strftime('%Y-%m-%dT%H:%M:%SZ','now'))",
                         -1, &st, NULL) == SQLITE_OK;
  if (ok) {
    sqlite3_bind_double(st, 1, t->gamma);
    sqlite3_bind_double(st, 2, t->gamma_eff);
    sqlite3_bind_int(st, 3, t->nbeta);
    sqlite3_bind_int(st, 4, t->nu);
    sqlite3_bind_double(st, 5, t->beta_min);
    sqlite3_bind_double(st, 6, t->beta_max);
    sqlite3_bind_int64(st, 7, t->samples);
    sqlite3_bind_double(st, 8, t->step);
    sqlite3_bind_int(st, 9, t->adapt);
    sqlite3_bind_int(st, 10, t->richardson);
    sqlite3_bind_int64(st, 11, (sqlite3_int64)seed);
    sqlite3_bind_double(st, 12, t->seconds);
    ok = sqlite3_step(st) == SQLITE_DONE;
  }
  sqlite3_finalize(st);
  st = NULL;
  sqlite3_int64 tab = sqlite3_last_insert_rowid(db);
  if (ok)
    ok = sqlite3_prepare_v2(db,
                            "INSERT INTO eps_table_points (tab, k, beta, j, u, eps) "
                            "VALUES (?,?,?,?,?,?)",
                            -1, &st, NULL) == SQLITE_OK;
  for (int k = 0; ok && k < t->nbeta; k++)
    for (int j = 0; ok && j < t->nu; j++) {
      sqlite3_bind_int64(st, 1, tab);
      sqlite3_bind_int(st, 2, k);
      sqlite3_bind_double(st, 3, hd_eps_table_beta(t, k));
      sqlite3_bind_int(st, 4, j);
      sqlite3_bind_double(st, 5, (double)j / (t->nu - 1));
      sqlite3_bind_double(st, 6, t->q[k * t->nu + j]);
      ok = sqlite3_step(st) == SQLITE_DONE;
      sqlite3_reset(st);
    }
  sqlite3_finalize(st);
  if (!ok) {
    int rc = db_fail(db, err, "insert");
    sqlite3_exec(db, "ROLLBACK", NULL, NULL, NULL);
    return rc;
  }
  if (sqlite3_exec(db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK) return db_fail(db, err, "commit");
  if (id) *id = tab;
  return HD_OK;
}
