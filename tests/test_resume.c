/* Resume from what a run left behind (run/hd_run.c, in-process, so that the sanitizer build
 * runs it too): damaged checkpoints are refused, never crash nor give wrong results. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gsl/gsl_rng.h>

#include "hd_db.h"
#include "hd_model.h"
#include "hd_run.h"
#include "hd_scene.h"
#include "test_util.h"

/* ---------------------------------------------------------------------------------------- */
/* helpers */

static char dir[256];

static int setup(void **state) {
  (void)state;
  const char *tmp = getenv("TMPDIR");
  snprintf(dir, sizeof dir, "%s/haff-test-resume-XXXXXX", tmp && *tmp ? tmp : "/tmp");
  return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  char cmd[400];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  return system(cmd) == 0 ? 0 : -1;
}

/* dir/name, in one of four rotating buffers. */
static const char *path_of(const char *name) {
  return test_path_in(dir, name);
}

/* Runs sql on database name (ref.db attached as ref when it exists); the first column of the
 * first row as an integer (0 if none). */
static long long q1(const char *name, const char *sql) {
  sqlite3 *h = NULL;
  assert_int_equal(sqlite3_open_v2(path_of(name), &h, SQLITE_OPEN_READWRITE, NULL), SQLITE_OK);
  if (access(path_of("ref.db"), F_OK) == 0) {
    char att[500];
    snprintf(att, sizeof att, "ATTACH '%s' AS ref", path_of("ref.db"));
    assert_int_equal(sqlite3_exec(h, att, NULL, NULL, NULL), SQLITE_OK);
  }
  sqlite3_stmt *st = NULL;
  if (sqlite3_prepare_v2(h, sql, -1, &st, NULL) != SQLITE_OK) fail_msg("%s", sqlite3_errmsg(h));
  long long v = 0;
  int s = sqlite3_step(st);
  if (s == SQLITE_ROW)
    v = sqlite3_column_int64(st, 0);
  else if (s != SQLITE_DONE)
    fail_msg("%s: %s", sql, sqlite3_errmsg(h));
  sqlite3_finalize(st);
  sqlite3_close(h);
  return v;
}

/* Runs scene text as a new run into database name; returns hd_run_new's status. */
static int run_scene(const char *text, const char *name) {
  hd_scene sc;
  hd_error err;
  hd_error_clear(&err);
  assert_int_equal(hd_scene_load_string(&sc, text, "t.ini", NULL, 0, &err), HD_OK);
  hd_run_opts o = {.db_path = path_of(name), .quiet = 1, .version = "test"};
  int64_t run = 0;
  int rc = hd_run_new(&sc, &o, &run, &err);
  if (rc) print_message("run: %s\n", err.msg);
  hd_scene_free(&sc);
  return rc;
}

/* Resumes the newest resumable run of database name; its status, err its message. */
static int resume(const char *name, hd_error *err) {
  hd_error_clear(err);
  hd_run_opts o = {.db_path = path_of(name), .quiet = 1, .version = "test"};
  int64_t run = 0;
  return hd_run_resume(0, &o, &run, err);
}

static void copy_file(const char *from, const char *to) {
  char cmd[1000];
  snprintf(cmd, sizeof cmd, "cp '%s' '%s' && rm -f '%s-wal' '%s-shm'", path_of(from), path_of(to),
           path_of(to), path_of(to));
  assert_int_equal(system(cmd), 0);
}

/* Database name holds the same run as ref.db: collisions, samples, states, status done. */
static void same_as_reference(const char *name) {
  static const struct {
    const char *table, *cols; /* the columns that must match row for row */
  } same[] = {{"collisions", "seq,t,kind,i,j,f,de,vn,eps"},
              {"samples", "t,cpd,e_tr,e_rot"},
              {"states", "label,t,body,x,y,phi,vx,vy,omega"}};
  for (size_t k = 0; k < sizeof same / sizeof same[0]; k++) {
    char sql[400], ref[400];
    snprintf(sql, sizeof sql, "SELECT count(*) FROM %s", same[k].table);
    snprintf(ref, sizeof ref, "SELECT count(*) FROM ref.%s", same[k].table);
    assert_int_equal(q1(name, sql), q1(name, ref));
    snprintf(sql, sizeof sql,
             "SELECT count(*) FROM (SELECT %s FROM %s EXCEPT SELECT %s FROM ref.%s)", same[k].cols,
             same[k].table, same[k].cols, same[k].table);
    assert_int_equal(q1(name, sql), 0);
  }
  assert_int_equal(q1(name, "SELECT count(*) FROM runs WHERE status = 'done'"), 1);
}

