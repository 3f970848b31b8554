/* Parameters as data (schema version 1): the views params and run_summary on databases made by
 * bin/haff (path in $HAFF_BIN), the upgrade of an older file, the query plans of db/queries/
 * with a run given (no SCAN of collisions or samples), and every question of docs/sql.md run
 * by the sqlite3 shell and by pandas (tests/sql_doc.py, Debian's /usr/bin/python3). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <ctype.h>
#include <glob.h>
#include <math.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "hd_db.h"

/* sh() sends the command's stdout and stderr to dir/out.txt. */
#define TEST_CLI_SH_FORMAT "cd %s && (%s) >out.txt 2>&1"
#include "test_cli_util.h"

static char root[4096]; /* the source tree (the tests run from it) */

/* The contents of a file (malloc'd, NUL-terminated), or NULL. */
static char *slurp(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *s = malloc((size_t)n + 1);
  size_t k = s ? fread(s, 1, (size_t)n, f) : 0;
  if (s) s[k] = 0;
  fclose(f);
  return s;
}

static sqlite3 *open_db(const char *name) {
  char p[300];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  sqlite3 *h;
  assert_int_equal(sqlite3_open(p, &h), SQLITE_OK);
  return h;
}

/* The first column of the first row of sql as a double (NAN when NULL or no row), its text into
 * txt (when given) and its type into type. */
static double qv(sqlite3 *h, const char *sql, char *txt, size_t n, int *type) {
  sqlite3_stmt *st;
  if (sqlite3_prepare_v2(h, sql, -1, &st, 0) != SQLITE_OK)
    fail_msg("%s: %s", sql, sqlite3_errmsg(h));
  double v = NAN;
  int t = SQLITE_NULL;
  if (txt) txt[0] = 0;
  if (sqlite3_step(st) == SQLITE_ROW) {
    t = sqlite3_column_type(st, 0);
    if (t != SQLITE_NULL) v = sqlite3_column_double(st, 0);
    if (txt && t != SQLITE_NULL) snprintf(txt, n, "%s", (const char *)sqlite3_column_text(st, 0));
  }
  if (type) *type = t;
  sqlite3_finalize(st);
  return v;
}

static double qd(sqlite3 *h, const char *sql) {
  return qv(h, sql, NULL, 0, NULL);
}

static const char base_ini[] =
    "[system]\narea_fraction = 0.1\nseed = 1\n[dimers]\ncount = 50\n"
    "[run]\nstop_cpd = 10\n[log]\ncollisions = all\nsamples_every = 0.5\n";
static const char mix_ini[] =
    "[system]\nbox = 20 15\nseed = 4\n[dimers]\ncount = 10\na = 0.5\nalpha = 0.9\n"
    "[disks]\ncount = 10\nsigma = 0.8\nalpha = 0.85\n[walls]\nsides = left right\n"
    "[run]\nstop_cpd = 3\n[log]\ncollisions = every 3\nsamples_every = 0.5\n";

/* The study of docs/sql.md and tests/sql_doc.py: runs 1-8 dimers (alpha x a x seed), 9 disks,
 * 10 a mixture. */
static int setup(void **state) {
  (void)state;
  if (!test_cli_find_haff()) return 0; /* these tests drive bin/haff, not sanitized */
  if (!getcwd(root, sizeof root)) return -1;
  if (test_cli_mkdtemp("sql")) return -1;
  write_file("base.ini", base_ini);
  write_file("mix.ini", mix_ini);
  const char *alphas[] = {"0.8", "0.95"}, *as[] = {"0.5", "1"};
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++)
      for (int s = 1; s <= 2; s++)
        if (sh("%s run base.ini -o study.db --quiet --set dimers.alpha=%s --set dimers.a=%s "
               "--seed %d",
               haff, alphas[i], as[j], s))
          return -1;
  if (sh("%s run base.ini -o study.db --quiet --set dimers.count=0 --set disks.count=60 "
         "--set disks.alpha=0.9",
         haff) ||
      sh("%s run mix.ini -o study.db --quiet", haff))
    return -1;
  return 0;
}

static int teardown(void **state) {
  (void)state;
  return haff && dir[0] ? test_cli_rmdir() : 0;
}

