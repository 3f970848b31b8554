/* libFuzzer target: haff merge's inputs (db/hd_merge.c, hd_db_merge).  The first byte picks how
 * the input database is made from the rest:
 *   even: page level: the bytes are the input file itself (a database image; the seeds are
 *         small haff databases, page size 512, that the fuzzer mutates page by page);
 *   odd:  SQL level: the bytes are SQL run on a copy of a valid haff database (one run with
 *         rows in every per-run table) before the merge: tables added, dropped, renamed or
 *         altered, names with quotes, rows of any type (ATTACH and VACUUM refused: they would
 *         write other files).
 * The input is then merged into a copy of a fixed OUT holding one run.  What must hold: no
 * crash or sanitizer report; a refused merge leaves OUT byte for byte as it was and no
 * temporary file; a merge that succeeds keeps OUT's run (same id, scene and rows) and adds at
 * most the input's runs.  Seeds: tests/fuzz/corpus/merge/. */
#include <dirent.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sqlite3.h>
#include <unistd.h>

#include "hd_db.h"
#include "hd_merge.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char dir[64], in_path[128], out_path[128], tmpl_in[128], tmpl_out[128];
static unsigned char *out_bytes;
static size_t out_size;

/* Writes a haff database at path with one run (seed) and a row in each per-run table. */
static void make_db(const char *path, int seed) {
  sqlite3 *h;
  if (sqlite3_open(path, &h) != SQLITE_OK ||
      sqlite3_exec(h, "PRAGMA page_size = 512", NULL, NULL, NULL) != SQLITE_OK)
    abort();
  sqlite3_close(h);
  hd_db *db;
  hd_error err;
  int64_t run;
  char scene[64];
  snprintf(scene, sizeof scene, "[system]\nseed = %d\n", seed);
  if (hd_db_open(&db, path, &err) ||
      hd_db_run_begin(db, scene, (unsigned long long)seed, "fuzz", &run, &err))
    abort();
  hd_collision_row c = {
      .seq = 1, .t = 0.5, .kind = hd_coll_kind_of(HD_KIND_DISK, HD_KIND_DISK), .j = 1, .f = 0.5};
  hd_sample_row s = {.t = 1, .cpd = 1, .e_tr = 1, .e_rot = 0};
  hd_species_rec sp = {2, "tri", "0 0 1 1", 2, 1, 0};
  hd_species_sample ss = {1, 2, 1, 0};
  hd_state_rec st = {.body = 0, .kind = 0, .x = 1, .y = 1};
  unsigned char frame[36] = {0};
  if (hd_db_log_collision(db, run, &c, &err) || hd_db_log_sample(db, run, &s, &err) ||
      hd_db_log_species(db, run, &sp, &err) || hd_db_log_species_sample(db, run, &ss, &err) ||
      hd_db_log_state(db, run, "initial", &st, &err) ||
      hd_db_log_frame(db, run, 1, 1, 1, frame, sizeof frame, &err) ||
      hd_db_checkpoint_save(db, run, 1, 1, "ck", 2, &err) ||
      hd_db_run_origin(db, run, "host", NULL, NULL, &err) ||
      hd_db_run_status(db, run, "done", 1, 0.1, &err) || hd_db_close(db, &err))
    abort();
  if (sqlite3_open(path, &h) != SQLITE_OK ||
      sqlite3_exec(h, "PRAGMA journal_mode = DELETE", NULL, NULL, NULL) != SQLITE_OK)
    abort();
  sqlite3_close(h);
}

static unsigned char *slurp(const char *path, size_t *n) {
  FILE *f = fopen(path, "rb");
  if (!f) abort();
  fseek(f, 0, SEEK_END);
  long len = ftell(f);
  rewind(f);
  unsigned char *b = malloc(len > 0 ? (size_t)len : 1);
  if (!b || fread(b, 1, (size_t)len, f) != (size_t)len) abort();
  fclose(f);
  *n = (size_t)len;
  return b;
}

static void spill(const char *path, const void *b, size_t n) {
  FILE *f = fopen(path, "wb");
  if (!f || (n && fwrite(b, 1, n, f) != n) || fclose(f)) abort();
}

/* Removes path and SQLite's files beside it. */
static void rm_db(const char *path) {
  static const char *const side[] = {"", "-wal", "-shm", "-journal"};
  for (int k = 0; k < 4; k++) {
    char p[160];
    snprintf(p, sizeof p, "%s%s", path, side[k]);
    unlink(p);
  }
}