/* ---------------------------------------------------------------------------------------- */
/* damaged checkpoints */

/* A checkpoint every 1024 collisions (checkpoint_every is 1e-9 s: the clock is looked at every
 * 1024 collisions), so the one kept is at collision 2048 of 3000, with counters, snapshots and
 * events under way: a mixture of dimers and disks between walls. */
static const char scene2d[] = "[system]\narea_fraction = 0.25\nseed = 5\n"
                              "[dimers]\ncount = 40\nalpha = 0.9\n"
                              "[disks]\ncount = 40\nalpha = 0.8\n"
                              "[walls]\nsides = left right\n"
                              "[run]\nstop_events = 3000\ncheckpoint_every = 1e-9\n"
                              "[log]\ncollisions = all\nsamples_every = 1\n"
                              "velocities_at = 10 30 70\n";

/* The rods ring: 3000 collisions of 20 rods, the stochastic model. */
static const char scene_rods[] = "[system]\nseed = 7\n[rods]\ncount = 20\n"
                                 "[run]\nstop_events = 3000\ncheckpoint_every = 1e-9\n"
                                 "[log]\ncollisions = all\nsamples_every = 5\n"
                                 "velocities_at = 50 100\n";

/* Makes kept.db: scene run to its end with its last checkpoint kept (a trigger keeps what
 * 'done' deletes), then set back to 'running' as if killed after it; and ref.db, the same run
 * uninterrupted. */
static void kept_checkpoint(const char *scene) {
  assert_int_equal(run_scene(scene, "ref.db"), HD_OK);
  hd_db *db = NULL;
  hd_error err;
  assert_int_equal(hd_db_open(&db, path_of("kept.db"), &err), HD_OK);
  assert_int_equal(hd_db_close(db, &err), HD_OK);
  q1("kept.db", "CREATE TRIGGER keep BEFORE DELETE ON checkpoints WHEN (SELECT status FROM runs "
                "WHERE id = OLD.run) = 'done' BEGIN SELECT RAISE(IGNORE); END");
  assert_int_equal(run_scene(scene, "kept.db"), HD_OK);
  q1("kept.db", "DROP TRIGGER keep");
  q1("kept.db", "UPDATE runs SET status = 'running', finished = NULL");
  assert_int_equal(q1("kept.db", "SELECT count(*) FROM checkpoints WHERE seq = 2048"), 1);
}

/* One bit flipped at `flips` places of the kept checkpoint (the first 256 bits, the runner's
 * counters and the model's header, one by one in steps of 7; the rest at random, fixed seed):
 * each resume either refuses with one line saying the checkpoint is damaged (HD_EINPUT, as
 * exit 2) or, never here since a checksum covers every byte, ends as the uninterrupted run.
 * Without the checksum and the checks it crashed (next_vel = -1e6 read velocities_at[-1e6]; a
 * cell link out of range in hd_cells_remove) or ended 'done' with other collisions. */
static void flip_bits(const char *scene, int flips) {
  kept_checkpoint(scene);
  long long nbits = 8 * q1("kept.db", "SELECT length(blob) FROM checkpoints");
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 17);
  int refused = 0;
  for (int k = 0; k < flips; k++) {
    long long bit = k < 37 ? 7 * k : (long long)gsl_rng_uniform_int(rng, (unsigned long)nbits);
    copy_file("kept.db", "f.db");
    assert_int_equal(test_flip_checkpoint_bit(path_of("f.db"), bit), 0);
    hd_error err;
    int rc = resume("f.db", &err);
    if (rc == HD_OK) {
      same_as_reference("f.db");
    } else {
      if (rc != HD_EINPUT || !strstr(err.msg, "the checkpoint of run 1 is damaged") ||
          strchr(err.msg, '\n'))
        fail_msg("bit %lld: status %d: %s", bit, rc, err.msg);
      refused++;
      /* nothing was changed: the kept run is still there to resume once mended */
      assert_int_equal(q1("f.db", "SELECT count(*) FROM runs WHERE status = 'running'"), 1);
    }
  }
  gsl_rng_free(rng);
  /* the checkpoint itself is fine: it resumes to the uninterrupted run's end */
  hd_error err;
  assert_int_equal(resume("kept.db", &err), HD_OK);
  same_as_reference("kept.db");
  print_message("%d of %d flipped bits refused\n", refused, flips);
  assert_int_equal(refused, flips);
}

