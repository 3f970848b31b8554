#include "hd_error.h"

#include <stdarg.h>
#include <stdio.h>

int hd_error_set(hd_error *err, int code, const char *fmt, ...) {
  if (err) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    err->code = code;
  }
  return code;
}

void hd_error_clear(hd_error *err) {
  if (err) {
    err->code = HD_OK;
    err->msg[0] = '\0';
  }
}

int hd_exit_code(int status) {
  if (status == HD_OK) return 0;
  return status == HD_EINPUT ? 2 : 1;
}
