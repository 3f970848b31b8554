/* Tests of db/hd_db.c, the example queries of db/queries/ and `haff export xyz`.
 * Every test works in its own mkdtemp folder.  Crashes are real: a forked child that is
 * killed with SIGKILL in the middle of a batch. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gsl/gsl_rng.h>
#include <gsl/gsl_statistics_double.h>

#include "hd_anaspecies.h"
#include "hd_db.h"
#include "hd_merge.h"

int hd_cmd_export(int argc, char **argv);

/* ---------------------------------------------------------------------------------------- */
/* helpers */

/* |a - b| <= tol * max(1, |b|): relative for large values, absolute below 1. */
#define assert_close(a, b, tol)                                                                    \
  do {                                                                                             \
    double a_ = (a), b_ = (b);                                                                     \
    if (!(fabs(a_ - b_) <= (tol)*fmax(1.0, fabs(b_))))                                             \
      fail_msg("%s = %.17g, want %.17g (tol %g)", #a, a_, b_, (double)(tol));                      \
  } while (0)

typedef struct fixture {
  char dir[256];
  char path[320]; /* dir/run.db */
} fixture;

/* Runs sql on db's connection after every row logged so far is written (hd_db_handle drains the
 * writer): HD_OK, or HD_EIO with SQLite's message (was hd_db_exec of the store, which nothing
 * but these tests called). */
static int db_exec(hd_db *db, const char *sql, hd_error *err) {
  sqlite3 *h = hd_db_handle(db);
  if (sqlite3_exec(h, sql, NULL, NULL, NULL) == SQLITE_OK) return HD_OK;
  return hd_error_set(err, HD_EIO, "%s: exec: %s", hd_db_path(db), sqlite3_errmsg(h));
}

static int setup(void **state) {
  fixture *fx = calloc(1, sizeof *fx);
  if (!fx) return -1;
  const char *tmp = getenv("TMPDIR");
  snprintf(fx->dir, sizeof fx->dir, "%s/haff-test-db-XXXXXX", tmp && *tmp ? tmp : "/tmp");
  if (!mkdtemp(fx->dir)) return -1;
  snprintf(fx->path, sizeof fx->path, "%s/run.db", fx->dir);
  *state = fx;
  return 0;
}

static int teardown(void **state) {
  fixture *fx = *state;
  chmod(fx->dir, 0700);
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", fx->dir);
  int rc = system(cmd);
  free(fx);
  return rc == 0 ? 0 : -1;
}

static hd_db *open_ok(const char *path) {
  hd_db *db = NULL;
  hd_error err;
  hd_error_clear(&err);
  int rc = hd_db_open(&db, path, &err);
  if (rc) fprintf(stderr, "open: %s\n", err.msg);
  assert_int_equal(rc, HD_OK);
  return db;
}

static void close_ok(hd_db *db) {
  hd_error err;
  hd_error_clear(&err);
  int rc = hd_db_close(db, &err);
  if (rc) fprintf(stderr, "close: %s\n", err.msg);
  assert_int_equal(rc, HD_OK);
}

/* A single integer from sql on handle h. */
static long long q_int(sqlite3 *h, const char *sql) {
  sqlite3_stmt *st = NULL;
  assert_int_equal(sqlite3_prepare_v2(h, sql, -1, &st, NULL), SQLITE_OK);
  assert_int_equal(sqlite3_step(st), SQLITE_ROW);
  long long v = sqlite3_column_int64(st, 0);
  sqlite3_finalize(st);
  return v;
}

/* A count through a second, independent connection (what another process would see). */
static long long count_other(const char *path, const char *sql) {
  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open_v2(path, &h, SQLITE_OPEN_READWRITE, NULL), SQLITE_OK);
  long long v = q_int(h, sql);
  sqlite3_close(h);
  return v;
}

static void assert_integrity_ok(const char *path) {
  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open_v2(path, &h, SQLITE_OPEN_READWRITE, NULL), SQLITE_OK);
  sqlite3_stmt *st = NULL;
  assert_int_equal(sqlite3_prepare_v2(h, "PRAGMA integrity_check", -1, &st, NULL), SQLITE_OK);
  assert_int_equal(sqlite3_step(st), SQLITE_ROW);
  assert_string_equal((const char *)sqlite3_column_text(st, 0), "ok");
  sqlite3_finalize(st);
  sqlite3_close(h);
}

/* The collision kinds of the paper's runs (dimers, disks, walls, rods) by number 0 .. 5:
 * dimer-dimer, dimer-disk, disk-disk, dimer-wall, disk-wall, rod-rod. */
enum { NCK = 6, CK_ROD = 5 };
static hd_coll_kind ck(int k) {
  static const hd_kind a[NCK] = {HD_KIND_DIMER, HD_KIND_DIMER, HD_KIND_DISK,
                                 HD_KIND_DIMER, HD_KIND_DISK,  HD_KIND_ROD};
  static const hd_kind b[NCK] = {HD_KIND_DIMER, HD_KIND_DISK, HD_KIND_DISK,
                                 HD_KIND_WALL,  HD_KIND_WALL, HD_KIND_ROD};
  return hd_coll_kind_of(a[k], b[k]);
}

static hd_collision_row coll(int64_t seq) {
  hd_collision_row r = {.seq = seq,
                        .t = 0.01 * (double)seq,
                        .kind = ck(0),
                        .i = seq % 7,
                        .j = seq % 5 + 7,
                        .disk_i = 0,
                        .disk_j = 1,
                        .theta_i = 0.25,
                        .theta_j = -0.5,
                        .f = 0.7,
                        .de = -0.01,
                        .vn = -0.3,
                        .eps = NAN,
                        .e_tr = NAN,
                        .tb_i = NAN,
                        .tb_j = NAN};
  return r;
}

static int64_t begin_run(hd_db *db, const char *scene, unsigned long long seed) {
  int64_t run = 0;
  hd_error err;
  assert_int_equal(hd_db_run_begin(db, scene, seed, "test", &run, &err), HD_OK);
  assert_true(run > 0);
  return run;
}

/* ---------------------------------------------------------------------------------------- */
/* round trip */

static void round_trip(void **state) {
  fixture *fx = *state;
  hd_error err;
  hd_db *db = open_ok(fx->path);
  const unsigned long long seed = 0x8000000000000005ULL; /* >= 2^63: stored as int64 */
  int64_t run = begin_run(db, "[system]\nbox = 3 4\n", seed);
  assert_int_equal(hd_db_run_box(db, run, 3.0, 4.0, &err), HD_OK);

  /* every collision kind once, with NaN in theta_j, f and vn for some */
  for (int k = 0; k < NCK; k++) {
    hd_collision_row r = {.seq = k + 1,
                          .t = 0.5 + k,
                          .kind = ck(k),
                          .i = k,
                          .j = k == 3 ? -2 : k + 1,
                          .disk_i = k % 2,
                          .disk_j = -1,
                          .theta_i = 0.125 * k,
                          .theta_j = k % 2 ? NAN : -0.25,
                          .f = k == 2 ? NAN : 0.6,
                          .de = -0.5 * k,
                          .vn = k == 4 ? NAN : -1.0,
                          .eps = 0.5,
                          .e_tr = 1.0,
                          .tb_i = 2.0,
                          .tb_j = 3.0};
    assert_int_equal(hd_db_log_collision(db, run, &r, &err), HD_OK);
  }
  hd_sample_row s = {1.25, 42, 0.84, 0.75, 0.5, NAN, NAN, NAN, NAN, NAN, NAN};
  assert_int_equal(hd_db_log_sample(db, run, &s, &err), HD_OK);
  hd_state_rec st0 = {0.0, 0, 1, 1.5, 2.5, -0.5, 0.1, 0.2, 3.0, NAN, 0};
  hd_state_rec st1 = {2.0, 1, 0, 0.5, 0.25, 0.0, -0.1, 0.3, 0.0, 1.5, 1};
  hd_state_rec st2 = {2.0, 2, HD_KIND_ROD, 7.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.5, -1};
  assert_int_equal(hd_db_log_state(db, run, "initial", &st0, &err), HD_OK);
  assert_int_equal(hd_db_log_state(db, run, "final", &st1, &err), HD_OK);
  assert_int_equal(hd_db_log_state(db, run, "final", &st2, &err), HD_OK);
  hd_state_rec bad = st1;
  bad.kind = 9;
  assert_int_equal(hd_db_log_state(db, run, "final", &bad, &err), HD_EINPUT);
  assert_int_equal(hd_db_run_status(db, run, "bogus", 1, 1.0, &err), HD_EINPUT);
  assert_non_null(strstr(err.msg, "bogus"));
  assert_int_equal(hd_db_run_status(db, run, "done", 1234, 5.5, &err), HD_OK);
  assert_int_equal(hd_db_run_message(db, run, "all fine", &err), HD_OK);
  assert_int_equal(hd_db_run_status(db, 999, "done", 1, 1.0, &err), HD_EINPUT);
  assert_int_equal(hd_db_build_indexes(db, &err), HD_OK);
  close_ok(db);

  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open(fx->path, &h), SQLITE_OK);
  /* runs */
  sqlite3_stmt *q = NULL;
  assert_int_equal(sqlite3_prepare_v2(h,
                                      "SELECT scene, seed, status, started, finished, version, "
                                      "events, wall_seconds, message, box_x, box_y FROM runs",
                                      -1, &q, NULL),
                   SQLITE_OK);
  assert_int_equal(sqlite3_step(q), SQLITE_ROW);
  assert_string_equal((const char *)sqlite3_column_text(q, 0), "[system]\nbox = 3 4\n");
  assert_true((unsigned long long)sqlite3_column_int64(q, 1) == seed);
  assert_string_equal((const char *)sqlite3_column_text(q, 2), "done");
  const char *started = (const char *)sqlite3_column_text(q, 3);
  /* ISO 8601 UTC: YYYY-MM-DDTHH:MM:SSZ */
  assert_int_equal(strlen(started), 20);
  assert_true(started[4] == '-' && started[10] == 'T' && started[19] == 'Z');
  assert_int_not_equal(sqlite3_column_type(q, 4), SQLITE_NULL);
  assert_string_equal((const char *)sqlite3_column_text(q, 5), "test");
  assert_int_equal(sqlite3_column_int64(q, 6), 1234);
  assert_true(sqlite3_column_double(q, 7) == 5.5);
  assert_string_equal((const char *)sqlite3_column_text(q, 8), "all fine");
  assert_true(sqlite3_column_double(q, 9) == 3.0 && sqlite3_column_double(q, 10) == 4.0);
  sqlite3_finalize(q);

  /* collisions */
  static const char *const kinds[] = {"dimer-dimer", "dimer-disk", "disk-disk",
                                      "dimer-wall",  "disk-wall",  "rod-rod"};
  assert_int_equal(sqlite3_prepare_v2(h,
                                      "SELECT seq, t, kind, i, j, disk_i, disk_j, theta_i, "
                                      "theta_j, f, de, vn, eps, e_tr, tb_i, tb_j FROM collisions "
                                      "ORDER BY seq",
                                      -1, &q, NULL),
                   SQLITE_OK);
  for (int k = 0; k < NCK; k++) {
    assert_int_equal(sqlite3_step(q), SQLITE_ROW);
    assert_int_equal(sqlite3_column_int64(q, 0), k + 1);
    assert_true(sqlite3_column_double(q, 1) == 0.5 + k);
    assert_string_equal((const char *)sqlite3_column_text(q, 2), kinds[k]);
    assert_string_equal(hd_coll_kind_name(ck(k)), kinds[k]);
    assert_int_equal(sqlite3_column_int64(q, 3), k);
    assert_int_equal(sqlite3_column_int64(q, 4), k == 3 ? -2 : k + 1);
    assert_int_equal(sqlite3_column_int(q, 5), k % 2);
    assert_int_equal(sqlite3_column_int(q, 6), -1);
    assert_true(sqlite3_column_double(q, 7) == 0.125 * k);
    if (k % 2)
      assert_int_equal(sqlite3_column_type(q, 8), SQLITE_NULL);
    else
      assert_true(sqlite3_column_double(q, 8) == -0.25);
    if (k == 2)
      assert_int_equal(sqlite3_column_type(q, 9), SQLITE_NULL);
    else
      assert_true(sqlite3_column_double(q, 9) == 0.6);
    assert_true(sqlite3_column_double(q, 10) == -0.5 * k);
    if (k == 4)
      assert_int_equal(sqlite3_column_type(q, 11), SQLITE_NULL);
    else
      assert_true(sqlite3_column_double(q, 11) == -1.0);
    /* rod columns: stored for rod-rod only, NULL for the other kinds */
    for (int c = 12; c < 16; c++)
      if (k == CK_ROD)
        assert_true(sqlite3_column_double(q, c) == (c == 12 ? 0.5 : c - 12.0));
      else
        assert_int_equal(sqlite3_column_type(q, c), SQLITE_NULL);
  }
  assert_int_equal(sqlite3_step(q), SQLITE_DONE);
  sqlite3_finalize(q);

  /* samples (NaN in them: nan_in_not_null_column) */
  assert_int_equal(q_int(h, "SELECT count(*) FROM samples WHERE t = 1.25 AND collisions = 42 "
                            "AND cpd = 0.84 AND e_tr = 0.75 AND e_rot = 0.5"),
                   1);
  /* states: kinds as text, cpd NaN -> NULL */
  assert_int_equal(q_int(h, "SELECT count(*) FROM states WHERE label = 'initial' AND body = 0 "
                            "AND kind = 'dimer' AND x = 1.5 AND y = 2.5 AND phi = -0.5 AND "
                            "vx = 0.1 AND vy = 0.2 AND omega = 3.0 AND cpd IS NULL AND t = 0"),
                   1);
  assert_int_equal(q_int(h, "SELECT count(*) FROM states WHERE label = 'final' AND body = 1 "
                            "AND kind = 'disk' AND cpd = 1.5 AND t = 2.0 AND vy = 0.3"),
                   1);
  assert_int_equal(q_int(h, "SELECT count(*) FROM states WHERE kind = 'rod' AND x = 7"), 1);
  assert_int_equal(q_int(h, "SELECT count(*) FROM sqlite_schema WHERE type = 'index' AND "
                            "name IN ('collisions_run_seq', 'collisions_run_kind', "
                            "'samples_run_t', 'states_run_label_t', 'checkpoints_run')"),
                   5);
  assert_int_equal(sqlite3_prepare_v2(h, "PRAGMA journal_mode", -1, &q, NULL), SQLITE_OK);
  assert_int_equal(sqlite3_step(q), SQLITE_ROW);
  assert_string_equal((const char *)sqlite3_column_text(q, 0), "wal");
  sqlite3_finalize(q);
  sqlite3_close(h);
}