static void damaged_checkpoint_2d(void **state) {
  (void)state;
  flip_bits(scene2d, getenv("HAFF_SANITIZE") && getenv("HAFF_SANITIZE")[0] == '1' ? 60 : 120);
}

static void damaged_checkpoint_rods(void **state) {
  (void)state;
  flip_bits(scene_rods, 60);
}

/* Issue 24 item 10: a HAFFCKP2 checkpoint with its 16-byte checksum trailer cut off, alone or
 * with a bit flipped as well, is refused as damaged and nothing changes (before: it was read
 * as an older blob without a trailer, unchecked, and 9 of 30 stripped blobs with a flip
 * resumed to exit 0 with other rows). */
static void stripped_trailer_refused(void **state) {
  (void)state;
  kept_checkpoint(scene2d);
  q1("kept.db", "UPDATE checkpoints SET blob = substr(blob, 1, length(blob) - 16)");
  for (int flip = 0; flip < 2; flip++) {
    copy_file("kept.db", "f.db");
    if (flip) assert_int_equal(test_flip_checkpoint_bit(path_of("f.db"), 8 * 200 + 3), 0);
    hd_error err;
    int rc = resume("f.db", &err);
    if (rc != HD_EINPUT || !strstr(err.msg, "the checkpoint of run 1 is damaged") ||
        !strstr(err.msg, "trailer is missing"))
      fail_msg("flip %d: status %d: %s", flip, rc, err.msg);
    assert_int_equal(q1("f.db", "SELECT count(*) FROM runs WHERE status = 'running'"), 1);
  }
}

/* ---------------------------------------------------------------------------------------- */
/* a run killed in its set-up */

/* Leaves in database name what a run of scene killed in its first milliseconds leaves: its row
 * 'running' (and, as a large run's set-up may commit them, some initial states and a sample),
 * no checkpoint. */
static void killed_in_setup(const char *scene, const char *name) {
  hd_scene sc;
  hd_error err;
  assert_int_equal(hd_scene_load_string(&sc, scene, "t.ini", NULL, 0, &err), HD_OK);
  hd_db *db = NULL;
  assert_int_equal(hd_db_open(&db, path_of(name), &err), HD_OK);
  int64_t run = 0;
  assert_int_equal(hd_db_run_begin(db, sc.text, sc.seed, "test", &run, &err), HD_OK);
  hd_state_rec st = {0.0, 0, 0, 1.0, 2.0, 0.0, 0.5, 0.5, 0.0, 0.0, 1};
  assert_int_equal(hd_db_log_state(db, run, "initial", &st, &err), HD_OK);
  hd_sample_row sa = {0.0, 0, 0.0, 1.0, 0.0, NAN, NAN, NAN, NAN, NAN, NAN};
  assert_int_equal(hd_db_log_sample(db, run, &sa, &err), HD_OK);
  assert_int_equal(hd_db_close(db, &err), HD_OK);
  hd_scene_free(&sc);
  assert_int_equal(q1(name, "SELECT count(*) FROM runs WHERE status = 'running'"), 1);
  assert_int_equal(q1(name, "SELECT count(*) FROM checkpoints"), 0);
}

/* A run killed before its first checkpoint stayed 'running' for ever, and resume said "no
 * interrupted run to resume": it is now run again from its stored scene and seed, and ends as
 * the run never stopped (every row equal).  Not while another process holds its lock: a run
 * in its set-up is not taken over. */
static void rerun_killed_in_setup(void **state) {
  (void)state;
  assert_int_equal(run_scene(scene2d, "ref.db"), HD_OK);
  killed_in_setup(scene2d, "early.db");
  /* another process holds the run's lock, as a live run in its set-up does */
  int pipefd[2];
  assert_int_equal(pipe(pipefd), 0);
  fflush(NULL);
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    int fd = open(path_of("early.db.lock"), O_RDWR | O_CREAT, 0644);
    struct flock fl = {.l_type = F_WRLCK, .l_whence = SEEK_SET, .l_start = 1, .l_len = 1};
    if (fd < 0 || fcntl(fd, F_SETLK, &fl)) _exit(1);
    char c = 'l';
    if (write(pipefd[1], &c, 1) != 1) _exit(2);
    pause();
    _exit(0);
  }
  char c = 0;
  assert_int_equal(read(pipefd[0], &c, 1), 1);
  hd_error err;
  int rc = resume("early.db", &err);
  kill(pid, SIGKILL);
  waitpid(pid, NULL, 0);
  close(pipefd[0]);
  close(pipefd[1]);
  assert_int_equal(rc, HD_EINPUT);
  assert_non_null(strstr(err.msg, "is being run by another process"));
  assert_int_equal(q1("early.db", "SELECT count(*) FROM states"), 1); /* untouched */
  /* its process gone, the run is run again */
  rc = resume("early.db", &err);
  if (rc) fail_msg("resume: %s", err.msg);
  same_as_reference("early.db");
  /* with the uninterrupted run's message ("velocities_at: 1 of 3 snapshots not taken ...") */
  assert_int_equal(q1("early.db", "SELECT count(*) FROM runs r, ref.runs f WHERE r.message IS "
                                  "NOT f.message OR r.events IS NOT f.events"),
                   0);
  /* the same for a rods run, asked for by its id */
  unlink(path_of("ref.db"));
  assert_int_equal(run_scene(scene_rods, "ref.db"), HD_OK);
  killed_in_setup(scene_rods, "early2.db");
  hd_run_opts o = {.db_path = path_of("early2.db"), .quiet = 1, .version = "test"};
  int64_t run = 0;
  assert_int_equal(hd_run_resume(1, &o, &run, &err), HD_OK);
  same_as_reference("early2.db");
}

