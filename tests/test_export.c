/* End-to-end tests of trajectories and what other tools read (issue 19, items 4 and 5), through
 * bin/haff (path in $HAFF_BIN): [log] frames_every / frames_every_time (count, exact times,
 * equal to the final state, resumed without a frame lost or repeated, the cap), `haff export
 * xyz` read back by the real ASE (Debian's python3-ase, tests/ase_check.py) for a dimer, disk,
 * mixture and rods run, and `haff movie` (frame count and size by ffprobe). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <signal.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "hd_run.h"
#include "hd_scene.h"

int hd_cmd_export(int argc, char **argv);

/* sh() sends the command's stdout and stderr to dir/out.txt. */
#define TEST_CLI_SH_FORMAT "cd %s && (%s) >out.txt 2>&1"
#include "test_cli_util.h"

static char root[4096]; /* the source tree (the tests run from it): tests/ase_check.py */

/* The output of the last sh(). */
static const char *out(void) {
  static char buf[8192];
  char p[300];
  snprintf(p, sizeof p, "%s/out.txt", dir);
  FILE *f = fopen(p, "r");
  size_t k = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
  buf[k] = 0;
  if (f) fclose(f);
  return buf;
}

/* One number from an SQL query on database db in dir (ATTACHing ref.db as ref when present). */
static double q1(const char *db, const char *sql) {
  sqlite3 *h;
  sqlite3_stmt *st = test_cli_query(db, sql, &h);
  double v = sqlite3_step(st) == SQLITE_ROW ? sqlite3_column_double(st, 0) : -1;
  sqlite3_finalize(st);
  sqlite3_close(h);
  return v;
}

/* A run that must succeed. */
static void run_ok(const char *ini, const char *db, const char *extra) {
  if (sh("%s run %s -o %s %s", haff, ini, db, extra) != 0) fail_msg("haff run %s: %s", ini, out());
}

/* A command that must fail with exit 2 and a message holding needle. */
static void bad(const char *args, const char *needle) {
  int rc = sh("%s %s", haff, args);
  if (rc != 2 || !strstr(out(), needle))
    fail_msg("haff %s: exit %d, wanted 2 and '%s'; said: %s", args, rc, needle, out());
}

static const char dimers_ini[] = "[system]\narea_fraction = 0.2\nseed = 1\n[dimers]\ncount = 50\n"
                                 "a = 0.7\nalpha = 0.9\n[disks]\ncount = 20\nsigma = 0.8\n"
                                 "mass = 0.5\n[run]\nstop_cpd = 10\n[log]\ncollisions = none\n";

/* frames_every = 0.5 cpd over 10 cpd: frames 0, 0.5, ..., 10 (one per multiple: a collision
 * adds 2/70 cpd); each frame is taken at the first collision past its cpd, so its cpd lies in
 * [k/2, k/2 + 2/70).  The last is the final state: positions and phi bit for bit (float64),
 * velocities to float32 (6e-8 relative).  A run that asks for no frames has none and its scene
 * text says nothing of them (the text identifies a run: it must not change). */
static void frames_by_cpd(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("f.ini", dimers_ini);
  run_ok("f.ini", "f.db", "--set log.frames_every=0.5");
  assert_true(strstr(out(), "21 frames of 70 bodies, ~0.0538 MB (frames_max_mb = 1000)"));
  assert_int_equal(q1("f.db", "SELECT count(*) FROM frames"), 21);
  assert_int_equal(q1("f.db", "SELECT count(*) FROM frames WHERE n = 70 AND length(data) = 2520"),
                   21);
  assert_int_equal(q1("f.db", "SELECT count(*) FROM (SELECT row_number() OVER (ORDER BY t) - 1 AS "
                              "k, cpd FROM frames) WHERE cpd < k * 0.5 OR cpd >= k * 0.5 + 2.0/70"),
                   0);
  /* the last frame is the final state: the same disk positions and phi, digit for digit */
  assert_int_equal(q1("f.db", "SELECT max(t) = (SELECT t FROM states WHERE label = 'final' "
                              "LIMIT 1) FROM frames"),
                   1);
  assert_int_equal(sh("%s export xyz f.db --label final -o a.xyz && %s export xyz f.db --label "
                      "frames -o b.xyz && tail -120 a.xyz | cut -d' ' -f1-4,17 > a.txt && "
                      "tail -120 b.xyz | cut -d' ' -f1-4,17 > b.txt && cmp a.txt b.txt && "
                      "test $(wc -l < a.txt) = 120",
                      haff, haff),
                   0);
  run_ok("f.ini", "none.db", "");
  assert_int_equal(q1("none.db", "SELECT count(*) FROM frames"), 0);
  assert_int_equal(q1("none.db", "SELECT count(*) FROM runs WHERE scene LIKE '%frames%'"), 0);
  assert_int_equal(sh("%s export xyz f.db --label frames -o f.xyz", haff), 0);
  assert_int_equal(sh("test $(grep -c 'Label=frames' f.xyz) = 21"), 0);
  /* ASE reads every frame: the final one's positions match the final states to 1e-12 */
  if (sh("%s export xyz f.db -o all.xyz && /usr/bin/python3 %s/tests/ase_check.py all.xyz f.db 1",
         haff, root))
    fail_msg("%s", out());
}