/* The samples row with e_rot = NaN: e_rot is NOT NULL in the schema, so NaN there is an
 * error that names the column, not a silent 0. */
static void nan_in_not_null_column(void **state) {
  fixture *fx = *state;
  hd_error err;
  hd_db *db = open_ok(fx->path);
  int64_t run = begin_run(db, "", 1);
  hd_sample_row ok = {1.0, 1, 0.5, 1.0, 2.0, NAN, NAN, NAN, NAN, NAN, NAN};
  assert_int_equal(hd_db_log_sample(db, run, &ok, &err), HD_OK);
  assert_int_equal(hd_db_commit(db, &err), HD_OK);
  hd_sample_row s = {1.0, 1, 0.5, 1.0, 2.0, NAN, NAN, NAN, NAN, NAN, NAN};
  assert_int_equal(hd_db_log_sample(db, run, &s, &err), HD_OK); /* batch opened */
  s.e_rot = NAN;
  /* rows are written by a writer thread: the error comes with the next call that waits for it */
  assert_int_equal(hd_db_log_sample(db, run, &s, &err), HD_OK);
  assert_int_equal(hd_db_commit(db, &err), HD_EIO);
  assert_non_null(strstr(err.msg, fx->path));
  assert_non_null(strstr(err.msg, "sample_rows.e_rot")); /* the table haff writes */
  /* the failed batch is rolled back whole: only the committed first row remains */
  assert_int_equal(count_other(fx->path, "SELECT count(*) FROM samples"), 1);
  assert_int_equal(hd_db_log_sample(db, run, &ok, &err), HD_OK); /* usable afterwards */
  close_ok(db);
  assert_int_equal(count_other(fx->path, "SELECT count(*) FROM samples"), 2);
}

/* ---------------------------------------------------------------------------------------- */
/* batches and crashes */

static void batches_and_kill9(void **state) {
  fixture *fx = *state;
  hd_error err;
  hd_db *db = open_ok(fx->path);
  hd_db_set_batch_rows(db, 100);
  int64_t run = begin_run(db, "", 7);
  for (int64_t k = 1; k <= 250; k++) {
    hd_collision_row r = coll(k);
    assert_int_equal(hd_db_log_collision(db, run, &r, &err), HD_OK);
    /* another connection sees whole batches only, while this one is writing (hd_db_handle
     * waits for the writer thread to have written every row logged so far) */
    if (k == 150) {
      (void)hd_db_handle(db);
      assert_int_equal(count_other(fx->path, "SELECT count(*) FROM collisions"), 100);
    }
  }
  (void)hd_db_handle(db);
  assert_int_equal(count_other(fx->path, "SELECT count(*) FROM collisions"), 200);
  assert_int_equal(hd_db_commit(db, &err), HD_OK);
  assert_int_equal(count_other(fx->path, "SELECT count(*) FROM collisions"), 250);
  close_ok(db);

  /* A child logs 250 rows of a new run in batches of 100 and is killed with SIGKILL. */
  fflush(NULL);
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    hd_db *c = NULL;
    hd_error e;
    if (hd_db_open(&c, fx->path, &e)) _exit(10);
    hd_db_set_batch_rows(c, 100);
    int64_t r2 = 0;
    if (hd_db_run_begin(c, "child", 8, "test", &r2, &e) || r2 != 2) _exit(11);
    /* a run resumes from a checkpoint: hd_run writes one before the first event */
    if (hd_db_checkpoint_save(c, r2, 0, 0.0, "ck", 2, &e)) _exit(14);
    for (int64_t k = 1; k <= 250; k++) {
      hd_collision_row r = coll(k);
      if (hd_db_log_collision(c, r2, &r, &e)) _exit(12);
    }
    (void)hd_db_handle(c); /* every row handed to SQLite; 50 of them in an open batch */
    raise(SIGKILL);
    _exit(13);
  }
  int ws = 0;
  assert_int_equal(waitpid(pid, &ws, 0), pid);
  assert_true(WIFSIGNALED(ws) && WTERMSIG(ws) == SIGKILL);
  assert_integrity_ok(fx->path);
  assert_int_equal(count_other(fx->path, "SELECT count(*) FROM collisions WHERE run = 2"), 200);
  assert_int_equal(count_other(fx->path, "SELECT max(seq) FROM collisions WHERE run = 2"), 200);
  assert_int_equal(count_other(fx->path, "SELECT count(*) FROM collisions WHERE run = 1"), 250);
  /* the killed run is left 'running', which hd_db_find_resumable accepts */
  db = open_ok(fx->path);
  int64_t found = 0;
  char *scene = NULL;
  unsigned long long seed = 0;
  assert_int_equal(hd_db_find_resumable(db, 0, &found, &scene, &seed, &err), HD_OK);
  assert_int_equal(found, 2);
  assert_string_equal(scene, "child");
  assert_true(seed == 8);
  free(scene);
  close_ok(db);
  assert_integrity_ok(fx->path);
}

/* A checkpoint is committed in one transaction with the rows logged before it: a child logs
 * 5 rows, saves a checkpoint, logs 3 more and is killed. */
static void checkpoint_with_its_rows(void **state) {
  fixture *fx = *state;
  hd_error err;
  hd_db *db = open_ok(fx->path);
  int64_t run = begin_run(db, "", 3);
  close_ok(db);
  fflush(NULL);
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    hd_db *c = NULL;
    hd_error e;
    if (hd_db_open(&c, fx->path, &e)) _exit(10);
    for (int64_t k = 1; k <= 8; k++) {
      hd_collision_row r = coll(k);
      if (hd_db_log_collision(c, run, &r, &e)) _exit(11);
      if (k == 5 && hd_db_checkpoint_save(c, run, 5, r.t, "state-at-5", 10, &e)) _exit(12);
    }
    raise(SIGKILL);
    _exit(13);
  }
  int ws = 0;
  assert_int_equal(waitpid(pid, &ws, 0), pid);
  assert_true(WIFSIGNALED(ws));
  assert_integrity_ok(fx->path);
  assert_int_equal(count_other(fx->path, "SELECT count(*) FROM collisions"), 5);
  db = open_ok(fx->path);
  void *blob = NULL;
  size_t n = 0;
  int64_t seq = 0;
  double t = 0;
  assert_int_equal(hd_db_checkpoint_load(db, run, &blob, &n, &seq, &t, &err), HD_OK);
  assert_int_equal(n, 10);
  assert_memory_equal(blob, "state-at-5", 10);
  assert_int_equal(seq, 5);
  assert_true(t == 0.01 * 5.0);
  free(blob);
  close_ok(db);
}