/* params: one row per key of runs.scene, in its section, with num a REAL or NULL for text. */
static void params_view(void **state) {
  (void)state;
  if (!haff) skip();
  sqlite3 *h = open_db("study.db");
  char t[200];
  int type;
  assert_int_equal((int)qd(h, "PRAGMA user_version"), HD_DB_SCHEMA_VERSION);
  /* the same key in three sections, three values */
  assert_true(qd(h, "SELECT num FROM params WHERE run = 10 AND section = 'dimers' AND key = "
                    "'alpha'") == 0.9);
  assert_true(qd(h, "SELECT num FROM params WHERE run = 10 AND section = 'disks' AND key = "
                    "'alpha'") == 0.85);
  assert_true(qd(h, "SELECT num FROM params WHERE run = 10 AND section = 'walls' AND key = "
                    "'alpha'") == 1);
  qv(h, "SELECT num FROM params WHERE run = 10 AND key = 'count' AND section = 'disks'", t,
     sizeof t, &type);
  assert_int_equal(type, SQLITE_FLOAT); /* REAL, so that num / num never divides integers */
  /* text values: kept as text, num NULL */
  qv(h, "SELECT value FROM params WHERE run = 10 AND section = 'walls' AND key = 'sides'", t,
     sizeof t, NULL);
  assert_string_equal(t, "left right");
  qv(h, "SELECT num FROM params WHERE run = 10 AND section = 'log' AND key = 'collisions'", t,
     sizeof t, &type);
  assert_int_equal(type, SQLITE_NULL);
  qv(h, "SELECT value FROM params WHERE run = 10 AND section = 'log' AND key = 'collisions'", t,
     sizeof t, NULL);
  assert_string_equal(t, "every 3");
  /* every "key = value" line of every run's scene is a row, and no other (comments are not) */
  sqlite3_stmt *st;
  assert_int_equal(sqlite3_prepare_v2(h, "SELECT id, scene FROM runs", -1, &st, 0), SQLITE_OK);
  int runs = 0;
  while (sqlite3_step(st) == SQLITE_ROW) {
    const char *s = (const char *)sqlite3_column_text(st, 1);
    long lines = 0;
    for (const char *p = s; *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : p + strlen(p))
      if (*p != '[' && *p != ';' && *p != '\n' && strchr(p, '=') &&
          (!strchr(p, '\n') || strchr(p, '=') < strchr(p, '\n')))
        lines++;
    char sql[100];
    snprintf(sql, sizeof sql, "SELECT count(*) FROM params WHERE run = %lld",
             (long long)sqlite3_column_int64(st, 0));
    assert_int_equal((long)qd(h, sql), lines);
    runs++;
  }
  sqlite3_finalize(st);
  assert_int_equal(runs, 10);
  sqlite3_close(h);
}

/* run_summary's area fraction: a box given is converted as the scene converts area_fraction to
 * a box (dimers with a < d, whose area is two disks less their lens). */
static void run_summary_area_fraction(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("af.ini", "[system]\narea_fraction = 0.23\nseed = 2\n[dimers]\ncount = 30\n"
                       "a = 0.6\n[disks]\ncount = 5\nsigma = 0.7\n[run]\nstop_events = 50\n"
                       "[log]\ncollisions = none\n");
  assert_int_equal(sh("%s run af.ini -o af.db --quiet", haff), 0);
  sqlite3 *h = open_db("af.db");
  double lx = qd(h, "SELECT box_x FROM runs WHERE id = 1");
  double ly = qd(h, "SELECT box_y FROM runs WHERE id = 1");
  sqlite3_close(h);
  char ini[400];
  snprintf(ini, sizeof ini,
           "[system]\nbox = %.17g %.17g\nseed = 2\n[dimers]\ncount = 30\na = 0.6\n[disks]\n"
           "count = 5\nsigma = 0.7\n[run]\nstop_events = 50\n[log]\ncollisions = none\n",
           lx, ly);
  write_file("box.ini", ini);
  assert_int_equal(sh("%s run box.ini -o af.db --quiet", haff), 0);
  h = open_db("af.db");
  assert_true(qd(h, "SELECT area_fraction FROM run_summary WHERE run = 1") == 0.23);
  double eta = qd(h, "SELECT area_fraction FROM run_summary WHERE run = 2");
  assert_true(fabs(eta - 0.23) < 1e-12);
  char t[100];
  qv(h, "SELECT species || ' ' || n || ' ' || a_over_d FROM run_summary WHERE run = 2", t, sizeof t,
     NULL);
  assert_string_equal(t, "mixture 35 0.6");
  sqlite3_close(h);
}

/* run_summary's area fraction of one species in a box given: the bodies' area over the box's,
 * for dimers alone (a = 1: two touching disks, pi d^2 / 2 each) and disks alone (pi sigma^2 / 4
 * each).  Before: NULL, the absent section's NULL d, a or sigma times its count 0.  Then a file
 * whose run_summary is an earlier build's (here a stand-in view of one column) gets the view of
 * db/schema.sql again when haff opens it for writing; before, IF NOT EXISTS kept the old one. */
