/* End-to-end tests of bin/haff (path in $HAFF_BIN): exit codes and messages for bad input,
 * SIGINT then resume, kill -9 then resume — each compared row by row with an uninterrupted
 * run of the same scene and seed. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <signal.h>
#include <sqlite3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "test_cli_util.h"
#include "test_util.h"

static char root[4096]; /* the source tree (the tests run from it): db/schema.sql */

/* The stderr of the last sh() (dir/err.txt), at most n - 1 bytes. */
static void read_err(char *buf, size_t n) {
  read_file("err.txt", buf, n);
}

/* One integer from an SQL query on a database in dir (ATTACHing b.db as b when present). */
static long long q1(const char *db, const char *sql) {
  sqlite3 *h;
  sqlite3_stmt *st = test_cli_query(db, sql, &h);
  long long v = sqlite3_step(st) == SQLITE_ROW ? sqlite3_column_int64(st, 0) : -1;
  sqlite3_finalize(st);
  sqlite3_close(h);
  return v;
}

/* The database file db in dir passes PRAGMA integrity_check. */
static void assert_sound(const char *db) {
  char p[300];
  snprintf(p, sizeof p, "%s/%s", dir, db);
  sqlite3 *h;
  assert_int_equal(sqlite3_open(p, &h), SQLITE_OK);
  sqlite3_stmt *st;
  sqlite3_prepare_v2(h, "PRAGMA integrity_check", -1, &st, 0);
  assert_int_equal(sqlite3_step(st), SQLITE_ROW);
  assert_string_equal((const char *)sqlite3_column_text(st, 0), "ok");
  sqlite3_finalize(st);
  sqlite3_close(h);
}

/* A scene of about a second, checkpointing every 0.1 s, of SCENE_EVENTS collisions. */
#define SCENE_EVENTS 800000
#define STR_(x) #x
#define STR(x) STR_(x)
static const char scene[] =
    "[system]\narea_fraction = 0.2\nseed = 3\n[disks]\ncount = 2000\n"
    "alpha = 0.97\n[run]\nstop_events = " STR(
        SCENE_EVENTS) "\n"
                      "checkpoint_every = 0.1\n"
                      "[log]\ncollisions = all\nsamples_every = 1\nvelocities_at = 2 50\n";

static int setup(void **state) {
  (void)state;
  if (!test_cli_find_haff()) return 0; /* these tests drive bin/haff, not sanitized */
  assert_non_null(getcwd(root, sizeof root));
  assert_int_equal(test_cli_mkdtemp("cli"), 0);
  write_file("s.ini", scene);
  assert_int_equal(sh("%s run s.ini -o ref.db --quiet", haff), 0);
  return 0;
}

static int teardown(void **state) {
  (void)state;
  if (!haff) return 0;
  return test_cli_rmdir();
}

/* Collisions committed so far in database db of dir, -1 while it cannot be read yet. */
static long long committed(const char *db) {
  char p[300];
  snprintf(p, sizeof p, "%s/%s", dir, db);
  sqlite3 *h;
  long long v = -1;
  if (sqlite3_open_v2(p, &h, SQLITE_OPEN_READONLY, NULL) == SQLITE_OK) {
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(h, "SELECT count(*) FROM collisions", -1, &st, 0) == SQLITE_OK) {
      if (sqlite3_step(st) == SQLITE_ROW) v = sqlite3_column_int64(st, 0);
      sqlite3_finalize(st);
    }
  }
  sqlite3_close(h);
  return v;
}

/* Starts haff run in the background and sends sig once the database holds `permille` per mille
 * of the scene's collisions (polled every millisecond: the moment is set by the run's progress,
 * not by the clock, so that a faster machine or build still interrupts it mid-run, at whatever
 * point of a batch the signal falls); returns the exit status. */
static int run_and_signal(const char *db, int sig, int permille) {
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    if (chdir(dir)) _exit(99);
    freopen("err.txt", "w", stderr);
    execl(haff, haff, "run", "s.ini", "-o", db, "--quiet", (char *)NULL);
    _exit(98);
  }
  int st;
  const struct timespec ms = {0, 1000000L};
  while (committed(db) < (long long)SCENE_EVENTS / 1000 * permille) {
    if (waitpid(pid, &st, WNOHANG) == pid) fail_msg("haff run ended before it was signalled");
    nanosleep(&ms, NULL);
  }
  kill(pid, sig);
  waitpid(pid, &st, 0);
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
}

/* The resumed database holds the same collisions, samples and final state as ref.db. */
static void same_as_reference(const char *db) {
  assert_int_equal(q1(db, "SELECT count(*) FROM collisions"),
                   q1(db, "SELECT count(*) FROM ref.collisions"));
  assert_int_equal(q1(db, "SELECT count(*) FROM (SELECT seq,t,kind,i,j,f,de,vn FROM collisions "
                          "EXCEPT SELECT seq,t,kind,i,j,f,de,vn FROM ref.collisions)"),
                   0);
  assert_int_equal(q1(db, "SELECT count(*) FROM (SELECT t,cpd,e_tr FROM samples "
                          "EXCEPT SELECT t,cpd,e_tr FROM ref.samples)"),
                   0);
  assert_int_equal(q1(db, "SELECT count(*) FROM samples"),
                   q1(db, "SELECT count(*) FROM ref.samples"));
  assert_int_equal(q1(db,
                      "SELECT count(*) FROM (SELECT label,t,body,x,y,vx,vy FROM states "
                      "WHERE label IN ('final','velocities') EXCEPT SELECT label,t,body,x,y,vx,vy "
                      "FROM ref.states WHERE label IN ('final','velocities'))"),
                   0);
  assert_int_equal(q1(db, "SELECT count(*) FROM states WHERE label='final'"), 2000);
  /* and no other states: the snapshot written at the interruption went with the resume */
  assert_int_equal(q1(db, "SELECT count(*) FROM states"),
                   q1(db, "SELECT count(*) FROM ref.states"));
  assert_int_equal(q1(db, "SELECT count(*) FROM states WHERE label='velocities'"), 4000);
  assert_int_equal(q1(db, "SELECT status='done' FROM runs"), 1);
  /* a done run cannot be resumed: its checkpoint is gone (~150 bytes per body) */
  assert_int_equal(q1(db, "SELECT count(*) FROM checkpoints"), 0);
  /* as the uninterrupted run: no message left from the stop ("interrupted at ...") */
  assert_int_equal(q1(db, "SELECT count(*) FROM runs WHERE message IS NOT NULL"), 0);
}

/* SIGINT: exit 1, status 'interrupted', a checkpoint; resume: exit 0 and the very same run. */
static void sigint_then_resume(void **state) {
  (void)state;
  if (!haff) skip();
  int rc = run_and_signal("int.db", SIGINT, 400);
  char e[2048];
  read_err(e, sizeof e);
  assert_int_equal(rc, 1);
  assert_non_null(strstr(e, "interrupted"));
  /* the command to go on names this file and run (it said "haff resume DB") */
  assert_non_null(strstr(e, "(continue with: haff resume int.db --run 1)"));
  assert_int_equal(q1("int.db", "SELECT status='interrupted' FROM runs"), 1);
  assert_int_equal(q1("int.db", "SELECT count(*) FROM checkpoints"), 1);
  /* the state at the interruption is readable in `states` too */
  assert_int_equal(q1("int.db", "SELECT count(*) FROM states WHERE label = 'checkpoint'"), 2000);
  long long before = q1("int.db", "SELECT count(*) FROM collisions");
  assert_true(before > 0 && before < SCENE_EVENTS);
  assert_int_equal(sh("%s resume int.db --quiet", haff), 0);
  same_as_reference("int.db");
}

/* Makes database db of dir (written by this haff, schema version 5) a file of schema version 4
 * as haff 4 wrote it: the table samples with the per-kind columns (filled from the view, which
 * gives version 4's values: tests/test_db.c schema5_*), no sample_rows, user_version 4. */
static void to_schema4(const char *db) {
  char p[400];
  snprintf(p, sizeof p, "%s/%s", dir, db);
  sqlite3 *h;
  assert_int_equal(sqlite3_open(p, &h), SQLITE_OK);
  char *msg = NULL;
  int rc = sqlite3_exec(
      h,
      "BEGIN; CREATE TEMP TABLE x AS SELECT * FROM samples; DROP VIEW samples; "
      "DROP TABLE sample_rows; CREATE TABLE samples (run INTEGER NOT NULL REFERENCES runs(id), t "
      "REAL NOT NULL, collisions INTEGER NOT NULL, cpd REAL NOT NULL, e_tr REAL NOT NULL, e_rot "
      "REAL NOT NULL, e_tr_dimer REAL, e_rot_dimer REAL, e_tr_disk REAL, flow_frac REAL, "
      "flow_chaos REAL, count_var REAL, s_rho REAL, s_perp REAL, s_par REAL); INSERT INTO "
      "samples SELECT * FROM temp.x; CREATE INDEX samples_run_t ON samples(run, t); "
      "PRAGMA user_version = 4; COMMIT; PRAGMA journal_mode = DELETE",
      NULL, NULL, &msg);
  if (rc != SQLITE_OK) fail_msg("%s: to schema 4: %s", db, msg ? msg : "?");
  sqlite3_close(h);
}

