/* End-to-end tests of studies through bin/haff ($HAFF_BIN): haff sweep (grid, points, bad
 * input, --status, --resume, re-running a finished study, the Slurm scripts with a stand-in
 * sbatch; the real Slurm is tests/slurm/run.sh), haff merge (ids, rows, provenance, refusals,
 * atomicity, old schema), haff resume --all, and the progress of a run seen from a batch log
 * and from its runs row. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <signal.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <fcntl.h>

#include "hd_db.h"
#include "hd_merge.h"
#include "hd_scene.h"

#include "test_cli_util.h"

/* One integer from an SQL query on database db in dir (-1 when there is no row or no file). */
static long long q1(const char *db, const char *sql) {
  char p[400];
  snprintf(p, sizeof p, "%s/%s", dir, db);
  sqlite3 *h;
  if (sqlite3_open_v2(p, &h, SQLITE_OPEN_READONLY, NULL) != SQLITE_OK) {
    sqlite3_close(h);
    return -1;
  }
  sqlite3_busy_timeout(h, 5000);
  sqlite3_stmt *st;
  long long v = -1;
  if (sqlite3_prepare_v2(h, sql, -1, &st, 0) == SQLITE_OK) {
    if (sqlite3_step(st) == SQLITE_ROW) v = sqlite3_column_int64(st, 0);
    sqlite3_finalize(st);
  }
  sqlite3_close(h);
  return v;
}

/* Starts `haff ARGS...` in dir with stderr to errfile (not a terminal); returns the pid. */
static pid_t start(const char *errfile, const char *const *args) {
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    if (chdir(dir)) _exit(99);
    if (!freopen(errfile, "w", stderr)) _exit(97);
    const char *argv[32];
    int n = 0;
    argv[n++] = haff;
    for (; args[n - 1] && n < 31; n++) argv[n] = args[n - 1];
    argv[n] = NULL;
    execv(haff, (char *const *)argv);
    _exit(98);
  }
  return pid;
}

/* Leaves in database name (in dir) what a run of scene file scene (with the overrides sets)
 * killed in its set-up leaves: its row 'running', no checkpoint, no lock held. */
static void killed_in_setup(const char *scene, const char *const *sets, int nset,
                            const char *name) {
  char sp[400], dp[400];
  snprintf(sp, sizeof sp, "%s/%s", dir, scene);
  snprintf(dp, sizeof dp, "%s/%s", dir, name);
  hd_scene sc;
  hd_error err;
  hd_error_clear(&err);
  if (hd_scene_load(&sc, sp, sets, nset, &err)) fail_msg("%s", err.msg);
  hd_db *db = NULL;
  assert_int_equal(hd_db_open(&db, dp, &err), HD_OK);
  int64_t run = 0;
  assert_int_equal(hd_db_run_begin(db, sc.text, sc.seed, "test", &run, &err), HD_OK);
  assert_int_equal(hd_db_close(db, &err), HD_OK);
  hd_scene_free(&sc);
  assert_int_equal(q1(name, "SELECT count(*) FROM runs WHERE status = 'running'"), 1);
  assert_int_equal(q1(name, "SELECT count(*) FROM checkpoints"), 0);
}

/* Forks a process that holds byte at of lock file name (in dir) until killed; returns its pid
 * once it holds it. */
static pid_t hold_lock(const char *name, off_t at) {
  int pipefd[2];
  assert_int_equal(pipe(pipefd), 0);
  fflush(NULL);
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    char p[400];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    int fd = open(p, O_RDWR | O_CREAT, 0644);
    struct flock fl = {.l_type = F_WRLCK, .l_whence = SEEK_SET, .l_start = at, .l_len = 1};
    if (fd < 0 || fcntl(fd, F_SETLK, &fl)) _exit(1);
    char c = 'l';
    if (write(pipefd[1], &c, 1) != 1) _exit(2);
    pause();
    _exit(0);
  }
  char c = 0;
  assert_int_equal(read(pipefd[0], &c, 1), 1);
  close(pipefd[0]);
  close(pipefd[1]);
  return pid;
}

static const struct timespec ms10 = {0, 10000000L};

/* Waits (at most 60 s) until the query on db gives a value > 0; returns it (or <= 0). */
static long long wait_positive(const char *db, const char *sql, pid_t pid) {
  long long v = -1;
  int st;
  for (int k = 0; k < 6000 && v <= 0; k++) {
    if (waitpid(pid, &st, WNOHANG) == pid) fail_msg("the process ended before %s", sql);
    nanosleep(&ms10, NULL);
    v = q1(db, sql);
  }
  return v;
}

/* A run of a few seconds (disks, nothing logged but samples), checkpointing often. */
static const char long_scene[] = "[system]\narea_fraction = 0.1\nseed = 1\n[disks]\ncount = 1000\n"
                                 "alpha = 0.95\n[run]\nstop_events = 2000000\n"
                                 "checkpoint_every = 0.1\n[log]\ncollisions = none\n"
                                 "samples_every = 5\n";
/* A short run (well under a second), collisions logged. */
static const char short_scene[] = "[system]\narea_fraction = 0.1\nseed = 1\n[disks]\ncount = 200\n"
                                  "alpha = 0.9\n[run]\nstop_cpd = 20\n[log]\n"
                                  "collisions = all\nsamples_every = 1\n";

static int setup(void **state) {
  (void)state;
  haff = getenv("HAFF_BIN");
  if (!haff) haff = "bin/haff";
  static char abs[4096];
  if (haff[0] != '/' && realpath(haff, abs)) haff = abs;
  if (getenv("HAFF_SANITIZE") && getenv("HAFF_SANITIZE")[0] == '1')
    haff = NULL; /* the tests that drive bin/haff skip: it is not the sanitized build */
  assert_int_equal(test_cli_mkdtemp("sweep"), 0);
  write_file("long.ini", long_scene);
  write_file("short.ini", short_scene);
  return 0;
}

static int teardown(void **state) {
  (void)state;
  return test_cli_rmdir();
}

/* ------------------------------------------------------------------------------------------ */
/* progress, runs.events, resume --all */

/* With stderr not a terminal a run writes one progress line every --progress seconds (whole
 * lines, no \r), and runs.events and runs.cpd grow while it goes (they stayed 0 until the end);
 * --progress 0 writes none. */
static void progress_in_a_batch_log(void **state) {
  (void)state;
  if (!haff) skip();
  pid_t pid = start("prog-err.txt", (const char *const[]){"run", "long.ini", "-o", "prog.db",
                                                          "--progress", "0.2", NULL});
  long long ev = wait_positive("prog.db", "SELECT events FROM runs WHERE status = 'running'", pid);
  long long cpd = q1("prog.db", "SELECT cpd > 0 FROM runs WHERE status = 'running'");
  int st;
  waitpid(pid, &st, 0);
  assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 0);
  assert_true(ev > 0);
  assert_int_equal(cpd, 1);
  long long total = q1("prog.db", "SELECT events FROM runs");
  assert_true(total >= ev);
  assert_int_equal(q1("prog.db", "SELECT abs(cpd - (SELECT max(cpd) FROM samples)) < 5 "
                                 "FROM runs"),
                   1); /* samples every 5 cpd: the last is within 5 of the end */
  char log[65536];
  read_file("prog-err.txt", log, sizeof log);
  int lines = 0;
  for (const char *p = log; (p = strstr(p, "haff: prog.db run 1: ")); p++) lines++;
  assert_true(lines >= 2);
  assert_null(strchr(log, '\r'));
  assert_int_equal(sh("%s run short.ini -o prog0.db --progress 0", haff), 0);
  read_file("err.txt", log, sizeof log);
  assert_null(strstr(log, "events"));
  assert_int_equal(sh("%s run short.ini -o prog0.db --progress -1", haff), 2);
}

/* haff resume DB --all brings every interrupted run of DB to done, each exactly as an
 * uninterrupted run of its seed (without --all only the newest was resumed). */
