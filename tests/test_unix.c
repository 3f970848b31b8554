/* bin/haff as a Unix tool (path in $HAFF_BIN): -V/--version (the version runs.version stores),
 * "-o -" as stdout where the output is a stream and refused for a database, `make install` /
 * `make uninstall` with PREFIX and DESTDIR, the man page made from the help texts (it lists
 * every subcommand of cli/haff.c's dispatcher table), the bash completion, and libhaff.so. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <dlfcn.h>
#include <sqlite3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* sh() sends the command's stdout to dir/out.txt, its stderr to dir/err.txt. */
#define TEST_CLI_SH_FORMAT "cd %s && (%s) >out.txt 2>err.txt"
#include "test_cli_util.h"

static char root[4096]; /* the source tree (the tests run from it) */

/* A file of dir (or an absolute path), malloc'd and NUL-terminated; "" when missing. */
static char *slurp(const char *name) {
  char p[4400];
  if (name[0] == '/')
    snprintf(p, sizeof p, "%s", name);
  else
    snprintf(p, sizeof p, "%s/%s", dir, name);
  FILE *f = fopen(p, "rb");
  if (!f) return strdup("");
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *s = malloc((size_t)n + 1);
  assert_non_null(s);
  size_t k = fread(s, 1, (size_t)n, f);
  s[k] = 0;
  fclose(f);
  return s;
}

/* The names of haff's own commands in the table haff_commands of cli/haff_commands.c, read from
 * the source: each entry starts with {"NAME", and a command of haff (not a program of a group
 * such as mc) has NULL as its group, {"NAME", NULL,.  Returns how many (at most max). */
static int dispatcher_names(char names[][32], int max) {
  char p[4200];
  snprintf(p, sizeof p, "%s/cli/haff_commands.c", root);
  char *src = slurp(p);
  char *t = strstr(src, "haff_commands[] = {");
  assert_non_null(t);
  char *end = strstr(t, "};");
  int n = 0;
  for (char *s = strstr(t, "{\""); s && s < end && n < max; s = strstr(s + 1, "{\"")) {
    size_t k = strcspn(s + 2, "\"");
    assert_true(k < 32);
    if (strncmp(s + 2 + k, "\", NULL,", 7)) continue; /* a program of a group */
    memcpy(names[n], s + 2, k);
    names[n++][k] = 0;
  }
  free(src);
  return n;
}

static int setup(void **state) {
  (void)state;
  if (getenv("HAFF_SANITIZE") && getenv("HAFF_SANITIZE")[0] == '1') {
    haff = NULL; /* these tests drive bin/haff and make, which are not the sanitized build */
    return 0;
  }
  haff = getenv("HAFF_BIN");
  if (!haff) haff = "bin/haff";
  if (!getcwd(root, sizeof root)) return -1;
  if (test_cli_mkdtemp("unix")) return -1;
  write_file("d.ini", "[system]\narea_fraction = 0.1\nseed = 3\n[dimers]\ncount = 40\n"
                      "alpha = 0.9\n[run]\nstop_cpd = 6\n[log]\nsamples_every = 0.5\n"
                      "velocities_at = 2\n");
  return sh("%s run d.ini -o d.db --quiet", haff) ? -1 : 0;
}

static int teardown(void **state) {
  (void)state;
  return haff && dir[0] ? test_cli_rmdir() : 0;
}

/* -V and --version print "haff VERSION", VERSION being what runs.version stores, then the
 * build's provenance as the run stored it: "commit HASH" (runs.git_commit; in a git work tree
 * of the source folder, its HEAD, with " (modified)" when git_dirty is 1), "compiler ..." and
 * "cflags ..." (runs.compiler, runs.cflags).  The run also stores its command line. */
