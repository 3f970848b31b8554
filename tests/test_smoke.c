/* Smoke test of the error helpers and the test harness itself. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <string.h>

#include "hd_error.h"

static void error_set_and_exit_codes(void **state) {
  (void)state;
  hd_error e;
  hd_error_clear(&e);
  assert_int_equal(e.code, HD_OK);
  assert_int_equal(hd_error_set(&e, HD_EINPUT, "x.ini:%d: bad", 3), HD_EINPUT);
  assert_string_equal(e.msg, "x.ini:3: bad");
  assert_int_equal(hd_exit_code(HD_OK), 0);
  assert_int_equal(hd_exit_code(HD_EINPUT), 2);
  assert_int_equal(hd_exit_code(HD_EIO), 1);
  assert_int_equal(hd_exit_code(HD_ECOLLAPSE), 1);
}

int main(void) {
  const struct CMUnitTest tests[] = {cmocka_unit_test(error_set_and_exit_codes)};
  return cmocka_run_group_tests(tests, NULL, NULL);
}
