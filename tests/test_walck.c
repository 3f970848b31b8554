/* Tests of db/hd_walck.c, the thread that checkpoints the write-ahead log off the writer's path.
 * In WAL mode the main database file is written only by checkpoints, so its size tells whether
 * (and by whom) a checkpoint ran. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "hd_walck.h"

typedef struct fixture {
  char dir[64];
  char path[128];
  sqlite3 *w;
} fixture;

static int setup(void **state) {
  fixture *fx = calloc(1, sizeof *fx);
  if (!fx) return -1;
  snprintf(fx->dir, sizeof fx->dir, "/tmp/haff-walck-XXXXXX");
  if (!mkdtemp(fx->dir)) return -1;
  snprintf(fx->path, sizeof fx->path, "%s/w.db", fx->dir);
  if (sqlite3_open(fx->path, &fx->w) != SQLITE_OK) return -1;
  if (sqlite3_exec(fx->w, "PRAGMA journal_mode=WAL; CREATE TABLE t (x BLOB)", NULL, NULL, NULL))
    return -1;
  *state = fx;
  return 0;
}

static int teardown(void **state) {
  fixture *fx = *state;
  sqlite3_close(fx->w);
  char p[160];
  const char *suffix[] = {"", "-wal", "-shm"};
  for (int k = 0; k < 3; k++) snprintf(p, sizeof p, "%s%s", fx->path, suffix[k]), unlink(p);
  rmdir(fx->dir);
  free(fx);
  return 0;
}

static long file_size(const char *path) {
  struct stat st;
  return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* Commits `tx` transactions of 100 rows of 1000-byte blobs: about 25 log frames each. */
static void write_rows(sqlite3 *w, int tx) {
  sqlite3_stmt *st;
  assert_int_equal(sqlite3_prepare_v2(w, "INSERT INTO t VALUES (randomblob(1000))", -1, &st, NULL),
                   SQLITE_OK);
  for (int k = 0; k < tx; k++) {
    assert_int_equal(sqlite3_exec(w, "BEGIN", NULL, NULL, NULL), SQLITE_OK);
    for (int r = 0; r < 100; r++) {
      assert_int_equal(sqlite3_step(st), SQLITE_DONE);
      sqlite3_reset(st);
    }
    assert_int_equal(sqlite3_exec(w, "COMMIT", NULL, NULL, NULL), SQLITE_OK);
  }
  sqlite3_finalize(st);
}

static long count_rows(const char *path) {
  sqlite3 *r;
  sqlite3_stmt *st;
  long n = -1;
  assert_int_equal(sqlite3_open_v2(path, &r, SQLITE_OPEN_READONLY, NULL), SQLITE_OK);
  assert_int_equal(sqlite3_prepare_v2(r, "SELECT count(*) FROM t", -1, &st, NULL), SQLITE_OK);
  if (sqlite3_step(st) == SQLITE_ROW) n = (long)sqlite3_column_int64(st, 0);
  sqlite3_finalize(st);
  assert_int_equal(sqlite3_prepare_v2(r, "PRAGMA integrity_check", -1, &st, NULL), SQLITE_OK);
  assert_int_equal(sqlite3_step(st), SQLITE_ROW);
  assert_string_equal((const char *)sqlite3_column_text(st, 0), "ok");
  sqlite3_finalize(st);
  sqlite3_close(r);
  return n;
}

/* With the checkpointer running, the log is copied back into the database file by the thread:
 * the file grows by the rows written (~6 MB here, 60 commits of ~25 frames, well past the
 * HD_WALCK_FRAMES threshold).  We wait for it up to 60 s (it takes milliseconds; the margin is
 * for a loaded machine and the sanitizer build). */
static void test_checkpoints_in_background(void **state) {
  fixture *fx = *state;
  hd_walck *c = NULL;
  hd_error err;
  long s0 = file_size(fx->path);
  assert_int_equal(hd_walck_start(&c, fx->w, fx->path, &err), HD_OK);
  assert_non_null(c);
  write_rows(fx->w, 60);
  long s = s0;
  for (int k = 0; k < 6000 && s < s0 + (2L << 20); k++) {
    struct timespec ts = {0, 10000000};
    nanosleep(&ts, NULL);
    s = file_size(fx->path);
  }
  assert_true(s >= s0 + (2L << 20)); /* at least one checkpoint of >= 1000 frames ran */
  hd_walck_stop(c);
  assert_int_equal(count_rows(fx->path), 6000);
}

/* After hd_walck_stop the writer checkpoints on its own again, inside its COMMIT: the file has
 * grown as soon as the commits return. */
static void test_stop_gives_automatic_checkpoints_back(void **state) {
  fixture *fx = *state;
  hd_walck *c = NULL;
  hd_error err;
  assert_int_equal(hd_walck_start(&c, fx->w, fx->path, &err), HD_OK);
  hd_walck_stop(c);
  long s0 = file_size(fx->path);
  write_rows(fx->w, 60); /* ~1500 frames: SQLite's automatic checkpoint at 1000 */
  assert_true(file_size(fx->path) >= s0 + (2L << 20));
  assert_int_equal(count_rows(fx->path), 6000);
}

/* The log restarts from its beginning once in a while, however long the writer goes on: after
 * 16000 frames (4x HD_WALCK_RESTART, ~64 MB) the -wal file is at most HD_WALCK_RESTART frames
 * plus a commit (25-30 frames; we allow 60) of 4096 + 24 bytes each; without the restart it
 * would hold every frame.  The bound is exact (the writer's last checkpoint past HD_WALCK_RESTART
 * copies every frame, so its next transaction restarts the log), not a matter of timing. */
static void test_log_stays_bounded(void **state) {
  fixture *fx = *state;
  hd_walck *c = NULL;
  hd_error err;
  assert_int_equal(hd_walck_start(&c, fx->w, fx->path, &err), HD_OK);
  write_rows(fx->w, 640);
  long wal = 0;
  char p[160];
  snprintf(p, sizeof p, "%s-wal", fx->path);
  wal = file_size(p);
  hd_walck_stop(c);
  assert_true(wal > 0);
  assert_true(wal <= (HD_WALCK_RESTART + 60L) * (4096 + 24) + 32);
  assert_int_equal(count_rows(fx->path), 64000);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup_teardown(test_checkpoints_in_background, setup, teardown),
      cmocka_unit_test_setup_teardown(test_stop_gives_automatic_checkpoints_back, setup, teardown),
      cmocka_unit_test_setup_teardown(test_log_stays_bounded, setup, teardown),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
