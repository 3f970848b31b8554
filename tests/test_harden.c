/* Hardening of the store (issue 24, items 1, 2, 3, 10 and the merge and stdout parts of 12):
 * an output that names its input is refused before anything is written; haff merge builds no
 * SQL from names found in a file; one list of per-run tables serves truncation, merge and
 * deletion; a HAFFCKP2 checkpoint without its trailer is refused; merge's special names,
 * signals and stdout messages.  Drives bin/haff ($HAFF_BIN) where the CLI is the subject. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <cmocka.h>
#include <signal.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "hd_db.h"
#include "hd_merge.h"
#include "hd_opt.h"
#include "hd_path.h"

#include "test_cli_util.h"

static const char disks_scene[] = "[system]\narea_fraction = 0.2\nseed = 3\n[disks]\ncount = 50\n"
                                  "alpha = 0.97\n[run]\nstop_cpd = 10\n[log]\ncollisions = all\n"
                                  "samples_every = 1\nvelocities_at = 2 5\n";

static int setup(void **state) {
  (void)state;
  assert_int_equal(test_cli_mkdtemp("harden"), 0);
  if (!test_cli_find_haff()) return 0;
  char abs[4096];
  if (haff[0] != '/' && realpath(haff, abs)) haff = strdup(abs);
  write_file("disks.ini", disks_scene);
  assert_int_equal(sh("%s run disks.ini -o d.db --quiet", haff), 0);
  return 0;
}

static int teardown(void **state) {
  (void)state;
  return test_cli_rmdir();
}

/* Whether dir/a and dir/b hold the same bytes. */
static int same_bytes(const char *a, const char *b) {
  return sh("cmp -s %s %s", a, b) == 0;
}

/* Item 1: an output (-o, --output, merge's OUT) naming an input, by its path, through a
 * symbolic or hard link, or as its SQLite log, is refused with exit 2 before anything is
 * written: the database stays byte-identical (before: haff-fit left a 341-byte TSV, energy and
 * export xyz a 0-byte file). */
static void output_is_not_input(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("cp d.db keep.db && ln -sf d.db link.db && ln -f d.db hard.db && "
                      "ln -sf d.db d.gsd"),
                   0);
  static const char *const cmds[] = {"haff-fit d.db -o d.db",
                                     "energy d.db -o d.db",
                                     "export xyz d.db -o d.db",
                                     "export xyz d.db --output link.db",
                                     "export gsd d.db", /* its default d.gsd links to d.db */
                                     "haff-fit link.db -o d.db",
                                     "energy d.db -o hard.db",
                                     "table1 d.db -o ./link.db",
                                     "veldist d.db --run 1 -o d.db-wal",
                                     "movie d.db -o d.db",
                                     "merge d.db link.db",
                                     "run disks.ini -o disks.ini",
                                     "mc eps --tabulate --db e.db --dump e.db",
                                     "angles d.db -o ../$(basename $PWD)/d.db"};
  for (size_t k = 0; k < sizeof cmds / sizeof *cmds; k++) {
    int rc = sh("%s %s", haff, cmds[k]);
    char err[2048];
    read_file("err.txt", err, sizeof err);
    if (rc != 2) fail_msg("haff %s: exit %d, not 2 (%s)", cmds[k], rc, err);
    if (!strstr(err, "would overwrite the input") && !strstr(err, "are the same file"))
      fail_msg("haff %s: %s", cmds[k], err);
    if (!same_bytes("d.db", "keep.db")) fail_msg("haff %s changed d.db", cmds[k]);
    if (!same_bytes("disks.ini", "../$(basename $PWD)/disks.ini") || exists("d.db-wal") ||
        exists("e.db"))
      fail_msg("haff %s wrote a file", cmds[k]);
  }
  assert_int_equal(sh("rm d.gsd"), 0);
  /* and an output that is another file goes on */
  assert_int_equal(sh("%s energy link.db -o e.tsv", haff), 0);
  assert_true(same_bytes("d.db", "keep.db"));
}