static void run_summary_box_one_species(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("b1.ini", "[system]\nbox = 60 50\nseed = 3\n[dimers]\ncount = 100\na = 1\nd = 1\n"
                       "[run]\nstop_events = 20\n[log]\ncollisions = none\n");
  assert_int_equal(sh("%s run b1.ini -o b1.db --quiet", haff), 0);
  assert_int_equal(sh("%s run b1.ini -o b1.db --quiet --set dimers.count=0 --set disks.count=80 "
                      "--set disks.sigma=1.5 --set disks.alpha=0.9",
                      haff),
                   0);
  sqlite3 *h = open_db("b1.db");
  double pi = acos(-1.0);
  int type;
  double eta = qv(h, "SELECT area_fraction FROM run_summary WHERE run = 1", NULL, 0, &type);
  assert_int_equal(type, SQLITE_FLOAT);
  assert_true(fabs(eta - 100 * pi / 2 / 3000) < 1e-12); /* rounding of the view's sum */
  eta = qv(h, "SELECT area_fraction FROM run_summary WHERE run = 2", NULL, 0, &type);
  assert_int_equal(type, SQLITE_FLOAT);
  assert_true(fabs(eta - 80 * pi * 2.25 / 4 / 3000) < 1e-12);
  /* an earlier build's view, in a file of this schema version */
  assert_int_equal(sqlite3_exec(h,
                                "DROP VIEW run_summary; CREATE VIEW run_summary AS SELECT id AS "
                                "run, NULL AS area_fraction FROM runs",
                                0, 0, 0),
                   SQLITE_OK);
  sqlite3_close(h);
  assert_int_equal(sh("%s run b1.ini -o b1.db --quiet --seed 9", haff), 0);
  h = open_db("b1.db");
  assert_int_equal((int)qd(h, "PRAGMA user_version"), HD_DB_SCHEMA_VERSION);
  eta = qv(h, "SELECT area_fraction FROM run_summary WHERE run = 3", NULL, 0, &type);
  assert_int_equal(type, SQLITE_FLOAT);
  assert_true(fabs(eta - 100 * pi / 2 / 3000) < 1e-12);
  assert_true(qd(h, "SELECT alpha FROM run_summary WHERE run = 2") == 0.9); /* all columns */
  sqlite3_close(h);
}

/* run_summary and run_species for named species (issue 28): scenes/shapes-mixture.ini (200
 * dimers, 200 triangles, 200 asymmetric dimers, restitutions 0.95, 0.9, 0.95 and 0.92 for
 * tri-dimers) and a triangle + linear trimer scene.  run_summary's species is the label of
 * haff haff-fit (read from its output), n every body, alpha NULL when the pairs differ and the
 * common value when they agree; run_species has one row per species with its own alpha, count
 * and shape.  (Before: species '' or 'dimers', n 0 or 200, alpha NULL or the dimers'.) */