/* frames_every_time = 0.25 up to stop_time = 3: 13 frames at exactly k/4 (the engine stops at
 * each, free flight is exact), the last at t = 3 equal to the final state. */
static void frames_by_time(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("f.ini", dimers_ini);
  run_ok("f.ini", "t.db",
         "--set run.stop_time=3 --set run.stop_cpd=1e6 "
         "--set log.frames_every_time=0.25");
  assert_int_equal(q1("t.db", "SELECT count(*) FROM frames"), 13);
  assert_int_equal(q1("t.db", "SELECT count(*) FROM (SELECT row_number() OVER (ORDER BY t) - 1 AS "
                              "k, t FROM frames) WHERE t != k * 0.25"),
                   0);
  if (sh("%s export xyz t.db -o t.xyz && /usr/bin/python3 %s/tests/ase_check.py t.xyz t.db 1", haff,
         root))
    fail_msg("%s", out());
  /* stopping the engine at the frames' times changes nothing of the run: the same collisions
   * and final state, bit for bit, as without frames (2D and rods) */
  run_ok("f.ini", "t0.db", "--set run.stop_time=3 --set run.stop_cpd=1e6 --set log.collisions=all");
  run_ok("f.ini", "ref.db",
         "--set run.stop_time=3 --set run.stop_cpd=1e6 --set log.collisions=all "
         "--set log.frames_every_time=0.1");
  assert_true(q1("t0.db", "SELECT count(*) FROM collisions") > 100);
  assert_int_equal(q1("ref.db", "SELECT count(*) FROM frames"), 31);
  const char *same = "SELECT (SELECT count(*) FROM (SELECT seq, t, i, j, de, eps FROM collisions "
                     "EXCEPT SELECT seq, t, i, j, de, eps FROM ref.collisions)) + (SELECT count(*) "
                     "FROM (SELECT body, t, x, y, phi, vx, vy, omega FROM states WHERE label = "
                     "'final' EXCEPT SELECT body, t, x, y, phi, vx, vy, omega FROM ref.states "
                     "WHERE label = 'final')) + abs((SELECT count(*) FROM collisions) - (SELECT "
                     "count(*) FROM ref.collisions))";
  assert_int_equal(q1("t0.db", same), 0);
  write_file("rods.ini", "[rods]\ncount = 40\ngamma = 0.5\n[run]\nstop_time = 30\n"
                         "[log]\ncollisions = all\n");
  run_ok("rods.ini", "r0.db", "--quiet");
  assert_int_equal(sh("rm ref.db"), 0);
  run_ok("rods.ini", "ref.db", "--quiet --set log.frames_every_time=0.7");
  assert_true(q1("r0.db", "SELECT count(*) FROM collisions") > 100);
  assert_int_equal(q1("ref.db", "SELECT count(*) FROM frames"), 43);
  assert_int_equal(q1("r0.db", same), 0);
}

/* Bad input: one line naming the key, exit 2; the cap at set-up (frames_max_mb), at run time
 * when the count cannot be known (stop_time and frames by cpd: frames stop, runs.message says
 * so); velocities_at's 64 values point to frames. */