/* The rule itself (hd_path_overwrites): the same file by path, link or log; not another. */
static void path_overwrites_rule(void **state) {
  (void)state;
  assert_int_equal(sh("touch a.db b.db && ln -sf a.db la.db"), 0);
  char a[400], b[400], la[400], wal[400], shm[400];
  snprintf(a, sizeof a, "%s/a.db", dir);
  snprintf(b, sizeof b, "%s/b.db", dir);
  snprintf(la, sizeof la, "%s/la.db", dir);
  snprintf(wal, sizeof wal, "%s/a.db-wal", dir);
  snprintf(shm, sizeof shm, "%s/./a.db-shm", dir);
  assert_true(hd_path_overwrites(a, a));
  assert_true(hd_path_overwrites(la, a));
  assert_true(hd_path_overwrites(a, la));
  assert_true(hd_path_overwrites(wal, la)); /* SQLite's log of a link is beside the file */
  assert_true(hd_path_overwrites(shm, a));
  assert_false(hd_path_overwrites(b, a));
  assert_false(hd_path_overwrites(a, b));
}

/* One value of sql on database name in dir (-1 when it fails). */
static long long q1(const char *name, const char *sql) {
  sqlite3 *h;
  char p[400];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  long long v = -1;
  if (sqlite3_open(p, &h) == SQLITE_OK) {
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(h, sql, -1, &st, NULL) == SQLITE_OK) {
      int r = sqlite3_step(st);
      if (r == SQLITE_ROW) v = sqlite3_column_int64(st, 0);
      if (r == SQLITE_DONE) v = 0;
      sqlite3_finalize(st);
    }
  }
  sqlite3_close(h);
  return v;
}

/* REVIEW14 (lower priority): an output that the command replaces whole (a TSV, an xyz, a movie,
 * mc eps --dump) is refused with exit 2 when it is an SQLite database, which stays byte-identical
 * (before: `haff mc eps --dump DB` wrote its text over a database of runs, exit 0); a text file
 * there is replaced as before, and a database output (run -o) is added to. */
static void text_output_not_a_database(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("cp d.db other.db && cp d.db keep2.db"), 0);
  static const char *const cmds[] = {"mc eps --gamma 1 --samples 10 --dump other.db",
                                     "haff-fit d.db -o other.db",
                                     "energy d.db -o other.db",
                                     "export xyz d.db -o other.db",
                                     "export gsd d.db -o other.db",
                                     "movie d.db -o other.db"};
  for (size_t k = 0; k < sizeof cmds / sizeof *cmds; k++) {
    int rc = sh("%s %s", haff, cmds[k]);
    char err[2048];
    read_file("err.txt", err, sizeof err);
    if (rc != 2) fail_msg("haff %s: exit %d, not 2 (%s)", cmds[k], rc, err);
    if (!strstr(err, "other.db is an SQLite database")) fail_msg("haff %s: %s", cmds[k], err);
    if (!same_bytes("other.db", "keep2.db")) fail_msg("haff %s changed other.db", cmds[k]);
  }
  assert_int_equal(sh("echo old > t.tsv && %s haff-fit d.db -o t.tsv", haff), 0);
  assert_int_equal(sh("grep -q old t.tsv"), 1); /* replaced */
  assert_int_equal(sh("%s run disks.ini -o other.db --quiet --seed 77", haff), 0);
  assert_int_equal(q1("other.db", "SELECT count(*) FROM runs"), 2);
}

/* REVIEW14 9: an output in a folder that does not exist (or is a file) is refused with exit 2
 * and one line naming the folder, before anything is opened (before: run "open: unable to open
 * database file" and merge naming its temporary file, exit 1; haff-fit and export "No such file
 * or directory", exit 1). */