static void version(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("%s -V", haff), 0);
  char *v = slurp("out.txt");
  assert_int_equal(sh("%s --version", haff), 0);
  char *v2 = slurp("out.txt");
  assert_string_equal(v, v2);
  assert_int_equal(sh("sqlite3 d.db \"SELECT 'haff ' || version || char(10) || 'commit ' || "
                      "git_commit || CASE git_dirty WHEN 1 THEN ' (modified)' WHEN 0 THEN '' "
                      "ELSE ' (not a git build)' END || char(10) || 'compiler ' || compiler || "
                      "char(10) || 'cflags ' || cflags FROM runs WHERE id = 1\""),
                   0);
  char *stored = slurp("out.txt");
  assert_string_equal(v, stored);
  /* the commit is the source tree's HEAD when the tree is a git work tree (else 'unknown') */
  char *nl = strchr(v, '\n');
  assert_non_null(nl);
  char commit[64] = "";
  assert_int_equal(sscanf(nl + 1, "commit %63s", commit), 1);
  if (sh("test \"$(git -C %s rev-parse --show-toplevel 2>/dev/null)\" = %s && "
         "git -C %s rev-parse HEAD",
         root, root, root) == 0) {
    char *head = slurp("out.txt");
    head[strcspn(head, "\n")] = 0;
    assert_string_equal(commit, head);
    free(head);
  } else {
    assert_string_equal(commit, "unknown");
  }
  assert_int_equal(sh("sqlite3 d.db \"SELECT command FROM runs WHERE id = 1\""), 0);
  char *cmd = slurp("out.txt"), want[4200];
  snprintf(want, sizeof want, "%s run d.ini -o d.db --quiet\n", haff);
  assert_string_equal(cmd, want);
  free(cmd);
  free(v);
  free(v2);
  free(stored);
}

/* -o - writes a stream to stdout: exactly what no -o writes, and no file named "-". */
static void dash_is_stdout(void **state) {
  (void)state;
  if (!haff) skip();
  static const char *const cmds[] = {
      "export xyz d.db",      "energy d.db --run 1",   "angles d.db --run 1 --block 20",
      "veldist d.db --run 1", "haff-fit d.db --run 1",
  };
  for (size_t k = 0; k < sizeof cmds / sizeof cmds[0]; k++) {
    int rc = sh("%s %s > plain.txt", haff, cmds[k]);
    assert_int_equal(sh("%s %s -o -", haff, cmds[k]), rc);
    char *a = slurp("plain.txt"), *b = slurp("out.txt");
    if (strcmp(a, b) || !a[0]) fail_msg("haff %s -o -: not its stdout", cmds[k]);
    free(a);
    free(b);
    assert_false(exists("-"));
  }
  /* mc eps --dump -: the samples on stdout (one number a line), the summary on stderr */
  assert_int_equal(sh("%s mc eps --gamma 0.8 --beta 1 --samples 50 --dump -", haff), 0);
  char *o = slurp("out.txt"), *e = slurp("err.txt");
  int lines = 0;
  for (char *p = o; *p; p++) lines += *p == '\n';
  assert_int_equal(lines, 50);
  assert_non_null(strstr(e, "eps_mean"));
  assert_null(strstr(o, "eps_mean"));
  free(o);
  free(e);
  assert_false(exists("-"));
}

/* haff run -o -: a database cannot be a stream; exit 2 with a clear line, nothing written. */
static void run_refuses_dash(void **state) {
  (void)state;
  if (!haff) skip();
  assert_int_equal(sh("%s run d.ini -o - --quiet", haff), 2);
  char *e = slurp("err.txt");
  assert_non_null(strstr(e, "haff run: -o -: a database cannot be written to stdout"));
  free(e);
  assert_false(exists("-"));
  assert_false(exists("-.lock"));
  /* nor is the table of mc eps --tabulate */
  assert_int_equal(
      sh("%s mc eps --tabulate --gamma 0.8 --nbeta 2 --nu 3 --samples 10 --db -", haff), 2);
  e = slurp("err.txt");
  assert_non_null(strstr(e, "haff mc eps: --db -: a database cannot be written to stdout"));
  free(e);
  assert_false(exists("-"));
}

/* make install PREFIX DESTDIR puts bin/haff, haff.1, the completion and the documentation
 * (PREFIX/share/doc/haff, which the man page names) under DESTDIR/PREFIX, and the Python module
 * in PREFIX/lib/python3.X/dist-packages/haff; the man page has a section for every subcommand
 * of the dispatcher table (and of `haff mc`); the completion offers them, a subcommand's own
 * options, export's formats and, after --set, the scene keys; make uninstall removes it all. */