/* A run interrupted (SIGINT) in a file of schema version 4 resumes to the uninterrupted run:
 * the resume brings the file to version 5 first (the samples table becomes sample_rows and the
 * view, in one transaction) and truncates and writes sample_rows and sample_species; the file
 * then has every sample and every species row of the uninterrupted run, once. */
static void schema4_file_resumed(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(run_and_signal("old4.db", SIGINT, 400), 1);
  to_schema4("old4.db");
  assert_int_equal(q1("old4.db", "SELECT user_version FROM pragma_user_version"), 4);
  assert_int_equal(sh("%s resume old4.db --quiet", haff), 0);
  same_as_reference("old4.db");
  assert_int_equal(q1("old4.db", "SELECT user_version FROM pragma_user_version"), 5);
  assert_int_equal(q1("old4.db", "SELECT count(*) FROM (SELECT t, species, e_tr, e_rot FROM "
                                 "sample_species EXCEPT SELECT t, species, e_tr, e_rot FROM "
                                 "ref.sample_species)"),
                   0);
  assert_int_equal(q1("old4.db", "SELECT count(*) FROM sample_species"),
                   q1("old4.db", "SELECT count(*) FROM ref.sample_species"));
  assert_sound("old4.db");
}

/* A file of schema version 4 (two dimer-disk mixtures, a mixture of named species, dimers)
 * analyses to the same numbers, byte for byte, as the file of version 5 it was made from: read
 * as it is (the analyses never change a file), after `haff merge` into a new file (the input
 * converted), and after a writer brought it to version 5 in place (`haff resume` with nothing to
 * resume opens it for writing and exits 2).  The files have one name (mix.db) in three folders,
 * so that the outputs may name it. */
static void schema4_file_analysed(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("m4.ini", "[system]\narea_fraction = 0.05\nseed = 9\n[dimers]\ncount = 100\n"
                       "alpha = 0.8\n[disks]\ncount = 100\nalpha = 0.7\nalpha_dimer = 0.9\n"
                       "[run]\nstop_cpd = 20\n[log]\nsamples_every = 0.5\n");
  write_file("n4.ini", "[system]\narea_fraction = 0.02\nseed = 1\n[species light]\ncount = 100\n"
                       "shape = disk\nm = 1\nalpha = 0.8\n[species heavy]\ncount = 100\nshape = "
                       "disk\nm = 4\nalpha = 0.8\n[run]\nstop_cpd = 20\n[log]\nsamples_every = "
                       "0.5\n");
  write_file("d4.ini", "[system]\narea_fraction = 0.05\nseed = 3\n[dimers]\ncount = 200\n"
                       "alpha = 0.9\n[run]\nstop_cpd = 20\n[log]\nsamples_every = 0.5\n");
  assert_int_equal(sh("mkdir -p v5 v4 mg && %s run m4.ini -o v5/mix.db --quiet && %s run m4.ini "
                      "--set system.seed=10 -o v5/mix.db --quiet && %s run n4.ini -o v5/mix.db "
                      "--quiet && %s run d4.ini -o v5/mix.db --quiet && cp v5/mix.db v4/mix.db",
                      haff, haff, haff, haff),
                   0);
  to_schema4("v4/mix.db");
  static const char *const an[] = {"haff-fit",
                                   "haff-fit --by-species",
                                   "energy",
                                   "energy --by-species",
                                   "table1",
                                   "table2",
                                   "haff-fit --run 3 --by-species",
                                   "haff-fit --alpha-group"};
  const size_t na = sizeof an / sizeof an[0];
  for (size_t k = 0; k < na; k++)
    assert_int_equal(sh("cd v5 && %s %s mix.db > out%zu.txt 2>&1", haff, an[k], k), 0);
  /* 0: read as it is; 1: merged into a new file; 2: converted in place */
  for (int stage = 0; stage < 3; stage++) {
    if (stage == 1) assert_int_equal(sh("cd mg && %s merge mix.db ../v4/mix.db", haff), 0);
    if (stage == 2) {
      assert_int_equal(sh("cd mg && rm -f mix.db && cp ../v4/mix.db . && %s resume mix.db", haff),
                       2);
      assert_int_equal(q1("mg/mix.db", "SELECT user_version FROM pragma_user_version"), 5);
    }
    const char *in = stage ? "mg" : "v4";
    assert_int_equal(
        q1(stage ? "mg/mix.db" : "v4/mix.db", "SELECT user_version FROM pragma_user_version"),
        stage ? 5 : 4);
    for (size_t k = 0; k < na; k++) {
      assert_int_equal(sh("cd %s && %s %s mix.db > out%zu.txt 2>&1", in, haff, an[k], k), 0);
      if (sh("cmp -s %s/out%zu.txt v5/out%zu.txt", in, k, k))
        fail_msg("stage %d: haff %s differs on the file of schema version 4", stage, an[k]);
    }
  }
  /* the per-species energies are stored once: as many sample_species rows as version 5 wrote */
  assert_int_equal(q1("mg/mix.db", "SELECT count(*) FROM sample_species"),
                   q1("v5/mix.db", "SELECT count(*) FROM sample_species"));
}

/* SIGTERM behaves as SIGINT. */
static void sigterm_then_resume(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(run_and_signal("term.db", SIGTERM, 300), 1);
  assert_int_equal(q1("term.db", "SELECT status='interrupted' FROM runs"), 1);
  assert_int_equal(sh("%s resume term.db --quiet", haff), 0);
  same_as_reference("term.db");
}

/* kill -9 at several moments: the database passes integrity_check, holds whole batches only
 * (batches end every 10^4 rows and at each checkpoint, so the rows are exactly collisions
 * 1..k with nothing missing), stays 'running', and resume gives the very same run. */
static void kill9_then_resume(void **state) {
  (void)state;
  if (!haff) skip();
  int at[3] = {50, 300, 600}; /* per mille of the collisions */
  for (int k = 0; k < 3; k++) {
    char db[32];
    snprintf(db, sizeof db, "k%d.db", k);
    assert_int_equal(run_and_signal(db, SIGKILL, at[k]), 128 + SIGKILL);
    assert_sound(db);
    assert_int_equal(q1(db, "SELECT count(*) = coalesce(max(seq), 0) FROM collisions"), 1);
    assert_int_equal(q1(db, "SELECT count(*) FROM (SELECT seq,t,i,j,de FROM collisions "
                            "EXCEPT SELECT seq,t,i,j,de FROM ref.collisions)"),
                     0);
    assert_int_equal(q1(db, "SELECT status='running' FROM runs"), 1);
    assert_int_equal(sh("%s resume %s --quiet", haff, db), 0);
    same_as_reference(db);
  }
}

/* `haff ARGS` (run in the test folder) exits 2 and says `needle` on stderr. */
/* Shell text that waits (at most 60 s) until a run of database DB has begun: its DB.lock exists
 * while it runs. */
#define WAIT_FOR_LOCK(db)                                                                          \
  "k=0; while [ ! -e " db ".lock ] && [ $k -lt 1200 ]; do sleep 0.05; k=$((k+1)); done; "

/* Runs `haff ARGS` in the background and sends it SIGINT after `delay` seconds, again every
 * 0.2 s until it ends (one sent before haff installs its handler is lost: a background job of a
 * script starts with SIGINT ignored); returns its exit status, its stderr in err.txt. */
static int interrupt_after(const char *args, const char *delay) {
  return sh("(%s %s & p=$!; sleep %s; while kill -INT $p 2>/dev/null; do sleep 0.2; done; "
            "wait $p)",
            haff, args, delay);
}

static void bad_usage(const char *args, const char *needle) {
  char e[2048];
  int rc = sh("%s %s", haff, args);
  read_err(e, sizeof e);
  if (rc != 2 || !strstr(e, needle))
    fail_msg("haff %s: exit %d, stderr \"%s\" (wanted 2 and \"%s\")", args, rc, e, needle);
}