static void output_folder_missing(void **state) {
  (void)state;
  if (!haff) skip();
  static const char *const cmds[] = {
      "run disks.ini -o nosuch/b.db",    "merge nosuch/o.db d.db",
      "haff-fit d.db -o nosuch/f.tsv",   "export xyz d.db -o nosuch/x.xyz",
      "export gsd d.db -o nosuch/x.gsd", "mc eps --gamma 1 --tabulate --db nosuch/e.db",
      "energy d.db -o nosuch//e.tsv",    "run disks.ini -o disks.ini/b.db"};
  size_t n = sizeof cmds / sizeof *cmds;
  for (size_t k = 0; k < n; k++) {
    int rc = sh("%s %s", haff, cmds[k]);
    char err[2048];
    read_file("err.txt", err, sizeof err);
    if (rc != 2) fail_msg("haff %s: exit %d, not 2 (%s)", cmds[k], rc, err);
    const char *want =
        k + 1 < n ? "the folder nosuch does not exist" : "the folder disks.ini is not a folder";
    if (!strstr(err, want)) fail_msg("haff %s: %s", cmds[k], err);
  }
  assert_false(exists("nosuch"));
}

/* Item 2: an input whose table name closes the quote of a statement merge builds (before:
 * `haff merge out.db evil.db` printed "1 runs merged", exit 0, and out.db's runs were gone) is
 * refused, out.db byte-identical; a user's table with plain names (plots_runs) still follows
 * its runs, its definition not run but rebuilt from its columns. */
static void merge_no_sql_from_names(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("cp d.db out.db && cp out.db keep.db && %s run disks.ini -o evil.db "
                      "--seed 9 --quiet",
                      haff),
                   0);
  static const char evil[] = "samples\"\" SELECT * FROM main.samples WHERE 0; DELETE FROM "
                             "main.runs; --";
  char sql[512];
  snprintf(sql, sizeof sql, "CREATE TABLE \"%s\" (run INTEGER); INSERT INTO \"%s\" VALUES (1)",
           evil, evil);
  sqlite3 *h;
  char p[400];
  snprintf(p, sizeof p, "%s/evil.db", dir);
  assert_int_equal(sqlite3_open(p, &h), SQLITE_OK);
  assert_int_equal(sqlite3_exec(h, sql, NULL, NULL, NULL), SQLITE_OK);
  sqlite3_close(h);
  int rc = sh("%s merge out.db evil.db", haff);
  char err[1024];
  read_file("err.txt", err, sizeof err);
  if (rc != 2 || !strstr(err, "not a plain identifier")) fail_msg("exit %d: %s", rc, err);
  assert_true(same_bytes("out.db", "keep.db"));
  assert_int_equal(q1("out.db", "SELECT count(*) FROM runs"), 1);
  /* a plain user table follows its run, with a constraint of its definition not copied */
  assert_int_equal(sh("%s run disks.ini -o ok.db --seed 8 --quiet && sqlite3 ok.db \"CREATE "
                      "TABLE plots_runs (run INTEGER, file TEXT CHECK (file <> 'x'), cpu_seconds "
                      "REAL); INSERT INTO plots_runs VALUES (1, 'ok.db', 2.5)\"",
                      haff),
                   0);
  assert_int_equal(sh("%s merge out.db ok.db --quiet", haff), 0);
  assert_int_equal(q1("out.db", "SELECT count(*) FROM runs"), 2);
  assert_int_equal(q1("out.db", "SELECT count(*) FROM plots_runs WHERE run = 2 AND file = "
                                "'ok.db' AND cpu_seconds = 2.5"),
                   1);
  assert_int_equal(q1("out.db", "SELECT count(*) FROM sqlite_schema WHERE name = 'plots_runs' "
                                "AND sql LIKE '%CHECK%'"),
                   0);
  assert_int_equal(q1("out.db", "SELECT count(*) FROM collisions WHERE run = 2"),
                   q1("ok.db", "SELECT count(*) FROM collisions"));
}

/* Item 3: the one list of per-run tables holds every table of db/schema.sql with a run column
 * (read from a fresh database): a table added to the schema and not to the list fails here. */