static void checkpoint_save_load_truncate(void **state) {
  fixture *fx = *state;
  hd_error err;
  hd_db *db = open_ok(fx->path);
  int64_t r1 = begin_run(db, "", 1), r2 = begin_run(db, "", 2);
  void *blob = NULL;
  size_t n = 0;
  int64_t seq = 0;
  double t = 0;
  assert_int_equal(hd_db_checkpoint_load(db, r1, &blob, &n, &seq, &t, &err), HD_EINPUT);
  assert_non_null(strstr(err.msg, "no checkpoint"));
  assert_null(blob);

  /* rows of r1: collisions seq 1..30 at t = seq - 1, samples at t = 0..29, states */
  for (int64_t k = 1; k <= 30; k++) {
    hd_collision_row r = coll(k);
    r.t = (double)(k - 1);
    assert_int_equal(hd_db_log_collision(db, r1, &r, &err), HD_OK);
    assert_int_equal(hd_db_log_collision(db, r2, &r, &err), HD_OK);
    hd_sample_row s = {(double)(k - 1), k, 0.1 * (double)k, 1.0, 0.5, NAN, NAN, NAN, NAN, NAN, NAN};
    assert_int_equal(hd_db_log_sample(db, r1, &s, &err), HD_OK);
    assert_int_equal(hd_db_log_sample(db, r2, &s, &err), HD_OK);
  }
  struct {
    const char *label;
    double t;
  } sts[] = {{"initial", 0},     {"velocities", 5},  {"checkpoint", 20},
             {"velocities", 25}, {"checkpoint", 25}, {"final", 29}};
  for (size_t k = 0; k < sizeof sts / sizeof sts[0]; k++) {
    hd_state_rec s = {sts[k].t, 0, 1, 0, 0, 0, 0, 0, 0, NAN, 0};
    assert_int_equal(hd_db_log_state(db, r1, sts[k].label, &s, &err), HD_OK);
    assert_int_equal(hd_db_log_state(db, r2, sts[k].label, &s, &err), HD_OK);
  }

  /* two checkpoints of r1 and one of r2: the newest of r1 replaces the older */
  unsigned char b1[64], b2[300];
  for (size_t k = 0; k < sizeof b1; k++) b1[k] = (unsigned char)(k * 7);
  for (size_t k = 0; k < sizeof b2; k++) b2[k] = (unsigned char)(255 - k % 256);
  const double t1 = 0.1 + 0.2, t2 = 1.0 / 3.0;
  assert_int_equal(hd_db_checkpoint_save(db, r1, 10, t1, b1, sizeof b1, &err), HD_OK);
  /* the rows logged before the checkpoint are committed with it */
  assert_int_equal(count_other(fx->path, "SELECT count(*) FROM collisions"), 60);
  assert_int_equal(hd_db_checkpoint_save(db, r2, 11, t1, b1, sizeof b1, &err), HD_OK);
  assert_int_equal(hd_db_checkpoint_save(db, r1, 20, t2, b2, sizeof b2, &err), HD_OK);
  assert_int_equal(q_int(hd_db_handle(db), "SELECT count(*) FROM checkpoints WHERE run = 1"), 1);
  assert_int_equal(q_int(hd_db_handle(db), "SELECT count(*) FROM checkpoints WHERE run = 2"), 1);
  assert_int_equal(hd_db_checkpoint_load(db, r1, &blob, &n, &seq, &t, &err), HD_OK);
  assert_int_equal(n, sizeof b2);
  assert_memory_equal(blob, b2, sizeof b2);
  assert_int_equal(seq, 20);
  assert_true(memcmp(&t, &t2, sizeof t) == 0); /* bit-exact */
  free(blob);
  assert_int_equal(hd_db_checkpoint_load(db, r2, &blob, &n, &seq, &t, &err), HD_OK);
  assert_int_equal(n, sizeof b1);
  assert_memory_equal(blob, b1, sizeof b1);
  assert_true(seq == 11 && memcmp(&t, &t1, sizeof t) == 0);
  free(blob);
  /* an empty blob is a valid checkpoint */
  int64_t r3 = begin_run(db, "", 3);
  assert_int_equal(hd_db_checkpoint_save(db, r3, 0, 0.0, NULL, 0, &err), HD_OK);
  assert_int_equal(hd_db_checkpoint_load(db, r3, &blob, &n, &seq, &t, &err), HD_OK);
  assert_int_equal(n, 0);
  assert_non_null(blob);
  free(blob);

  /* truncate r1 after seq 20 / t = 20 */
  assert_int_equal(hd_db_truncate_after(db, r1, 20, 20.0, &err), HD_OK);
  sqlite3 *h = hd_db_handle(db);
  assert_int_equal(q_int(h, "SELECT count(*) FROM collisions WHERE run = 1"), 20);
  assert_int_equal(q_int(h, "SELECT max(seq) FROM collisions WHERE run = 1"), 20);
  assert_int_equal(q_int(h, "SELECT count(*) FROM samples WHERE run = 1"), 21); /* t 0..20 */
  /* states: initial 0 and velocities 5 stay; velocities 25 and final 29 go, and so do the
   * checkpoint snapshots (where the run stopped: it goes on from there) */
  assert_int_equal(q_int(h, "SELECT count(*) FROM states WHERE run = 1"), 2);
  assert_int_equal(q_int(h, "SELECT count(*) FROM states WHERE run = 1 AND "
                            "label IN ('final') OR (run = 1 AND label = 'velocities' AND t = 25)"),
                   0);
  /* r2 untouched */
  assert_int_equal(q_int(h, "SELECT count(*) FROM collisions WHERE run = 2"), 30);
  assert_int_equal(q_int(h, "SELECT count(*) FROM samples WHERE run = 2"), 30);
  assert_int_equal(q_int(h, "SELECT count(*) FROM states WHERE run = 2"), 6);
  close_ok(db);
  assert_integrity_ok(fx->path);
}

/* How a run was made (schema version 4): hd_db_run_provenance stores it in runs (text "" and
 * git_dirty -1 as NULL); hd_db_find_same_run finds the first run of a scene text and seed
 * (exactly: another seed or another text is not it), open for writing or read-only, and in a
 * file whose runs have no git_commit column (before version 4) gives commit 'unknown'. */
static void provenance_and_same_run(void **state) {
  fixture *fx = *state;
  hd_error err;
  hd_db *db = open_ok(fx->path);
  int64_t r1 = begin_run(db, "[system]\nseed = 7\n", 7);
  hd_run_prov p = {.git_commit = "0123abcd",
                   .git_dirty = 1,
                   .compiler = "cc 1",
                   .cflags = "-O2",
                   .command = "haff run \"a b.ini\"",
                   .sweep_point = ""};
  assert_int_equal(hd_db_run_provenance(db, r1, &p, &err), HD_OK);
  int64_t r2 = begin_run(db, "[system]\nseed = 7\n", 7);
  p.git_dirty = -1;
  p.git_commit = "unknown";
  assert_int_equal(hd_db_run_provenance(db, r2, &p, &err), HD_OK);
  hd_same_run same;
  assert_int_equal(hd_db_find_same_run(db, "[system]\nseed = 7\n", 7, &same, &err), HD_OK);
  assert_int_equal(same.run, r1);
  assert_string_equal(same.status, "running");
  assert_string_equal(same.commit, "0123abcd");
  assert_int_equal(hd_db_find_same_run(db, "[system]\nseed = 7\n", 8, &same, &err), HD_OK);
  assert_int_equal(same.run, 0);
  assert_int_equal(hd_db_find_same_run(db, "[system]\nseed = 7\n\n", 7, &same, &err), HD_OK);
  assert_int_equal(same.run, 0);
  close_ok(db);
  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open_v2(fx->path, &h, SQLITE_OPEN_READWRITE, NULL), SQLITE_OK);
  assert_int_equal(q_int(h, "SELECT count(*) FROM runs WHERE id = 1 AND git_commit = '0123abcd' "
                            "AND git_dirty = 1 AND compiler = 'cc 1' AND cflags = '-O2' AND "
                            "command = 'haff run \"a b.ini\"' AND sweep_point IS NULL"),
                   1);
  assert_int_equal(q_int(h, "SELECT count(*) FROM runs WHERE id = 2 AND git_dirty IS NULL"), 1);
  /* a file from before version 4: read-only, no column, the commit 'unknown' */
  assert_int_equal(sqlite3_exec(h,
                                "DROP VIEW run_summary; ALTER TABLE runs DROP COLUMN git_commit; "
                                "PRAGMA user_version = 3",
                                NULL, NULL, NULL),
                   SQLITE_OK);
  sqlite3_close(h);
  assert_int_equal(hd_db_open_readonly(&db, fx->path, &err), HD_OK);
  assert_int_equal(hd_db_find_same_run(db, "[system]\nseed = 7\n", 7, &same, &err), HD_OK);
  assert_int_equal(same.run, r1);
  assert_string_equal(same.commit, "unknown");
  hd_db_close(db, NULL);
}

static void find_resumable(void **state) {
  fixture *fx = *state;
  hd_error err;
  hd_db *db = open_ok(fx->path);
  int64_t run = 0;
  char *scene = NULL;
  unsigned long long seed = 0;
  assert_int_equal(hd_db_find_resumable(db, 0, &run, &scene, &seed, &err), HD_EINPUT);
  assert_non_null(strstr(err.msg, "no interrupted run"));
  const char *status[] = {"done", "interrupted", "running", "collapsed", "failed", "done"};
  for (int k = 0; k < 6; k++) {
    char sc[32];
    snprintf(sc, sizeof sc, "scene %d", k + 1);
    int64_t r = begin_run(db, sc, 100 + (unsigned)k);
    assert_int_equal(r, k + 1);
    assert_int_equal(hd_db_checkpoint_save(db, r, 0, 0.0, "ck", 2, &err), HD_OK);
    assert_int_equal(hd_db_run_status(db, r, status[k], 10, 1.0, &err), HD_OK);
  }
  /* a run that failed in its set-up has no checkpoint: never the default choice */
  int64_t r7 = begin_run(db, "scene 7", 106);
  assert_int_equal(hd_db_run_status(db, r7, "failed", 0, 0.0, &err), HD_OK);
  /* newest resumable: run 5 ('failed': a full disk, resumable once there is room) */
  assert_int_equal(hd_db_find_resumable(db, 0, &run, &scene, &seed, &err), HD_OK);
  assert_int_equal(run, 5);
  assert_string_equal(scene, "scene 5");
  assert_true(seed == 104);
  free(scene);
  assert_int_equal(hd_db_find_resumable(db, 3, &run, &scene, &seed, &err), HD_OK);
  assert_int_equal(run, 3); /* 'running': a killed process */
  free(scene);
  assert_int_equal(hd_db_find_resumable(db, 2, &run, &scene, &seed, &err), HD_OK);
  assert_int_equal(run, 2);
  assert_string_equal(scene, "scene 2");
  assert_true(seed == 101);
  free(scene);
  scene = NULL;
  assert_int_equal(hd_db_find_resumable(db, 1, &run, &scene, &seed, &err), HD_EINPUT);
  assert_non_null(strstr(err.msg, "run 1 is done"));
  assert_null(scene);
  assert_int_equal(hd_db_find_resumable(db, 4, &run, &scene, &seed, &err), HD_EINPUT);
  assert_non_null(strstr(err.msg, "collapsed"));
  assert_int_equal(hd_db_find_resumable(db, 99, &run, &scene, &seed, &err), HD_EINPUT);
  assert_non_null(strstr(err.msg, "no run 99"));
  /* 'finished' is set for final statuses and cleared for 'running' */
  sqlite3 *h = hd_db_handle(db);
  assert_int_equal(q_int(h, "SELECT count(*) FROM runs WHERE finished IS NULL"), 1);
  assert_int_equal(q_int(h, "SELECT id FROM runs WHERE finished IS NULL"), 3);
  close_ok(db);
}

/* ---------------------------------------------------------------------------------------- */
/* read-only and disk full */

/* The checks on a read-only file and folder; returns a bit mask of failures (0: all passed).
 * Runs in a child without root privileges when the tests run as root. */