/* Bad input: exit 2, one line naming the file, line and key; nothing written. */
static void bad_input(void **state) {
  (void)state;
  if (!haff) skip();
  char e[2048];
  write_file("bad1.ini",
             "[system]\nbox = 10 10\n[disks]\ncount = 5\nalpha = 1.5\n[run]\nstop_time = 1\n");
  bad_usage("run bad1.ini -o bad.db", "bad1.ini:5: [disks] alpha");
  assert_false(exists("bad.db"));
  write_file("bad2.ini", "[system]\nbox = 10 10\n[diskz]\ncount = 5\n[run]\nstop_time = 1\n");
  bad_usage("run bad2.ini -o bad.db", "bad2.ini:3");
  bad_usage("run missing.ini -o bad.db", "missing.ini");
  bad_usage("run s.ini --set disks.alpha=2 -o bad.db", "--set disks.alpha=2");
  /* --seed: out of range is refused (not clamped), and two seeds are a conflict that names
   * what the user typed */
  bad_usage("run s.ini -o bad.db --seed 18446744073709551616",
            "--seed 18446744073709551616: too large");
  bad_usage("run s.ini -o bad.db --seed ' -1'", "--seed  -1: not a non-negative integer");
  bad_usage("run s.ini -o bad.db --seed 5 --set system.seed=3",
            "--seed and --set system.seed=3 both set [system] seed");
  assert_false(exists("bad.db"));
  assert_int_equal(sh("%s run s.ini --bogus", haff), 2);
  assert_int_equal(sh("%s nosuchcommand", haff), 2);
  /* a mistyped database name: exit 2 and no file created (resume used to create it) */
  assert_int_equal(sh("%s resume nothere.db", haff), 2);
  assert_false(exists("nothere.db"));
  assert_int_equal(sh("%s haff-fit nothere.db", haff), 2);
  /* a file that is not SQLite is bad input too (it was exit 1, a failed run) */
  write_file("notadb.db", "not a database\n");
  bad_usage("haff-fit notadb.db", "not a haff database");
  bad_usage("export xyz notadb.db", "file is not a database");
  /* a lone body with only stop_cpd or stop_events would never end (a lone disk, at rest, ran to
   * t = inf and failed on an event time of NaN; a lone dimer spun for ever): refused */
  /* a file that is not haff's: resume reads it without writing (it added haff's tables and
   * WAL mode to any SQLite file), the analyses and export say the same with exit 2 */
  assert_int_equal(sh("sqlite3 foreign.db \"CREATE TABLE mydata(a)\" && : > empty.db && mkdir -p "
                      "adir.db"),
                   0);
  bad_usage("resume foreign.db", "foreign.db: not a haff database");
  assert_int_equal(q1("foreign.db", "SELECT count(*) FROM sqlite_schema"), 1);
  bad_usage("resume empty.db", "empty.db: not a haff database");
  assert_int_equal(sh("test ! -s empty.db"), 0);
  bad_usage("export xyz empty.db", "not a haff database");
  bad_usage("export xyz foreign.db", "not a haff database");
  bad_usage("haff-fit adir.db", "adir.db: is a directory");
  bad_usage("rods-energy adir.db", "adir.db: is a directory");
  bad_usage("export xyz adir.db", "adir.db: is a directory");
  bad_usage("resume adir.db", "adir.db: is a directory");
  bad_usage("run s.ini -o adir.db", "adir.db: is a directory");
  write_file("junk.db", "this is not an SQLite database, and it is long enough to be read as one "
                        "by SQLite's header check, which wants at least a hundred bytes of it\n");
  bad_usage("run s.ini -o junk.db", "file is not a database");
  bad_usage("resume junk.db", "file is not a database");
  /* a gamma the rods' sampler cannot grid is refused at its key, file and line (the engine's
   * set-up said only "eps: step 0.01 too small for gamma 1e-06") */
  write_file("g6.ini", "[rods]\ncount = 10\ngamma = 1e-6\n[run]\nstop_cpd = 1\n");
  bad_usage("run g6.ini -o g6.db", "g6.ini:3: [rods] gamma = 1e-6: too small for the eps sampler");
  bad_usage("run g6.ini -o g6.db --set rods.gamma=1.2", "[rods] gamma = 1.2: must be in (0, 1]");
  /* a state whose speeds square to inf ran for ever, crossing cells without a collision */
  write_file("fast.csv", "kind,x,y,phi,vx,vy,omega\ndisk,5,5,0,1e160,0,0\ndisk,10,5,0,-1,0,0\n");
  write_file("fast.ini", "[system]\nbox = 20 20\n[init]\nstate = fast.csv\n[run]\n"
                         "stop_events = 100\n");
  bad_usage("run fast.ini -o fast.db", "fast.csv:2: velocity (1e+160, 0) or omega 0 too large");
  assert_false(exists("fast.db"));
  write_file("one.ini", "[system]\nbox = 10 10\n[disks]\ncount = 1\n[run]\nstop_cpd = 10\n");
  bad_usage("run one.ini -o one.db", "one body alone never collides with another");
  assert_false(exists("one.db"));
  /* SIGINT in a long set-up (3e5 disks past the jamming density: random addition then a melted
   * lattice, some 20 s here) stops it at once: exit 1, no file (it waited for the set-up's end,
   * then wrote a run 'interrupted' at t = 1e-9) */
  write_file("dense.ini", "[system]\narea_fraction = 0.7\n[disks]\ncount = 300000\n[run]\n"
                          "stop_cpd = 1\n");
  assert_int_equal(interrupt_after("run dense.ini -o dense.db --quiet", "0.5"), 1);
  read_err(e, sizeof e);
  assert_non_null(strstr(e, "of the set-up, before the run began: nothing was written"));
  assert_false(exists("dense.db"));
  /* a run whose collisions are rare still sees SIGINT (hd_sim_next returns every 2^22 events
   * without a collision): ten disks in a box of 1e9 */
  write_file("rare.ini", "[system]\nbox = 1e9 1e9\n[disks]\ncount = 10\n[run]\nstop_events = "
                         "10\n");
  assert_int_equal(sh("(%s run rare.ini -o rare.db --quiet & p=$!; " WAIT_FOR_LOCK(
                          "rare.db") "sleep 1; kill -INT $p; "
                                     "wait $p)",
                      haff),
                   1);
  assert_int_equal(q1("rare.db", "SELECT count(*) FROM runs WHERE status = 'interrupted'"), 1);
  /* a resume interrupted says how to go on too (only haff run did) */
  assert_int_equal(interrupt_after("resume rare.db --quiet", "1"), 1);
  read_err(e, sizeof e);
  assert_non_null(strstr(e, "(continue with: haff resume rare.db --run 1)"));
  /* haff mc without a known program: one line (it printed the usage) */
  bad_usage("mc bogus", "haff mc: unknown program 'bogus'");
  assert_int_equal(sh("(%s mc 2>&1 | wc -l | grep -qx 1)", haff), 0);
  /* an unknown option is one line naming it (it printed the whole usage) */
  bad_usage("run s.ini --bogus", "haff run: unknown option or missing value '--bogus'");
  assert_int_equal(sh("(%s resume --bogus x.db 2>&1 | wc -l | grep -qx 1)", haff), 0);
  assert_int_equal(sh("%s run --help >/dev/null", haff), 0);
  assert_int_equal(sh("%s --help >/dev/null", haff), 0);
  /* mc fmean: an option its mode does not read is refused (--fig4-data --scan printed NaN
   * geometry with exit 0; --convergence ignored --model, --scan and a lone --d; --scan ignored
   * --a) */
  bad_usage("mc fmean --fig4-data --scan 1:2:1", "--scan does not apply with --fig4-data");
  bad_usage("mc fmean --convergence --model collision",
            "--model does not apply with --convergence");
  bad_usage("mc fmean --convergence --scan 1:2:1", "--scan does not apply with --convergence");
  bad_usage("mc fmean --convergence --d 2", "--convergence with --d needs --a");
  /* ints given past their range were cast (4294967312 -> 16, accepted); a long past its own
   * range was LONG_MAX */
  bad_usage("mc eps --gamma 0.8 --adapt 4294967312",
            "--adapt '4294967312': expected a whole number in [1, 2147483647]");
  bad_usage("mc eps --gamma 0.8 --tabulate --db x.db --nbeta 4294967321",
            "--nbeta '4294967321': expected a whole number in");
  bad_usage("mc eps --gamma 0.8 --samples 99999999999999999999", "--samples '9999");
  /* K = E_tr/E_rot of a file without dimers: it printed a header only, exit 0 */
  bad_usage("table2 ref.db", "no dimer run to fit");
  /* options a mode does not read were ignored without a word */
  bad_usage("mc eps --gamma 0.8 --tabulate --db x.db --beta 5", "--beta does not apply with");
  bad_usage("mc eps --gamma 0.8 --nbeta 5", "--nbeta does not apply without --tabulate");
  bad_usage("mc eps --gamma 0.8 --convergence --adapt 4", "--adapt does not apply with");
  bad_usage("mc eps --gamma 0.8 --adapt -4",
            "--adapt '-4': expected a whole number in [1,"); /* -1 meant unset */
  /* a convergence sequence too short for a slope printed no row and a slope of nan, exit 0 */
  bad_usage("mc fmean --convergence --samples 100", "needs n >= 1e4");
  bad_usage("mc fmean --scan 1:2:1 --a 1", "--a does not apply with --scan");
  bad_usage("mc fmean --fig4-data --a 1 --samples 10", "--samples does not apply with --fig4-data");
  assert_int_equal(sh("%s mc fmean --fig4-data --a 1 --d 2 >/dev/null", haff), 0);
  /* a set-up that only the engine can refuse (the dense lattice of the random placement does
   * not fit between the walls) names the scene file and the line of its box too */
  write_file("nw.ini", "[system]\nbox = 1.5 10\n[disks]\ncount = 1\nsigma = 1.5\n[walls]\n"
                       "sides = left right\n[run]\nstop_time = 1\n");
  bad_usage("run nw.ini -o nw.db", "nw.ini:2: [system] box 1.5 x 10: 1 bodies do not fit");
  assert_false(exists("nw.db"));
  /* a state file with overlapping bodies names the file and line */
  write_file("st.csv", "kind,x,y,phi,vx,vy,omega\ndisk,1,1,0,0,0,0\ndisk,1.5,1,0,0,0,0\n");
  write_file(
      "st.ini",
      "[system]\nbox = 10 10\n[disks]\ncount = 2\n[init]\nstate = st.csv\n[run]\nstop_time = 1\n");
  assert_int_equal(sh("%s run st.ini -o bad.db", haff), 2);
  read_err(e, sizeof e);
  assert_non_null(strstr(e, "st.csv:3"));
  assert_non_null(strstr(e, "overlap"));
}