static void run_tables_list_complete(void **state) {
  (void)state;
  char p[400];
  snprintf(p, sizeof p, "%s/fresh.db", dir);
  hd_db *db;
  hd_error err;
  assert_int_equal(hd_db_open(&db, p, &err), HD_OK);
  sqlite3 *h = hd_db_handle(db);
  sqlite3_stmt *st;
  assert_int_equal(sqlite3_prepare_v2(h,
                                      "SELECT name FROM sqlite_schema t WHERE type = 'table' AND "
                                      "EXISTS (SELECT 1 FROM pragma_table_info(t.name) WHERE "
                                      "name = 'run') ORDER BY name",
                                      -1, &st, NULL),
                   SQLITE_OK);
  int n_schema = 0;
  while (sqlite3_step(st) == SQLITE_ROW) {
    const char *t = (const char *)sqlite3_column_text(st, 0);
    int found = 0;
    for (const hd_run_table *k = hd_db_run_tables(); k->name; k++) found |= !strcmp(k->name, t);
    if (!found) fail_msg("table %s has a run column and is not in hd_db_run_tables", t);
    n_schema++;
  }
  sqlite3_finalize(st);
  int n_list = 0;
  for (const hd_run_table *k = hd_db_run_tables(); k->name; k++) n_list++;
  assert_int_equal(n_list, n_schema); /* and nothing in the list that the schema lacks */
  assert_int_equal(hd_db_close(db, &err), HD_OK);
}

/* Item 3: rows of a run written past its checkpoint in every per-run table, then truncated
 * to it (what a resume after kill -9 or a full disk does): no sample_species row past the
 * checkpoint stays (before: all did, and the resumed run wrote them again: duplicated (t,
 * species) rows); hd_db_run_delete leaves no row of the run in any table. */
static void truncate_and_delete_every_table(void **state) {
  (void)state;
  char p[400];
  snprintf(p, sizeof p, "%s/trunc.db", dir);
  hd_db *db;
  hd_error err;
  int64_t run, other;
  assert_int_equal(hd_db_open(&db, p, &err), HD_OK);
  assert_int_equal(hd_db_run_begin(db, "[system]\nseed = 1\n", 1, "t", &run, &err), HD_OK);
  assert_int_equal(hd_db_run_begin(db, "[system]\nseed = 2\n", 2, "t", &other, &err), HD_OK);
  hd_species_rec sp = {2, "tri", "0 0 1 1", 5, 1, 0.1};
  for (int64_t r = run; r <= other; r++) {
    assert_int_equal(hd_db_log_species(db, r, &sp, &err), HD_OK);
    for (int k = 0; k <= 10; k++) {
      hd_sample_row s = {0};
      s.t = k, s.cpd = k, s.e_tr = 1, s.e_rot = 1;
      s.flow_frac = s.flow_chaos = s.count_var = s.s_rho = s.s_perp = s.s_par = NAN;
      assert_int_equal(hd_db_log_sample(db, r, &s, &err), HD_OK);
      hd_species_sample ss = {k, 2, 1, 1};
      assert_int_equal(hd_db_log_species_sample(db, r, &ss, &err), HD_OK);
    }
  }
  assert_int_equal(hd_db_checkpoint_save(db, run, 50, 5.0, "x", 1, &err), HD_OK);
  assert_int_equal(hd_db_truncate_after(db, run, 50, 5.0, &err), HD_OK);
  sqlite3 *h = hd_db_handle(db);
  static const char *const counts[] = {
      "SELECT count(*) FROM sample_species WHERE run = 1 AND t > 5",
      "SELECT count(*) FROM samples WHERE run = 1 AND t > 5",
      "SELECT count(*) FROM sample_species WHERE run = 2 AND t > 5"};
  static const long long want[] = {0, 0, 5};
  for (int k = 0; k < 3; k++) {
    sqlite3_stmt *st;
    assert_int_equal(sqlite3_prepare_v2(h, counts[k], -1, &st, NULL), SQLITE_OK);
    assert_int_equal(sqlite3_step(st), SQLITE_ROW);
    if (sqlite3_column_int64(st, 0) != want[k])
      fail_msg("%s: %lld, not %lld", counts[k], (long long)sqlite3_column_int64(st, 0), want[k]);
    sqlite3_finalize(st);
  }
  /* species are kept by a resume from a checkpoint, dropped when begun again from set-up */
  sqlite3_stmt *st;
  assert_int_equal(
      sqlite3_prepare_v2(h, "SELECT count(*) FROM species WHERE run = 1", -1, &st, NULL),
      SQLITE_OK);
  assert_int_equal(sqlite3_step(st), SQLITE_ROW);
  assert_int_equal(sqlite3_column_int(st, 0), 1);
  sqlite3_reset(st);
  assert_int_equal(hd_db_truncate_after(db, run, 0, -INFINITY, &err), HD_OK);
  assert_int_equal(sqlite3_step(st), SQLITE_ROW);
  assert_int_equal(sqlite3_column_int(st, 0), 0);
  sqlite3_finalize(st);
  /* deletion: nothing of run 2 in any per-run table, nor its runs row */
  assert_int_equal(hd_db_run_delete(db, other, &err), HD_OK);
  assert_int_equal(hd_db_run_delete(db, other, &err), HD_EINPUT);
  for (const hd_run_table *k = hd_db_run_tables(); k->name; k++) {
    char sql[128];
    snprintf(sql, sizeof sql, "SELECT count(*) FROM %s WHERE run = 2", k->name);
    assert_int_equal(sqlite3_prepare_v2(h, sql, -1, &st, NULL), SQLITE_OK);
    assert_int_equal(sqlite3_step(st), SQLITE_ROW);
    if (sqlite3_column_int(st, 0)) fail_msg("%s still holds rows of the deleted run", k->name);
    sqlite3_finalize(st);
  }
  assert_int_equal(hd_db_close(db, &err), HD_OK);
  assert_int_equal(q1("trunc.db", "SELECT count(*) FROM runs"), 1);
}