static int readonly_checks(const char *dir, const char *path) {
  int bad = 0;
  hd_db *db = NULL;
  hd_error err;
  hd_error_clear(&err);
  if (hd_db_open(&db, path, &err) != HD_EIO || db) bad |= 1;
  if (!strstr(err.msg, path) || !strstr(err.msg, "read-only")) bad |= 2;
  char fresh[400];
  snprintf(fresh, sizeof fresh, "%s/new.db", dir);
  hd_error_clear(&err);
  if (hd_db_open(&db, fresh, &err) != HD_EIO || db) bad |= 4;
  if (!strstr(err.msg, fresh) || !strstr(err.msg, "open")) bad |= 8;
  /* readers still read it: no -shm can be made in the folder, so as immutable */
  hd_error_clear(&err);
  if (hd_db_open_readonly(&db, path, &err) != HD_OK || !db) {
    bad |= 16;
  } else {
    if (q_int(hd_db_handle(db), "SELECT count(*) FROM runs") != 1) bad |= 32;
    hd_db_close(db, NULL);
  }
  if (bad) fprintf(stderr, "readonly_checks: %d: %s\n", bad, err.msg);
  return bad;
}

static void read_only_file(void **state) {
  fixture *fx = *state;
  hd_db *db = open_ok(fx->path);
  begin_run(db, "", 1);
  close_ok(db);
  assert_int_equal(chmod(fx->path, 0444), 0);
  assert_int_equal(chmod(fx->dir, 0555), 0);
  if (geteuid() != 0) {
    assert_int_equal(readonly_checks(fx->dir, fx->path), 0);
  } else {
    /* root writes any file: check as an unprivileged user in a child */
    fflush(NULL);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
      if (setgid(65534) || setuid(65534)) _exit(100);
      _exit(readonly_checks(fx->dir, fx->path));
    }
    int ws = 0;
    assert_int_equal(waitpid(pid, &ws, 0), pid);
    assert_true(WIFEXITED(ws));
    if (WEXITSTATUS(ws) == 100) {
      printf("# skipped: root, and the check as user nobody (65534) could not become it\n");
      skip();
    }
    assert_int_equal(WEXITSTATUS(ws), 0);
  }
  chmod(fx->dir, 0700);
  chmod(fx->path, 0644);
}

/* A connection that may not write (query_only): every write is HD_EIO, nothing crashes, and
 * the database is still sound and writable once allowed again. */
static void read_only_connection(void **state) {
  fixture *fx = *state;
  hd_error err;
  hd_db *db = open_ok(fx->path);
  int64_t run = begin_run(db, "", 1);
  assert_int_equal(db_exec(db, "PRAGMA query_only = 1", &err), HD_OK);
  hd_collision_row r = coll(1);
  assert_int_equal(hd_db_log_collision(db, run, &r, &err), HD_OK); /* buffered */
  assert_int_equal(hd_db_commit(db, &err), HD_EIO);                /* written: refused */
  assert_true(strncmp(err.msg, fx->path, strlen(fx->path)) == 0);
  assert_non_null(strstr(err.msg, "readonly"));
  int64_t r2 = 0;
  assert_int_equal(hd_db_run_begin(db, "", 2, "test", &r2, &err), HD_EIO);
  assert_int_equal(hd_db_checkpoint_save(db, run, 1, 0.0, "x", 1, &err), HD_EIO);
  assert_int_equal(db_exec(db, "INSERT INTO runs (scene) VALUES ('x')", &err), HD_EIO);
  assert_int_equal(db_exec(db, "PRAGMA query_only = 0", &err), HD_OK);
  assert_int_equal(hd_db_log_collision(db, run, &r, &err), HD_OK);
  close_ok(db);
  assert_integrity_ok(fx->path);
  assert_int_equal(count_other(fx->path, "SELECT count(*) FROM collisions"), 1);

  /* a readonly handle refuses writes with a clear message */
  assert_int_equal(hd_db_open_readonly(&db, fx->path, &err), HD_OK);
  assert_int_equal(hd_db_log_collision(db, run, &r, &err), HD_EIO);
  assert_non_null(strstr(err.msg, "read-only"));
  assert_int_equal(hd_db_close(db, &err), HD_OK);
  /* and a file that is not a database is an error, not a crash */
  char junk[400];
  snprintf(junk, sizeof junk, "%s/junk.db", fx->dir);
  FILE *f = fopen(junk, "w");
  assert_non_null(f);
  for (int k = 0; k < 200; k++) fputs("this is not an SQLite database\n", f);
  fclose(f);
  db = NULL;
  assert_int_equal(hd_db_open(&db, junk, &err), HD_EINPUT); /* bad input: exit 2 */
  assert_null(db);
  assert_non_null(strstr(err.msg, "not a database"));
}

static void disk_full(void **state) {
  fixture *fx = *state;
  hd_error err;
  hd_db *db = open_ok(fx->path);
  int64_t run = begin_run(db, "", 1);
  hd_db_set_batch_rows(db, 50);
  sqlite3 *h = hd_db_handle(db);
  long long pages = q_int(h, "PRAGMA page_count");
  char sql[80];
  /* a few pages more than now: room for some hundreds of rows, then SQLITE_FULL */
  snprintf(sql, sizeof sql, "PRAGMA max_page_count = %lld", pages + 6);
  assert_int_equal(db_exec(db, sql, &err), HD_OK);
  int rc = HD_OK;
  int64_t k;
  for (k = 1; k <= 100000 && rc == HD_OK; k++) {
    hd_collision_row r = coll(k);
    rc = hd_db_log_collision(db, run, &r, &err);
  }
  assert_int_equal(rc, HD_EIO);
  assert_true(k > 51); /* at least one batch fitted */
  assert_true(strncmp(err.msg, fx->path, strlen(fx->path)) == 0);
  assert_non_null(strstr(err.msg, "full"));
  long long n = count_other(fx->path, "SELECT count(*) FROM collisions");
  assert_true(n > 0 && n % 50 == 0); /* whole batches only */
  assert_int_equal(count_other(fx->path, "SELECT max(seq) FROM collisions"), n);
  assert_integrity_ok(fx->path);
  /* still full: the next batch fails before it is whole too (the failed one did), and then
   * nothing is pending, so close has nothing to commit */
  hd_collision_row r = coll(k);
  rc = HD_OK;
  for (int m = 0; m < 50 && rc == HD_OK; m++) rc = hd_db_log_collision(db, run, &r, &err);
  if (rc == HD_OK) rc = hd_db_commit(db, &err);
  assert_int_equal(rc, HD_EIO);
  close_ok(db);
  assert_integrity_ok(fx->path);
  assert_int_equal(count_other(fx->path, "SELECT count(*) FROM collisions"), n);
  /* the limit is per connection: reopened, the database takes rows again */
  db = open_ok(fx->path);
  assert_int_equal(hd_db_log_collision(db, run, &r, &err), HD_OK);
  close_ok(db);
  assert_int_equal(count_other(fx->path, "SELECT count(*) FROM collisions"), n + 1);
}

/* ---------------------------------------------------------------------------------------- */
/* the example queries of db/queries/ */

/* The result of the last statement of a query file that returned rows. */
typedef struct qres {
  int ncol, nrow, cap;
  char *names[32];
  double *v;  /* nrow x ncol, NAN for NULL */
  char **txt; /* nrow x ncol, strdup'd text of TEXT cells, else NULL */
} qres;

static void qres_free(qres *r) {
  for (int c = 0; c < r->ncol; c++) free(r->names[c]);
  for (long k = 0; k < (long)r->nrow * r->ncol; k++) free(r->txt[k]);
  free(r->v);
  free(r->txt);
  memset(r, 0, sizeof *r);
}

static int col(const qres *r, const char *name) {
  for (int c = 0; c < r->ncol; c++)
    if (!strcmp(r->names[c], name)) return c;
  fail_msg("no column %s", name);
  return -1;
}

static double val(const qres *r, int row, const char *name) {
  return r->v[(long)row * r->ncol + col(r, name)];
}

static char *read_text(const char *name) {
  const char *dirs[] = {"db/queries", "../db/queries"};
  for (size_t d = 0; d < 2; d++) {
    char p[256];
    snprintf(p, sizeof p, "%s/%s", dirs[d], name);
    FILE *f = fopen(p, "rb");
    if (!f) continue;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    assert_non_null(s);
    assert_int_equal(fread(s, 1, (size_t)n, f), (size_t)n);
    s[n] = 0;
    fclose(f);
    return s;
  }
  fail_msg("cannot find db/queries/%s (run from the source tree)", name);
  return NULL;
}

/* Runs a query file as the sqlite3 shell would, with @run and @block set (0: unset). */
static void run_query(sqlite3 *h, const char *file, long long run, long long block, qres *out) {
  char *sql = read_text(file);
  memset(out, 0, sizeof *out);
  const char *p = sql;
  while (*p) {
    sqlite3_stmt *st = NULL;
    const char *tail = NULL;
    int rc = sqlite3_prepare_v2(h, p, -1, &st, &tail);
    if (rc != SQLITE_OK) fail_msg("%s: %s", file, sqlite3_errmsg(h));
    p = tail;
    if (!st) continue; /* comments or white space */
    int ip = sqlite3_bind_parameter_index(st, "@run");
    if (ip && run > 0) sqlite3_bind_int64(st, ip, run);
    ip = sqlite3_bind_parameter_index(st, "@block");
    if (ip && block > 0) sqlite3_bind_int64(st, ip, block);
    qres r = {0};
    int s;
    while ((s = sqlite3_step(st)) == SQLITE_ROW) {
      if (r.nrow == 0) {
        r.ncol = sqlite3_column_count(st);
        assert_true(r.ncol <= 32);
        for (int c = 0; c < r.ncol; c++) r.names[c] = strdup(sqlite3_column_name(st, c));
      }
      if (r.nrow == r.cap) {
        r.cap = r.cap ? 2 * r.cap : 64;
        r.v = realloc(r.v, sizeof *r.v * (size_t)r.cap * (size_t)r.ncol);
        r.txt = realloc(r.txt, sizeof *r.txt * (size_t)r.cap * (size_t)r.ncol);
        assert_true(r.v && r.txt);
      }
      for (int c = 0; c < r.ncol; c++) {
        long k = (long)r.nrow * r.ncol + c;
        int ty = sqlite3_column_type(st, c);
        r.v[k] = ty == SQLITE_NULL ? NAN : sqlite3_column_double(st, c);
        r.txt[k] = ty == SQLITE_TEXT ? strdup((const char *)sqlite3_column_text(st, c)) : NULL;
      }
      r.nrow++;
    }
    if (s != SQLITE_DONE) fail_msg("%s: %s", file, sqlite3_errmsg(h));
    sqlite3_finalize(st);
    if (r.nrow > 0) {
      qres_free(out);
      *out = r;
    } else {
      qres_free(&r);
    }
  }
  free(sql);
}

/* The synthetic database of the query tests, with what the queries must find, computed here. */
#define Q_RUNS 2
#define Q_BLOCK 1000
typedef struct qdata {
  long n_coll[Q_RUNS];
  long kind_n[Q_RUNS][6];
  double kind_de[Q_RUNS][6];
  long hist[Q_RUNS][3][36]; /* [run][block of Q_BLOCK][bin] */
  long hist_all[Q_RUNS][36];
  double *f[Q_RUNS]; /* f of the dimer-dimer collisions */
  long nf[Q_RUNS];
  double e_tr[Q_RUNS][20], e_rot[Q_RUNS][20];
} qdata;