static void resume_all(void **state) {
  (void)state;
  if (!haff) skip();
  for (int s = 1; s <= 2; s++) {
    char seed[16];
    snprintf(seed, sizeof seed, "%d", s);
    pid_t pid = start("ra-err.txt", (const char *const[]){"run", "long.ini", "-o", "ra.db",
                                                          "--seed", seed, "--quiet", NULL});
    char sql[200];
    snprintf(sql, sizeof sql, "SELECT events FROM runs WHERE seed = %d", s);
    assert_true(wait_positive("ra.db", sql, pid) > 0);
    kill(pid, SIGTERM);
    int st;
    waitpid(pid, &st, 0);
    assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 1);
  }
  assert_int_equal(q1("ra.db", "SELECT count(*) FROM runs WHERE status = 'interrupted'"), 2);
  assert_int_equal(sh("%s resume ra.db --all --run 1", haff), 2);
  assert_int_equal(sh("%s resume ra.db --all --quiet", haff), 0);
  assert_int_equal(q1("ra.db", "SELECT count(*) FROM runs WHERE status = 'done'"), 2);
  for (int s = 1; s <= 2; s++) {
    assert_int_equal(sh("%s run long.ini -o ra-ref%d.db --seed %d --quiet", haff, s, s), 0);
    char db[32], sql[200];
    snprintf(db, sizeof db, "ra-ref%d.db", s);
    long long ref = q1(db, "SELECT events FROM runs");
    snprintf(sql, sizeof sql, "SELECT events FROM runs WHERE seed = %d", s);
    assert_int_equal(q1("ra.db", sql), ref);
  }
  assert_int_equal(sh("%s resume ra.db --all", haff), 0); /* nothing left: says so, exit 0 */
  char e[1024];
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "no run to resume"));
}

/* haff resume DB --all runs again a run killed in its set-up (left 'running' without a
 * checkpoint), as plain haff resume does: it said "no run to resume" and exited 0. */
static void resume_all_killed_in_setup(void **state) {
  (void)state;
  if (!haff) skip();
  killed_in_setup("short.ini", NULL, 0, "ks7.db");
  assert_int_equal(sh("%s resume ks7.db --all --quiet", haff), 0);
  assert_int_equal(q1("ks7.db", "SELECT count(*) FROM runs WHERE status = 'done'"), 1);
  assert_int_equal(q1("ks7.db", "SELECT count(*) FROM runs"), 1);
  assert_int_equal(sh("%s run short.ini -o ks7ref.db --quiet", haff), 0);
  assert_int_equal(q1("ks7.db", "SELECT events FROM runs"),
                   q1("ks7ref.db", "SELECT events FROM runs"));
  /* one that another process holds is left to it, and said so */
  killed_in_setup("short.ini", NULL, 0, "ks7b.db");
  pid_t holder = hold_lock("ks7b.db.lock", 1);
  int rc = sh("%s resume ks7b.db --all", haff);
  kill(holder, SIGKILL);
  waitpid(holder, NULL, 0);
  assert_int_equal(rc, 0);
  char e[2048];
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "run 1 is being run by another process: left to it"));
  assert_int_equal(q1("ks7b.db", "SELECT count(*) FROM runs WHERE status = 'running'"), 1);
}

/* ------------------------------------------------------------------------------------------ */
/* merge */

/* Two inputs merge into one: ids 1..3, every row under its new id, provenance naming the
 * source file and id; then a run already present, a file given twice (by another path too),
 * a non-haff file and a corrupt one are refused with exit 2 and OUT left as it was. */
static void merge_runs_and_refusals(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("%s run short.ini -o m1.db --seed 1 --quiet", haff), 0);
  assert_int_equal(sh("%s run short.ini -o m2.db --seed 2 --quiet", haff), 0);
  assert_int_equal(sh("%s run short.ini -o m2.db --seed 3 --quiet", haff), 0);
  long long c1 = q1("m1.db", "SELECT count(*) FROM collisions");
  long long c2 = q1("m2.db", "SELECT count(*) FROM collisions WHERE run = 2");
  assert_true(c1 > 1000);
  assert_int_equal(sh("%s merge out.db m1.db m2.db", haff), 0);
  assert_int_equal(q1("out.db", "SELECT group_concat(id || ':' || seed) = '1:1,2:2,3:3' FROM "
                                "(SELECT id, seed FROM runs ORDER BY id)"),
                   1);
  assert_int_equal(q1("out.db", "SELECT count(*) FROM collisions WHERE run = 1"), c1);
  assert_int_equal(q1("out.db", "SELECT count(*) FROM collisions WHERE run = 3"), c2);
  assert_int_equal(q1("out.db", "SELECT count(*) FROM states WHERE run = 3 AND label = 'final'"),
                   200);
  assert_int_equal(q1("out.db", "SELECT count(*) FROM provenance WHERE run = 3 AND source_run = "
                                "2 AND source LIKE '%/m2.db' AND host IS NOT NULL"),
                   1);
  assert_int_equal(q1("out.db", "PRAGMA user_version"), HD_DB_SCHEMA_VERSION);
  /* refusals: exit 2, one line naming the file, OUT as it was */
  char e[2048];
  assert_int_equal(sh("%s merge out.db m2.db", haff), 2);
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "m2.db: run 1 (seed 2) is already in out.db as run 2"));
  assert_int_equal(sh("%s merge new.db m1.db ./m1.db", haff), 2);
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "given twice"));
  assert_false(exists("new.db"));
  assert_int_equal(sh("ln m1.db hard.db && %s merge new.db m1.db hard.db", haff), 2);
  assert_false(exists("new.db"));
  write_file("text.db", "not a database, just text long enough to be looked at by sqlite\n");
  assert_int_equal(sh("%s merge out.db text.db", haff), 2);
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "text.db: not a haff database"));
  assert_int_equal(sh("sqlite3 other.db 'CREATE TABLE t (x)'"), 0);
  assert_int_equal(sh("%s merge out.db other.db", haff), 2);
  /* a corrupt input: a page of the collisions' b-tree overwritten */
  assert_int_equal(sh("cp m1.db bad.db && dd if=/dev/urandom of=bad.db bs=4096 seek=20 count=2 "
                      "conv=notrunc status=none"),
                   0);
  assert_int_equal(sh("%s merge out.db bad.db", haff), 2);
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "bad.db"));
  assert_int_equal(q1("out.db", "SELECT count(*) FROM runs"), 3);
  assert_int_equal(sh("%s merge out.db out.db", haff), 2);
  /* a merged file merges on, its runs keeping the file they were made in */
  assert_int_equal(sh("%s run short.ini -o m3.db --seed 4 --quiet", haff), 0);
  assert_int_equal(sh("%s merge out.db m3.db", haff), 0);
  assert_int_equal(sh("%s merge again.db out.db", haff), 0);
  assert_int_equal(q1("again.db", "SELECT count(*) FROM provenance WHERE run = 3 AND source "
                                  "LIKE '%/m2.db' AND source_run = 2"),
                   1);
  assert_int_equal(q1("again.db", "SELECT count(*) FROM runs"), 4);
  assert_int_equal(sh("%s haff-fit again.db > /dev/null", haff), 0);
}

/* A merge killed midway leaves OUT as it was (it is built in a file beside OUT and renamed):
 * a merge of ~10^6 rows is killed after 50 ms, many times over; OUT then holds its one run,
 * passes the integrity check, and the merge finishes when let run. */
static void merge_killed_leaves_out(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("big.ini", "[system]\narea_fraction = 0.1\n[disks]\ncount = 2000\n[run]\n"
                        "stop_events = 1000000\n[log]\ncollisions = all\n");
  assert_int_equal(sh("%s run big.ini -o big.db --quiet", haff), 0);
  assert_int_equal(sh("%s run short.ini -o k.db --quiet", haff), 0);
  int killed = 0;
  for (int k = 0; k < 5; k++) {
    pid_t pid = start("kill-err.txt", (const char *const[]){"merge", "k.db", "big.db", NULL});
    const struct timespec ms50 = {0, 50000000L};
    nanosleep(&ms50, NULL);
    kill(pid, SIGKILL);
    int st;
    waitpid(pid, &st, 0);
    killed += WIFSIGNALED(st);
    if (!WIFSIGNALED(st)) break; /* it finished first: nothing more to see */
    assert_int_equal(q1("k.db", "SELECT count(*) FROM runs"), 1);
    assert_int_equal(q1("k.db", "SELECT count(*) FROM pragma_integrity_check WHERE "
                                "integrity_check = 'ok'"),
                     1);
  }
  assert_true(killed >= 1);
  assert_int_equal(sh("rm -f k.db.merge-*.tmp* && %s merge k.db big.db --quiet", haff), 0);
  assert_int_equal(q1("k.db", "SELECT count(*) FROM runs"), 2);
  assert_int_equal(q1("k.db", "SELECT count(*) FROM collisions WHERE run = 2"),
                   q1("big.db", "SELECT count(*) FROM collisions"));
}

