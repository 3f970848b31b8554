/* Hardening of the store (issue 24, items 1, 2, 3, 10 and the merge and stdout parts of 12):
 * an output that names its input is refused before anything is written; haff merge builds no
 * SQL from names found in a file; one list of per-run tables serves truncation, merge and
 * deletion; a HAFFCKP2 checkpoint without its trailer is refused; merge's special names,
 * signals and stdout messages.  Drives bin/haff ($HAFF_BIN) where the CLI is the subject. */
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
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "hd_db.h"
#include "hd_merge.h"
#include "hd_opt.h"

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
  assert_int_equal(sh("cp d.db keep.db && ln -sf d.db link.db && ln -f d.db hard.db"), 0);
  static const char *const cmds[] = {"haff-fit d.db -o d.db",
                                     "energy d.db -o d.db",
                                     "export xyz d.db -o d.db",
                                     "export xyz d.db --output link.db",
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

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(output_is_not_input),
      cmocka_unit_test(path_overwrites_rule),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