/* Bin of theta in (-pi, pi]: k with -pi + k w < theta <= -pi + (k+1) w, found by comparing
 * with the bin edges (not by the query's formula). */
static int bin_of(double theta) {
  const double w = 2 * M_PI / 36;
  for (int k = 0; k < 36; k++)
    if (theta <= -M_PI + (k + 1) * w) return k;
  return 35;
}

static void fill_query_db(const char *path, qdata *q) {
  memset(q, 0, sizeof *q);
  hd_error err;
  hd_db *db = open_ok(path);
  hd_db_set_batch_rows(db, 500);
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 2024);
  const long ncoll[Q_RUNS] = {2500, 700};
  for (int r = 0; r < Q_RUNS; r++) {
    int64_t run = begin_run(db, "", (unsigned)r);
    assert_int_equal(run, r + 1);
    q->f[r] = malloc(sizeof(double) * (size_t)ncoll[r]);
    assert_non_null(q->f[r]);
    for (int64_t s = 1; s <= ncoll[r]; s++) {
      hd_collision_row c = coll(s);
      int kk = (int)gsl_rng_uniform_int(rng, NCK);
      c.kind = ck(kk);
      /* theta uniform in (-2pi/3, 2pi/3] for dimers, NaN for others; some exactly +-pi/bin
       * edges are avoided by the random draw */
      int has_i = kk == 0 || kk == 1 || kk == 3; /* dimer-dimer, dimer-disk, dimer-wall */
      c.theta_i = has_i ? (2 * gsl_rng_uniform(rng) - 1) * 2 * M_PI / 3 : NAN;
      if (has_i && s % 97 == 0) c.theta_i = M_PI; /* the closed end of the last bin */
      c.theta_j = kk == 0 ? (2 * gsl_rng_uniform(rng) - 1) * 2 * M_PI / 3 : NAN;
      if (kk == 0) {
        double ci = cos(c.theta_i), cj = cos(c.theta_j);
        c.f = 1.0 / (2.0 - (ci * ci + cj * cj) / 2.0);
        q->f[r][q->nf[r]++] = c.f;
      } else {
        c.f = kk == 2 ? 0.5 : NAN;
      }
      c.de = -gsl_rng_uniform(rng);
      assert_int_equal(hd_db_log_collision(db, run, &c, &err), HD_OK);
      q->n_coll[r]++;
      q->kind_n[r][kk]++;
      q->kind_de[r][kk] += c.de;
      if (has_i) {
        q->hist[r][(s - 1) / Q_BLOCK][bin_of(c.theta_i)]++;
        q->hist_all[r][bin_of(c.theta_i)]++;
      }
    }
    for (int k = 0; k < 20; k++) {
      q->e_tr[r][k] = 2.0 * exp(-0.1 * k) + r;
      q->e_rot[r][k] = 1.0 * exp(-0.05 * k);
      hd_sample_row sm = {0.5 * k, 100 * k, 0.2 * k, q->e_tr[r][k], q->e_rot[r][k], NAN, NAN, NAN,
                          NAN,     NAN,     NAN};
      assert_int_equal(hd_db_log_sample(db, run, &sm, &err), HD_OK);
    }
    assert_int_equal(
        hd_db_run_status(db, run, r ? "interrupted" : "done", 1000 * (r + 1), 4.0, &err), HD_OK);
  }
  gsl_rng_free(rng);
  close_ok(db);
}

static void queries(void **state) {
  fixture *fx = *state;
  qdata q;
  fill_query_db(fx->path, &q);
  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open(fx->path, &h), SQLITE_OK);
  qres r;
  const double w = 2 * M_PI / 36;

  /* angle histogram of run 1 in blocks of 1000: 3 blocks x 36 bins, exact counts */
  run_query(h, "angle_histogram_per_block.sql", 1, Q_BLOCK, &r);
  assert_int_equal(r.nrow, 3 * 36);
  long total = 0;
  for (int row = 0; row < r.nrow; row++) {
    int b = (int)val(&r, row, "block"), k = (int)val(&r, row, "bin");
    assert_int_equal(val(&r, row, "run"), 1);
    assert_int_equal(b, row / 36);
    assert_int_equal(k, row % 36);
    assert_int_equal((long)val(&r, row, "n"), q.hist[0][b][k]);
    long nb = 0;
    for (int j = 0; j < 36; j++) nb += q.hist[0][b][j];
    assert_int_equal((long)val(&r, row, "n_block"), nb);
    assert_close(val(&r, row, "density"), (double)q.hist[0][b][k] / ((double)nb * w), 1e-12);
    assert_close(val(&r, row, "theta_lo"), -M_PI + k * w, 1e-12);
    total += (long)val(&r, row, "n");
  }
  long want = q.kind_n[0][0] + q.kind_n[0][1] + q.kind_n[0][3];
  assert_int_equal(total, want);
  assert_true(q.hist[0][0][35] + q.hist[0][1][35] + q.hist[0][2][35] > 0); /* theta = pi */
  qres_free(&r);
  /* default block (10000): one block per run, every run */
  run_query(h, "angle_histogram_per_block.sql", 0, 0, &r);
  assert_int_equal(r.nrow, 2 * 36);
  for (int row = 0; row < r.nrow; row++)
    assert_int_equal((long)val(&r, row, "n"), q.hist_all[row / 36][row % 36]);
  qres_free(&r);

  /* mean f per run, with the standard error from GSL's sample standard deviation */
  run_query(h, "mean_f_per_run.sql", 0, 0, &r);
  assert_int_equal(r.nrow, Q_RUNS);
  for (int k = 0; k < Q_RUNS; k++) {
    double mean = gsl_stats_mean(q.f[k], 1, (size_t)q.nf[k]);
    double sd = gsl_stats_sd(q.f[k], 1, (size_t)q.nf[k]);
    assert_int_equal(val(&r, k, "run"), k + 1);
    assert_int_equal((long)val(&r, k, "n"), q.nf[k]);
    /* sums of ~10^3 terms in another order: agree to ~1e-13 relative */
    assert_close(val(&r, k, "mean_f"), mean, 1e-12);
    assert_close(val(&r, k, "sd_f"), sd, 1e-12);
    assert_close(val(&r, k, "stderr_f"), sd / sqrt((double)q.nf[k]), 1e-12);
    assert_close(val(&r, k, "d_e"), 2.0 / mean, 1e-11);
    /* f for theta uniform on |theta| <= 2pi/3 averages to about 0.64 (paper, sec. 5).  Seed
     * 2024; ~420 and ~120 dimer-dimer rows, sd(f) ~ 0.1, so the standard error is <= 0.01 and
     * the window +-0.04 is more than 3 sigma wide. */
    assert_true(mean > 0.6 && mean < 0.68);
  }
  qres_free(&r);
  run_query(h, "mean_f_per_run.sql", 2, 0, &r);
  assert_int_equal(r.nrow, 1);
  assert_int_equal(val(&r, 0, "run"), 2);
  qres_free(&r);

  /* energy against cpd */
  run_query(h, "energy_vs_cpd.sql", 2, 0, &r);
  assert_int_equal(r.nrow, 20);
  for (int k = 0; k < 20; k++) {
    double e = q.e_tr[1][k] + q.e_rot[1][k], e0 = q.e_tr[1][0] + q.e_rot[1][0];
    assert_close(val(&r, k, "cpd"), 0.2 * k, 1e-15);
    assert_close(val(&r, k, "e"), e, 1e-14);
    assert_close(val(&r, k, "t_rot"), 2 * q.e_rot[1][k], 1e-14);
    assert_close(val(&r, k, "k"), q.e_tr[1][k] / q.e_rot[1][k], 1e-13);
    assert_close(val(&r, k, "e_over_e0"), e / e0, 1e-14);
  }
  qres_free(&r);

  /* collisions per kind: every run, kinds in alphabetical order */
  run_query(h, "collisions_per_kind.sql", 0, 0, &r);
  assert_int_equal(r.nrow, 2 * 6);
  for (int row = 0; row < r.nrow; row++) {
    int run = (int)val(&r, row, "run") - 1;
    const char *kind = r.txt[(long)row * r.ncol + col(&r, "kind")];
    int k = 0;
    while (k < 6 && strcmp(hd_coll_kind_name(ck(k)), kind)) k++;
    assert_true(k < 6);
    assert_int_equal((long)val(&r, row, "n"), q.kind_n[run][k]);
    assert_close(val(&r, row, "fraction"), (double)q.kind_n[run][k] / (double)q.n_coll[run], 1e-15);
    assert_close(val(&r, row, "mean_de"), q.kind_de[run][k] / (double)q.kind_n[run][k], 1e-12);
  }
  qres_free(&r);

  /* runs overview */
  run_query(h, "runs_overview.sql", 0, 0, &r);
  assert_int_equal(r.nrow, 2);
  for (int k = 0; k < 2; k++) {
    assert_string_equal(r.txt[(long)k * r.ncol + col(&r, "status")], k ? "interrupted" : "done");
    assert_int_equal((long)val(&r, k, "collisions_logged"), q.n_coll[k]);
    assert_close(val(&r, k, "events_per_s"), 1000.0 * (k + 1) / 4.0, 1e-12);
    assert_close(val(&r, k, "last_cpd"), 0.2 * 19, 1e-15);
    assert_int_equal((long)val(&r, k, "samples"), 20);
  }
  qres_free(&r);

  /* the views */
  run_query(h, "views.sql", 0, 0, &r);
  qres_free(&r);
  assert_int_equal(q_int(h, "SELECT count(*) FROM v_dimer_collisions"),
                   q.kind_n[0][0] + q.kind_n[1][0]);
  assert_int_equal(q_int(h, "SELECT count(*) FROM v_dimer_collisions "
                            "WHERE abs(f - f_eq36) > 1e-14"),
                   0);
  assert_int_equal(q_int(h, "SELECT count(*) FROM v_wall_collisions"),
                   q.kind_n[0][3] + q.kind_n[0][4] + q.kind_n[1][3] + q.kind_n[1][4]);
  assert_int_equal(q_int(h, "SELECT count(*) FROM v_energy WHERE abs(e - e_tr - e_rot) < 1e-15"),
                   40);
  assert_int_equal(q_int(h, "SELECT collisions_logged FROM v_runs WHERE id = 2"), q.n_coll[1]);
  sqlite3_close(h);
  for (int k = 0; k < Q_RUNS; k++) free(q.f[k]);
}

/* ---------------------------------------------------------------------------------------- */
/* the collisions column table (HD_COLLISION_COLUMNS) */

/* The value of column c in collision row k of every_collision_column_round_trips, by the bind
 * kind of the column: distinct in every row and column; row 40 is the rod-rod one. */
static int64_t coll_val_INT64(int k, int c) {
  return 1000 * k + c;
}
static int coll_val_INT(int k, int c) {
  return 1000 * k + c;
}
static double coll_val_REAL(int k, int c) {
  return 1000.0 * k + c + 0.25;
}
static hd_coll_kind coll_val_KIND(int k, int c) {
  (void)c;
  return ck(k == 40 ? CK_ROD : k % 5);
}

/* Every column of HD_COLLISION_COLUMNS goes from its field into its column through each of the
 * three inserts of hd_db.c (HD_DB_GROUP = 32 2D rows at once, 32 rows with a rod-rod one, then a
 * row alone), and is NULL where its scope says (a rod-rod column in a 2D row, a 2D column in a
 * rod-rod row): a column added to the table is tested here without an edit. */