/* Dimers with the smallest bond a scene accepts (a = 1e-9 d) among disks, with verify on: a
 * collision of one disk of a dimer leaves its twin disk within ~1e-10 of the partner, and the
 * t = 0 rule used to collide that twin at once whether or not it would touch: 930 of 50000
 * collisions repeated the pair before them at the same instant (fixed seed), now 8 (the twin
 * really touching).  We allow 50.  No overlap at any event (verify). */
static void tiny_bond_twin_contacts(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("tiny.ini", "[system]\narea_fraction = 0.2\nseed = 7\n[dimers]\ncount = 400\n"
                         "a = 1e-9\nalpha = 0.9\n[disks]\ncount = 400\nalpha = 0.9\n"
                         "alpha_dimer = 0.9\n[run]\nstop_events = 50000\nverify = 1\n"
                         "[log]\ncollisions = all\nsamples_every = 10\n");
  assert_int_equal(sh("%s run tiny.ini -o tiny.db --quiet", haff), 0);
  assert_int_equal(q1("tiny.db", "SELECT count(*) FROM collisions"), 50000);
  long long rep = q1("tiny.db", "SELECT count(*) FROM collisions c JOIN collisions p ON p.run = "
                                "c.run AND p.seq = c.seq - 1 WHERE c.t = p.t AND ((c.i = p.i AND "
                                "c.j = p.j) OR (c.i = p.j AND c.j = p.i))");
  printf("# a = 1e-9: %lld of 50000 collisions repeat the previous pair at the same instant\n",
         rep);
  assert_true(rep <= 50);
}

/* rods-collapse counts every collapsed ring: it kept at most 64 (the size of its median buffer),
 * so 70 rings of 8 rods at eps = 0.3, all of which collapse (McNamara-Young: N_c = 0.51), gave
 * frac = 64/70.  Its numbers are checked before any ring runs. */
static void rods_collapse_counts(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("%s rods-collapse --n 8 --eps 0.3 --seeds 70 --cpd 200 > rc.tsv", haff), 0);
  char p[300], line[400];
  snprintf(p, sizeof p, "%s/rc.tsv", dir);
  FILE *f = fopen(p, "r");
  assert_non_null(f);
  assert_non_null(fgets(line, sizeof line, f)); /* header */
  assert_non_null(fgets(line, sizeof line, f));
  fclose(f);
  long n, col, runs;
  double eps, frac;
  assert_int_equal(sscanf(line, "%ld %lf %ld %ld %lf", &n, &eps, &col, &runs, &frac), 5);
  assert_int_equal(col, 70);
  assert_int_equal(runs, 70);
  assert_true(frac == 1.0);
  /* --n 1e1 is N = 10 (atol read it as 1, an odd count that was refused) */
  assert_int_equal(
      sh("(%s rods-collapse --n 1e1 --eps 3e-1 --seeds 2 --cpd 50 > e1.tsv && %s rods-collapse "
         "--n 10 --eps 0.3 --seeds 2 --cpd 50 > e2.tsv && cmp -s e1.tsv e2.tsv)",
         haff, haff),
      0);
  /* 4 rods at eps 0.3 cool for ever (no collapse) until time runs out near DBL_MAX: counted as
   * not collapsed (it stopped the scan with an error once the ring kept cooling, 2d753ec) */
  assert_int_equal(sh("%s rods-collapse --n 4 --eps 0.3 --seeds 1 --cpd 1000 > rc4.tsv", haff), 0);
  snprintf(p, sizeof p, "%s/rc4.tsv", dir);
  f = fopen(p, "r");
  assert_non_null(f);
  assert_non_null(fgets(line, sizeof line, f));
  assert_non_null(fgets(line, sizeof line, f));
  fclose(f);
  assert_int_equal(sscanf(line, "%ld %lf %ld %ld %lf", &n, &eps, &col, &runs, &frac), 5);
  assert_int_equal(col, 0);
  /* the same ring run as a scene ends 'done' at t ~ 1e308 (cpd 671 of 1000), and says so in
   * runs.message and on stderr instead of looking like a full run */
  write_file("r4.ini", "[rods]\ncount = 4\ngamma = 1\nmodel = constant\neps = 0.3\n[run]\n"
                       "stop_cpd = 1000\n[log]\ncollisions = none\nsamples_every = 10\n");
  assert_int_equal(sh("%s run r4.ini -o r4.db --quiet", haff), 0);
  char e[2048];
  read_err(e, sizeof e);
  assert_non_null(strstr(e, "no event left"));
  assert_int_equal(q1("r4.db", "SELECT count(*) FROM runs WHERE status = 'done' AND message LIKE "
                               "'no event left at t = %'"),
                   1);
  bad_usage("rods-collapse --n 8x", "--n '8x'");
  bad_usage("rods-collapse --eps 1.5", "--eps '1.5'");
  bad_usage("rods-collapse --seeds 2.5", "--seeds '2.5'");
  bad_usage("rods-energy x.db --bins 2.5", "--bins '2.5'");
  bad_usage("rods-energy x.db --gap abc", "--gap 'abc'");
  /* a --cpd whose collision count is past a long ran no ring and printed "0 collapsed" */
  bad_usage("rods-collapse --n 4 --eps 0.5 --seeds 1 --cpd 1e300", "--cpd '1e300'");
  /* empty items were skipped, an odd N failed after the header */
  bad_usage("rods-collapse --n 4,,8", "--n '4,,8'");
  bad_usage("rods-collapse --n ''", "--n ''");
  assert_int_equal(sh("%s rods-collapse --n 3 --seeds 1 > odd.tsv", haff), 2);
  assert_int_equal(sh("test ! -s odd.tsv"), 0);
  /* a --range so small that d / dx is past a long wrote h[LONG_MIN], which aliased bin 0 */
  assert_int_equal(sh("%s rods-gofr r4.db --t 0 --range 1e-300 --bins 2 > g.tsv", haff), 0);
  assert_int_equal(sh("(tail -n 2 g.tsv | awk '$2 != 0 { bad = 1 } END { exit bad }')"), 0);
  bad_usage("rods-clusters r4.db --gap 0", "rods-clusters: --gap must be > 0");
}

/* A full disk (the file size limit of RLIMIT_FSIZE: haff ignores SIGXFSZ, which used to kill it
 * with the run left 'running', so that writes fail with EFBIG as on a full disk): exit 1 and a
 * clear message, a sound database, and once there is room again resume completes the very same run.
 */
static void disk_full_then_resume(void **state) {
  (void)state;
  if (!haff) skip();
  char e[2048];
  int rc = sh("(ulimit -f 3000; exec %s run s.ini -o full.db --quiet)", haff);
  read_err(e, sizeof e);
  assert_int_equal(rc, 1);
  assert_true(strstr(e, "full") || strstr(e, "I/O") || strstr(e, "disk"));
  assert_sound("full.db");
  assert_int_equal(q1("full.db", "SELECT count(*) = coalesce(max(seq), 0) FROM collisions"), 1);
  assert_int_equal(sh("%s resume full.db --quiet", haff), 0);
  same_as_reference("full.db");
}

/* On every logged collision of an inelastic mixture with walls the restitution law holds:
 * dE = -(1 - alpha^2)/2 * mu_eff * vn^2 with mu_eff = f m (f = mu_eff / m by definition), to
 * 1e-9 relative; dE <= 0; the logged losses add up to what the bodies lost; the contact angles of
 * dimers lie in the allowed range |theta| <= pi - arccos(a/2d) = 2 pi/3 (a = d); samples carry
 * per-species energies. */
