/* The Python module python/haff (issue 28), tested by python/tests/test_haff.py with Debian's
 * /usr/bin/python3 and unittest: each TestCase there is one test here (its output is shown when
 * it fails).  TestStudy: a study made with haff.run and merged, read back against docs/sql.md's
 * SQL (<f>, D_e, K) and `haff export xyz` (every disk of every frame, exactly), sample_species,
 * negative frame indices, bad run ids and labels; TestRunResume: a run interrupted by SIGINT and
 * resumed with haff.resume (the id of the run resumed; --all; nothing to resume), haff.run's id
 * with another writer and for a collapse; TestErrors: bad files, a missing haff, bad scenes.
 * These drive bin/haff (HAFF_BIN), so they skip in the sanitized build. */
#include <limits.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* sh() sends the command's stdout and stderr to dir/out.txt. */
#define TEST_CLI_SH_FORMAT "cd %s && (%s) >out.txt 2>&1"
#include "test_cli_util.h"

static char root[PATH_MAX]; /* the source tree (the tests run from it) */
static char exe[PATH_MAX];  /* haff's absolute path */

/* The last lines of dir/out.txt. */
static const char *out(void) {
  static char buf[16384];
  char p[300];
  snprintf(p, sizeof p, "%s/out.txt", dir);
  FILE *f = fopen(p, "r");
  buf[0] = 0;
  if (!f) return buf;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, n > (long)sizeof buf - 1 ? n - (long)sizeof buf + 1 : 0, SEEK_SET);
  size_t k = fread(buf, 1, sizeof buf - 1, f);
  buf[k] = 0;
  fclose(f);
  return buf;
}

/* Runs TestCase `name` of python/tests/test_haff.py; fails with its output. */
static void unittest_case(const char *name) {
  if (!haff) skip();
  if (sh("HAFF_BIN='%s' /usr/bin/python3 -W error::ResourceWarning '%s/python/tests/test_haff.py' "
         "-v %s",
         exe, root, name))
    fail_msg("python/tests/test_haff.py %s:\n%s", name, out());
}

static void study(void **state) {
  (void)state;
  unittest_case("TestStudy");
}

static void run_resume(void **state) {
  (void)state;
  unittest_case("TestRunResume");
}

static void errors(void **state) {
  (void)state;
  unittest_case("TestErrors");
}

static int setup(void **state) {
  (void)state;
  assert_non_null(getcwd(root, sizeof root));
  if (test_cli_setup("python")) return -1; /* these tests drive bin/haff, not sanitized */
  if (haff) assert_non_null(realpath(haff, exe));
  return 0;
}

static int teardown(void **state) {
  (void)state;
  return test_cli_teardown();
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(study),
      cmocka_unit_test(run_resume),
      cmocka_unit_test(errors),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