/* A database of schema version 0 (before runs.cpd and provenance) is read and merged (its runs
 * get a provenance row naming it) and, when a run is added to it, brought to this version (its
 * species table made). */
static void old_schema_reads_and_upgrades(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(
      sh("%s run short.ini -o old.db --quiet && sqlite3 old.db 'ALTER TABLE runs "
         "DROP COLUMN cpd; DROP TABLE provenance; CREATE TEMP TABLE x AS SELECT run, t, "
         "collisions, cpd, e_tr, e_rot, e_tr_dimer, e_rot_dimer, e_tr_disk FROM samples; DROP "
         "VIEW samples; DROP TABLE sample_rows; CREATE TABLE samples (run INTEGER NOT NULL, t "
         "REAL NOT NULL, collisions INTEGER NOT NULL, cpd REAL NOT NULL, e_tr REAL NOT NULL, "
         "e_rot REAL NOT NULL, e_tr_dimer REAL, e_rot_dimer REAL, e_tr_disk REAL); INSERT INTO "
         "samples SELECT * FROM temp.x; DROP TABLE species; DROP TABLE sample_species; "
         "PRAGMA user_version = 0'",
         haff),
      0);
  assert_int_equal(q1("old.db", "SELECT count(*) FROM pragma_table_info('runs') WHERE name = "
                                "'cpd'"),
                   0);
  assert_int_equal(sh("%s haff-fit old.db > /dev/null", haff), 0);
  assert_int_equal(sh("%s merge fromold.db old.db", haff), 0);
  assert_int_equal(q1("fromold.db", "SELECT count(*) FROM provenance WHERE run = 1 AND source "
                                    "LIKE '%/old.db' AND host IS NULL"),
                   1);
  assert_int_equal(sh("%s run short.ini -o old.db --seed 9 --quiet", haff), 0);
  assert_int_equal(q1("old.db", "PRAGMA user_version"), HD_DB_SCHEMA_VERSION);
  assert_int_equal(q1("old.db", "SELECT count(*) FROM runs WHERE cpd >= 20"), 1);
  assert_true(q1("old.db", "SELECT count(*) FROM species WHERE run = 2") >= 1); /* version 3 */
  /* version 5: the table samples (no state measures) became sample_rows and the view */
  assert_int_equal(q1("old.db", "SELECT count(*) FROM sqlite_schema WHERE name = 'samples' AND "
                                "type = 'view'"),
                   1);
  assert_int_equal(q1("old.db", "SELECT count(*) FROM samples WHERE run = 1"),
                   q1("fromold.db", "SELECT count(*) FROM samples WHERE run = 1"));
  assert_int_equal(q1("old.db", "SELECT count(*) FROM samples WHERE run = 1 AND flow_frac IS "
                                "NULL"),
                   q1("old.db", "SELECT count(*) FROM samples WHERE run = 1"));
}

/* A run's identity is (scene, seed, commit) (issue 28): haff run refuses a second run of a
 * scene and seed into one database (exit 2, one line naming the run, nothing written) unless
 * --force; haff merge refuses a run of the same identity, and takes one of another commit (a
 * rerun by another build; before, the version "0.1.0" of every build made it a duplicate).  An
 * input from before schema version 4 (no runs.git_commit) counts as commit 'unknown'.  Each run
 * records the command line that began it, and a sweep's run its point. */
static void run_identity_and_duplicates(void **state) {
  (void)state;
  if (!haff) skip();
  char e[2048];
  assert_int_equal(sh("%s run short.ini -o id.db --seed 5 --quiet", haff), 0);
  assert_int_equal(sh("%s run short.ini -o id.db --seed 5 --quiet", haff), 2);
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "haff run: id.db has run 1 of this scene and seed already (status "
                            "done, commit "));
  assert_non_null(strstr(e, "--force"));
  assert_int_equal(q1("id.db", "SELECT count(*) FROM runs"), 1);
  assert_int_equal(sh("%s run short.ini -o id.db --seed 6 --quiet", haff), 0); /* other seed */
  assert_int_equal(sh("%s run short.ini -o id.db --seed 5 --quiet --force", haff), 0);
  assert_int_equal(q1("id.db", "SELECT count(*) FROM runs WHERE seed = 5"), 2);
  assert_int_equal(q1("id.db", "SELECT count(*) FROM runs WHERE id = 3 AND command LIKE "
                               "'%/haff run short.ini -o id.db --seed 5 --quiet --force' AND "
                               "git_commit IS NOT NULL AND compiler IS NOT NULL AND cflags LIKE "
                               "'%-std=c11%' AND sweep_point IS NULL"),
                   1);
  /* merge: the same identity refused, another commit taken */
  assert_int_equal(sh("%s run short.ini -o id2.db --seed 5 --quiet", haff), 0);
  assert_int_equal(sh("%s merge idm.db id.db", haff), 0);
  assert_int_equal(sh("%s merge idm.db id2.db", haff), 2);
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "id2.db: run 1 (seed 5) is already in idm.db as run 1 (the same "
                            "scene, seed and commit)"));
  assert_int_equal(sh("sqlite3 id2.db \"UPDATE runs SET git_commit = 'another'\""), 0);
  assert_int_equal(sh("%s merge idm.db id2.db", haff), 0);
  assert_int_equal(q1("idm.db", "SELECT count(*) FROM runs WHERE seed = 5"), 3);
  assert_int_equal(q1("idm.db", "SELECT count(*) FROM runs WHERE git_commit = 'another'"), 1);
  /* an input of schema version 3 (no git_commit): 'unknown', a duplicate of an 'unknown' run */
  assert_int_equal(
      sh("%s run short.ini -o v3.db --seed 7 --quiet && cp v3.db v3b.db && "
         "for f in v3.db v3b.db; do sqlite3 $f 'DROP VIEW run_summary; ALTER TABLE runs "
         "DROP COLUMN git_commit; PRAGMA user_version = 3' || exit 1; done",
         haff),
      0);
  assert_int_equal(sh("%s merge idm.db v3.db", haff), 0);
  assert_int_equal(q1("idm.db", "SELECT count(*) FROM runs WHERE seed = 7 AND git_commit IS "
                                "NULL"),
                   1);
  assert_int_equal(sh("%s merge idm.db v3b.db", haff), 2);
  /* a file of version 3 is brought to 4 by a run, its old rows NULL */
  assert_int_equal(sh("%s run short.ini -o v3.db --seed 8 --quiet", haff), 0);
  assert_int_equal(q1("v3.db", "PRAGMA user_version"), HD_DB_SCHEMA_VERSION);
  assert_int_equal(q1("v3.db", "SELECT count(*) FROM runs WHERE git_commit IS NULL"), 1);
  assert_int_equal(q1("v3.db", "SELECT count(*) FROM runs WHERE git_commit IS NOT NULL"), 1);
  assert_int_equal(sh("%s run short.ini -o v3.db --seed 7 --quiet", haff), 2); /* still refused */
  /* a sweep's runs record their point */
  write_file("pt.ini", "[sweep]\nscene = short.ini\n[points]\npoint = disks.alpha=0.5\n"
                       "point = disks.alpha=0.6 system.seed=4\n");
  assert_int_equal(sh("%s sweep pt.ini --quiet", haff), 0);
  assert_int_equal(q1("pt/study.db", "SELECT count(*) FROM runs WHERE id = 2 AND sweep_point "
                                     "LIKE '%/pt point 1: disks.alpha=0.6 system.seed=4'"),
                   1);
}

/* hd_db_merge from the library (so that the sanitized build runs it too): runs written with
 * the hd_db API, two inputs into a new OUT and a third into it, ids shifted and every row under
 * its run; a duplicate run and a file given twice refused with OUT as it was; a writer refuses a
 * file of a newer schema version. */