static void run_summary_named_species(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("%s run %s/scenes/shapes-mixture.ini -o shapes.db --quiet --set "
                      "run.stop_cpd=1.5",
                      haff, root),
                   0);
  write_file("tt.ini", "[system]\narea_fraction = 0.1\nseed = 5\n[species tri]\ncount = 30\n"
                       "shape = triangle\nalpha = 0.9\n[species rod3]\ncount = 20\n"
                       "shape = linear 3\nalpha = 0.8\nalpha_tri = 0.85\n[run]\nstop_cpd = 1\n"
                       "[log]\nsamples_every = 0.5\n");
  assert_int_equal(sh("%s run tt.ini -o shapes.db --quiet", haff), 0);
  /* the same pair of species, every restitution 0.9: alpha is that value */
  assert_int_equal(sh("%s run tt.ini -o shapes.db --quiet --set species.rod3.alpha=0.9 --set "
                      "species.rod3.alpha_tri=0.9",
                      haff),
                   0);
  assert_int_equal(sh("%s haff-fit shapes.db > fit.tsv 2>/dev/null; test -s fit.tsv", haff), 0);
  char p[300];
  snprintf(p, sizeof p, "%s/fit.tsv", dir);
  char *fit = slurp(p);
  assert_non_null(fit);
  sqlite3 *h = open_db("shapes.db");
  static const char *const want[3] = {"shapes:dimers+tri+asym 600 200 NULL",
                                      "shapes:tri+rod3 50 NULL NULL",
                                      "shapes:tri+rod3 50 NULL 0.9"};
  for (int run = 1; run <= 3; run++) {
    char sql[300], t[200], label[100];
    snprintf(sql, sizeof sql,
             "SELECT species || ' ' || n || ' ' || coalesce(n_dimers, 'NULL') || ' ' || "
             "coalesce(alpha, 'NULL') FROM run_summary WHERE run = %d",
             run);
    qv(h, sql, t, sizeof t, NULL);
    assert_string_equal(t, want[run - 1]);
    /* haff-fit's label of the run: its row "run<TAB>species<TAB>..." */
    char key[16];
    snprintf(key, sizeof key, "\n%d\t", run);
    const char *row = strstr(fit, key);
    if (!row) fail_msg("haff-fit printed no row for run %d:\n%s", run, fit);
    assert_int_equal(sscanf(row + strlen(key), "%99[^\t]", label), 1);
    snprintf(sql, sizeof sql, "SELECT species FROM run_summary WHERE run = %d", run);
    qv(h, sql, t, sizeof t, NULL);
    assert_string_equal(t, label);
  }
  char t[1000];
  qv(h,
     "SELECT group_concat(species || ':' || n || ':' || alpha || ':' || coalesce(shape, '-'), ' ') "
     "FROM (SELECT * FROM run_species WHERE run = 1 ORDER BY idx)",
     t, sizeof t, NULL);
  assert_string_equal(t, "dimers:200:0.95:dimer 1 tri:200:0.9:triangle 1 asym:200:0.95:-");
  qv(h,
     "SELECT group_concat(idx || ':' || species || ':' || n || ':' || alpha || ':' || shape || "
     "':' || mass, ' ') FROM (SELECT * FROM run_species WHERE run = 2 ORDER BY idx)",
     t, sizeof t, NULL);
  assert_string_equal(t, "2:tri:30:0.9:triangle 1:3.0 3:rod3:20:0.8:linear 3 1:3.0");
  /* every body is in one species row */
  assert_true(qd(h, "SELECT count(*) FROM run_summary r WHERE n <> (SELECT sum(n) FROM "
                    "run_species s WHERE s.run = r.run)") == 0);
  sqlite3_close(h);
  free(fit);
}

/* A file of schema version 0 (before the views) stays readable as it is, and gets the views,
 * made anew, the first time haff opens it for writing; a stale view of the same name is
 * replaced. */
static void schema_upgrade(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("cp study.db old.db"), 0);
  sqlite3 *h = open_db("old.db");
  assert_int_equal(sqlite3_exec(h,
                                "DROP VIEW params; DROP VIEW run_summary; "
                                "CREATE VIEW params AS SELECT 1 AS stale; PRAGMA user_version = 0",
                                0, 0, 0),
                   SQLITE_OK);
  sqlite3_close(h);
  /* read as before: an export and an analysis */
  assert_int_equal(sh("%s export xyz old.db --run 3 -o old.xyz", haff), 0);
  assert_int_equal(sh("%s energy old.db --run 3 -o old.tsv", haff), 0);
  h = open_db("old.db");
  assert_int_equal((int)qd(h, "PRAGMA user_version"), 0); /* readers leave it as it is */
  sqlite3_close(h);
  assert_int_equal(sh("%s run mix.ini -o old.db --quiet --seed 1234", haff), 0);
  h = open_db("old.db");
  assert_int_equal((int)qd(h, "PRAGMA user_version"), HD_DB_SCHEMA_VERSION);
  assert_int_equal((int)qd(h, "SELECT count(*) FROM run_summary"), 11);
  assert_true(qd(h, "SELECT alpha FROM run_summary WHERE run = 5") == 0.95);
  assert_true(qd(h, "SELECT num FROM params WHERE run = 11 AND section = 'disks' AND key = "
                    "'sigma'") == 0.8);
  sqlite3_close(h);
}

/* Whether an EXPLAIN QUERY PLAN detail line scans collisions or samples: "SCAN collisions",
 * "SCAN samples" (a file before schema version 5), "SCAN sample_rows" (the table of the view
 * samples) or "SCAN x" for an alias x given to them in sql ("collisions AS x"). */
static int scans_big_table(const char *detail, const char *sql) {
  const char *p = strstr(detail, "SCAN ");
  if (!p) return 0;
  p += 5;
  size_t n = strcspn(p, " ");
  if ((n == 10 && !strncmp(p, "collisions", 10)) || (n == 7 && !strncmp(p, "samples", 7)) ||
      (n == 11 && !strncmp(p, "sample_rows", 11))) /* the table of the view samples */
    return 1;
  static const char *const tabs[] = {"collisions AS ", "samples AS "};
  for (int k = 0; k < 2; k++)
    for (const char *s = strstr(sql, tabs[k]); s; s = strstr(s + 1, tabs[k])) {
      const char *a = s + strlen(tabs[k]);
      size_t m = 0;
      while (isalnum((unsigned char)a[m]) || a[m] == '_') m++;
      if (m == n && !strncmp(a, p, n)) return 1;
    }
  return 0;
}