/* ---------------------------------------------------------------------------------------- */
/* checkpoint restore below the checksum: the fuzz target and its corpus */

#include "fuzz/fuzz_checkpoint.c"

#define CORPUS "tests/fuzz/corpus/checkpoint"

/* The bytes of file path (malloc'd, *n bytes). */
static unsigned char *slurp(const char *path, size_t *n) {
  FILE *f = fopen(path, "rb");
  assert_non_null(f);
  assert_int_equal(fseek(f, 0, SEEK_END), 0);
  long len = ftell(f);
  assert_true(len >= 0);
  rewind(f);
  unsigned char *b = malloc((size_t)len + 1);
  assert_non_null(b);
  assert_int_equal(fread(b, 1, (size_t)len, f), (size_t)len);
  fclose(f);
  *n = (size_t)len;
  return b;
}

/* Every input of the fuzz corpus (real blobs of the target's scenes, and what the fuzzer found)
 * goes through the target without a crash (the sanitizer build runs this too); the seeds, real
 * checkpoints, restore; and 300 single-bit flips of each seed (fixed seed) are refused or run,
 * never crash: the models' own checks, which the checksum shields from such flips in a resume,
 * are what keeps a blob written whole but wrong from crashing the engine. */
static void fuzz_corpus_replays(void **state) {
  (void)state;
  DIR *d = opendir(CORPUS);
  assert_non_null(d);
  struct dirent *e;
  int files = 0, seeds = 0;
  gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, 23);
  while ((e = readdir(d))) {
    if (e->d_name[0] == '.') continue;
    char p[600];
    snprintf(p, sizeof p, CORPUS "/%s", e->d_name);
    size_t n = 0;
    unsigned char *b = slurp(p, &n);
    LLVMFuzzerTestOneInput(b, n);
    files++;
    if (!strncmp(e->d_name, "bodies2d-", 9) || !strncmp(e->d_name, "rods-", 5)) {
      seeds++;
      hd_scene sc;
      hd_error err;
      assert_int_equal(
          hd_scene_load_string(&sc, fuzz_ckpt_scenes[b[0] & 1], "fuzz.ini", NULL, 0, &err), HD_OK);
      const hd_model_ops *ops = hd_model_for_scene(&sc);
      void *m = NULL;
      if (ops->alloc_restore(&m, &sc, b + 1, n - 1, &err)) fail_msg("%s: %s", p, err.msg);
      ops->free(m);
      hd_scene_free(&sc);
      for (int k = 0; k < 300; k++) {
        size_t bit = 8 + gsl_rng_uniform_int(rng, (unsigned long)(8 * (n - 1)));
        b[bit / 8] ^= (unsigned char)(1u << (bit % 8));
        LLVMFuzzerTestOneInput(b, n);
        b[bit / 8] ^= (unsigned char)(1u << (bit % 8));
      }
    }
    free(b);
  }
  closedir(d);
  gsl_rng_free(rng);
  print_message("%d inputs, %d seeds\n", files, seeds);
  assert_true(seeds >= 6);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_setup_teardown(damaged_checkpoint_2d, setup, teardown),
      cmocka_unit_test_setup_teardown(damaged_checkpoint_rods, setup, teardown),
      cmocka_unit_test_setup_teardown(stripped_trailer_refused, setup, teardown),
      cmocka_unit_test_setup_teardown(rerun_killed_in_setup, setup, teardown),
      cmocka_unit_test(fuzz_corpus_replays),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