static void merge_library(void **state) {
  (void)state;
  char path[3][400], out[400];
  for (int f = 0; f < 3; f++) {
    snprintf(path[f], sizeof path[f], "%s/lib%d.db", dir, f);
    hd_db *db;
    hd_error err;
    assert_int_equal(hd_db_open(&db, path[f], &err), HD_OK);
    for (int r = 0; r <= f; r++) {
      int64_t run;
      char scene[64];
      snprintf(scene, sizeof scene, "[system]\nseed = %d\n", 10 * f + r);
      assert_int_equal(
          hd_db_run_begin(db, scene, (unsigned long long)(10 * f + r), "t", &run, &err), HD_OK);
      for (int k = 1; k <= 50 * (r + 1); k++) {
        hd_collision_row row = {.seq = k,
                                .t = k,
                                .kind = hd_coll_kind_of(HD_KIND_DISK, HD_KIND_DISK),
                                .i = 0,
                                .j = 1,
                                .theta_i = NAN,
                                .theta_j = NAN,
                                .f = 0.5,
                                .de = -1,
                                .vn = -1,
                                .eps = NAN,
                                .e_tr = NAN,
                                .tb_i = NAN,
                                .tb_j = NAN};
        assert_int_equal(hd_db_log_collision(db, run, &row, &err), HD_OK);
      }
      assert_int_equal(hd_db_run_origin(db, run, "node7", "123", "4", &err), HD_OK);
      assert_int_equal(hd_db_run_status(db, run, "done", 50, 0.1, &err), HD_OK);
    }
    assert_int_equal(hd_db_close(db, &err), HD_OK);
  }
  snprintf(out, sizeof out, "%s/libout.db", dir);
  const char *in01[] = {path[0], path[1]};
  int64_t n = 0;
  hd_error err;
  assert_int_equal(hd_db_merge(out, in01, 2, &n, &err), HD_OK);
  assert_int_equal(n, 3);
  const char *in2[] = {path[2]};
  assert_int_equal(hd_db_merge(out, in2, 1, &n, &err), HD_OK);
  assert_int_equal(n, 3);
  assert_int_equal(q1("libout.db", "SELECT count(*) FROM runs"), 6);
  /* run 6 is lib2's run 3 (seed 22), with 150 collisions, from node7, task 4 */
  assert_int_equal(q1("libout.db", "SELECT count(*) FROM collisions WHERE run = 6"), 150);
  assert_int_equal(q1("libout.db", "SELECT seed FROM runs WHERE id = 6"), 22);
  assert_int_equal(q1("libout.db", "SELECT count(*) FROM provenance WHERE run = 6 AND host = "
                                   "'node7' AND slurm_job = '123' AND slurm_task = '4' AND "
                                   "source_run = 3 AND source LIKE '%/lib2.db'"),
                   1);
  assert_int_equal(q1("libout.db", "SELECT count(*) FROM collisions"),
                   50 + 50 + 100 + 50 + 100 + 150);
  assert_int_equal(hd_db_merge(out, in2, 1, &n, &err), HD_EINPUT);
  assert_non_null(strstr(err.msg, "is already in"));
  const char *twice[] = {path[0], path[0]};
  assert_int_equal(hd_db_merge(out, twice, 2, &n, &err), HD_EINPUT);
  assert_int_equal(q1("libout.db", "SELECT count(*) FROM runs"), 6);
  /* a file of a newer schema version is not written to */
  assert_int_equal(sh("sqlite3 libout.db 'PRAGMA user_version = %d'", HD_DB_SCHEMA_VERSION + 1), 0);
  hd_db *db;
  assert_int_equal(hd_db_open(&db, out, &err), HD_EINPUT);
  assert_non_null(strstr(err.msg, "newer than this haff's"));
}

/* ------------------------------------------------------------------------------------------ */
/* sweep */

/* A grid of 2 values x 2 seeds runs with --jobs 2 into 4 databases and one merged study.db
 * whose runs carry their overrides; --status says done; a second haff sweep does nothing. */
static void sweep_grid_runs_and_merges(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("g.ini", "; a study\n[sweep]\nscene = short.ini\nseeds = 1:2:1\n[axes]\n"
                      "disks.alpha = 0.8 0.9   ; two values\n");
  assert_int_equal(sh("%s sweep g.ini --dry-run > dry.txt", haff), 0);
  char m[4096];
  read_file("dry.txt", m, sizeof m);
  assert_non_null(strstr(m, "\n3\tpoints/p0003.db\tdisks.alpha=0.9 system.seed=2\n"));
  assert_false(exists("g"));
  assert_int_equal(sh("%s sweep g.ini --jobs 2", haff), 0);
  assert_int_equal(q1("g/study.db", "SELECT count(*) FROM runs WHERE status = 'done'"), 4);
  assert_int_equal(q1("g/study.db", "SELECT count(*) FROM runs WHERE id = 4 AND seed = 2 AND "
                                    "scene LIKE '%alpha = 0.9%'"),
                   1);
  assert_int_equal(q1("g/study.db", "SELECT count(DISTINCT source) FROM provenance"), 4);
  assert_int_equal(q1("g/points/p0002.db", "SELECT count(*) FROM runs WHERE seed = 1 AND scene "
                                           "LIKE '%alpha = 0.9%'"),
                   1);
  assert_int_equal(sh("%s sweep --status g > status.txt", haff), 0);
  read_file("status.txt", m, sizeof m);
  int done = 0;
  for (const char *p = m; (p = strstr(p, "\tdone\tdone\t")); p++) done++;
  assert_int_equal(done, 4);
  struct stat a, b;
  char p[400];
  snprintf(p, sizeof p, "%s/g/study.db", dir);
  assert_int_equal(stat(p, &a), 0);
  assert_int_equal(sh("%s sweep g.ini", haff), 0);
  read_file("err.txt", m, sizeof m);
  assert_non_null(strstr(m, "nothing to do"));
  assert_int_equal(stat(p, &b), 0);
  assert_true(a.st_mtim.tv_sec == b.st_mtim.tv_sec && a.st_mtim.tv_nsec == b.st_mtim.tv_nsec);
  /* another sweep into the same folder is refused */
  write_file("g2.ini", "[sweep]\nscene = short.ini\n[axes]\ndisks.alpha = 0.7\n");
  assert_int_equal(sh("%s sweep g2.ini -o g", haff), 2);
  /* listed points */
  write_file("l.ini", "[sweep]\nscene = short.ini\n[points]\npoint = disks.alpha=0.5 "
                      "disks.count=100\npoint = disks.alpha=0.6\n");
  assert_int_equal(sh("%s sweep l.ini -o lst --quiet", haff), 0);
  assert_int_equal(q1("lst/study.db", "SELECT count(*) FROM runs WHERE id = 1 AND scene LIKE "
                                      "'%count = 100%'"),
                   1);
  assert_int_equal(q1("lst/study.db", "SELECT count(*) FROM runs"), 2);
}