static void frames_bad_input_and_cap(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("f.ini", dimers_ini);
  bad("run f.ini -o b.db --set log.frames_every=0.5 --set log.frames_max_mb=0.05",
      "[log] frames_every = 0.5: 21 frames of 70 bodies take ~0.05376 MB, more than "
      "frames_max_mb = 0.05");
  bad("run f.ini -o b.db --set log.frames_every=0.5 --set log.frames_every_time=1",
      "frames_every_time = 1: give frames_every (cpd) or frames_every_time, not both");
  bad("run f.ini -o b.db --set log.frames_every_time=1", "needs [run] stop_time");
  bad("run f.ini -o b.db --set log.frames_max_mb=5", "set without frames_every");
  bad("run f.ini -o b.db --set log.frames_every=-1", "frames_every = -1: must be >= 0");
  char many[1024] = "run f.ini -o b.db --set 'log.velocities_at=";
  for (int i = 1; i <= 65; i++) snprintf(many + strlen(many), sizeof many - strlen(many), " %d", i);
  strcat(many, "'");
  bad(many, "more than 64 values (snapshots for a movie or a trajectory: frames_every");
  /* 2560 B a frame: 3 fit in 0.01 MB, the 4th does not */
  run_ok("f.ini", "cap.db",
         "--set run.stop_time=5 --set run.stop_cpd=1e9 "
         "--set log.frames_every=0.5 --set log.frames_max_mb=0.01");
  assert_true(strstr(out(), "at most 2000000001 frames"));
  assert_int_equal(q1("cap.db", "SELECT count(*) FROM frames"), 3);
  assert_int_equal(q1("cap.db", "SELECT count(*) FROM runs WHERE status = 'done' AND message LIKE "
                                "'frames: frames_max_mb = 0.01 reached at t = %'"),
                   1);
}

/* Interrupted (SIGINT once 8 of 21 frames are committed) and resumed, a run stores the very
 * frames of an uninterrupted one: none lost, none twice (the next frame's index is in the
 * checkpoint). */
static void frames_resumed(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("r.ini", "[system]\narea_fraction = 0.3\nseed = 5\n[disks]\ncount = 2000\n"
                      "alpha = 0.95\n[run]\nstop_cpd = 100\n[log]\ncollisions = all\n"
                      "frames_every = 5\n");
  assert_int_equal(sh("rm -f ref.db r.db"), 0);
  run_ok("r.ini", "ref.db", "--quiet");
  assert_int_equal(q1("ref.db", "SELECT count(*) FROM frames"), 21);
  pid_t pid = fork();
  assert_true(pid >= 0);
  if (pid == 0) {
    if (chdir(dir)) _exit(99);
    freopen("/dev/null", "w", stderr);
    execl(haff, haff, "run", "r.ini", "-o", "r.db", "--quiet", (char *)NULL);
    _exit(98);
  }
  const struct timespec ms = {0, 1000000L};
  int st;
  char p[300];
  snprintf(p, sizeof p, "%s/r.db", dir);
  for (;;) {
    long long n = -1;
    sqlite3 *h;
    if (sqlite3_open_v2(p, &h, SQLITE_OPEN_READONLY, NULL) == SQLITE_OK) {
      sqlite3_stmt *s;
      if (sqlite3_prepare_v2(h, "SELECT count(*) FROM frames", -1, &s, 0) == SQLITE_OK) {
        if (sqlite3_step(s) == SQLITE_ROW) n = sqlite3_column_int64(s, 0);
        sqlite3_finalize(s);
      }
    }
    sqlite3_close(h);
    if (n >= 8) break;
    if (waitpid(pid, &st, WNOHANG) == pid) fail_msg("haff run ended before it was signalled");
    nanosleep(&ms, NULL);
  }
  kill(pid, SIGINT);
  waitpid(pid, &st, 0);
  assert_int_equal(WEXITSTATUS(st), 1);
  assert_true(q1("r.db", "SELECT count(*) FROM frames") < 21);
  assert_int_equal(sh("%s resume r.db --quiet", haff), 0);
  assert_int_equal(q1("r.db", "SELECT count(*) FROM frames"), 21);
  assert_int_equal(q1("r.db", "SELECT count(*) FROM (SELECT t, cpd, n, data FROM frames EXCEPT "
                              "SELECT t, cpd, n, data FROM ref.frames)"),
                   0);
}