static void install_man_completion(void **state) {
  (void)state;
  if (!haff) skip();
  /* MAKEFLAGS of the make that runs the tests would hand this make its jobserver */
  const char *mk = "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make --no-print-directory -C";
  assert_int_equal(sh("%s %s install PREFIX=/opt/h DESTDIR=%s/stage", mk, root, dir), 0);
  assert_true(exists("stage/opt/h/bin/haff"));
  assert_true(exists("stage/opt/h/share/man/man1/haff.1"));
  assert_true(exists("stage/opt/h/share/bash-completion/completions/haff"));
  /* the documentation, in the source tree's layout, and the man page points there */
#define DOC "stage/opt/h/share/doc/haff/"
  static const char *const docs[] = {DOC "README.md",          DOC "docs/sql.md",
                                     DOC "docs/scene-keys.md", DOC "db/README.md",
                                     DOC "db/schema.sql",      DOC "db/queries/views.sql"};
  for (size_t k = 0; k < sizeof docs / sizeof *docs; k++)
    if (!exists(docs[k])) fail_msg("make install did not install %s", docs[k]);
  assert_int_equal(sh("stage/opt/h/bin/haff -V"), 0);
  /* the Python module, where /usr/bin/python3 finds it under that prefix (issue 28) */
  assert_int_equal(sh("cd stage/opt/h/lib/python3.*/dist-packages && /usr/bin/python3 -c "
                      "'import haff; assert haff.__file__.startswith(\"'$PWD'\")'"),
                   0);
  char names[64][32];
  int n = dispatcher_names(names, 64);
  assert_true(n >= 17);
  char *man = slurp("stage/opt/h/share/man/man1/haff.1");
  for (int i = 0; i < n; i++) {
    char want[64];
    snprintf(want, sizeof want, "\n.SS haff %.32s\n", names[i]);
    if (!strstr(man, want)) fail_msg("the man page has no section for '%s'", names[i]);
  }
  assert_non_null(strstr(man, "\n.SS haff mc fmean\n"));
  assert_non_null(strstr(man, "\n.SS haff mc eps\n"));
  assert_non_null(strstr(man, ".TH HAFF 1"));
  assert_non_null(strstr(man, "\n.I /opt/h/share/doc/haff\n"));
  assert_null(strstr(man, "source tree"));
  free(man);
  /* troff formats it without a warning (an unescaped "." or "\\" of a help text would give one) */
  assert_int_equal(sh("groff -man -ww -z -Tutf8 stage/opt/h/share/man/man1/haff.1"), 0);
  char *w = slurp("err.txt");
  assert_string_equal(w, "");
  free(w);
  /* completion: COMPREPLY for "haff <TAB>", "haff run --<TAB>", "haff mc <TAB>" */
  static const char comp[] =
      "source stage/opt/h/share/bash-completion/completions/haff; "
      "c() { COMP_WORDS=(\"$@\"); COMP_CWORD=$(($# - 1)); _haff; echo \"${COMPREPLY[*]}\"; }; "
      "c stage/opt/h/bin/haff ''; c stage/opt/h/bin/haff run --; c stage/opt/h/bin/haff mc ''; "
      "c stage/opt/h/bin/haff mc fmean --sc; c stage/opt/h/bin/haff sweep --s; "
      "c stage/opt/h/bin/haff export ''; c stage/opt/h/bin/haff run --set di; "
      "c stage/opt/h/bin/haff run sp.ini --set species.tr; "
      "c stage/opt/h/bin/haff run sp.ini --set species.rod3.alpha_";
  write_file("comp.sh", comp);
  write_file("sp.ini", "[species tri]\ncount = 3\nshape = triangle\n[species rod3]\ncount = 2\n"
                       "shape = linear 3\n");
  assert_int_equal(sh("bash comp.sh"), 0);
  char *out = slurp("out.txt");
  char *l2 = strchr(out, '\n');
  assert_non_null(l2);
  *l2++ = 0;
  for (int i = 0; i < n; i++) {
    char want[40], line[4096];
    snprintf(want, sizeof want, " %.32s ", names[i]);
    snprintf(line, sizeof line, " %.4000s ", out);
    if (!strstr(line, want)) fail_msg("completion of 'haff ' lacks '%s': %s", names[i], out);
  }
  char *l3 = strchr(l2, '\n');
  assert_non_null(l3);
  *l3++ = 0;
  assert_non_null(strstr(l2, "--set"));
  assert_non_null(strstr(l2, "--seed"));
  assert_non_null(strstr(l2, "--quiet"));
  char *l4 = strchr(l3, '\n');
  assert_non_null(l4);
  *l4++ = 0;
  assert_string_equal(l3, "fmean eps rate"); /* haff mc rate (issue 25) */
  char *l5 = strchr(l4, '\n');
  assert_non_null(l5);
  *l5++ = 0;
  assert_string_equal(l4, "--scan");
  /* sweep's options are its own (not --set, which its help names in the prose); export's
   * formats; --set: the scene keys of haff run --list-keys, a species' with the scene's names */
  char *l6 = strchr(l5, '\n'), *l7, *l8, *l9, *l10;
  assert_non_null(l6);
  *l6++ = 0;
  assert_string_equal(l5, "--sbatch --slurm --status");
  assert_non_null(l7 = strchr(l6, '\n'));
  *l7++ = 0;
  assert_string_equal(l6, "xyz gsd");
  assert_non_null(l8 = strchr(l7, '\n'));
  *l8++ = 0;
  assert_string_equal(l7, "dimers.count= dimers.d= dimers.a= dimers.m= dimers.alpha= "
                          "dimers.beta= dimers.q= disks.count= disks.sigma= disks.mass= "
                          "disks.alpha= disks.alpha_dimer= disks.beta= disks.beta_dimer= disks.q=");
  assert_non_null(l9 = strchr(l8, '\n'));
  *l9++ = 0;
  assert_string_equal(l8, "species.tri.count= species.tri.alpha= species.tri.shape= "
                          "species.tri.d= species.tri.m= species.tri.disks= "
                          "species.tri.alpha_rod3= species.tri.alpha_dimers= "
                          "species.tri.alpha_disks= species.tri.beta= species.tri.q= "
                          "species.tri.beta_rod3= species.tri.beta_dimers= "
                          "species.tri.beta_disks=");
  assert_non_null(l10 = strchr(l9, '\n'));
  *l10 = 0;
  assert_string_equal(l9, "species.rod3.alpha_tri= species.rod3.alpha_dimers= "
                          "species.rod3.alpha_disks=");
  free(out);
  assert_int_equal(sh("%s %s uninstall PREFIX=/opt/h DESTDIR=%s/stage", mk, root, dir), 0);
  assert_false(exists("stage/opt/h/bin/haff"));
  assert_false(exists("stage/opt/h/share/man/man1/haff.1"));
  assert_false(exists("stage/opt/h/share/bash-completion/completions/haff"));
  assert_int_equal(sh("test ! -e stage/opt/h/lib/python3.*/dist-packages/haff"), 0);
  assert_false(exists("stage/opt/h/share/doc/haff"));
}