static void every_collision_column_round_trips(void **state) {
  fixture *fx = *state;
  hd_error err;
  hd_db *db = open_ok(fx->path);
  int64_t run = begin_run(db, "[system]\nbox = 3 4\n", 1);
  enum { NROW = 2 * 32 + 1 };
  for (int k = 0; k < NROW; k++) {
    hd_collision_row r;
    memset(&r, 0, sizeof r);
    int c = 0;
#define COLL_SET(name, ctype, bind, sqltype, scope, since, doc) r.name = coll_val_##bind(k, c++);
    HD_COLLISION_COLUMNS(COLL_SET)
#undef COLL_SET
    assert_int_equal(hd_db_log_collision(db, run, &r, &err), HD_OK);
  }
  close_ok(db);

  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open_v2(fx->path, &h, SQLITE_OPEN_READONLY, NULL), SQLITE_OK);
  int c = 0, ncol = 0;
#define COLL_CHECK(name, ctype, bind, sqltype, scope, since, doc)                                  \
  do {                                                                                             \
    sqlite3_stmt *q = NULL;                                                                        \
    assert_int_equal(sqlite3_prepare_v2(h, "SELECT " #name ", run FROM collisions ORDER BY rowid", \
                                        -1, &q, NULL),                                             \
                     SQLITE_OK);                                                                   \
    for (int k = 0; k < NROW; k++) {                                                               \
      assert_int_equal(sqlite3_step(q), SQLITE_ROW);                                               \
      assert_int_equal(sqlite3_column_int64(q, 1), run);                                           \
      int rod = coll_val_KIND(k, 0) == ck(CK_ROD);                                                 \
      int keep = (scope) == HD_COLL_ALL || ((scope) == HD_COLL_ROD) == rod;                        \
      if (!keep) {                                                                                 \
        if (sqlite3_column_type(q, 0) != SQLITE_NULL)                                              \
          fail_msg("collisions.%s of row %d (kind %s): not NULL", #name, k,                        \
                   hd_coll_kind_name(coll_val_KIND(k, 0)));                                        \
      } else if (!strcmp(#bind, "KIND")) {                                                         \
        assert_string_equal((const char *)sqlite3_column_text(q, 0),                               \
                            hd_coll_kind_name(coll_val_KIND(k, c)));                               \
      } else if (sqlite3_column_double(q, 0) != (double)coll_val_##bind(k, c)) {                   \
        fail_msg("collisions.%s of row %d: %.17g, want %.17g", #name, k,                           \
                 sqlite3_column_double(q, 0), (double)coll_val_##bind(k, c));                      \
      }                                                                                            \
    }                                                                                              \
    assert_int_equal(sqlite3_step(q), SQLITE_DONE);                                                \
    sqlite3_finalize(q);                                                                           \
    c++;                                                                                           \
  } while (0);
  HD_COLLISION_COLUMNS(COLL_CHECK)
#undef COLL_CHECK
  /* and the table has no column the column table lacks: run, then its columns */
  ncol = (int)q_int(h, "SELECT count(*) FROM pragma_table_info('collisions')");
  assert_int_equal(ncol, 1 + c);
  sqlite3_close(h);
}

/* db/schema.sql holds the CREATE TABLE of collisions that HD_COLLISION_COLUMNS gives, column
 * comments and all (`make schema` rewrites it). */
static void schema_sql_collisions_is_the_column_table(void **state) {
  (void)state;
  FILE *f = fopen("db/schema.sql", "rb");
  assert_non_null(f);
  static char sql[1 << 16];
  size_t n = fread(sql, 1, sizeof sql - 1, f);
  fclose(f);
  sql[n] = '\0';
  char *gen = hd_db_collisions_create_sql();
  assert_non_null(gen);
  if (!strstr(sql, gen))
    fail_msg("db/schema.sql is not what the column table gives: run make schema; the table gives\n"
             "%s",
             gen);
  free(gen);
}

/* ---------------------------------------------------------------------------------------- */
/* haff export xyz */

static char *slurp(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  static char buf[8192];
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  buf[n] = 0;
  fclose(f);
  return buf;
}

/* states.species (schema version 4, issue 28): each body's species.idx is stored (NULL for a
 * rod); a file of version 3 (states without the column, one row) opened for writing gets the
 * column, its old row reads NULL, new rows carry their species, and user_version is this haff's. */
static void states_species(void **state) {
  fixture *fx = *state;
  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open(fx->path, &h), SQLITE_OK);
  assert_int_equal(sqlite3_exec(h,
                                "CREATE TABLE states (run INTEGER NOT NULL, label TEXT NOT NULL, "
                                "t REAL NOT NULL, cpd REAL, body INTEGER NOT NULL, kind TEXT NOT "
                                "NULL, x REAL, y REAL, phi REAL, vx REAL, vy REAL, omega REAL);"
                                "INSERT INTO states VALUES (1, 'initial', 0, 0, 0, 'dimer', 1, 2, "
                                "0, 0, 0, 0); PRAGMA user_version = 3",
                                NULL, NULL, NULL),
                   SQLITE_OK);
  sqlite3_close(h);
  hd_db *db = open_ok(fx->path);
  hd_error err;
  hd_error_clear(&err);
  hd_state_rec named = {1.0, 7, HD_KIND_BODY, 1, 2, 0.5, 0, 0, 0, 0.1, 3};
  hd_state_rec disk = {1.0, 3, HD_KIND_DISK, 1, 2, 0, 0, 0, 0, 0.1, 1};
  hd_state_rec rod = {1.0, 0, HD_KIND_ROD, 1, 0, 0, 0, 0, 0, 0.1, 5};
  assert_int_equal(hd_db_log_state(db, 1, "final", &named, &err), HD_OK);
  assert_int_equal(hd_db_log_state(db, 1, "final", &disk, &err), HD_OK);
  assert_int_equal(hd_db_log_state(db, 1, "final", &rod, &err), HD_OK);
  close_ok(db);
  assert_int_equal(sqlite3_open(fx->path, &h), SQLITE_OK);
  sqlite3_stmt *q = NULL;
  assert_int_equal(sqlite3_prepare_v2(h,
                                      "SELECT group_concat(coalesce(species, 'null'), ' '), "
                                      "(SELECT user_version FROM pragma_user_version) FROM "
                                      "(SELECT species FROM states ORDER BY rowid)",
                                      -1, &q, NULL),
                   SQLITE_OK);
  assert_int_equal(sqlite3_step(q), SQLITE_ROW);
  assert_string_equal((const char *)sqlite3_column_text(q, 0), "null 3 1 null");
  assert_int_equal(sqlite3_column_int(q, 1), HD_DB_SCHEMA_VERSION);
  sqlite3_finalize(q);
  sqlite3_close(h);
}

/* ---------------------------------------------------------------------------------------- */
/* schema version 5: per-species energies stored in sample_species only (issue 29) */

/* Version 4's table samples, as db/schema.sql of haff 4 made it (the per-kind columns). */
static const char samples_v4_sql[] =
    "CREATE TABLE samples (run INTEGER NOT NULL REFERENCES runs(id), t REAL NOT NULL, collisions "
    "INTEGER NOT NULL, cpd REAL NOT NULL, e_tr REAL NOT NULL, e_rot REAL NOT NULL, e_tr_dimer "
    "REAL, e_rot_dimer REAL, e_tr_disk REAL, flow_frac REAL, flow_chaos REAL, count_var REAL, "
    "s_rho REAL, s_perp REAL, s_par REAL)";

/* The energies of sample k of run r, species sp (-1: all): numbers of full mantissa. */
static double e_of(int r, int k, int sp) {
  return exp(-0.037 * k) * (1.0 + 0.1 * r) / (sp < 0 ? 1.0 : 1.3 + 0.71 * sp);
}

/* Makes path a file of schema version `version` (4: samples with the per-kind columns and
 * sample_species with every species, as haff 4 wrote them; 2: no sample_species nor species,
 * the per-kind columns alone) holding three runs of 10 samples: 1 a dimer-disk mixture, 2
 * dimers only, 3 two named species (idx 2 and 3); and a user's view of samples
 * (db/queries/views.sql's kind).  The tables other than samples are this haff's. */
static void make_old_file(const char *path, int version) {
  hd_db *db = open_ok(path);
  for (int r = 1; r <= 3; r++) begin_run(db, "[system]\nseed = 1\n", (unsigned long long)r);
  close_ok(db);
  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open(path, &h), SQLITE_OK);
  assert_int_equal(sqlite3_exec(h, "DROP VIEW samples; DROP TABLE sample_rows", NULL, NULL, NULL),
                   SQLITE_OK);
  assert_int_equal(sqlite3_exec(h, samples_v4_sql, NULL, NULL, NULL), SQLITE_OK);
  assert_int_equal(sqlite3_exec(h,
                                "CREATE VIEW v_energy AS SELECT run, t, e_tr + e_rot AS e FROM "
                                "samples",
                                NULL, NULL, NULL),
                   SQLITE_OK);
  sqlite3_stmt *ins = NULL, *sp = NULL;
  assert_int_equal(sqlite3_prepare_v2(h,
                                      "INSERT INTO samples VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, "
                                      "?9, ?10, 0.01, 1, 1.5, 1.25, 0.75)",
                                      -1, &ins, NULL),
                   SQLITE_OK);
  assert_int_equal(sqlite3_prepare_v2(h, "INSERT INTO sample_species VALUES (?1, ?2, ?3, ?4, ?5)",
                                      -1, &sp, NULL),
                   SQLITE_OK);
  static const int species[4][2] = {{0, 0}, {0, 1}, {0, -1}, {2, 3}}; /* run r: its species */
  for (int r = 1; r <= 3; r++)
    for (int k = 0; k < 10; k++) {
      double t = 0.37 * k + 0.01 * r;
      sqlite3_bind_int(ins, 1, r);
      sqlite3_bind_double(ins, 2, t);
      sqlite3_bind_int(ins, 3, 100 * k);
      sqlite3_bind_double(ins, 4, 0.5 * k);
      sqlite3_bind_double(ins, 5, e_of(r, k, -1));
      sqlite3_bind_double(ins, 6, e_of(r, k, -1) / 2.1);
      for (int c = 7; c <= 9; c++) sqlite3_bind_null(ins, c);
      if (r == 1) { /* the mixture's columns, as haff 4 filled them */
        sqlite3_bind_double(ins, 7, e_of(r, k, 0));
        sqlite3_bind_double(ins, 8, e_of(r, k, 0) / 2.3);
        sqlite3_bind_double(ins, 9, e_of(r, k, 1));
      }
      sqlite3_bind_double(ins, 10, 0.001 * k);
      assert_int_equal(sqlite3_step(ins), SQLITE_DONE);
      sqlite3_reset(ins);
      for (int j = 0; j < 2 && version >= 3; j++) {
        int s = species[r][j];
        if (s < 0) continue;
        sqlite3_bind_int(sp, 1, r);
        sqlite3_bind_double(sp, 2, t);
        sqlite3_bind_int(sp, 3, s);
        sqlite3_bind_double(sp, 4, e_of(r, k, s));
        sqlite3_bind_double(sp, 5, s == 1 ? 0.0 : e_of(r, k, s) / 2.3);
        assert_int_equal(sqlite3_step(sp), SQLITE_DONE);
        sqlite3_reset(sp);
      }
    }
  sqlite3_finalize(ins);
  sqlite3_finalize(sp);
  char set[64];
  snprintf(set, sizeof set, "PRAGMA user_version = %d", version);
  assert_int_equal(sqlite3_exec(h, set, NULL, NULL, NULL), SQLITE_OK);
  if (version < 3)
    assert_int_equal(
        sqlite3_exec(h, "DROP TABLE sample_species; DROP TABLE species", NULL, NULL, NULL),
        SQLITE_OK);
  sqlite3_close(h);
}

