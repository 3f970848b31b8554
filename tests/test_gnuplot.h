/* The check every figure test makes of a gnuplot script (include after <cmocka.h>). */
#ifndef HD_TEST_GNUPLOT_H
#define HD_TEST_GNUPLOT_H

#include <stdio.h>
#include <stdlib.h>

/* Runs cmd, a gnuplot call whose stderr goes to errf and whose figure goes to outf, and fails
 * the test (naming `what`) unless gnuplot exits 0, prints nothing (a warning fails too) and
 * writes more than min_bytes. */
static inline void test_gnuplot_ok(const char *cmd, const char *errf, const char *outf,
                                   long min_bytes, const char *what) {
  int rc = system(cmd);
  FILE *f = fopen(errf, "r");
  assert_non_null(f);
  char buf[512] = "";
  size_t got = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  if (rc != 0 || got != 0) fail_msg("%s: rc %d, stderr: %s", what, rc, buf);
  f = fopen(outf, "r");
  assert_non_null(f);
  fseek(f, 0, SEEK_END);
  assert_true(ftell(f) > min_bytes);
  fclose(f);
}

#endif