/* Item 12: merge's special names: OUT "-", ":memory:" or "file:..." refused (exit 2, no file
 * made: before, "-" became a file and ":memory:" failed with "no such table: s.runs"); an input
 * file named ":memory:" or "file:x" is read as the file it is. */
static void merge_special_names(void **state) {
  (void)state;
  if (!haff) skip();
  static const char *const outs[] = {"-", ":memory:", "file:m.db", "file:m.db?mode=memory"};
  for (size_t k = 0; k < sizeof outs / sizeof *outs; k++) {
    int rc = sh("%s merge '%s' d.db", haff, outs[k]);
    char err[1024];
    read_file("err.txt", err, sizeof err);
    if (rc != 2 || !strstr(err, "nothing merged"))
      fail_msg("OUT %s: exit %d: %s", outs[k], rc, err);
    if (exists(outs[k]) || exists("m.db")) fail_msg("OUT %s: a file was made", outs[k]);
  }
  assert_int_equal(sh("cp d.db ./:memory: && %s run disks.ini -o ./file:x.db --seed 5 --quiet && "
                      "%s merge ./sp.db :memory: file:x.db --quiet",
                      haff, haff),
                   0);
  assert_int_equal(q1("sp.db", "SELECT count(*) FROM runs"), 2);
}

/* Item 12: a merge stopped by SIGTERM or SIGINT leaves OUT as it was and no OUT.merge-PID.tmp
 * (before: the full-size temporary file stayed).  A large input (about 10^6 collisions rows)
 * keeps the merge busy long enough to be stopped in its copy. */