/* tests/run-tests ends with "N passed, N failed" as its last line (CI parses it) and says on
 * the line before how many tests were skipped and why: those of the sanitizer build as one
 * count, those of the normal build by name with the reason each printed ("# skipped: ...").
 * The programs here are stand-ins that print what cmocka prints. */
static void run_tests_counts_skips(void **state) {
  (void)state;
  if (!haff) skip();
  write_file("a.sh", "#!/bin/sh\necho '[ RUN      ] plot'\necho '# skipped: no gnuplot'\n"
                     "echo '[  SKIPPED ] plot'\necho '[==========] 3 test(s) run.'\n"
                     "echo '[  PASSED  ] 2 test(s).'\necho '[  SKIPPED ] 1 test(s), listed "
                     "below:'\necho '[  SKIPPED ] plot'\n");
  write_file("b.sh", "#!/bin/sh\necho '[  PASSED  ] 4 test(s).'\n");
  write_file("c.sh", "#!/bin/sh\necho '[  PASSED  ] 1 test(s).'\necho '[  SKIPPED ] 3 "
                     "test(s), listed below:'\n");
  assert_int_equal(sh("chmod +x a.sh b.sh c.sh && %s/tests/run-tests ./a.sh ./b.sh -- ./c.sh "
                      "| tail -2",
                      root),
                   0);
  char *out = slurp("out.txt");
  assert_string_equal(out, "4 skipped: 3 in the sanitizer build (the tests that drive bin/haff, "
                           "which is not built with the sanitizers, and long physics tests; the "
                           "normal build runs them), 1 in the normal build (a.sh plot: no "
                           "gnuplot)\n7 passed, 0 failed\n");
  free(out);
  /* nothing skipped: the closing line alone */
  assert_int_equal(sh("%s/tests/run-tests ./b.sh | tail -2", root), 0);
  out = slurp("out.txt");
  assert_string_equal(out, "\n4 passed, 0 failed\n");
  free(out);
}

/* Docs that were wrong (issue 28): README's database paragraph said half of it twice; README
 * named ../shared/DESIGN.md as if it were in the repository; docs/scene-keys.md said the engine
 * refuses [species] sections, which it runs (tests/test_cluster.c). */