/* Bad sweep files: one line naming file, line and key, exit 2, no study folder made. */
static void sweep_bad_input(void **state) {
  (void)state;
  if (!haff) skip();
  static const struct {
    const char *text, *needle;
  } cases[] = {
      {"[sweep]\nscene = short.ini\ncolour = 1\n", "b.ini:3: [sweep] colour: unknown key"},
      {"[sweep]\nscene = short.ini\n[axes]\ndisks.colour = 1 2\n",
       "b.ini:4: [axes] disks.colour: --set disks.colour=1: [disks] colour = 1: unknown key"},
      {"[sweep]\nscene = short.ini\n[axes]\nhats.size = 1 2\n", "b.ini:4: [axes] hats.size:"},
      {"[sweep]\nscene = short.ini\n[axes]\ndisks.alpha = 0.5 1.5\n",
       "b.ini:4: [axes] disks.alpha: --set disks.alpha=1.5: [disks] alpha = 1.5: must be in"},
      {"[sweep]\nscene = short.ini\n[axes]\ndisks.alpha = 0.9:0.5:0.1\n",
       "b.ini:4: [axes] disks.alpha: '0.9:0.5:0.1': a range needs FROM <= TO"},
      {"[sweep]\nscene = short.ini\nseeds = 1 x\n", "b.ini:3: [sweep] seeds: 'x'"},
      {"[sweep]\nscene = nothere.ini\n", "b.ini:2: [sweep] scene: 'nothere.ini'"},
      {"[sweep]\nseeds = 1\n", "[sweep] scene: missing"},
      {"[sweep]\nscene = short.ini\n[axes]\ndisks.alpha = 0.5\n[points]\npoint = disks.count=9\n",
       "b.ini:6: [points] point: a sweep has [axes] or [points], not both"},
      {"[sweep]\nscene = short.ini\n[points]\npoint = disks.count=9 run.stop_cpd\n",
       "b.ini:4: [points] point: 'run.stop_cpd': not SECTION.KEY=VALUE"},
      {"[sweep]\nscene = short.ini\n[grid]\n", "b.ini:3: [grid]: unknown section"},
  };
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    write_file("b.ini", cases[k].text);
    int rc = sh("%s sweep b.ini", haff);
    char e[2048];
    read_file("err.txt", e, sizeof e);
    if (rc != 2 || !strstr(e, cases[k].needle) || strchr(e, '\n') != e + strlen(e) - 1)
      fail_msg("case %zu: exit %d, stderr '%s', wanted '%s'", k, rc, e, cases[k].needle);
    assert_false(exists("b"));
  }
  assert_int_equal(sh("%s sweep --status nowhere", haff), 2);
  assert_int_equal(sh("%s sweep", haff), 2);
  assert_int_equal(sh("%s sweep short.ini --jobs 0", haff), 2);
  assert_int_equal(sh("%s sweep short.ini --time 5", haff), 2); /* --time without --slurm */
}

/* [axes] is validated point by point, not value by value: run.stop_cpd = 12 is bad alone with
 * the base scene's velocities_at = 10 15 but fine with log.velocities_at = 5 (as with --set);
 * a combination that is bad is named with all its overrides. */
static void sweep_axes_validates_whole_points(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("vbase.ini", "[system]\narea_fraction = 0.1\nseed = 1\n[disks]\ncount = 50\n"
                          "alpha = 0.9\n[run]\nstop_cpd = 20\n[log]\nvelocities_at = 10 15\n");
  write_file("va.ini", "[sweep]\nscene = vbase.ini\n[axes]\nlog.velocities_at = 5\n"
                       "run.stop_cpd = 12 20\n");
  assert_int_equal(sh("%s sweep va.ini --dry-run > va.txt", haff), 0);
  char m[4096];
  read_file("va.txt", m, sizeof m);
  assert_non_null(strstr(m, "log.velocities_at=5 run.stop_cpd=12\n"));
  /* velocities_at = 30 is fine with stop_cpd = 40, not with 12: that point is named */
  write_file("vb.ini", "[sweep]\nscene = vbase.ini\n[axes]\nlog.velocities_at = 5 30\n"
                       "run.stop_cpd = 12 40\n");
  assert_int_equal(sh("%s sweep vb.ini", haff), 2);
  read_file("err.txt", m, sizeof m);
  if (!strstr(m, "vb.ini:5: [axes]: point 2 (log.velocities_at=30 run.stop_cpd=12): ") ||
      !strstr(m, "30 is past stop_cpd = 12"))
    fail_msg("stderr '%s'", m);
  assert_false(exists("vb"));
}

/* A local sweep stopped with SIGTERM passes it to its points (checkpointed, interrupted, exit
 * 1, not merged); --status says so; --resume finishes them, each exactly as an uninterrupted
 * run of the point, and merges. */
static void sweep_interrupted_then_resumed(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("r.ini", "[sweep]\nscene = long.ini\nseeds = 1 2\n");
  pid_t pid = start(
      "r-err.txt", (const char *const[]){"sweep", "r.ini", "--jobs", "2", "--progress", "0", NULL});
  assert_true(wait_positive("r/points/p0001.db", "SELECT events FROM runs", pid) > 0);
  kill(pid, SIGTERM);
  int st;
  waitpid(pid, &st, 0);
  assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 1);
  assert_false(exists("r/study.db"));
  assert_int_equal(sh("%s sweep --status r > rs.txt", haff), 0);
  char m[4096];
  read_file("rs.txt", m, sizeof m);
  assert_non_null(strstr(m, "\n1\tinterrupted\tinterrupted\t"));
  assert_int_equal(sh("%s sweep --merge r", haff), 1); /* not every point done */
  assert_int_equal(sh("%s sweep --resume r --jobs 2 --quiet", haff), 0);
  assert_int_equal(q1("r/study.db", "SELECT count(*) FROM runs WHERE status = 'done'"), 2);
  assert_int_equal(sh("%s run long.ini -o rref.db --seed 2 --quiet", haff), 0);
  assert_int_equal(q1("r/points/p0001.db", "SELECT events FROM runs"),
                   q1("rref.db", "SELECT events FROM runs"));
  read_file("r/logs/p0001.log", m, sizeof m);
  assert_non_null(strstr(m, "interrupted"));
}

/* A point whose run collapses (the rods' inelastic collapse, exit 1 from haff run) has ended:
 * it is done for the study, which merges it (judged by its exit status it failed the sweep and
 * blocked the merge). */
static void sweep_collapsed_point_is_done(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("rc.ini", "[system]\nseed = 1998\n[rods]\ncount = 1000\ngamma = 0.8\nnmod = 1000\n"
                       "model = constant\n[run]\nstop_time = 1e4\n[log]\ncollisions = none\n");
  write_file("c.ini", "[sweep]\nscene = rc.ini\nseeds = 1998 1999\n");
  assert_int_equal(sh("%s sweep c.ini --quiet", haff), 0);
  assert_int_equal(q1("c/study.db", "SELECT count(*) FROM runs WHERE status = 'collapsed'"), 2);
}

/* A point killed in its set-up (its row 'running', no checkpoint, nobody's lock) is run again
 * as that same run by --resume: it was run as a second run, and the stale 'running' row was
 * merged into study.db beside it. */
static void sweep_point_killed_in_setup(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("ks.ini", "[sweep]\nscene = short.ini\nseeds = 3\n");
  assert_int_equal(sh("%s sweep ks.ini --quiet", haff), 0);
  long long events = q1("ks/points/p0000.db", "SELECT events FROM runs");
  assert_true(events > 0);
  assert_int_equal(sh("rm ks/points/p0000.db ks/study.db"), 0);
  killed_in_setup("short.ini", (const char *const[]){"system.seed=3"}, 1, "ks/points/p0000.db");
  assert_int_equal(sh("%s sweep --status ks > kss.txt", haff), 0);
  char m[2048];
  read_file("kss.txt", m, sizeof m);
  assert_non_null(strstr(m, "\n0\tinterrupted\trunning\t"));
  assert_int_equal(sh("%s sweep --resume ks --quiet", haff), 0);
  assert_int_equal(q1("ks/points/p0000.db", "SELECT count(*) FROM runs"), 1);
  assert_int_equal(q1("ks/points/p0000.db", "SELECT events FROM runs WHERE status = 'done'"),
                   events);
  assert_int_equal(q1("ks/study.db", "SELECT count(*) FROM runs"), 1);
  assert_int_equal(q1("ks/study.db", "SELECT count(*) FROM runs WHERE status = 'done'"), 1);
}

/* One lock per study folder (DIR/sweep.lock): while a sweep works on a folder, a second sweep
 * of the same file, a --resume and a --merge are refused (exit 1, naming the holder's pid);
 * --status still reads it.  Two --resume started at once end with every run once in study.db. */