static void logged_restitution(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("mix.ini", "[system]\narea_fraction = 0.15\nseed = 9\n[dimers]\ncount = 150\n"
                        "alpha = 0.8\n[disks]\ncount = 150\nalpha = 0.7\nalpha_dimer = 0.9\n"
                        "[walls]\nsides = left right\nalpha = 0.6\n[run]\nstop_events = 30000\n"
                        "[log]\nsamples_every = 1\n");
  assert_int_equal(sh("%s run mix.ini -o mix.db --quiet", haff), 0);
  assert_true(q1("mix.db", "SELECT count(DISTINCT kind) FROM collisions") == 5);
  /* wall_seconds is this run's own time (it once included the machine's uptime) */
  assert_int_equal(q1("mix.db", "SELECT wall_seconds > 0 AND wall_seconds < 60 FROM runs"), 1);
  /* the restitution of each kind, from the scene */
  assert_int_equal(q1("mix.db",
                      "SELECT count(*) FROM collisions WHERE abs(de + 0.5 * (1 - "
                      "(CASE kind WHEN 'dimer-dimer' THEN 0.8 WHEN 'disk-disk' THEN 0.7 "
                      "WHEN 'dimer-disk' THEN 0.9 ELSE 0.6 END) * (CASE kind WHEN "
                      "'dimer-dimer' THEN 0.8 WHEN 'disk-disk' THEN 0.7 WHEN 'dimer-disk' "
                      "THEN 0.9 ELSE 0.6 END)) * f * vn * vn) > 1e-9 * abs(de) + 1e-300"),
                   0);
  assert_int_equal(q1("mix.db", "SELECT count(*) FROM collisions WHERE de > 0 OR vn >= 0"), 0);
  /* the check above uses the logged de, f and vn, which come from one formula; the bodies
   * themselves must have lost what the log says: the kinetic energy of the final state minus
   * that of the initial one (from `states`: a dimer has mass 2, I = m a^2 / 2 = 1/2; a disk
   * mass 1) equals the sum of de, to 1e-10 of the initial energy (30000 sums of round-off;
   * measured 1e-14) */
#define KE                                                                                         \
  "sum(CASE kind WHEN 'dimer' THEN vx*vx + vy*vy + 0.25*omega*omega ELSE 0.5*(vx*vx + vy*vy) END)"
  assert_int_equal(q1("mix.db",
                      "SELECT abs((SELECT " KE " FROM states WHERE label = 'final') - (SELECT " KE
                      " FROM states WHERE label = 'initial') - (SELECT sum(de) FROM "
                      "collisions)) < 1e-10 * (SELECT " KE " FROM states WHERE label = "
                      "'initial')"),
                   1);
#undef KE
  assert_int_equal(q1("mix.db",
                      "SELECT count(*) FROM collisions WHERE kind = 'dimer-dimer' AND "
                      "(abs(theta_i) > 2 * pi() / 3 + 1e-9 OR abs(theta_j) > 2 * pi() / 3 "
                      "+ 1e-9)"),
                   0);
  assert_int_equal(q1("mix.db", "SELECT count(*) FROM collisions WHERE kind = 'dimer-dimer' AND "
                                "abs(f - 1.0 / (2 - (cos(theta_i) * cos(theta_i) + cos(theta_j) * "
                                "cos(theta_j)) / 2)) > 1e-12"),
                   0);
  assert_int_equal(q1("mix.db", "SELECT count(*) FROM samples WHERE e_tr_dimer IS NULL OR "
                                "e_tr_disk IS NULL"),
                   0);
  assert_int_equal(q1("mix.db", "SELECT count(*) FROM samples WHERE abs(e_tr - (e_tr_dimer + "
                                "e_tr_disk) / 2) > 1e-12 * e_tr"),
                   0);
}

/* Killed after its final state and checkpoint were written but before its status was: the
 * run is still 'running', and resume must not add a second set of 'final' states (it deleted
 * only states after the checkpoint's t, and the final ones are at that t; review).  Simulated
 * on the reference scene run into a file whose trigger keeps the checkpoint that 'done'
 * deletes, the status then set back by hand.  Then a 'failed' run whose final write broke
 * (status set by hand the same way) resumes to the same end. */
static void resume_after_the_last_step(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("(sqlite3 kept.db < '%s/db/schema.sql' > /dev/null && sqlite3 kept.db "
                      "\"CREATE TRIGGER keep BEFORE DELETE ON checkpoints WHEN (SELECT status "
                      "FROM runs WHERE id = OLD.run) = 'done' BEGIN SELECT RAISE(IGNORE); END\" "
                      "&& %s run s.ini -o kept.db --quiet && sqlite3 kept.db \"DROP TRIGGER "
                      "keep\")",
                      root, haff),
                   0);
  assert_int_equal(q1("kept.db", "SELECT count(*) FROM checkpoints"), 1);
  for (int k = 0; k < 2; k++) {
    assert_int_equal(sh("cp kept.db last.db && sqlite3 last.db \"UPDATE runs SET status = '%s', "
                        "message = 'x'\"",
                        k ? "failed" : "running"),
                     0);
    assert_int_equal(sh("%s resume last.db --quiet", haff), 0);
    same_as_reference("last.db");
    assert_int_equal(sh("rm -f last.db last.db-wal last.db-shm"), 0);
  }
  /* a later run that failed in its set-up (no checkpoint) does not hide the resumable one */
  assert_int_equal(sh("cp kept.db last.db && sqlite3 last.db \"UPDATE runs SET status = "
                      "'interrupted'; INSERT INTO runs(id, scene, seed, status, started, version) "
                      "VALUES (2, '', 1, 'failed', 'x', 'x')\""),
                   0);
  assert_int_equal(sh("%s resume last.db --quiet", haff), 0);
  assert_int_equal(q1("last.db", "SELECT status = 'done' FROM runs WHERE id = 1"), 1);
}

/* A resume of a run that another process is still driving is refused (exit 2, nothing written
 * by it): it used to take the run over and write every row twice (review: 4.0e6 collision rows
 * for 2.2e6 collisions).  The run's lock (DB.lock) goes with its process, so once the run is
 * interrupted it is resumable as usual. */
static void resume_refuses_a_live_run(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("lk.ini", "[system]\narea_fraction = 0.2\nseed = 3\n[disks]\ncount = 2000\n[run]\n"
                       "stop_cpd = 1e6\n[log]\ncollisions = none\nsamples_every = 10\n");
  /* in a subshell, so that $! is haff's own pid and stderr goes to err.txt */
  int rc = sh("(%s run lk.ini -o lk.db --quiet 2>/dev/null & p=$!; " WAIT_FOR_LOCK(
                  "lk.db") "sleep 0.3; "
                           "%s resume lk.db; r=$?; kill -INT $p; wait $p; exit $r)",
              haff, haff);
  char e[2048];
  read_err(e, sizeof e);
  assert_int_equal(rc, 2);
  assert_non_null(strstr(e, "is being run by another process"));
  assert_int_equal(q1("lk.db", "SELECT count(*) FROM runs WHERE status = 'interrupted'"), 1);
  assert_int_equal(q1("lk.db", "SELECT count(*) FROM collisions"), 0);
}

/* Two velocities_at times passed by one event give one snapshot (they gave two sets of rows at
 * one t, which export merged into one frame of twice the bodies); a rods run exports (its
 * runs.box_y is 0: it was "box unknown"); veldist on a rods run names the rods command. */
static void snapshots_and_exports(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("vs.ini", "[system]\nbox = 20 20\nseed = 4\n[disks]\ncount = 100\n[run]\n"
                       "stop_cpd = 4\n[log]\ncollisions = none\nvelocities_at = 1.001 1.002 3\n");
  assert_int_equal(sh("%s run vs.ini -o vs.db --quiet", haff), 0);
  assert_int_equal(q1("vs.db", "SELECT count(*) FROM states WHERE label = 'velocities'"), 200);
  assert_int_equal(q1("vs.db", "SELECT count(DISTINCT t) FROM states WHERE label = 'velocities'"),
                   2);
  write_file("rx.ini", "[rods]\ncount = 50\n[run]\nstop_time = 5\n[log]\ncollisions = none\n");
  assert_int_equal(sh("%s run rx.ini -o rx.db --quiet", haff), 0);
  assert_int_equal(sh("%s export xyz rx.db > rx.xyz", haff), 0);
  assert_int_equal(sh("head -2 rx.xyz | grep -q 'Lattice=\"50 0 0 0 1 0 0 0 1\"'"), 0);
  bad_usage("veldist rx.db --run 1", "is a rods run: see haff rods-veldist");
  /* samples_every far below a collision's cpd step: one sample per collision at most (1e-12
   * wrote millions of rows per collision) */
  write_file("tiny.ini", "[system]\nbox = 20 20\n[disks]\ncount = 10\n[run]\nstop_events = 10\n"
                         "[log]\nsamples_every = 1e-12\n");
  assert_int_equal(sh("%s run tiny.ini -o tinys.db --quiet", haff), 0);
  assert_true(q1("tinys.db", "SELECT count(*) FROM samples") <= 11);
  /* velocities_at values the run did not reach (a stop in another unit) are said, not dropped
   * silently; past a stop in the same unit they are refused at set-up (issue 16) */
  write_file("va.ini", "[system]\nbox = 20 20\n[disks]\ncount = 100\n[run]\nstop_events = 100\n"
                       "[log]\ncollisions = none\nvelocities_at = 1 5 10\n");
  assert_int_equal(sh("%s run va.ini -o va.db --quiet", haff), 0);
  assert_int_equal(q1("va.db", "SELECT count(*) FROM runs WHERE message LIKE "
                               "'velocities_at: 2 of 3 snapshots not taken%'"),
                   1);
  bad_usage("run va.ini -o va2.db --seed 1 --seed 2", "--seed given twice");
  /* REVIEW14 10: an output, an input or a run given twice is refused (before: the last one
   * counted, `run -o a.db -o b.db` wrote b.db alone, haff-fit --run 1 --run 2 read run 2) */
  bad_usage("run va.ini -o va4.db -o va5.db", "-o given twice: give one");
  assert_false(exists("va4.db") || exists("va5.db"));
  bad_usage("haff-fit va.db --run 1 --run 1", "--run given twice: give one");
  bad_usage("energy va.db -o e1.tsv -o e2.tsv", "-o given twice: give one");
  bad_usage("export xyz va.db --run 1 --run 1", "--run given twice: give one");
  bad_usage("mc eps --tabulate --db e1.db --db e2.db", "--db given twice: give one");
  bad_usage("sweep x.ini --status a --status b", "--status given twice: give one");
  bad_usage("run va.ini -o va3.db --set run.stop_cpd=2",
            "va.ini:9: [log] velocities_at = 1 5 10: 10 is past stop_cpd = 2");
  /* snapshot times are taken at those times exactly, the last one at stop_time */
  write_file("vt.ini", "[rods]\ncount = 50\n[run]\nstop_time = 5\n[log]\ncollisions = none\n"
                       "velocities_at_time = 0 0.5 1.25 5\n");
  assert_int_equal(sh("%s run vt.ini -o vt.db --quiet", haff), 0);
  assert_int_equal(q1("vt.db", "SELECT count(*) FROM states WHERE label = 'velocities' AND t IN "
                               "(0, 0.5, 1.25, 5)"),
                   200);
}