static void docs_say_what_is(void **state) {
  (void)state;
  if (!haff) skip();
  char p[4200];
  snprintf(p, sizeof p, "%s/README.md", root);
  char *readme = slurp(p);
  const char *once = "a killed process leaves whole batches only";
  char *first = strstr(readme, once);
  assert_non_null(first);
  assert_null(strstr(first + 1, once));
  assert_null(strstr(readme, "a run that can be resumed; a done or collapsed run's is deleted, "
                             "~150 bytes per body), `frames`"));
  for (char *q = strstr(readme, "DESIGN.md"); q; q = strstr(q + 1, "DESIGN.md"))
    if (q >= readme + 10 && !strncmp(q - 10, "../shared/", 10))
      fail_msg("README.md names ../shared/DESIGN.md, which is not in the repository");
  free(readme);
  snprintf(p, sizeof p, "%s/docs/scene-keys.md", root);
  char *keys = slurp(p);
  assert_null(strstr(keys, "not supported by this"));
  assert_null(strstr(keys, "refuses a scene with `[species]` sections"));
  free(keys);
}

/* The Makefile's package groups (BUILD_PKGS, DEMO_PKGS, PLOTS_PKGS, TEST_PKGS): building bin/haff
 * checks only the build's packages, make demo those and the demo's, a test program all of them
 * (a user without root and without a test-only package can still build); make -n prints the
 * checks with the package names, given here as names no package has.  And README.md names every
 * package `make deps` installs, in backquotes. */
static void deps_groups(void **state) {
  (void)state;
  if (!haff) skip();
  const char *mk = "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make --no-print-directory -n -C";
  const char *bogus = "BUILD_PKGS='libgsl-dev haff-bogus-build' DEMO_PKGS=haff-bogus-demo "
                      "PLOTS_PKGS=haff-bogus-plots TEST_PKGS=haff-bogus-test";
  static const char *const names[] = {"haff-bogus-build", "haff-bogus-demo", "haff-bogus-plots",
                                      "haff-bogus-test"};
  /* target, how many groups of names[] (in order) its checks name */
  static const struct {
    const char *target;
    int groups;
  } want[] = {{"bin/haff", 1}, {"all", 1}, {"demo", 2}, {"%s/b/tests/test_smoke", 4}};
  for (size_t k = 0; k < sizeof want / sizeof *want; k++) {
    char target[512];
    snprintf(target, sizeof target, want[k].target, dir);
    assert_int_equal(sh("%s %s BUILD=%s/b %s %s", mk, root, dir, bogus, target), 0);
    char *out = slurp("out.txt");
    for (int g = 0; g < 4; g++)
      if ((strstr(out, names[g]) != NULL) != (g < want[k].groups))
        fail_msg("make -n %s: the package check %s %s", want[k].target,
                 g < want[k].groups ? "lacks" : "names", names[g]);
    free(out);
  }
  /* make deps installs DEPS_PKGS, every group: its check's "for p in LIST; do" */
  assert_int_equal(sh("%s %s BUILD=%s/b deps", mk, root, dir), 0);
  char *out = slurp("out.txt");
  char *list = strstr(out, "for p in ");
  assert_non_null(list);
  list += strlen("for p in ");
  char *end = strstr(list, "; do");
  assert_non_null(end);
  *end = 0;
  char p[4200];
  snprintf(p, sizeof p, "%s/README.md", root);
  char *readme = slurp(p);
  int n = 0;
  for (char *w = strtok(list, " "); w; w = strtok(NULL, " "), n++) {
    char quoted[128];
    snprintf(quoted, sizeof quoted, "`%s`", w);
    if (!strstr(readme, quoted))
      fail_msg("README.md does not name %s, which make deps installs", w);
  }
  assert_true(n >= 19);
  free(readme);
  free(out);
}

/* build/libhaff.so is built with `make` and loads, with the library's functions in it. */
static void shared_library(void **state) {
  (void)state;
  if (!haff) skip();
  char p[4200];
  snprintf(p, sizeof p, "%s/build/libhaff.so", root);
  void *h = dlopen(p, RTLD_NOW | RTLD_LOCAL);
  if (!h) fail_msg("dlopen %s: %s", p, dlerror());
  assert_non_null(dlsym(h, "hd_db_open"));
  assert_non_null(dlsym(h, "hd_scene_load_string"));
  dlclose(h);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(version),          cmocka_unit_test(dash_is_stdout),
      cmocka_unit_test(run_refuses_dash), cmocka_unit_test(install_man_completion),
      cmocka_unit_test(shared_library),   cmocka_unit_test(run_tests_counts_skips),
      cmocka_unit_test(docs_say_what_is), cmocka_unit_test(deps_groups),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