/* ASE reads every frame of a pure dimer run (frames by cpd), a pure disk run between walls
 * left and right (pbc "F T F"), a mixture with masses of its own between walls bottom and top
 * (pbc "T F F", with velocities_at snapshots) and a rods run (masses 1 + gamma, 1 + 1/gamma;
 * pbc "T F F"), and a mixture of dimers and two named species between walls left and right,
 * whose species names ASE reads intact (column species_name, an element per species: issue
 * 28; ase_check.py checks them, and the disks of the named bodies, for every kind of run). */
static void ase_reads_every_kind_of_run(void **state) {
  (void)state;
  if (!haff) skip();
  static const struct {
    const char *ini, *pbc;
  } runs[] = {
      {"[system]\narea_fraction = 0.3\nseed = 7\n[dimers]\ncount = 60\nalpha = 0.8\n[run]\n"
       "stop_cpd = 6\n[log]\ncollisions = none\nframes_every = 2\n",
       "T T F"},
      {"[system]\nbox = 15 12\nseed = 8\n[disks]\ncount = 40\nalpha = 0.9\n[walls]\n"
       "sides = left right\n[run]\nstop_time = 4\n[log]\ncollisions = none\n"
       "frames_every_time = 1\n",
       "F T F"},
      {"[system]\nbox = 20 16\nseed = 2\n[dimers]\ncount = 30\na = 0.7\nm = 2\nalpha = 0.9\n"
       "[disks]\ncount = 10\nmass = 0.3\n[walls]\nsides = bottom top\n[run]\nstop_cpd = 4\n"
       "[log]\ncollisions = none\nvelocities_at = 1 2\nframes_every = 1\n",
       "T F F"},
      {"[rods]\ncount = 40\ngamma = 0.5\n[run]\nstop_time = 3\n[log]\ncollisions = none\n"
       "frames_every_time = 1\n",
       "T F F"},
      {"[system]\nbox = 30 30\nseed = 18\n[dimers]\ncount = 10\n[species tri]\ncount = 10\n"
       "shape = triangle\n[species asym]\ncount = 10\ndisks = 0 0 1 1; 0.8 0 0.6 0.5\n"
       "[walls]\nsides = left right\n[run]\nstop_cpd = 4\n[log]\ncollisions = none\n"
       "velocities_at = 2\nframes_every = 1\n",
       "F T F"},
  };
  for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
    write_file("a.ini", runs[k].ini);
    assert_int_equal(sh("rm -f a.db"), 0);
    run_ok("a.ini", "a.db", "--quiet");
    assert_true(q1("a.db", "SELECT count(*) FROM frames") >= 4);
    if (sh("%s export xyz a.db -o a.xyz && /usr/bin/python3 %s/tests/ase_check.py a.xyz a.db 1",
           haff, root))
      fail_msg("run %zu: %s", k, out());
    char grep[200];
    snprintf(grep, sizeof grep, "head -2 a.xyz | grep -q 'pbc=\"%s\"'", runs[k].pbc);
    assert_int_equal(sh("%s", grep), 0);
  }
}

/* `haff export gsd` (issue 28) read by Debian's real GSD reader (python3-gsd, gsd.hoomd) and
 * checked field by field, exactly, against the database by tests/gsd_check.py: a dimer run
 * (frames by cpd, velocities_at), a mixture of dimers, disks and two named species (a triangle,
 * an asymmetric pair) between walls, and a ring of rods.  The default output name is the
 * database's with .gsd; stdout, an unknown format and a missing run are refused with exit 2 and
 * leave no file. */
