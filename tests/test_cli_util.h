/* Helpers shared by the tests that drive bin/haff from a shell: a temporary folder dir where
 * the commands run, the path of the haff binary, and small file helpers on dir.  Each test
 * program includes this once (all of it is static). */
#ifndef HD_TEST_CLI_UTIL_H
#define HD_TEST_CLI_UTIL_H

#include <sqlite3.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

/* How sh() runs a command: a printf format taking dir then the command.  The default sends
 * stderr to dir/err.txt; a test program defines its own before including this header. */
#ifndef TEST_CLI_SH_FORMAT
#define TEST_CLI_SH_FORMAT "cd %s && %s 2>err.txt"
#endif

/* The temporary folder of the test program (made by test_cli_mkdtemp), where sh() runs. */
static char dir[256];
/* The haff binary (HAFF_BIN, else bin/haff); NULL in the sanitized build, where the tests
 * that drive it skip.  Set by each program's setup. */
static __attribute__((unused)) const char *haff;

/* Runs a shell command (printf-style) in dir as TEST_CLI_SH_FORMAT says; returns its exit
 * status, -1 when it did not exit normally. */
static inline __attribute__((format(printf, 1, 2))) int sh(const char *fmt, ...) {
  char cmd[8192];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(cmd, sizeof cmd, fmt, ap);
  va_end(ap);
  char full[8800];
  snprintf(full, sizeof full, TEST_CLI_SH_FORMAT, dir, cmd);
  int st = system(full);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* The contents of dir/name in buf (at most n - 1 bytes, NUL-terminated; "" when missing). */
static inline void read_file(const char *name, char *buf, size_t n) {
  char p[400];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  FILE *f = fopen(p, "r");
  size_t k = f ? fread(buf, 1, n - 1, f) : 0;
  buf[k] = 0;
  if (f) fclose(f);
}

/* Writes text to dir/name (replacing it); fails the test when the file cannot be opened. */
static inline void write_file(const char *name, const char *text) {
  char p[400];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  FILE *f = fopen(p, "w");
  assert_non_null(f);
  fputs(text, f);
  fclose(f);
}

/* Whether dir/name exists. */
static inline int exists(const char *name) {
  char p[400];
  snprintf(p, sizeof p, "%s/%s", dir, name);
  return access(p, F_OK) == 0;
}

/* Makes dir a new folder /tmp/haff-NAME-XXXXXX; 0, or -1 when it cannot. */
static inline int test_cli_mkdtemp(const char *name) {
  char tmpl[200];
  snprintf(tmpl, sizeof tmpl, "/tmp/haff-%s-XXXXXX", name);
  if (!mkdtemp(tmpl)) return -1;
  snprintf(dir, sizeof dir, "%s", tmpl);
  return 0;
}

/* Sets haff for the tests that drive it: HAFF_BIN, else bin/haff; NULL in the sanitized build
 * (HAFF_SANITIZE=1), which bin/haff is not.  Returns whether haff is set (the setup goes on). */
static inline int test_cli_find_haff(void) {
  const char *san = getenv("HAFF_SANITIZE");
  if (san && san[0] == '1') {
    haff = NULL;
    return 0;
  }
  haff = getenv("HAFF_BIN");
  if (!haff) haff = "bin/haff";
  return 1;
}

/* Opens database db in dir (*h, with dir/ref.db ATTACHed as ref) and prepares sql on it; fails
 * the test when sql does not compile.  The caller steps the statement, finalizes it and closes
 * *h. */
static inline sqlite3_stmt *test_cli_query(const char *db, const char *sql, sqlite3 **h) {
  char p[300];
  snprintf(p, sizeof p, "%s/%s", dir, db);
  assert_int_equal(sqlite3_open(p, h), SQLITE_OK);
  char att[400];
  snprintf(att, sizeof att, "ATTACH '%s/ref.db' AS ref", dir);
  sqlite3_exec(*h, att, 0, 0, 0);
  sqlite3_stmt *st;
  if (sqlite3_prepare_v2(*h, sql, -1, &st, 0) != SQLITE_OK)
    fail_msg("%s: %s", sql, sqlite3_errmsg(*h));
  return st;
}

/* Removes dir and all it holds; 0, or -1 when rm fails. */
static inline int test_cli_rmdir(void) {
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
  return system(cmd) == 0 ? 0 : -1;
}

/* The setup of a program whose tests all drive bin/haff: haff (test_cli_find_haff) and dir, a
 * new folder /tmp/haff-NAME-XXXXXX; in the sanitized build neither (haff NULL: the tests skip).
 * 0, or -1 when dir cannot be made. */
static inline int test_cli_setup(const char *name) {
  return test_cli_find_haff() ? test_cli_mkdtemp(name) : 0;
}

/* Its teardown: removes dir (when the setup made it). */
static inline int test_cli_teardown(void) {
  return haff && dir[0] ? test_cli_rmdir() : 0;
}

#endif