static void sweep_lock_refuses_a_second(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("lk.ini", "[sweep]\nscene = long.ini\nseeds = 1 2\n");
  pid_t pid = start("lk-err.txt",
                    (const char *const[]){"sweep", "lk.ini", "--progress", "0", "--quiet", NULL});
  assert_true(wait_positive("lk/points/p0000.db", "SELECT events FROM runs", pid) > 0);
  char want[64], e[4096];
  snprintf(want, sizeof want, "pid %ld on ", (long)pid);
  static const char *const second[] = {"sweep lk.ini", "sweep --resume lk", "sweep --merge lk"};
  for (int k = 0; k < 3; k++) {
    int rc = sh("%s %s", haff, second[k]);
    read_file("err.txt", e, sizeof e);
    if (rc != 1 || !strstr(e, "another haff sweep works on this study") || !strstr(e, want))
      fail_msg("haff %s: exit %d, '%s'", second[k], rc, e);
  }
  assert_int_equal(sh("%s sweep --status lk > lks.txt", haff), 0);
  read_file("lks.txt", e, sizeof e);
  assert_non_null(strstr(e, "\n0\trunning\t"));
  kill(pid, SIGTERM);
  int st;
  waitpid(pid, &st, 0);
  assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 1);
  /* two at once: one works, the other is refused or finds nothing to do */
  pid_t a = start("lka.txt", (const char *const[]){"sweep", "--resume", "lk", "--jobs", "2",
                                                   "--progress", "0", NULL});
  pid_t b = start("lkb.txt", (const char *const[]){"sweep", "--resume", "lk", "--jobs", "2",
                                                   "--progress", "0", NULL});
  int sa, sb;
  waitpid(a, &sa, 0);
  waitpid(b, &sb, 0);
  assert_true(WIFEXITED(sa) && WIFEXITED(sb));
  int ea = WEXITSTATUS(sa), eb = WEXITSTATUS(sb);
  assert_true((ea == 0 && (eb == 0 || eb == 1)) || (eb == 0 && ea == 1));
  assert_int_equal(q1("lk/study.db", "SELECT count(*) FROM runs"), 2);
  assert_int_equal(q1("lk/study.db", "SELECT count(DISTINCT seed) FROM runs WHERE status = "
                                     "'done'"),
                   2);
  for (int k = 0; k < 2; k++) {
    char db[64];
    snprintf(db, sizeof db, "lk/points/p%04d.db", k);
    assert_int_equal(q1(db, "SELECT count(*) FROM runs"), 1);
  }
}

/* A point database that another process is writing (its DB.lock held) is running, whatever
 * its file says: not classed failed, not renamed .failed-N, its -wal untouched (it was
 * renamed and its -wal unlinked under the writer); once nobody holds it, a file that is not a
 * database is kept aside and the point is run. */
static void sweep_point_being_written_is_not_failed(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("gf.ini", "[sweep]\nscene = short.ini\n");
  assert_int_equal(sh("%s sweep gf.ini --quiet", haff), 0);
  assert_int_equal(sh("rm gf/study.db"), 0);
  write_file("gf/points/p0000.db", "not yet a database, being written");
  write_file("gf/points/p0000.db-wal", "its wal");
  pid_t holder = hold_lock("gf/points/p0000.db.lock", 1);
  int rc = sh("%s sweep --resume gf --quiet", haff);
  int rs = sh("%s sweep --status gf > gfs.txt", haff);
  kill(holder, SIGKILL);
  waitpid(holder, NULL, 0);
  assert_int_equal(rc, 1);
  assert_int_equal(rs, 0);
  char m[2048];
  read_file("gfs.txt", m, sizeof m);
  assert_non_null(strstr(m, "\n0\trunning\t"));
  assert_false(exists("gf/points/p0000.db.failed-1"));
  read_file("gf/points/p0000.db", m, sizeof m);
  assert_string_equal(m, "not yet a database, being written");
  read_file("gf/points/p0000.db-wal", m, sizeof m);
  assert_string_equal(m, "its wal");
  /* nobody holds it now: kept aside, then run */
  assert_int_equal(sh("%s sweep --resume gf --quiet", haff), 0);
  assert_true(exists("gf/points/p0000.db.failed-1"));
  assert_int_equal(q1("gf/study.db", "SELECT count(*) FROM runs WHERE status = 'done'"), 1);
}

/* --slurm with a stand-in sbatch on PATH: the array script (one task per chunk of points, the
 * --time/--partition/--account given) and the merge job submitted afterok on the array. */
static void sweep_slurm_scripts(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("mkdir -p fakebin && printf '#!/bin/sh\\necho \"$@\" >> %s/sbatch.txt\\n"
                      "n=$(wc -l < %s/sbatch.txt); echo $((100 + n))\\n' > fakebin/sbatch && "
                      "chmod +x fakebin/sbatch",
                      dir, dir),
                   0);
  write_file("s.ini", "[sweep]\nscene = short.ini\nseeds = 1:5:1\n");
  assert_int_equal(sh("PATH=%s/fakebin:$PATH %s sweep s.ini --slurm --chunk 2 --time 10 "
                      "--partition short --account phys > ids.txt",
                      dir, haff),
                   0);
  char m[4096];
  read_file("ids.txt", m, sizeof m);
  assert_string_equal(m, "101\t102\n");
  read_file("sbatch.txt", m, sizeof m);
  assert_non_null(strstr(m, "--parsable --dependency=afterok:101 "));
  read_file("s/slurm/array-1.sh", m, sizeof m);
  assert_non_null(strstr(m, "#SBATCH --array=0-2\n")); /* 5 points, 2 per task */
  assert_non_null(strstr(m, "#SBATCH --time=10\n#SBATCH --partition=short\n"
                            "#SBATCH --account=phys\n"));
  assert_non_null(strstr(m, "sweep --task "));
  read_file("s/slurm/todo-1.txt", m, sizeof m);
  assert_string_equal(m, "0\n1\n2\n3\n4\n");
  /* a task runs its chunk: task 2 is point 4 alone */
  assert_int_equal(sh("SLURM_ARRAY_TASK_ID=2 %s sweep --task s s/slurm/todo-1.txt --chunk 2 "
                      "--quiet",
                      haff),
                   0);
  assert_int_equal(q1("s/points/p0004.db", "SELECT count(*) FROM runs WHERE status = 'done'"), 1);
  assert_false(exists("s/points/p0003.db"));
  /* --resume --slurm: a new array of the 4 points left */
  assert_int_equal(sh("PATH=%s/fakebin:$PATH %s sweep --resume s --slurm > ids.txt", dir, haff), 0);
  read_file("s/slurm/todo-2.txt", m, sizeof m);
  assert_string_equal(m, "0\n1\n2\n3\n");
  assert_int_equal(sh("PATH=%s/fakebin:$PATH %s sweep s.ini --slurm --time 'a b'", dir, haff), 2);
}

/* --slurm --dry-run writes the study folder, the manifest and the job scripts and submits
 * nothing; the folder's path is quoted in #SBATCH --output (a blank split it; a quote and a %
 * are escaped) and a path with a newline (which injected a shell line into the script) is
 * refused; --sbatch 'OPTIONS' reaches both scripts as one quoted #SBATCH line, and what would
 * break the array is refused.  Each script passes bash -n. */
static void sweep_slurm_dry_run_and_quoting(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("mkdir -p fakebin2 && printf '#!/bin/sh\\necho \"$@\" >> %s/sbatch2.txt\\n"
                      "echo 7\\n' > fakebin2/sbatch && chmod +x fakebin2/sbatch",
                      dir),
                   0);
  write_file("q.ini", "[sweep]\nscene = short.ini\nseeds = 1:3:1\n");
  assert_int_equal(sh("PATH=%s/fakebin2:$PATH %s sweep q.ini --slurm --dry-run -o 'q dir %%x\"y' "
                      "--time 5 --sbatch '--mem=1G --qos \"high prio\" --comment=a#b' > qp.txt",
                      dir, haff),
                   0);
  assert_false(exists("sbatch2.txt")); /* nothing submitted */
  assert_true(exists("q dir %x\"y/manifest.tsv"));
  char m[8192], want[1024];
  read_file("qp.txt", m, sizeof m);
  snprintf(want, sizeof want,
           "%s/q dir %%x\"y/slurm/array-1.sh\t%s/q dir %%x\"y/slurm/merge-1.sh\n", dir, dir);
  assert_string_equal(m, want);
  read_file("q dir %x\"y/slurm/array-1.sh", m, sizeof m);
  snprintf(want, sizeof want, "\n#SBATCH \"--output=%s/q dir %%%%x\\\"y/logs/slurm-%%A_%%a.out\"\n",
           dir);
  if (!strstr(m, want)) fail_msg("no line '%s' in\n%s", want, m);
  assert_non_null(strstr(m, "\n#SBATCH --time=5\n#SBATCH --mem=1G --qos \"high prio\" "
                            "\"--comment=a#b\"\n"));
  assert_non_null(strstr(m, "#SBATCH --array=0-2\n"));
  read_file("q dir %x\"y/slurm/merge-1.sh", m, sizeof m);
  assert_non_null(strstr(m, "\n#SBATCH --mem=1G --qos \"high prio\" \"--comment=a#b\"\n"));
  assert_int_equal(sh("bash -n 'q dir %%x\"y/slurm/array-1.sh' && bash -n 'q dir "
                      "%%x\"y/slurm/merge-1.sh'"),
                   0);
  /* a newline in the folder: refused before anything is made */
  int rc = sh("%s sweep q.ini --slurm --dry-run -o \"$(printf 'nl\\nx')\"", haff);
  read_file("err.txt", m, sizeof m);
  assert_int_equal(rc, 2);
  assert_non_null(strstr(m, "control character"));
  assert_false(exists("nl\nx"));
  /* --sbatch refusals */
  static const char *const bad_opts[] = {"--array=1-3", "mem=1G", "--qos 'a", "-a 1", ""};
  for (int k = 0; k < 5; k++) {
    rc = sh("%s sweep q.ini --slurm --dry-run -o q2 --sbatch '%s'", haff, bad_opts[k]);
    if (rc != 2) fail_msg("--sbatch '%s': exit %d", bad_opts[k], rc);
  }
  assert_int_equal(sh("%s sweep q.ini --sbatch --mem=1G", haff), 2); /* without --slurm */
  assert_false(exists("sbatch2.txt"));
}