/* A run from a state file resumes without it (resume read the CSV again, and failed once it
 * was moved or edited, though the checkpoint holds every body): interrupted, its CSV deleted,
 * resumed, it ends in the final state of an uninterrupted run. */
static void resume_without_the_state_file(void **state) {
  (void)state;
  if (!haff) skip();
  char csv[8192] = "kind,x,y,phi,vx,vy,omega\n";
  for (int i = 0; i < 100; i++) {
    char row[96];
    snprintf(row, sizeof row, "disk,%g,%g,0,%g,%g,0\n", 1.5 * (i % 10) + 0.75,
             1.5 * (i / 10) + 0.75, sin(1.0 + i), cos(2.0 * i));
    strcat(csv, row);
  }
  write_file("sf.csv", csv);
  write_file("sf.ini", "[system]\nbox = 15 15\n[init]\nstate = sf.csv\n[run]\nstop_events = "
                       "4000000\n[log]\ncollisions = none\n");
  assert_int_equal(sh("%s run sf.ini -o sf-ref.db --quiet", haff), 0);
  assert_int_equal(sh("(%s run sf.ini -o sf.db --quiet & p=$!; " WAIT_FOR_LOCK(
                          "sf.db") "sleep 0.5; kill -INT $p; "
                                   "wait $p)",
                      haff),
                   1);
  assert_int_equal(sh("rm sf.csv && %s resume sf.db --quiet", haff), 0);
  assert_int_equal(q1("sf.db", "SELECT count(*) FROM runs WHERE status = 'done'"), 1);
  assert_int_equal(sh("sqlite3 sf.db \"ATTACH 'sf-ref.db' AS r; SELECT count(*) FROM (SELECT "
                      "body, x, y, vx, vy FROM states WHERE label = 'final' EXCEPT SELECT body, x, "
                      "y, vx, vy FROM r.states WHERE label = 'final')\" | grep -qx 0"),
                   0);
}

/* Review 14, item 7: a scene too dense for placement = random is told to use the lattice only
 * when the lattice holds its bodies (before: always, though it holds at most pi/8 of the box
 * for dimers, so the advice failed for every dimer scene); a box that came from area_fraction
 * is named by that key, with its line or its --set (before: `FILE:2: [system] box 22.1 x 22.1`
 * for a file's area_fraction, and `FILE: [system] box ...` with no line for a --set). */
static void dense_placement_messages(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("dd.ini", "[system]\narea_fraction = 0.8\n[dimers]\ncount = 300\n[run]\n"
                       "stop_events = 10\n");
  bad_usage("run dd.ini -o dd.db",
            "dd.ini:2: [system] area_fraction = 0.8: too dense: the bodies cover 0.8 of the box, "
            "above 0.75 for placement = random, and placement = lattice holds only 144 of the 300 "
            "bodies");
  bad_usage("run dd.ini -o dd.db --set init.placement=lattice", "give a lower area_fraction");
  /* disks at 0.77: above random's 0.75, below the lattice's pi/4, which holds them */
  write_file("dk.ini", "[system]\narea_fraction = 0.77\n[disks]\ncount = 100\n[run]\n"
                       "stop_events = 10\n");
  bad_usage("run dk.ini -o dd.db", "(use placement = lattice, which holds them, or a lower "
                                   "area_fraction)");
  assert_int_equal(sh("%s run dk.ini -o dd.db --quiet --set init.placement=lattice", haff), 0);
  /* the engine's set-up refusal of a mixture: by the key written, where */
  write_file("el6.ini", "[system]\narea_fraction = 0.6\n[dimers]\ncount = 100\na = 0.6\n[disks]\n"
                        "count = 50\nsigma = 1.5\n[species tri]\ncount = 30\nshape = bent 100\n"
                        "[walls]\nsides = left right top bottom\n[run]\nstop_cpd = 2\n");
  bad_usage("run el6.ini -o el.db", "el6.ini:2: [system] area_fraction = 0.6: the box 22.1268");
  bad_usage("run el6.ini -o el.db --set system.area_fraction=0.6",
            "--set system.area_fraction=0.6: [system] area_fraction = 0.6: the box 22.1268");
  write_file("el7.ini", "[system]\nbox = 22 22\n[dimers]\ncount = 100\na = 0.6\n[disks]\n"
                        "count = 50\nsigma = 1.5\n[species tri]\ncount = 30\nshape = bent 100\n"
                        "[walls]\nsides = left right top bottom\n[run]\nstop_cpd = 2\n");
  bad_usage("run el7.ini -o el.db", "el7.ini:2: [system] box 22 x 22: 180 bodies do not fit");
  bad_usage("run el7.ini -o el.db --set 'system.box=22 22'",
            "--set system.box=22 22: [system] box 22 x 22: 180 bodies do not fit");
  assert_false(exists("el.db"));
}

/* A database directory where no file can be made (/proc, even for root): exit 1 with a clear
 * message, no crash.  One that does not exist is bad usage, refused before anything is opened
 * (exit 2, naming it; review 14: it was exit 1, "unable to open database file"). */
static void unwritable_db(void **state) {
  (void)state;
  if (!haff) skip();
  char e[2048];
  assert_int_equal(sh("%s run s.ini -o /proc/x.db --quiet", haff), 1);
  read_err(e, sizeof e);
  assert_non_null(strstr(e, "x.db"));
  bad_usage("run s.ini -o /proc/nope/x.db --quiet",
            "-o /proc/nope/x.db: the folder /proc/nope does not exist");
}

/* A sparsely logged run commits what it has every second (hd_run.c), so that its rows can be
 * read while it goes on, and another run appends to the same file meanwhile; the lock file
 * DB.lock stays while a run holds a lock in it and goes with the last.  Logging every
 * 10^4th collision gives ~10^2 rows/s here: without the 1-s commit its first rows would wait
 * for the writer's 4096-row buffer and a 10^4-row batch (minutes), and the deadline of 30 s
 * below would fail; with it they are there after about a second. */
static void live_run_commits_every_second(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("live.ini", "[system]\nbox = 80 80\n[disks]\ncount = 2000\n[run]\nstop_time = 1e9\n"
                         "[log]\ncollisions = every 10000\nsamples_every = 1e9\n");
  write_file("short.ini", "[system]\nbox = 20 20\n[disks]\ncount = 100\n[run]\n"
                          "stop_events = 10000\n");
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    if (chdir(dir)) _exit(99);
    freopen("live-err.txt", "w", stderr);
    execl(haff, haff, "run", "live.ini", "-o", "live.db", "--quiet", (char *)NULL);
    _exit(98);
  }
  int st;
  const struct timespec ms10 = {0, 10000000L};
  long long seen = 0;
  for (int k = 0; k < 3000 && seen <= 0; k++) { /* 30 s */
    if (waitpid(pid, &st, WNOHANG) == pid) fail_msg("the live run ended");
    nanosleep(&ms10, NULL);
    seen = committed("live.db");
  }
  if (seen <= 0) kill(pid, SIGKILL), waitpid(pid, &st, 0);
  assert_true(seen > 0);
  /* a second run appends to the file while the first goes on */
  int rc = sh("%s run short.ini -o live.db --quiet", haff);
  /* which leaves the lock file, which holds the live run's lock, in place: a resume of the live
   * run is still refused (a new file at the path would have let it through) */
  int lock_kept = exists("live.db.lock");
  int resume_rc = sh("%s resume live.db --run 1 --quiet", haff);
  kill(pid, SIGINT);
  waitpid(pid, &st, 0);
  assert_int_equal(rc, 0);
  assert_true(lock_kept);
  assert_int_equal(resume_rc, 2);
  /* the last run to let go of the lock file removes it; readers leave no -wal or -shm */
  assert_false(exists("live.db.lock"));
  assert_int_equal(sh("%s export xyz live.db --run 2 > /dev/null", haff), 0);
  assert_false(exists("live.db-wal"));
  assert_false(exists("live.db-shm"));
  assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 1);
  assert_int_equal(
      q1("live.db", "SELECT count(*) FROM runs WHERE id = 1 AND status = 'interrupted'"), 1);
  assert_int_equal(q1("live.db", "SELECT count(*) FROM runs WHERE id = 2 AND status = 'done'"), 1);
  assert_true(q1("live.db", "SELECT count(*) FROM collisions WHERE run = 1") >= seen);
}

/* Writes scene text base followed by extra sections to name in dir. */
static void write_scene(const char *name, const char *base, const char *extra) {
  char text[1024];
  snprintf(text, sizeof text, "%s%s", base, extra);
  write_file(name, text);
}

/* Runs the scenes NAME.ini of the space-separated names, in order, into database db. */
static void run_scenes(const char *names, const char *db) {
  assert_int_equal(
      sh("(for s in %s; do %s run $s.ini -o %s --quiet || exit 1; done)", names, haff, db), 0);
}