/* Copies file a to b (a file closed by every connection: no log beside it). */
static void copy_file(const char *a, const char *b) {
  char cmd[1024];
  snprintf(cmd, sizeof cmd, "cp '%s' '%s'", a, b);
  assert_int_equal(system(cmd), 0);
}

/* Rows of db's samples (main) that equal, column by column and bit for bit (IS: NULL too), a row
 * of the samples of the file `other` (run shifted by `off`), in one connection. */
static long long samples_same(sqlite3 *h, const char *other, int off) {
  char sql[2048];
  snprintf(sql, sizeof sql, "ATTACH '%s' AS o", other);
  assert_int_equal(sqlite3_exec(h, sql, NULL, NULL, NULL), SQLITE_OK);
  snprintf(sql, sizeof sql,
           "SELECT count(*) FROM main.samples a JOIN o.samples b ON a.run = b.run + %d AND a.t "
           "IS b.t AND a.collisions IS b.collisions AND a.cpd IS b.cpd AND a.e_tr IS b.e_tr AND "
           "a.e_rot IS b.e_rot AND a.e_tr_dimer IS b.e_tr_dimer AND a.e_rot_dimer IS "
           "b.e_rot_dimer AND a.e_tr_disk IS b.e_tr_disk AND a.flow_frac IS b.flow_frac AND "
           "a.flow_chaos IS b.flow_chaos AND a.count_var IS b.count_var AND a.s_rho IS b.s_rho "
           "AND a.s_perp IS b.s_perp AND a.s_par IS b.s_par",
           off);
  long long n = q_int(h, sql);
  assert_int_equal(sqlite3_exec(h, "DETACH o", NULL, NULL, NULL), SQLITE_OK);
  return n;
}

/* A new file keeps per-species energies in sample_species only: its table sample_rows has no
 * per-kind column, samples is a view, and the view answers version 4's query (SELECT e_tr_dimer,
 * e_rot_dimer, e_tr_disk FROM samples) from sample_species: set where the run has species 0 and
 * 1 at that t, NULL where it has one of them or named species only.  Before: samples was a
 * table that held both forms. */
static void schema5_samples_view(void **state) {
  fixture *fx = *state;
  hd_error err;
  hd_db *db = open_ok(fx->path);
  int64_t mix = begin_run(db, "[system]\nseed = 1\n", 1);
  int64_t one = begin_run(db, "[system]\nseed = 2\n", 2);
  for (int k = 0; k < 4; k++) {
    hd_sample_row s = {.t = k, .collisions = k, .cpd = k, .e_tr = 1.5, .e_rot = 0.5};
    s.flow_frac = s.flow_chaos = s.count_var = s.s_rho = s.s_perp = s.s_par = NAN;
    assert_int_equal(hd_db_log_sample(db, mix, &s, &err), HD_OK);
    assert_int_equal(hd_db_log_sample(db, one, &s, &err), HD_OK);
    hd_species_sample d = {k, 0, e_of(1, k, 0), e_of(1, k, 0) / 3}, c = {k, 1, e_of(1, k, 1), 0};
    assert_int_equal(hd_db_log_species_sample(db, mix, &d, &err), HD_OK);
    assert_int_equal(hd_db_log_species_sample(db, mix, &c, &err), HD_OK);
    assert_int_equal(hd_db_log_species_sample(db, one, &d, &err), HD_OK);
  }
  assert_int_equal(hd_db_build_indexes(db, &err), HD_OK);
  close_ok(db);
  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open(fx->path, &h), SQLITE_OK);
  assert_int_equal(q_int(h, "SELECT user_version FROM pragma_user_version"), 5);
  assert_int_equal(q_int(h, "SELECT count(*) FROM sqlite_schema WHERE name = 'samples' AND type "
                            "= 'view'"),
                   1);
  assert_int_equal(q_int(h, "SELECT count(*) FROM pragma_table_info('sample_rows') WHERE name "
                            "LIKE '%dimer%' OR name LIKE '%disk%'"),
                   0);
  /* version 4's columns, in its order */
  sqlite3_stmt *st = NULL;
  assert_int_equal(sqlite3_prepare_v2(h,
                                      "SELECT group_concat(name, ' ') FROM (SELECT name FROM "
                                      "pragma_table_info('samples') ORDER BY cid)",
                                      -1, &st, NULL),
                   SQLITE_OK);
  assert_int_equal(sqlite3_step(st), SQLITE_ROW);
  assert_string_equal((const char *)sqlite3_column_text(st, 0),
                      "run t collisions cpd e_tr e_rot e_tr_dimer e_rot_dimer e_tr_disk flow_frac "
                      "flow_chaos count_var s_rho s_perp s_par");
  sqlite3_finalize(st);
  assert_int_equal(sqlite3_prepare_v2(h,
                                      "SELECT run, t, e_tr_dimer, e_rot_dimer, e_tr_disk FROM "
                                      "samples ORDER BY run, t",
                                      -1, &st, NULL),
                   SQLITE_OK);
  for (int r = 1; r <= 2; r++)
    for (int k = 0; k < 4; k++) {
      assert_int_equal(sqlite3_step(st), SQLITE_ROW);
      assert_int_equal(sqlite3_column_int(st, 0), r);
      if (r == 1) {
        assert_true(sqlite3_column_double(st, 2) == e_of(1, k, 0));
        assert_true(sqlite3_column_double(st, 3) == e_of(1, k, 0) / 3);
        assert_true(sqlite3_column_double(st, 4) == e_of(1, k, 1));
      } else {
        for (int c = 2; c <= 4; c++) assert_int_equal(sqlite3_column_type(st, c), SQLITE_NULL);
      }
    }
  assert_int_equal(sqlite3_step(st), SQLITE_DONE);
  sqlite3_finalize(st);
  /* a one-run query of samples searches the index of sample_rows (no scan of the table) */
  assert_int_equal(sqlite3_prepare_v2(h,
                                      "EXPLAIN QUERY PLAN SELECT t, e_tr_dimer FROM samples WHERE "
                                      "run = 1",
                                      -1, &st, NULL),
                   SQLITE_OK);
  while (sqlite3_step(st) == SQLITE_ROW) {
    const char *d = (const char *)sqlite3_column_text(st, 3);
    if (strstr(d, "SCAN")) fail_msg("plan: %s", d);
  }
  sqlite3_finalize(st);
  sqlite3_close(h);
}

/* A file of schema version 4 (both forms) or 2 (the per-kind columns only) opened for writing
 * is brought to 5: samples reads the same rows bit for bit as before (every column, the
 * mixture's per-kind ones from sample_species now), sample_species gains the rows that only the
 * columns had (version 2: 2 per sample of the mixture; version 4: none), the per-species series
 * that the analyses read (hd_ana_spseries_read) is the same before (the old file, read as it is)
 * and after, a user's view of samples still reads, and the old table is gone.  Before: the file
 * kept its table samples, with the per-kind columns. */
static void schema5_old_files_converted(void **state) {
  fixture *fx = *state;
  for (int version = 4; version >= 2; version -= 2) {
    char old[400];
    snprintf(old, sizeof old, "%s/v%d-orig.db", fx->dir, version);
    unlink(fx->path);
    make_old_file(fx->path, version);
    copy_file(fx->path, old);
    hd_ana_mix mix = {.k = 2};
    mix.sp[0].idx = 0, mix.sp[1].idx = 1;
    hd_ana_spseries before, after;
    hd_error err;
    sqlite3 *h = NULL;
    assert_int_equal(sqlite3_open_v2(old, &h, SQLITE_OPEN_READONLY, NULL), SQLITE_OK);
    assert_int_equal(hd_ana_spseries_read(h, 1, &mix, &before, &err), HD_OK);
    sqlite3_close(h);
    assert_int_equal(before.n, 10);
    long long ss_old = version >= 3 ? count_other(old, "SELECT count(*) FROM sample_species") : 0;
    close_ok(open_ok(fx->path)); /* a writer opens it: the upgrade */
    assert_int_equal(sqlite3_open(fx->path, &h), SQLITE_OK);
    assert_int_equal(q_int(h, "SELECT user_version FROM pragma_user_version"), 5);
    assert_int_equal(q_int(h, "SELECT count(*) FROM sqlite_schema WHERE name = 'samples' AND "
                              "type = 'view'"),
                     1);
    assert_int_equal(q_int(h, "SELECT count(*) FROM pragma_table_info('sample_rows') WHERE name "
                              "LIKE 'e_tr_di%'"),
                     0);
    assert_int_equal(q_int(h, "SELECT count(*) FROM samples"), 30);
    assert_int_equal(samples_same(h, old, 0), 30);
    assert_int_equal(q_int(h, "SELECT count(*) FROM sample_species"), ss_old + (version < 3) * 20);
    assert_int_equal(q_int(h, "SELECT count(*) FROM v_energy"), 30);
    assert_int_equal(hd_ana_spseries_read(h, 1, &mix, &after, &err), HD_OK);
    assert_int_equal(after.n, before.n);
    for (size_t f = 0; f < 2 * after.n; f++) {
      assert_true(after.e_tr[f] == before.e_tr[f]);
      assert_true(after.e_rot[f] == before.e_rot[f]);
    }
    assert_true(after.t[9] == before.t[9]);
    hd_ana_spseries_free(&before);
    hd_ana_spseries_free(&after);
    sqlite3_close(h);
    assert_integrity_ok(fx->path);
  }
}

/* haff merge of a file of version 4 and one of version 5, into a new OUT and into a copy of
 * the version 4 file: OUT is of version 5 and reads every input's samples as it read them (run
 * numbers shifted), bit for bit, with the mixture's per-kind values from sample_species.
 * Before: a version 4 input's per-kind columns were copied into OUT's table samples. */