static void merge_signal_cleans_up(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("big.ini", "[system]\narea_fraction = 0.2\nseed = 4\n[disks]\ncount = 2000\n"
                        "alpha = 0.97\n[run]\nstop_cpd = 400\n[log]\ncollisions = all\n");
  assert_int_equal(sh("%s run big.ini -o big.db --quiet", haff), 0);
  for (int s = 0; s < 2; s++) {
    assert_int_equal(sh("cp d.db mo.db && cp mo.db mkeep.db"), 0);
    /* "true;": sh() runs "cd DIR && CMD", and "cd && haff &" would put the cd in the background too
     */
    int rc =
        sh("true; %s merge mo.db big.db & pid=$!; sleep 0.3; kill -%s $pid; wait $pid; echo $? "
           "> rc.txt",
           haff, s ? "INT" : "TERM");
    assert_int_equal(rc, 0);
    char out[64];
    read_file("rc.txt", out, sizeof out);
    assert_true(same_bytes("mo.db", "mkeep.db"));
    if (sh("ls mo.db.merge-* 2>/dev/null | grep -q .") == 0)
      fail_msg("SIG%s: a temporary file stayed (exit %s)", s ? "INT" : "TERM", out);
    if (atoi(out) == 0)
      fail_msg("SIG%s: the merge ended before the signal: make big.db larger", s ? "INT" : "TERM");
  }
}

/* Item 12: "write error" lines name the subcommand and the reason (before: "haff: stdout:
 * write error" with neither, for the analyses and rods-collapse). */
static void write_errors_say_why(void **state) {
  (void)state;
  if (!haff) skip();
  static const char *const cmds[] = {"haff-fit d.db", "energy d.db", "energy d.db -o /dev/full",
                                     "rods-collapse --n 10 --eps 0.1 --seeds 2 --cpd 100"};
  for (size_t k = 0; k < sizeof cmds / sizeof *cmds; k++) {
    char name[64];
    snprintf(name, sizeof name, "haff %.*s:", (int)strcspn(cmds[k], " "), cmds[k]);
    assert_int_equal(sh("%s %s > /dev/full", haff, cmds[k]), 1);
    char err[2048];
    read_file("err.txt", err, sizeof err);
    const char *w = strstr(err, "write error");
    if (!w || !strstr(err, name) || !strstr(w, "No space left on device"))
      fail_msg("%s: %s", cmds[k], err);
  }
}

/* Found by this round's own campaign: merge refused (exit 2, OUT byte-identical) for an input
 * a run is still writing (before: its 'running' run was copied half-way, exit 0), an input of a
 * newer schema version (before: merged with its unknown columns dropped), a write-protected
 * OUT (before: replaced by rename), an OUT with more hard links; OUT keeps its file mode
 * (before: the temporary file's 0644) and a symbolic link OUT stays a link. */
static void merge_campaign_refusals(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("cp d.db o.db && cp d.db okeep.db && %s run disks.ini -o live.db --seed 6 "
                      "--quiet && cp live.db fut.db && sqlite3 fut.db 'PRAGMA user_version = 9'",
                      haff),
                   0);
  char lk[400];
  snprintf(lk, sizeof lk, "%s/live.db.lock", dir);
  int fd = open(lk, O_RDWR | O_CREAT, 0644);
  assert_true(fd >= 0);
  struct flock fl = {.l_type = F_WRLCK, .l_whence = SEEK_SET, .l_start = 1, .l_len = 1};
  assert_int_equal(fcntl(fd, F_SETLK, &fl), 0); /* as a run writing run 1 holds it */
  static const struct {
    const char *cmd, *why;
  } cases[] = {{"merge o.db live.db", "a run is writing to it"},
               {"merge o.db fut.db", "newer than this haff's"},
               {"chmod 444 o.db && %s merge o.db d2.db", "write-protected"}};
  assert_int_equal(sh("%s run disks.ini -o d2.db --seed 12 --quiet", haff), 0);
  for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
    char cmd[512];
    if (strstr(cases[k].cmd, "%s"))
      snprintf(cmd, sizeof cmd, cases[k].cmd, haff);
    else
      snprintf(cmd, sizeof cmd, "%s %s", haff, cases[k].cmd);
    int rc = sh("%s", cmd);
    char err[1024];
    read_file("err.txt", err, sizeof err);
    if (rc != 2 || !strstr(err, cases[k].why)) fail_msg("%s: exit %d: %s", cmd, rc, err);
    assert_true(same_bytes("o.db", "okeep.db"));
  }
  close(fd);
  assert_int_equal(sh("chmod 640 o.db && %s merge o.db live.db --quiet && stat -c %%a o.db > "
                      "mode.txt",
                      haff),
                   0);
  char mode[16];
  read_file("mode.txt", mode, sizeof mode);
  assert_string_equal(mode, "640\n");
  /* OUT through a symbolic link: the file it leads to gets the runs, the link stays (before:
   * the link was replaced by a file and the database it named kept its old runs); OUT with a
   * second hard link: refused (the rename would replace one name only) */
  assert_int_equal(sh("cp d.db tg.db && ln -s tg.db ln.db && %s merge ln.db d2.db --quiet && "
                      "test -L ln.db",
                      haff),
                   0);
  assert_int_equal(q1("tg.db", "SELECT count(*) FROM runs"), 2);
  assert_int_equal(sh("ln tg.db hl.db && cp tg.db tgkeep.db"), 0);
  assert_int_equal(sh("%s merge hl.db fut.db", haff), 2);
  assert_int_equal(sh("%s merge hl.db live.db", haff), 2);
  assert_true(same_bytes("tg.db", "tgkeep.db"));
}