/* Runs that are not the papers' case (dimers mixed with disks, walls) are told apart: haff-fit
 * and energy label them dimers+disks and dimers+walls (both read "dimers"), and table1/table2
 * leave them out with a note (their rows looked like the pure runs', same alpha and a/d). */
static void mixtures_and_walls_labelled(void **state) {
  (void)state;
  if (!haff) skip();
  const char *base = "[system]\narea_fraction = 0.05\n[dimers]\ncount = 100\nalpha = 0.9\n"
                     "a = 0.5\n[run]\nstop_cpd = 30\n[log]\ncollisions = none\n"
                     "samples_every = 0.5\n";
  /* 30 cpd: over 5-20 cpd E decays by less than a factor e at alpha = 0.9, and the fits flag
   * such a window short (issue 25) and the tables leave it out */
  write_scene("pure.ini", base, "");
  write_scene("mixed.ini", base, "[disks]\ncount = 50\nalpha = 0.9\n"); /* one alpha: fitted */
  write_scene("walled.ini", base, "[walls]\nsides = left right\n");
  write_scene("tri.ini",
              "[system]\narea_fraction = 0.05\n[species tri]\ncount = 60\nshape = triangle\n"
              "alpha = 0.9\n[run]\nstop_cpd = 30\n[log]\ncollisions = none\n"
              "samples_every = 0.5\n",
              "");
  run_scenes("pure mixed walled tri", "lab.db");
  assert_int_equal(sh("(%s haff-fit lab.db | cut -f2 | tr '\\n' ' ' > species.txt)", haff), 0);
  char p[300], line[200] = "";
  snprintf(p, sizeof p, "%s/species.txt", dir);
  FILE *f = fopen(p, "r");
  assert_non_null(f);
  assert_non_null(fgets(line, sizeof line, f));
  fclose(f);
  assert_string_equal(line, "species dimers dimers+disks dimers+walls shapes:tri ");
  assert_int_equal(
      sh("(%s energy lab.db > en.tsv && grep -q '^# dimers+disks alpha=0.9' en.tsv)", haff), 0);
  assert_int_equal(sh("(%s table1 lab.db > t1.tsv && test $(wc -l < t1.tsv) = 2)", haff), 0);
  char e[2048];
  read_err(e, sizeof e);
  assert_non_null(strstr(e, "left out 1 run of dimers+disks (alpha 0.9 a/d 0.5)"));
  assert_non_null(strstr(e, "left out 1 run of dimers+walls"));
  /* a/d does not apply to triangles: the note leaves it out (it printed "a/d nan") */
  assert_non_null(strstr(e, "left out 1 run of shapes:tri (alpha 0.9):"));
  assert_null(strstr(e, "nan"));
  assert_int_equal(sh("(%s table2 lab.db > t2.tsv && test $(wc -l < t2.tsv) = 2)", haff), 0);
  /* no run fitted (too few samples below --cpd-max): rows of nan and exit 2, not 0 */
  assert_int_equal(sh("(%s haff-fit lab.db --cpd-max 0.5 > nan.tsv; r=$?; test $(wc -l < nan.tsv) "
                      "= 5 && exit $r)",
                      haff),
                   2);
  /* nothing left to tabulate is bad input, as in table2 (it printed a header, exit 0) */
  assert_int_equal(sh("%s run mixed.ini -o mixonly.db --quiet", haff), 0);
  bad_usage("table1 mixonly.db", "no run of one species in a periodic box to tabulate");
}

/* Issue-14 review, item 11: a gas of paper dimers written as a named species (`shape = dimer
 * 1`) runs bit for bit as [dimers] with the same seed, and the dimer analyses now read it as
 * dimers: angles (its body-body collisions) and veldist (its 'body' snapshots) print exactly
 * what they print for the [dimers] run, table1 and table2 give it a row (they refused it as "not
 * one species in a periodic box" and "no dimer run", angles found "no logged dimer-dimer
 * collisions", veldist refused named species); a species of other bodies is still refused,
 * with that reason. */
static void named_dimers_analysed(void **state) {
  (void)state;
  if (!haff) skip();
  const char *run = "[run]\nstop_cpd = 30\n[log]\nsamples_every = 0.5\nvelocities_at = 10\n";
  char text[512];
  snprintf(text, sizeof text,
           "[system]\narea_fraction = 0.05\n[dimers]\ncount = 100\nalpha = 0.9\n%s", run);
  write_file("pd.ini", text);
  snprintf(text, sizeof text,
           "[system]\narea_fraction = 0.05\n[species dim]\ncount = 100\nshape = dimer 1\n"
           "alpha = 0.9\n%s",
           run);
  write_file("nd.ini", text);
  snprintf(text, sizeof text,
           "[system]\narea_fraction = 0.05\n[species tri]\ncount = 100\nshape = triangle\n"
           "alpha = 0.9\n%s",
           run);
  write_file("nt.ini", text);
  assert_int_equal(sh("rm -f nd.db nt.db && %s run pd.ini -o nd.db -q && %s run nd.ini -o nd.db -q "
                      "&& %s run nt.ini -o nt.db -q",
                      haff, haff, haff),
                   0);
  assert_int_equal(sh("%s angles nd.db --run 1 --block 100 > a1.tsv && %s angles nd.db --run 2 "
                      "--block 100 > a2.tsv && cmp a1.tsv a2.tsv",
                      haff, haff),
                   0);
  assert_int_equal(sh("%s veldist nd.db --run 1 > v1.tsv && %s veldist nd.db --run 2 > v2.tsv && "
                      "cmp v1.tsv v2.tsv && test $(wc -l < v1.tsv) -gt 10",
                      haff, haff),
                   0);
  /* a row each: header + 2 (equal numbers: the same dynamics), and a warning that says why the
   * two rows are apart */
  assert_int_equal(sh("(%s table1 nd.db --keep-flagged > t1.tsv && test $(wc -l < t1.tsv) = 3 && "
                      "test \"$(sed -n 2p t1.tsv)\" = \"$(sed -n 3p t1.tsv)\")",
                      haff),
                   0);
  char e[4096];
  read_err(e, sizeof e);
  assert_non_null(strstr(e, "differ in species label"));
  assert_int_equal(
      sh("(%s table2 nd.db --keep-flagged > t2.tsv && test $(wc -l < t2.tsv) = 3)", haff), 0);
  bad_usage("angles nt.db --run 1", "run 1 has named species (shapes:tri) and no logged "
                                    "dimer-dimer collisions");
  bad_usage("table1 nt.db", "the table is for dimers (of [dimers], or a gas of one named species");
}

/* Named species (issue 18) are analysed as the gas they are, not through [dimers]: they used to
 * be fitted as "dimers" with the dimers' alpha, N and Enskog nu0 (ratio 7.4 for
 * scenes/shapes-mixture.ini), or skipped as rods without [dimers].  One species of triangles
 * gets its own label and an eq. 31 fit (with NaN a/d and Enskog reference); triangles with
 * dimers at other restitutions get no D_e (eq. 31 has one alpha) and say why; veldist refuses. */
static void named_species_labelled(void **state) {
  (void)state;
  if (!haff) skip();
  const char *tri = "[system]\narea_fraction = 0.05\n[species tri]\ncount = 150\nshape = triangle\n"
                    "alpha = 0.9\n[run]\nstop_cpd = 20\n[log]\ncollisions = none\n"
                    "samples_every = 0.5\n";
  write_scene("tri.ini", tri, "");
  write_scene("trimix.ini", tri, "[dimers]\ncount = 50\nalpha = 0.95\n");
  run_scenes("tri trimix", "sh.db");
  assert_int_equal(sh("(%s haff-fit sh.db > shfit.tsv; test $? = 0)", haff), 0);
  char p[300], line[512];
  snprintf(p, sizeof p, "%s/shfit.tsv", dir);
  FILE *f = fopen(p, "r");
  assert_non_null(f);
  assert_non_null(fgets(line, sizeof line, f)); /* header */
  char lab[2][64] = {"", ""};
  double alpha[2], ad[2], De[2], n0e[2];
  for (int r = 0; r < 2; r++) {
    assert_non_null(fgets(line, sizeof line, f));
    /* run species alpha a_over_d n_used detected t_end cpd_end D_e err nu0 err nu0_enskog, split
     * at tabs: a missing value is an empty cell (issue 25), which reads as NaN here */
    double v[13];
    char *q = line;
    for (int c = 0; c < 13; c++) {
      char *tab = strchr(q, '\t');
      if (tab) *tab = 0;
      if (c == 1) snprintf(lab[r], sizeof lab[r], "%.63s", q);
      v[c] = *q ? strtod(q, NULL) : NAN;
      q = tab ? tab + 1 : q + strlen(q);
    }
    alpha[r] = v[2], ad[r] = v[3], De[r] = v[8], n0e[r] = v[12];
  }
  fclose(f);
  printf("# named species: %s alpha %g D_e %g; %s alpha %g D_e %g\n", lab[0], alpha[0], De[0],
         lab[1], alpha[1], De[1]);
  assert_string_equal(lab[0], "shapes:tri");
  assert_string_equal(lab[1], "shapes:dimers+tri"); /* scene order: [dimers] is species 0 */
  assert_true(fabs(alpha[0] - 0.9) < 1e-12);
  assert_true(isnan(alpha[1]) && isnan(ad[0]) && isnan(ad[1]) && isnan(n0e[0]));
  /* 20 cpd at alpha = 0.9: a positive, finite D_e (its value is test_cluster's business) */
  assert_true(De[0] > 0.5 && De[0] < 20);
  assert_true(isnan(De[1]));
  char e[4096];
  read_err(e, sizeof e);
  assert_non_null(strstr(e, "the species' restitutions differ (alpha 0.9 to 0.95)"));
  bad_usage("veldist sh.db --run 1", "has named species (shapes:tri)");
  bad_usage("table1 sh.db", "no run of one species in a periodic box to tabulate");
}