static void schema5_merge_old_and_new(void **state) {
  fixture *fx = *state;
  char v4[400], v5[400], out[400], out4[400];
  snprintf(v4, sizeof v4, "%s/v4.db", fx->dir);
  snprintf(v5, sizeof v5, "%s/v5.db", fx->dir);
  snprintf(out, sizeof out, "%s/out.db", fx->dir);
  snprintf(out4, sizeof out4, "%s/out4.db", fx->dir);
  make_old_file(v4, 4);
  copy_file(v4, out4);
  hd_error err;
  hd_db *db = open_ok(v5);
  int64_t run = begin_run(db, "[system]\nseed = 9\n", 9);
  for (int k = 0; k < 5; k++) {
    hd_sample_row s = {.t = k, .collisions = k, .cpd = k, .e_tr = e_of(4, k, -1), .e_rot = 0.5};
    s.flow_frac = s.flow_chaos = s.count_var = s.s_rho = s.s_perp = s.s_par = NAN;
    assert_int_equal(hd_db_log_sample(db, run, &s, &err), HD_OK);
    for (int sp = 0; sp < 2; sp++) {
      hd_species_sample e = {k, sp, e_of(4, k, sp), sp ? 0 : 0.25};
      assert_int_equal(hd_db_log_species_sample(db, run, &e, &err), HD_OK);
    }
  }
  close_ok(db);
  const char *both[] = {v4, v5};
  int64_t n = 0;
  assert_int_equal(hd_db_merge(out, both, 2, &n, &err), HD_OK);
  assert_int_equal(n, 4);
  assert_int_equal(hd_db_merge(out4, both + 1, 1, &n, &err), HD_OK);
  assert_int_equal(n, 1);
  const char *outs[] = {out, out4};
  for (int o = 0; o < 2; o++) {
    sqlite3 *h = NULL;
    assert_int_equal(sqlite3_open(outs[o], &h), SQLITE_OK);
    assert_int_equal(q_int(h, "SELECT user_version FROM pragma_user_version"), 5);
    assert_int_equal(q_int(h, "SELECT count(*) FROM samples"), 35);
    assert_int_equal(samples_same(h, v4, 0), 30);
    assert_int_equal(samples_same(h, v5, 3), 5);
    assert_int_equal(q_int(h, "SELECT count(*) FROM samples WHERE e_tr_dimer IS NOT NULL"), 15);
    assert_int_equal(q_int(h, "SELECT count(*) FROM sample_species"), 50 + 10);
    sqlite3_close(h);
  }
}

static int export_run(char *a1, char *a2, char *a3, char *a4, char *a5, char *a6, char *a7,
                      char *a8) {
  char *argv[] = {"export", "xyz", a1, a2, a3, a4, a5, a6, a7, a8, NULL};
  int argc = 2;
  while (argv[argc]) argc++;
  return hd_cmd_export(argc, argv);
}

static void export_xyz(void **state) {
  fixture *fx = *state;
  hd_error err;
  hd_db *db = open_ok(fx->path);
  int64_t run = begin_run(db,
                          "[system]\nbox = 10 8   ; periodic\nseed = 3\n[dimers]\ncount = 1\n"
                          "d = 1\na = 1\n[disks]\ncount = 1\nsigma = 0.5\n",
                          3);
  /* a dimer at (2.5, 3), phi = 0, V = (1, 0), omega = 2; a disk at (6, 4), v = (0, -1) */
  hd_state_rec d0 = {0.0, 0, 1, 2.5, 3.0, 0.0, 1.0, 0.0, 2.0, NAN, 0};
  hd_state_rec s0 = {0.0, 1, 0, 6.0, 4.0, 0.0, 0.0, -1.0, 0.0, NAN, 1};
  hd_state_rec d1 = {1.5, 0, 1, 4.0, 3.0, M_PI, 1.0, 0.0, 2.0, 0.25, 0};
  hd_state_rec s1 = {1.5, 1, 0, 6.0, 2.5, 0.0, 0.0, -1.0, 0.0, 0.25, 1};
  assert_int_equal(hd_db_log_state(db, run, "final", &d1, &err), HD_OK);
  assert_int_equal(hd_db_log_state(db, run, "final", &s1, &err), HD_OK);
  assert_int_equal(hd_db_log_state(db, run, "initial", &s0, &err), HD_OK);
  assert_int_equal(hd_db_log_state(db, run, "initial", &d0, &err), HD_OK);
  int64_t empty = begin_run(db, "[system]\nbox = 1 1\n", 4);
  close_ok(db);

  char out[400];
  snprintf(out, sizeof out, "%s/out.xyz", fx->dir);
  assert_int_equal(export_run(fx->path, "--run", "1", "--label", "initial", "-o", out, NULL), 0);
  /* Disk 0 of the dimer at R - (a/2)(1, 0) = (2, 3) with velocity V + omega z x (-1/2, 0) =
   * (1, -1); disk 1 at (3, 3) with (1, 1).  Masses m = 1 (momenta = velocities), radii d/2 =
   * 0.5 and sigma/2 = 0.25; phi and omega of the body.  Chemical symbols N (a dimer's disk) and
   * Ar (a disk), which ASE reads, and the species names (dimer, disk: a run without a species
   * table); pbc: periodic in x and y, not z. */
  const char *want =
      "3\n"
      "Lattice=\"10 0 0 0 8 0 0 0 1\" "
      "Properties=species:S:1:pos:R:3:velo:R:3:masses:R:1:momenta:R:3:radius:R:1:body:I:1:"
      "phi:R:1:omega:R:1:species_name:S:1 pbc=\"T T F\" Time=0 Label=initial\n"
      "N 2 3 0 1 -1 0 1 1 -1 0 0.5 0 0 2 dimer\n"
      "N 3 3 0 1 1 0 1 1 1 0 0.5 0 0 2 dimer\n"
      "Ar 6 4 0 0 -1 0 1 0 -1 0 0.25 1 0 0 disk\n";
  assert_string_equal(slurp(out), want);

  /* all labels: two frames in time order; phi = pi puts disk 0 at R + (a/2, 0), and its
   * velocity V - (a/2) omega (-sin phi, cos phi) = (1 + sin(pi), 1) with sin(pi) = 1.2e-16,
   * which rounds 1 + 1.2e-16 up to the next double: the shortest exact form shows it */
  const char *want_final =
      "3\n"
      "Lattice=\"10 0 0 0 8 0 0 0 1\" "
      "Properties=species:S:1:pos:R:3:velo:R:3:masses:R:1:momenta:R:3:radius:R:1:body:I:1:"
      "phi:R:1:omega:R:1:species_name:S:1 pbc=\"T T F\" Time=1.5 Label=final Cpd=0.25\n"
      "N 4.5 3 0 1.0000000000000002 1 0 1 1.0000000000000002 1 0 0.5 0 3.141592653589793 2 "
      "dimer\n"
      "N 3.5 3 0 0.9999999999999999 -1 0 1 0.9999999999999999 -1 0 0.5 0 3.141592653589793 2 "
      "dimer\n"
      "Ar 6 2.5 0 0 -1 0 1 0 -1 0 0.25 1 0 0 disk\n";
  char both[2048];
  snprintf(both, sizeof both, "%s%s", want, want_final);
  /* the newest run (2) has no states: exit 2 with a message; so give --run 1 */
  assert_int_equal(export_run(fx->path, "--run", "1", "-o", out, NULL, NULL, NULL), 0);
  assert_string_equal(slurp(out), both);
  /* the GSD writer in process (so the sanitized build runs it too; tests/test_export.c reads
   * its files with the real gsd.hoomd): a file with GSD's magic and the hoomd schema, the
   * index's two frames (step 0 and 1) and no .tmp left */
  {
    char gsd[400], tmp[420];
    snprintf(gsd, sizeof gsd, "%s/out.gsd", fx->dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", gsd);
    char *argv[] = {"export", "gsd", fx->path, "--run", "1", "-o", gsd, NULL};
    assert_int_equal(hd_cmd_export(7, argv), 0);
    FILE *g = fopen(gsd, "rb");
    assert_non_null(g);
    unsigned char h[256];
    assert_int_equal(fread(h, 1, sizeof h, g), sizeof h);
    uint64_t magic = 0, index_at = 0, last_frame = 0;
    for (int k = 7; k >= 0; k--) magic = magic << 8 | h[k], index_at = index_at << 8 | h[8 + k];
    assert_true(magic == 0x65DF65DF65DF65DFull);
    assert_string_equal((const char *)h + 112, "hoomd");
    /* the frame of the index's last entry (before the zero entry that ends it) */
    unsigned char e[32];
    assert_int_equal(fseek(g, (long)index_at, SEEK_SET), 0);
    while (fread(e, 1, sizeof e, g) == sizeof e && (e[16] | e[17] | e[18] | e[19]))
      for (int k = 7; k >= 0; k--) last_frame = (k == 7 ? 0 : last_frame << 8) | e[k];
    assert_int_equal(last_frame, 1);
    fclose(g);
    assert_int_equal(access(tmp, F_OK), -1);
  }

  /* a box stored with hd_db_run_box wins over the scene's */
  db = open_ok(fx->path);
  assert_int_equal(hd_db_run_box(db, run, 12.0, 9.0, &err), HD_OK);
  close_ok(db);
  assert_int_equal(export_run(fx->path, "--run", "1", "--label", "final", "-o", out, NULL), 0);
  assert_non_null(strstr(slurp(out), "Lattice=\"12 0 0 0 9 0 0 0 1\""));
  assert_null(strstr(slurp(out), "initial"));

  /* errors: bad label, unknown run, run without states, missing file, bad format */
  char rid[32];
  snprintf(rid, sizeof rid, "%lld", (long long)empty);
  assert_int_equal(export_run(fx->path, "--label", "middle", NULL, NULL, NULL, NULL, NULL), 2);
  assert_int_equal(export_run(fx->path, "--run", "77", NULL, NULL, NULL, NULL, NULL), 2);
  assert_int_equal(export_run(fx->path, "--run", rid, "-o", out, NULL, NULL, NULL), 2);
  assert_int_equal(export_run(fx->path, NULL, NULL, NULL, NULL, NULL, NULL, NULL), 2); /* newest */
  char missing[400];
  snprintf(missing, sizeof missing, "%s/nope.db", fx->dir);
  assert_int_equal(export_run(missing, NULL, NULL, NULL, NULL, NULL, NULL, NULL), 2);
  char *argv_bad[] = {"export", "pdb", fx->path, NULL};
  assert_int_equal(hd_cmd_export(3, argv_bad), 2);
  char *argv_help[] = {"export", "--help", NULL};
  assert_int_equal(hd_cmd_export(2, argv_help), 0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup_teardown(round_trip, setup, teardown),
      cmocka_unit_test_setup_teardown(every_collision_column_round_trips, setup, teardown),
      cmocka_unit_test(schema_sql_collisions_is_the_column_table),
      cmocka_unit_test_setup_teardown(nan_in_not_null_column, setup, teardown),
      cmocka_unit_test_setup_teardown(batches_and_kill9, setup, teardown),
      cmocka_unit_test_setup_teardown(checkpoint_with_its_rows, setup, teardown),
      cmocka_unit_test_setup_teardown(checkpoint_save_load_truncate, setup, teardown),
      cmocka_unit_test_setup_teardown(find_resumable, setup, teardown),
      cmocka_unit_test_setup_teardown(provenance_and_same_run, setup, teardown),
      cmocka_unit_test_setup_teardown(read_only_file, setup, teardown),
      cmocka_unit_test_setup_teardown(read_only_connection, setup, teardown),
      cmocka_unit_test_setup_teardown(disk_full, setup, teardown),
      cmocka_unit_test_setup_teardown(queries, setup, teardown),
      cmocka_unit_test_setup_teardown(export_xyz, setup, teardown),
      cmocka_unit_test_setup_teardown(states_species, setup, teardown),
      cmocka_unit_test_setup_teardown(schema5_samples_view, setup, teardown),
      cmocka_unit_test_setup_teardown(schema5_old_files_converted, setup, teardown),
      cmocka_unit_test_setup_teardown(schema5_merge_old_and_new, setup, teardown),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