static void gsd_reads_every_kind_of_run(void **state) {
  (void)state;
  if (!haff) skip();
  static const char *const runs[] = {
      "[system]\narea_fraction = 0.3\nseed = 7\n[dimers]\ncount = 60\nalpha = 0.8\n[run]\n"
      "stop_cpd = 6\n[log]\ncollisions = none\nvelocities_at = 3\nframes_every = 2\n",
      "[system]\nbox = 30 30\nseed = 18\n[dimers]\ncount = 10\n[disks]\ncount = 10\n"
      "sigma = 0.8\nmass = 0.5\n[species tri]\ncount = 10\nshape = triangle\n"
      "[species asym]\ncount = 10\ndisks = 0 0 1 1; 0.8 0 0.6 0.5\n[walls]\n"
      "sides = left right\n[run]\nstop_cpd = 4\n[log]\ncollisions = none\nframes_every = 1\n",
      "[rods]\ncount = 40\ngamma = 0.5\n[run]\nstop_time = 3\n[log]\ncollisions = none\n"
      "frames_every_time = 1\n",
  };
  for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
    write_file("g.ini", runs[k]);
    assert_int_equal(sh("rm -f g.db g.gsd"), 0);
    run_ok("g.ini", "g.db", "--quiet");
    assert_true(q1("g.db", "SELECT count(*) FROM frames") >= 4);
    if (sh("%s export gsd g.db && /usr/bin/python3 %s/tests/gsd_check.py g.gsd g.db 1", haff, root))
      fail_msg("run %zu: %s", k, out());
  }
  bad("export gsd g.db -o -", "stdout");
  bad("export pdb g.db -o x.pdb", "unknown format");
  bad("export gsd g.db --run 9 -o none.gsd", "no run 9");
  assert_int_equal(sh("test ! -e none.gsd && test ! -e none.gsd.tmp"), 0);
}

/* haff movie: as many video frames as stored frames (ffprobe counts them), the size asked for
 * (720 wide, the height from the square box plus the title), a file of reasonable size, both
 * formats, and the temporary folder removed; a run without frames, a bad file name or colour
 * and a ring of rods are bad input, with no movie left. */
static void movie_of_frames(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("f.ini", dimers_ini);
  run_ok("f.ini", "m.db", "--quiet --set log.frames_every=1 --set run.stop_cpd=8");
  assert_int_equal(q1("m.db", "SELECT count(*) FROM frames"), 9);
  assert_int_equal(sh("ls -d /tmp/haff-movie-* 2>/dev/null | wc -l > before.txt"), 0);
  if (sh("%s movie m.db -o m.mp4", haff)) fail_msg("%s", out());
  assert_non_null(strstr(out(), "m.mp4: 9 frames of run 1"));
  assert_int_equal(sh("test \"$(ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                      "stream=nb_read_frames,width,height,codec_name -of csv=p=0 m.mp4)\" = "
                      "'h264,720,780,9'"),
                   0);
  assert_int_equal(sh("s=$(stat -c %%s m.mp4); test $s -gt 10000 && test $s -lt 5000000"), 0);
  if (sh("%s movie m.db -o m.gif --color density --size 400 --fps 5", haff)) fail_msg("%s", out());
  assert_int_equal(sh("test \"$(ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                      "stream=nb_read_frames,width,height,codec_name -of csv=p=0 m.gif)\" = "
                      "'gif,400,460,9'"),
                   0);
  assert_int_equal(sh("ls -d /tmp/haff-movie-* 2>/dev/null | wc -l | cmp - before.txt"), 0);
  run_ok("f.ini", "noframes.db", "--quiet");
  bad("movie noframes.db -o x.mp4", "run 1 has no frames: run it with [log] frames_every");
  /* a database from before the frames table: export as before, no movie (exit 2, not 1) */
  assert_int_equal(sh("sqlite3 noframes.db 'DROP TABLE frames' && chmod a-w noframes.db"), 0);
  bad("movie noframes.db -o x.mp4", "run 1 has no frames: run it with [log] frames_every");
  bad("export xyz noframes.db --label frames", "run 1 has no frames (run it with [log]");
  /* a failed export to a file leaves no file (it was left empty), as export gsd; a path that is
   * not a regular file is still written directly */
  bad("export xyz noframes.db --label frames -o nf0.xyz", "run 1 has no frames (run it with");
  assert_int_equal(sh("test ! -e nf0.xyz && test ! -e nf0.xyz.tmp"), 0);
  if (sh("%s export xyz noframes.db -o /dev/null", haff)) fail_msg("%s", out());
  if (sh("%s export xyz noframes.db -o nf.xyz && /usr/bin/python3 %s/tests/ase_check.py nf.xyz "
         "noframes.db 1",
         haff, root))
    fail_msg("%s", out());
  bad("movie m.db -o x.avi", "-o x.avi: give the movie's file, ending in .mp4 or .gif");
  bad("movie m.db -o x.mp4 --color mass", "--color 'mass': expected speed, density or species");
  bad("movie m.db -o x.mp4 --run 7", "there is no such run");
  /* a ring of rods would be a strip of disks one unit high: refused, naming what shows it */
  write_file("mr.ini", "[rods]\ncount = 40\ngamma = 0.5\n[run]\nstop_time = 3\n[log]\n"
                       "collisions = none\nframes_every_time = 1\n");
  run_ok("mr.ini", "mr.db", "--quiet");
  bad("movie mr.db -o x.mp4", "run 1 is a ring of rods, which a movie of disks does not show: use "
                              "haff rods-phase or haff rods-density");
  assert_int_equal(sh("test ! -e x.mp4 && test ! -e x.avi"), 0);
}