/* ---- issue 17 (database side): special names, files of other programs, busy handling,
 * damaged checkpoints, runs killed before their first checkpoint ---- */

/* A small scene of 200 collisions. */
static const char small_scene[] =
    "[system]\narea_fraction = 0.1\nseed = 1\n[disks]\ncount = 50\n"
    "[run]\nstop_events = 200\n[log]\ncollisions = all\nsamples_every = 0.1\n";

/* md5sum of file name in dir, into sum (33 bytes). */
static void md5_of(const char *name, char *sum) {
  char cmd[600];
  snprintf(cmd, sizeof cmd, "md5sum '%s/%s'", dir, name);
  FILE *p = popen(cmd, "r");
  assert_non_null(p);
  assert_non_null(fgets(sum, 33, p));
  pclose(p);
}

/* SQLite's special names are plain file names: `-o :memory:` wrote nothing ("run 1 done" and
 * exit 0, the run in memory), `-o 'file:u.db?mode=memory'` neither, `-o file:o.db` wrote o.db.
 * Each is now the file of that very name, for run, resume, the analyses, export and mc eps. */
static void special_names_are_files(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("small.ini", small_scene);
  const char *names[3] = {":memory:", "file:u.db?mode=memory", "file:o.db"};
  for (int k = 0; k < 3; k++) {
    assert_int_equal(sh("%s run small.ini -o '%s' --quiet", haff, names[k]), 0);
    assert_true(exists(names[k]));
    assert_int_equal(q1(names[k], "SELECT count(*) FROM runs WHERE status = 'done'"), 1);
    assert_int_equal(q1(names[k], "SELECT count(*) FROM collisions"), 200);
  }
  assert_false(exists("o.db"));
  assert_false(exists("u.db"));
  /* the readers (export through hd_db_open_readonly, the analyses through hd_db_open_read)
   * read the file: they said "no runs table" of the empty database in memory */
  assert_int_equal(sh("%s export xyz :memory: -o m.xyz", haff), 0);
  assert_int_equal(sh("test -s m.xyz"), 0);
  assert_int_equal(sh("%s energy 'file:o.db' > /dev/null", haff), 0);
  /* resume opens the file too (it said "no runs table", exit 2) */
  assert_int_equal(sh("sqlite3 ./:memory: \"UPDATE runs SET status = 'running'\""), 0);
  assert_int_equal(sh("%s resume :memory: --quiet", haff), 0);
  assert_int_equal(q1(":memory:", "SELECT count(*) FROM runs WHERE status = 'done'"), 1);
  /* mc eps --tabulate --db ':memory:' stores its table in the file */
  assert_int_equal(sh("%s mc eps --gamma 0.8 --tabulate --db :memory: --nbeta 3 --nu 9 "
                      "--samples 50 > /dev/null",
                      haff),
                   0);
  assert_int_equal(q1(":memory:", "SELECT count(*) FROM eps_tables"), 1);
}

/* A database of another program is bad input, and left byte for byte as it was: `run -o` and
 * `mc eps --tabulate --db` added haff's seven tables to it (exit 0); with a `runs` table of
 * another shape `run` exited 1 and left its tables behind.  An empty file is a new database. */
static void foreign_database_untouched(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("small.ini", small_scene);
  assert_int_equal(sh("sqlite3 other.db \"CREATE TABLE t(x); INSERT INTO t VALUES (1)\" && "
                      "sqlite3 otherruns.db \"CREATE TABLE runs(x); INSERT INTO runs VALUES (2)\""),
                   0);
  char before[40], after[40];
  md5_of("other.db", before);
  bad_usage("run small.ini -o other.db --quiet",
            "other.db: not a haff database: it holds tables of another program (t)");
  bad_usage("mc eps --gamma 0.8 --tabulate --db other.db --nbeta 3 --nu 9 --samples 50",
            "other.db: not a haff database");
  md5_of("other.db", after);
  assert_string_equal(before, after);
  assert_false(exists("other.db-wal"));
  md5_of("otherruns.db", before);
  bad_usage("run small.ini -o otherruns.db --quiet",
            "otherruns.db: not a haff database: its table runs has no column id");
  md5_of("otherruns.db", after);
  assert_string_equal(before, after);
  assert_int_equal(q1("otherruns.db", "SELECT count(*) FROM sqlite_schema"), 1);
  /* an empty file is fine, and a haff database takes a second run and an eps table */
  assert_int_equal(sh(": > empty0.db && %s run small.ini -o empty0.db --quiet && %s run "
                      "small.ini -o empty0.db --quiet --seed 2",
                      haff, haff),
                   0);
  assert_int_equal(q1("empty0.db", "SELECT count(*) FROM runs WHERE status = 'done'"), 2);
  assert_int_equal(sh("%s mc eps --gamma 0.8 --tabulate --db empty0.db --nbeta 3 --nu 9 "
                      "--samples 50 > /dev/null",
                      haff),
                   0);
}

/* mc eps --tabulate --db waits for a run that writes the same file, as a second run does (it
 * failed at once with "database is locked"). */
static void eps_table_waits_for_a_run(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("busy.ini", "[system]\narea_fraction = 0.2\nseed = 3\n[disks]\ncount = 2000\n[run]\n"
                         "stop_cpd = 1e6\n[log]\ncollisions = all\n");
  int rc = sh("(%s run busy.ini -o busy.db --quiet 2>/dev/null & p=$!; " WAIT_FOR_LOCK(
                  "busy.db") "sleep 0.5; "
                             "%s mc eps --gamma 0.8 --tabulate --db busy.db --nbeta 3 --nu 9 "
                             "--samples 50 > /dev/null; r=$?; kill -INT $p; wait $p; exit $r)",
              haff, haff);
  char e[2048];
  read_err(e, sizeof e);
  if (rc) fail_msg("mc eps against a live run: exit %d: %s", rc, e);
  assert_int_equal(q1("busy.db", "SELECT count(*) FROM eps_tables"), 1);
  assert_int_equal(q1("busy.db", "SELECT count(*) FROM runs WHERE status = 'interrupted'"), 1);
}

/* Flips bit `bit` of the checkpoint of database db in dir. */
static void flip_bit(const char *db, long bit) {
  char p[300];
  snprintf(p, sizeof p, "%s/%s", dir, db);
  assert_int_equal(test_flip_checkpoint_bit(p, bit), 0);
}

/* A damaged checkpoint: resume exits 2 with one line saying so (a flipped bit crashed it or
 * ended 'done' with wrong data; tests/test_resume.c flips many more, in-process). */
static void damaged_checkpoint_exit_2(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(run_and_signal("dmg.db", SIGINT, 300), 1);
  flip_bit("dmg.db", 8 * 40 + 3); /* in the engine's header */
  char e[2048];
  assert_int_equal(sh("%s resume dmg.db --quiet", haff), 2);
  read_err(e, sizeof e);
  assert_non_null(strstr(e, "dmg.db: the checkpoint of run 1 is damaged"));
  assert_int_equal(sh("test $(wc -l < err.txt) = 1"), 0);
  assert_int_equal(q1("dmg.db", "SELECT status = 'interrupted' FROM runs"), 1);
  flip_bit("dmg.db", 8 * 40 + 3); /* mended: it resumes to the very same run */
  assert_int_equal(sh("%s resume dmg.db --quiet", haff), 0);
  same_as_reference("dmg.db");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(bad_input),
      cmocka_unit_test(unwritable_db),
      cmocka_unit_test(dense_placement_messages),
      cmocka_unit_test(logged_restitution),
      cmocka_unit_test(disk_full_then_resume),
      cmocka_unit_test(sigint_then_resume),
      cmocka_unit_test(sigterm_then_resume),
      cmocka_unit_test(schema4_file_resumed),
      cmocka_unit_test(schema4_file_analysed),
      cmocka_unit_test(kill9_then_resume),
      cmocka_unit_test(rods_collapse_counts),
      cmocka_unit_test(tiny_bond_twin_contacts),
      cmocka_unit_test(resume_after_the_last_step),
      cmocka_unit_test(resume_refuses_a_live_run),
      cmocka_unit_test(snapshots_and_exports),
      cmocka_unit_test(resume_without_the_state_file),
      cmocka_unit_test(live_run_commits_every_second),
      cmocka_unit_test(mixtures_and_walls_labelled),
      cmocka_unit_test(named_dimers_analysed),
      cmocka_unit_test(named_species_labelled),
      cmocka_unit_test(special_names_are_files),
      cmocka_unit_test(foreign_database_untouched),
      cmocka_unit_test(eps_table_waits_for_a_run),
      cmocka_unit_test(damaged_checkpoint_exit_2),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
