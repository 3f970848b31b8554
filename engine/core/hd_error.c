#include "hd_error.h"

#include <getopt.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Length of the UTF-8 sequence at s that encodes a printable character (not a C1 control,
 * U+0080..U+009F), or 0 when s does not start a valid one. */
static size_t utf8_printable(const unsigned char *s) {
  size_t n = s[0] >= 0xf0 && s[0] <= 0xf4 ? 4 : s[0] >= 0xe0 ? 3 : s[0] >= 0xc2 ? 2 : 0;
  if (n == 0 || (n == 2 && s[0] == 0xc2 && s[1] < 0xa0)) return 0;
  for (size_t k = 1; k < n; k++)
    if ((s[k] & 0xc0) != 0x80) return 0;
  if (n == 3 && ((s[0] == 0xe0 && s[1] < 0xa0) || (s[0] == 0xed && s[1] >= 0xa0))) return 0;
  if (n == 4 && ((s[0] == 0xf0 && s[1] < 0x90) || (s[0] == 0xf4 && s[1] >= 0x90))) return 0;
  return n;
}

void hd_text_escape(const char *in, char *out, size_t n) {
  if (n == 0) return;
  size_t o = 0;
  const unsigned char *s = (const unsigned char *)in;
  while (*s) {
    char esc[8];
    size_t len = 1;
    const char *piece = (const char *)s;
    if (*s == '\n' || *s == '\t' || *s == '\r') {
      snprintf(esc, sizeof esc, "\\%c", *s == '\n' ? 'n' : *s == '\t' ? 't' : 'r');
      piece = esc;
    } else if ((*s < 0x20 || *s >= 0x7f) && (len = utf8_printable(s)) == 0) {
      snprintf(esc, sizeof esc, "\\x%02x", *s);
      piece = esc, len = 1;
    }
    size_t plen = piece == (const char *)s ? len : strlen(piece);
    if (o + plen >= n) break; /* cut at a whole character */
    memcpy(out + o, piece, plen);
    o += plen;
    s += len;
  }
  out[o] = '\0';
}

int hd_error_set(hd_error *err, int code, const char *fmt, ...) {
  if (err) {
    char raw[sizeof err->msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(raw, sizeof raw, fmt, ap);
    va_end(ap);
    hd_text_escape(raw, err->msg, sizeof err->msg);
    err->code = code;
  }
  return code;
}

const char *hd_opt_culprit(char *const *argv, const struct option *opts, char *buf, size_t n) {
  const char *arg = optind > 0 ? argv[optind - 1] : "?";
  if (!strncmp(arg, "--", 2)) {
    if (optopt == 0) return arg; /* an unknown long option */
    size_t len = strcspn(arg + 2, "=");
    for (const struct option *o = opts; o && o->name; o++)
      if (o->val == optopt && !strncmp(o->name, arg + 2, len)) return arg; /* missing value */
  }
  if (optopt > 0x20 && optopt < 0x7f) { /* a short option, alone or inside a cluster */
    snprintf(buf, n, "-%c", optopt);
    return buf;
  }
  return arg;
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