/* haff movie --color species (issue 26): a mixture of dimers and a named species, and a run
 * without a species table's dimers and disks, each drawn as a movie of all its frames. */
static void movie_colour_species(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("mix.ini", "[system]\nbox = 14 14\nseed = 3\n[dimers]\ncount = 12\n[species tri]\n"
                        "count = 8\nshape = triangle\n[run]\nstop_cpd = 4\n[log]\n"
                        "collisions = none\nframes_every = 1\n");
  run_ok("mix.ini", "mix.db", "--quiet");
  if (sh("%s movie mix.db -o mix.gif --color species --size 300", haff)) fail_msg("%s", out());
  assert_non_null(strstr(out(), "mix.gif: 5 frames of run 1"));
  assert_int_equal(sh("test \"$(ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                      "stream=nb_read_frames -of csv=p=0 mix.gif)\" = 5"),
                   0);
  write_file("dd.ini", "[system]\nbox = 14 14\nseed = 3\n[dimers]\ncount = 10\n[disks]\n"
                       "count = 10\n[run]\nstop_cpd = 2\n[log]\ncollisions = none\n"
                       "frames_every = 1\n");
  run_ok("dd.ini", "dd.db", "--quiet");
  if (sh("%s movie dd.db -o dd.mp4 --color species", haff)) fail_msg("%s", out());
  assert_non_null(strstr(out(), "dd.mp4: 3 frames of run 1"));
}

/* Issue 24 item 12: `movie -o -x.gif` said "is ffmpeg installed?" (ffmpeg took the name for an
 * option): now it writes ./-x.gif; a failing ffmpeg is not blamed on its installation; and a
 * movie killed by SIGTERM while it draws (or failing) leaves no haff-movie-* folder in the
 * temporary directory ($TMPDIR, else /tmp: the old code used /tmp whatever TMPDIR said and
 * left its folder there when killed). */
static void movie_failures(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("g.ini", dimers_ini);
  run_ok("g.ini", "g.db", "--quiet --set log.frames_every=0.05 --set run.stop_cpd=10");
  assert_int_equal(sh("rm -rf tmpd && mkdir tmpd && ls -d /tmp/haff-movie-* 2>/dev/null | wc -l "
                      "> before.txt"),
                   0);
  if (sh("TMPDIR=$PWD/tmpd %s movie g.db -o -x.gif --size 200", haff)) fail_msg("%s", out());
  assert_int_equal(sh("test -s ./-x.gif"), 0);
  /* ffmpeg fails on a folder named like the movie (a missing folder is refused before any
   * work, exit 2: review 14) */
  assert_int_equal(
      sh("mkdir -p isdir.gif && TMPDIR=$PWD/tmpd %s movie g.db -o isdir.gif --size 200", haff), 1);
  if (strstr(out(), "installed")) fail_msg("blamed on the installation: %s", out());
  assert_non_null(strstr(out(), "ffmpeg could not write isdir.gif"));
  assert_int_equal(sh("TMPDIR=$PWD/tmpd %s movie g.db -o nodir/x.gif --size 200", haff), 2);
  assert_non_null(strstr(out(), "the folder nodir does not exist"));
  /* killed while gnuplot draws its 201 frames (~seconds): status 1, no folder, no movie */
  assert_int_equal(sh("TMPDIR=$PWD/tmpd %s movie g.db -o k.mp4 & p=$!; sleep 0.7; kill -TERM $p; "
                      "wait $p; test $? -eq 1",
                      haff),
                   0);
  assert_non_null(strstr(out(), "interrupted"));
  assert_int_equal(sh("test -z \"$(ls tmpd)\" && test ! -e k.mp4"), 0);
  assert_int_equal(sh("ls -d /tmp/haff-movie-* 2>/dev/null | wc -l | cmp - before.txt"), 0);
}