/* --drop-points: after a merge that reads back with one done run per point, the points'
 * databases are removed and DIR/points/DROPPED says so; the study stays done (--status: done,
 * dropped; a second sweep and --merge leave study.db as it is). */
static void sweep_drop_points(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("dp.ini", "[sweep]\nscene = short.ini\nseeds = 1 2\n");
  assert_int_equal(sh("%s sweep dp.ini --drop-points --quiet", haff), 0);
  assert_int_equal(q1("dp/study.db", "SELECT count(*) FROM runs WHERE status = 'done'"), 2);
  assert_false(exists("dp/points/p0000.db"));
  assert_false(exists("dp/points/p0001.db"));
  assert_true(exists("dp/points/DROPPED"));
  assert_int_equal(sh("%s sweep --status dp > dps.txt", haff), 0);
  char m[2048];
  read_file("dps.txt", m, sizeof m);
  assert_non_null(strstr(m, "\n1\tdone\tdropped\t"));
  struct stat a, b;
  char p[400];
  snprintf(p, sizeof p, "%s/dp/study.db", dir);
  assert_int_equal(stat(p, &a), 0);
  assert_int_equal(sh("%s sweep dp.ini", haff), 0);
  assert_int_equal(sh("%s sweep --merge dp", haff), 0);
  assert_int_equal(stat(p, &b), 0);
  assert_true(a.st_mtim.tv_sec == b.st_mtim.tv_sec && a.st_mtim.tv_nsec == b.st_mtim.tv_nsec);
  /* without it the points stay */
  assert_int_equal(sh("%s sweep dp.ini -o dk --quiet", haff), 0);
  assert_true(exists("dk/points/p0001.db"));
  assert_int_equal(sh("%s sweep --status dk --drop-points", haff), 2);
}

/* Writes n bytes of text to file name in dir. */
static void write_bytes(const char *name, const char *text, size_t n) {
  char p[400];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  FILE *f = fopen(p, "wb");
  assert_non_null(f);
  assert_int_equal(fwrite(text, 1, n, f), n);
  assert_int_equal(fclose(f), 0);
}

/* The sweep file's messages and what it accepts (issue 24 item 12): seeds above 1e12 as a
 * range (refused as "not a non-negative integer seed": the range was printed %.12g, 1e+12), a
 * NUL byte named as such (was "line too long"), a control byte never echoed raw, a directory
 * named as one (was "missing: the base scene"), a UTF-8 byte order mark skipped (was refused). */
static void sweep_file_messages(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("big.ini", "[sweep]\nscene = short.ini\nseeds = 1000000000000:1000000000002:1\n");
  assert_int_equal(sh("%s sweep big.ini --dry-run > big.txt", haff), 0);
  char m[4096], e[2048];
  read_file("big.txt", m, sizeof m);
  assert_non_null(strstr(m, "\n1\tpoints/p0001.db\tsystem.seed=1000000000001\n"));
  write_file("big2.ini", "[sweep]\nscene = short.ini\nseeds = 18446744073709551615 "
                         "18446744073709551616\n");
  assert_int_equal(sh("%s sweep big2.ini --dry-run", haff), 2);
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "big2.ini:3: [sweep] seeds: '18446744073709551616': a seed above "));
  static const char nul[] = "[sweep]\nscene = short.ini\n\0seeds = 1\n";
  write_bytes("nul.ini", nul, sizeof nul - 1);
  assert_int_equal(sh("%s sweep nul.ini --dry-run", haff), 2);
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "nul.ini:3: [sweep]: a NUL byte: not a text file"));
  write_file("esc.ini", "[sweep]\nscene = short.ini\n[axes]\ndisks.alpha = 0.9 \x1b[31mred\n");
  assert_int_equal(sh("%s sweep esc.ini --dry-run", haff), 2);
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "esc.ini:4: [axes]: a control character (byte 0x1b)"));
  for (const char *c = e; *c; c++)
    if ((unsigned char)*c < 0x20 && *c != '\n') fail_msg("a raw control byte in '%s'", e);
  write_file("esc2.ini", "[sweep]\nscene = short.ini\n[axes]\ndisks.al\x7fpha = 0.9\n");
  assert_int_equal(sh("%s sweep esc2.ini --dry-run", haff), 2);
  read_file("err.txt", e, sizeof e);
  assert_null(strchr(e, 0x7f));
  assert_int_equal(sh("mkdir -p adir.ini && %s sweep adir.ini --dry-run", haff), 2);
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "adir.ini: a directory, not a sweep file"));
  write_file("sdir.ini", "[sweep]\nscene = adir.ini\n");
  assert_int_equal(sh("%s sweep sdir.ini --dry-run", haff), 2);
  read_file("err.txt", e, sizeof e);
  assert_non_null(strstr(e, "sdir.ini:2: [sweep] scene: 'adir.ini': a directory"));
  write_file("bom.ini", "\xEF\xBB\xBF[sweep]\r\nscene = short.ini\r\nseeds = 4 5\r\n");
  assert_int_equal(sh("%s sweep bom.ini --dry-run > bom.txt", haff), 0);
  read_file("bom.txt", m, sizeof m);
  assert_non_null(strstr(m, "\n1\tpoints/p0001.db\tsystem.seed=5\n"));
}

/* Values with blanks are swept when quoted (`shape = linear 3` could not be): in [axes] and in
 * [points]; the manifest keeps the quotes and each point's run has the value. */
static void sweep_values_with_blanks(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("mix.ini", "[system]\narea_fraction = 0.05\nseed = 3\n[species tri]\ncount = 20\n"
                        "shape = triangle\nalpha = 0.9\n[run]\nstop_cpd = 2\n[log]\n"
                        "collisions = none\n");
  write_file("vb.ini", "[sweep]\nscene = mix.ini\n[axes]\n"
                       "species.tri.shape = \"linear 3\" triangle \"bent 90\"  ; quoted\n");
  assert_int_equal(sh("%s sweep vb.ini --dry-run > vb.txt", haff), 0);
  char m[4096];
  read_file("vb.txt", m, sizeof m);
  assert_non_null(strstr(m, "\n0\tpoints/p0000.db\tspecies.tri.shape=\"linear 3\"\n"));
  assert_non_null(strstr(m, "\n1\tpoints/p0001.db\tspecies.tri.shape=triangle\n"));
  assert_int_equal(sh("%s sweep vb.ini --quiet", haff), 0);
  assert_int_equal(q1("vb/points/p0000.db", "SELECT count(*) FROM runs WHERE status = 'done' AND "
                                            "scene LIKE '%shape = linear 3%'"),
                   1);
  assert_int_equal(q1("vb/study.db", "SELECT count(*) FROM runs"), 3);
  write_file("vp.ini", "[sweep]\nscene = mix.ini\n[points]\n"
                       "point = species.tri.shape=\"linear 4\" species.tri.count=10\n");
  assert_int_equal(sh("%s sweep vp.ini --quiet", haff), 0);
  assert_int_equal(q1("vp/study.db", "SELECT count(*) FROM runs WHERE scene LIKE '%shape = "
                                     "linear 4%' AND scene LIKE '%count = 10%'"),
                   1);
  write_file("vq.ini",
             "[sweep]\nscene = mix.ini\n[points]\npoint = species.tri.shape=\"linear 4\n");
  assert_int_equal(sh("%s sweep vq.ini --dry-run", haff), 2);
  read_file("err.txt", m, sizeof m);
  assert_non_null(strstr(m, "vq.ini:4: [points] point: an unclosed quote"));
}