static int deny_files(void *arg, int action, const char *a, const char *b, const char *c,
                      const char *d) {
  (void)arg, (void)a, (void)b, (void)c, (void)d;
  return action == SQLITE_ATTACH || action == SQLITE_DETACH ? SQLITE_DENY : SQLITE_OK;
}

static int too_long(void *arg) {
  return ++*(int *)arg > 2000; /* 2000 * 1000 virtual machine steps */
}

/* One value of sql on path, -1 when it fails. */
static long long q1(const char *path, const char *sql) {
  sqlite3 *h;
  long long v = -1;
  if (sqlite3_open_v2(path, &h, SQLITE_OPEN_READONLY, NULL) == SQLITE_OK) {
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(h, sql, -1, &st, NULL) == SQLITE_OK) {
      if (sqlite3_step(st) == SQLITE_ROW) v = sqlite3_column_int64(st, 0);
      sqlite3_finalize(st);
    }
  }
  sqlite3_close(h);
  return v;
}

/* Removes the working folder when the fuzzer ends (libFuzzer exits through exit()). */
static void cleanup(void) {
  DIR *d = opendir(dir);
  for (struct dirent *e; d && (e = readdir(d));) {
    char p[400];
    snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
    if (e->d_name[0] != '.') unlink(p);
  }
  if (d) closedir(d);
  rmdir(dir);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (!dir[0]) {
    snprintf(dir, sizeof dir, "/tmp/haff-fuzz-merge-XXXXXX");
    if (!mkdtemp(dir)) abort();
    snprintf(in_path, sizeof in_path, "%s/in.db", dir);
    snprintf(out_path, sizeof out_path, "%s/out.db", dir);
    snprintf(tmpl_in, sizeof tmpl_in, "%s/tmpl-in.db", dir);
    snprintf(tmpl_out, sizeof tmpl_out, "%s/tmpl-out.db", dir);
    make_db(tmpl_in, 2);
    make_db(tmpl_out, 1);
    out_bytes = slurp(tmpl_out, &out_size);
    atexit(cleanup);
  }
  if (size < 1 || size > (1 << 20)) return 0;
  rm_db(in_path);
  rm_db(out_path);
  if (!(data[0] & 1)) {
    spill(in_path, data + 1, size - 1);
  } else {
    char *sql = malloc(size);
    if (!sql) abort();
    memcpy(sql, data + 1, size - 1);
    sql[size - 1] = 0;
    size_t n;
    unsigned char *b = slurp(tmpl_in, &n);
    spill(in_path, b, n);
    free(b);
    int ok = !strcasestr(sql, "vacuum");
    sqlite3 *h;
    if (ok && sqlite3_open(in_path, &h) == SQLITE_OK) {
      int steps = 0;
      sqlite3_set_authorizer(h, deny_files, NULL);
      sqlite3_progress_handler(h, 1000, too_long, &steps);
      sqlite3_exec(h, sql, NULL, NULL, NULL);
      sqlite3_close(h);
    }
    free(sql);
    if (!ok) return 0;
  }
  spill(out_path, out_bytes, out_size);
  long long in_runs = q1(in_path, "SELECT count(*) FROM runs");
  const char *in[1] = {in_path};
  int64_t runs = 0;
  hd_error err;
  int rc = hd_db_merge(out_path, in, 1, &runs, &err);
  if (rc != HD_OK) { /* OUT as it was, nothing left beside it */
    size_t n;
    unsigned char *b = slurp(out_path, &n);
    if (n != out_size || memcmp(b, out_bytes, n)) abort();
    free(b);
  } else {
    if (q1(out_path, "SELECT count(*) FROM runs WHERE id = 1 AND seed = 1") != 1 ||
        q1(out_path, "SELECT count(*) FROM collisions WHERE run = 1") != 1 ||
        q1(out_path, "SELECT count(*) FROM sample_species WHERE run = 1") != 1 ||
        (in_runs >= 0 && runs > in_runs) || runs < 0)
      abort();
  }
  DIR *d = opendir(dir); /* no OUT.merge-PID.tmp */
  for (struct dirent *e; d && (e = readdir(d));)
    if (strstr(e->d_name, ".merge-")) abort();
  if (d) closedir(d);
  return 0;
}