/* Campaign: two merges into one OUT at once.  The second merge stops the first (SIGSTOP) once
 * its temporary file exists (it has copied OUT), merges a small input and ends; the first then
 * goes on: it must not rename its copy over OUT (that lost the second merge's runs, both exit
 * 0), but refuse with exit 2 and OUT keeping the second merge's run. */
static void concurrent_merges_lose_nothing(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("cp d.db cm.db && %s run disks.ini -o s21.db --seed 21 --quiet", haff), 0);
  if (!exists("big.db")) {
    write_file("big.ini", "[system]\narea_fraction = 0.2\nseed = 4\n[disks]\ncount = 2000\n"
                          "alpha = 0.97\n[run]\nstop_cpd = 400\n[log]\ncollisions = all\n");
    assert_int_equal(sh("%s run big.ini -o big.db --quiet", haff), 0);
  }
  int rc = sh("true; %s merge cm.db big.db --quiet 2> big.err & pid=$!; "
              "for i in $(seq 1000); do ls cm.db.merge-*.tmp >/dev/null 2>&1 && break; sleep 0.01; "
              "done; kill -STOP $pid; %s merge cm.db s21.db --quiet; echo $? > small.rc; "
              "kill -CONT $pid; wait $pid; echo $? > big.rc",
              haff, haff);
  assert_int_equal(rc, 0);
  char small[16], big[16], err[1024];
  read_file("small.rc", small, sizeof small);
  read_file("big.rc", big, sizeof big);
  read_file("big.err", err, sizeof err);
  assert_string_equal(small, "0\n");
  if (strcmp(big, "2\n") || !strstr(err, "changed while the merge was made"))
    fail_msg("the first merge: exit %s: %s", big, err);
  assert_int_equal(q1("cm.db", "SELECT count(*) FROM runs WHERE seed = 21"), 1);
  assert_int_equal(q1("cm.db", "SELECT count(*) FROM runs"), 2);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(output_is_not_input),
      cmocka_unit_test(path_overwrites_rule),
      cmocka_unit_test(text_output_not_a_database),
      cmocka_unit_test(output_folder_missing),
      cmocka_unit_test(merge_no_sql_from_names),
      cmocka_unit_test(run_tables_list_complete),
      cmocka_unit_test(truncate_and_delete_every_table),
      cmocka_unit_test(merge_special_names),
      cmocka_unit_test(merge_signal_cleans_up),
      cmocka_unit_test(write_errors_say_why),
      cmocka_unit_test(merge_campaign_refusals),
      cmocka_unit_test(concurrent_merges_lose_nothing),
  };
  const char *only = getenv("TEST_FILTER"); /* e.g. TEST_FILTER=merge_* */
  if (only && *only) cmocka_set_test_filter(only);
  return cmocka_run_group_tests(tests, setup, teardown);
}