/* The bash completion of `haff sweep --` (which offers every --option its help names) offers
 * --sbatch and --drop-points, and not --set, which sweep refuses (its help named "--set
 * overrides"). */
static void sweep_completion_offers_no_set(void **state) {
  (void)state;
  if (!haff) skip();
  char comp[4200];
  if (!realpath("cli/haff-completion.bash", comp)) skip(); /* not run from the source tree */
  assert_int_equal(sh("bash -c 'source %s; COMP_WORDS=(%s sweep --); COMP_CWORD=2; _haff; "
                      "printf \"%%s\\n\" \"${COMPREPLY[@]}\"' > comp.txt",
                      comp, haff),
                   0);
  char m[4096];
  m[0] = '\n';
  read_file("comp.txt", m + 1, sizeof m - 1);
  assert_non_null(strstr(m, "\n--sbatch\n"));
  assert_non_null(strstr(m, "\n--drop-points\n"));
  assert_non_null(strstr(m, "\n--dry-run\n"));
  assert_null(strstr(m, "\n--set\n"));
}

/* ------------------------------------------------------------------------------------------ */
/* the sweep file parser below the CLI: the fuzz target on its corpus and on edge inputs */

#include <dirent.h>
#include <ini.h>
#include <stdbool.h>

#include "fuzz/fuzz_sweep.c"

/* Every seed of tests/fuzz/corpus/sweep/ and some edge inputs pass the fuzz target's checks
 * (an abort would end this program), and what each seed should give it gives. */
static void fuzz_sweep_corpus(void **state) {
  (void)state;
  DIR *d = opendir("tests/fuzz/corpus/sweep");
  if (!d) skip(); /* not run from the source tree */
  int n = 0;
  for (struct dirent *e; (e = readdir(d));) {
    if (e->d_name[0] == '.') continue;
    char p[600];
    snprintf(p, sizeof p, "tests/fuzz/corpus/sweep/%s", e->d_name);
    FILE *f = fopen(p, "rb");
    assert_non_null(f);
    static char buf[1 << 16];
    size_t len = fread(buf, 1, sizeof buf, f);
    fclose(f);
    LLVMFuzzerTestOneInput((const uint8_t *)buf, len);
    hd_sweepfile s;
    hd_error err;
    int rc = hd_sweepfile_parse(&s, buf, len, p, &err);
    int want = strcmp(e->d_name, "nul.ini") && strcmp(e->d_name, "bad.ini") ? HD_OK : HD_EINPUT;
    if (rc != want) fail_msg("%s: %d (%s), wanted %d", p, rc, err.msg, want);
    if (!rc) hd_sweepfile_free(&s);
    n++;
  }
  closedir(d);
  assert_true(n >= 5);
  static const char *const edge[] = {"",
                                     "\xEF\xBB\xBF",
                                     "[sweep]\nscene=\"",
                                     "[points]\npoint=\"\"",
                                     "[sweep]\nscene = a\n[axes]\na.b = 1:1e300:1e-300\n",
                                     "[sweep]\nscene = a\nseeds = 0:18446744073709551615:1\n"};
  for (size_t k = 0; k < sizeof edge / sizeof edge[0]; k++)
    LLVMFuzzerTestOneInput((const uint8_t *)edge[k], strlen(edge[k]));
}

/* The sweep file parser on libinih (hd_sweepfile.c): a line far longer than libinih's default
 * buffer (an axis of 20000 values, ~110 kB: on libinih's stack buffer it overflowed), a ';'
 * inside quotes kept and one after a blank cut, a key with ':' before '=' refused (libinih would
 * split it there), a NUL byte refused after the refusals of the lines before it, and libinih's
 * process-wide settings as they were before (the scene parser relies on them). */
static void sweep_parser_on_libinih(void **state) {
  (void)state;
  int max_line = ini_max_line, initial = ini_initial_alloc;
  bool stack = ini_use_stack, inl = ini_allow_inline_comments, multi = ini_allow_multiline;
  size_t cap = 200000, n = 0;
  char *text = malloc(cap);
  assert_non_null(text);
  n += (size_t)snprintf(text + n, cap - n, "[sweep]\nscene = a.ini\n[axes]\na.b =");
  for (int k = 0; k < 20000; k++) n += (size_t)snprintf(text + n, cap - n, " %d", k);
  n += (size_t)snprintf(text + n, cap - n, "\nc.d = \"x ; y\" z ; a comment\n  e.f = 1#2 3 #4\n");
  hd_sweepfile s;
  hd_error err;
  assert_int_equal(hd_sweepfile_parse(&s, text, n, "l.ini", &err), HD_OK);
  assert_int_equal(s.nax, 3);
  assert_int_equal(s.ax[0].n, 20000);
  assert_string_equal(s.ax[0].v[19999], "19999");
  assert_int_equal(s.ax[1].n, 2);
  assert_string_equal(s.ax[1].v[0], "x ; y");
  assert_string_equal(s.ax[1].v[1], "z");
  assert_int_equal(s.ax[2].line, 6);
  assert_int_equal(s.ax[2].n, 2);
  assert_string_equal(s.ax[2].v[0], "1#2");
  hd_sweepfile_free(&s);
  free(text);
  static const char colon[] = "[sweep]\nscene = a.ini\n[axes]\na:b = 1\n";
  assert_int_equal(hd_sweepfile_parse(&s, colon, sizeof colon - 1, "c.ini", &err), HD_EINPUT);
  assert_string_equal(err.msg, "c.ini:4: [axes]: 'a:b = 1': not KEY = VALUE");
  static const char nul[] = "[sweep]\nscene = a.ini\n[grid]\n\0\n";
  assert_int_equal(hd_sweepfile_parse(&s, nul, sizeof nul - 1, "n.ini", &err), HD_EINPUT);
  assert_string_equal(err.msg, "n.ini:3: [grid]: unknown section (sweep, axes, points)");
  assert_int_equal(hd_sweepfile_parse(&s, nul, 22, "n.ini", &err), HD_OK); /* before [grid] */
  hd_sweepfile_free(&s);
  assert_int_equal(ini_max_line, max_line);
  assert_int_equal(ini_initial_alloc, initial);
  assert_true(ini_use_stack == stack && ini_allow_inline_comments == inl &&
              ini_allow_multiline == multi);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(progress_in_a_batch_log),
      cmocka_unit_test(resume_all),
      cmocka_unit_test(resume_all_killed_in_setup),
      cmocka_unit_test(merge_runs_and_refusals),
      cmocka_unit_test(merge_killed_leaves_out),
      cmocka_unit_test(old_schema_reads_and_upgrades),
      cmocka_unit_test(run_identity_and_duplicates),
      cmocka_unit_test(merge_library),
      cmocka_unit_test(sweep_grid_runs_and_merges),
      cmocka_unit_test(sweep_bad_input),
      cmocka_unit_test(sweep_axes_validates_whole_points),
      cmocka_unit_test(sweep_interrupted_then_resumed),
      cmocka_unit_test(sweep_collapsed_point_is_done),
      cmocka_unit_test(sweep_point_killed_in_setup),
      cmocka_unit_test(sweep_lock_refuses_a_second),
      cmocka_unit_test(sweep_point_being_written_is_not_failed),
      cmocka_unit_test(sweep_slurm_scripts),
      cmocka_unit_test(sweep_slurm_dry_run_and_quoting),
      cmocka_unit_test(sweep_drop_points),
      cmocka_unit_test(sweep_file_messages),
      cmocka_unit_test(sweep_values_with_blanks),
      cmocka_unit_test(sweep_completion_offers_no_set),
      cmocka_unit_test(fuzz_sweep_corpus),
      cmocka_unit_test(sweep_parser_on_libinih),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