/* The plan of sql on h with @run = 1 (and other parameters unset): fails on a scan of
 * collisions or samples. Returns the number of plan lines. */
static int check_plan(sqlite3 *h, const char *name, const char *sql) {
  size_t n = strlen(sql);
  char *e = malloc(n + 32);
  assert_non_null(e);
  snprintf(e, n + 32, "EXPLAIN QUERY PLAN %s", sql);
  sqlite3_stmt *st;
  if (sqlite3_prepare_v2(h, e, -1, &st, 0) != SQLITE_OK)
    fail_msg("%s: %s", name, sqlite3_errmsg(h));
  int i = sqlite3_bind_parameter_index(st, "@run");
  if (i > 0) sqlite3_bind_int(st, i, 1);
  int lines = 0;
  while (sqlite3_step(st) == SQLITE_ROW) {
    const char *d = (const char *)sqlite3_column_text(st, 3);
    if (scans_big_table(d, sql)) fail_msg("%s with a run given: %s (a full scan)", name, d);
    lines++;
  }
  sqlite3_finalize(st);
  free(e);
  return lines;
}

/* Every query of db/queries/ searches the indexes when @run is given, and so does a select of
 * one run from every view (views.sql's, params, run_summary). */
static void queries_use_indexes(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("cp study.db plans.db"), 0);
  sqlite3 *h = open_db("plans.db");
  char pat[4200];
  snprintf(pat, sizeof pat, "%s/db/queries/*.sql", root);
  glob_t g;
  assert_int_equal(glob(pat, 0, NULL, &g), 0);
  int files = 0;
  for (size_t k = 0; k < g.gl_pathc; k++) {
    char *sql = slurp(g.gl_pathv[k]);
    assert_non_null(sql);
    if (strstr(g.gl_pathv[k], "/views.sql")) { /* statements that make views: checked below */
      char *err = NULL;
      if (sqlite3_exec(h, sql, 0, 0, &err) != SQLITE_OK) fail_msg("views.sql: %s", err);
    } else {
      assert_true(check_plan(h, g.gl_pathv[k], sql) > 0);
      files++;
    }
    free(sql);
  }
  globfree(&g);
  assert_true(files >= 5);
  sqlite3_stmt *st;
  assert_int_equal(
      sqlite3_prepare_v2(h, "SELECT name FROM sqlite_master WHERE type = 'view'", -1, &st, 0),
      SQLITE_OK);
  int views = 0;
  while (sqlite3_step(st) == SQLITE_ROW) {
    const char *v = (const char *)sqlite3_column_text(st, 0);
    char sql[300], probe[300];
    snprintf(probe, sizeof probe, "SELECT run FROM %s LIMIT 0", v);
    int has_run = sqlite3_exec(h, probe, 0, 0, 0) == SQLITE_OK;
    snprintf(sql, sizeof sql, "SELECT * FROM %s WHERE %s = @run", v, has_run ? "run" : "id");
    check_plan(h, v, sql);
    views++;
  }
  sqlite3_finalize(st);
  assert_true(views >= 6); /* v_dimer_collisions, v_wall_collisions, v_energy, v_runs, ... */
  sqlite3_close(h);
}

/* docs/sql.md: ten questions, each in SQL (run by the sqlite3 shell) and in pandas; they agree
 * and their answers are right for the study (tests/sql_doc.py). */
static void sql_doc_questions(void **state) {
  (void)state;
  if (!haff) skip();
  int rc = sh("/usr/bin/python3 %s/tests/sql_doc.py study.db %s/docs/sql.md", root, root);
  if (rc) {
    char p[300];
    snprintf(p, sizeof p, "%s/out.txt", dir);
    char *out = slurp(p);
    fail_msg("tests/sql_doc.py: exit %d:\n%s", rc, out ? out : "");
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(params_view),
      cmocka_unit_test(run_summary_area_fraction),
      cmocka_unit_test(run_summary_box_one_species),
      cmocka_unit_test(run_summary_named_species),
      cmocka_unit_test(schema_upgrade),
      cmocka_unit_test(queries_use_indexes),
      cmocka_unit_test(sql_doc_questions),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