/* In this process (so that the ASan+UBSan build checks them too, as the other tests drive
 * bin/haff): frames by time of a mixture and by cpd of rods through hd_run_new, their count,
 * sizes and exact times, and their export. */
static void frames_in_process(void **state) {
  (void)state;
  char tmpl[] = "/tmp/haff-frames-XXXXXX";
  assert_non_null(mkdtemp(tmpl));
  static const char *const scenes[2] = {
      "[system]\nbox = 12 12\nseed = 4\n[dimers]\ncount = 20\na = 0.5\n[disks]\ncount = 10\n"
      "[run]\nstop_time = 2\n[log]\ncollisions = none\nframes_every_time = 0.5\n",
      "[rods]\ncount = 30\n[run]\nstop_cpd = 6\n[log]\ncollisions = none\nframes_every = 2\n"};
  static const long bodies[2] = {30, 30};
  for (int k = 0; k < 2; k++) {
    char db[300], xyz[300];
    snprintf(db, sizeof db, "%s/p%d.db", tmpl, k);
    snprintf(xyz, sizeof xyz, "%s/p%d.xyz", tmpl, k);
    hd_scene sc;
    hd_error err;
    assert_int_equal(hd_scene_load_string(&sc, scenes[k], "p.ini", NULL, 0, &err), HD_OK);
    assert_int_equal(hd_scene_frames_estimate(&sc), k ? 4 : 5);
    hd_run_opts o = {.db_path = db, .quiet = 1, .version = "test"};
    int64_t run = 0;
    if (hd_run_new(&sc, &o, &run, &err) != HD_OK) fail_msg("%s", err.msg);
    hd_scene_free(&sc);
    sqlite3 *h;
    assert_int_equal(sqlite3_open(db, &h), SQLITE_OK);
    sqlite3_stmt *st;
    assert_int_equal(sqlite3_prepare_v2(h, "SELECT t, cpd, n, length(data) FROM frames ORDER BY t",
                                        -1, &st, NULL),
                     SQLITE_OK);
    int n = 0;
    while (sqlite3_step(st) == SQLITE_ROW) {
      if (k == 0)
        assert_true(sqlite3_column_double(st, 0) == 0.5 * n);
      else
        assert_true(sqlite3_column_double(st, 1) >= 2.0 * n &&
                    sqlite3_column_double(st, 1) < 2.0 * n + 2.0 / 30);
      assert_int_equal(sqlite3_column_int64(st, 2), bodies[k]);
      assert_int_equal(sqlite3_column_int64(st, 3), bodies[k] * HD_FRAME_BODY_BYTES);
      n++;
    }
    sqlite3_finalize(st);
    sqlite3_close(h);
    assert_int_equal(n, k ? 4 : 5);
    char *argv[] = {"export", "xyz", db, "--label", "frames", "-o", xyz, NULL};
    assert_int_equal(hd_cmd_export(7, argv), 0);
    FILE *f = fopen(xyz, "r");
    assert_non_null(f);
    char line[512];
    int headers = 0;
    long lines = 0;
    while (fgets(line, sizeof line, f)) {
      headers += strstr(line, "Label=frames") != NULL;
      lines++;
    }
    fclose(f);
    assert_int_equal(headers, n);
    long disks = k ? 30 : 50; /* a dimer gives its two disks */
    assert_int_equal(lines, n * (disks + 2));
  }
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf %s", tmpl);
  assert_int_equal(system(cmd), 0);
}

static int setup(void **state) {
  (void)state;
  assert_non_null(getcwd(root, sizeof root));
  return test_cli_setup("export"); /* these tests drive bin/haff, not sanitized */
}

static int teardown(void **state) {
  (void)state;
  return test_cli_teardown();
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(frames_by_cpd),
      cmocka_unit_test(frames_by_time),
      cmocka_unit_test(frames_bad_input_and_cap),
      cmocka_unit_test(frames_resumed),
      cmocka_unit_test(ase_reads_every_kind_of_run),
      cmocka_unit_test(gsd_reads_every_kind_of_run),
      cmocka_unit_test(movie_of_frames),
      cmocka_unit_test(movie_colour_species),
      cmocka_unit_test(movie_failures),
      cmocka_unit_test(frames_in_process),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
