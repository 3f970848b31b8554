/* hd_scene_value: the messages of the scene parser ("WHERE: [section] key = value: why") and the
 * parsing of a value by its key's type (hd_scene_set_value; numbers, ranges, words). */
#include "hd_scene_internal.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int hd_scene_sec_of(int si) {
  return si >= N_SEC ? S_SPECIES : si;
}

int hd_scene_is_set(loc l) {
  return l.line > 0 || l.over > 0;
}

int hd_scene_key_set(const ctx *c, int si, int k) {
  return hd_scene_is_set(c->key_at[si][k]);
}

/* Where key k of section si is stored. */
void *hd_scene_field(const ctx *c, int si, int k) {
  char *base = si >= N_SEC ? (char *)&c->sc->named[si - N_SEC] : (char *)c->sc;
  return base + hd_scene_keys[k].off;
}

/* "dimers", or "species NAME" */
void hd_scene_sec_label(const ctx *c, int si, char *buf, size_t n) {
  if (si >= N_SEC)
    snprintf(buf, n, "species %s", c->sc->named[si - N_SEC].name);
  else
    snprintf(buf, n, "%s", si >= 0 ? hd_scene_sec_name[si] : "?");
}

void hd_scene_where(const ctx *c, loc l, char *buf, size_t n) {
  if (l.over)
    snprintf(buf, n, "--set %s", c->over[l.over - 1]);
  else
    snprintf(buf, n, "%s:%ld", c->name, l.line);
}

/* Records a failure: sets c->err and stops the parse.  Returns code. */
__attribute__((format(printf, 3, 4))) int hd_scene_cfail(ctx *c, int code, const char *fmt, ...) {
  char msg[sizeof c->err->msg];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  c->failed = 1;
  c->code = code;
  return hd_error_set(c->err, code, "%s", msg);
}

/* Shortens a value for a message. */
void hd_scene_shorten(const char *v, char *buf, size_t n) {
  size_t len = strlen(v);
  if (len < n) {
    memcpy(buf, v, len + 1);
  } else {
    memcpy(buf, v, n - 4);
    memcpy(buf + n - 4, "...", 4);
  }
}

/* "WHERE: [sec] key = value: why" (key NULL: "WHERE: [sec]: why"; val NULL: "[sec] key: why"). */
__attribute__((format(printf, 7, 8))) int hd_scene_fail(ctx *c, int code, loc l, int si,
                                                        const char *key, const char *val,
                                                        const char *fmt, ...) {
  char at[600], why[400], v[96], what[240], sec[64];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, sizeof why, fmt, ap);
  va_end(ap);
  hd_scene_where(c, l, at, sizeof at);
  hd_scene_sec_label(c, si, sec, sizeof sec);
  if (!key)
    snprintf(what, sizeof what, "[%s]", sec);
  else if (!val)
    snprintf(what, sizeof what, "[%s] %s", sec, key);
  else {
    hd_scene_shorten(val, v, sizeof v);
    snprintf(what, sizeof what, "[%s] %s = %s", sec, key, v);
  }
  return hd_scene_cfail(c, code, "%s: %s: %s", at, what, why);
}

/* A finite number that is the whole of s (no hex, no nan/inf). 1 on success. */
int hd_scene_parse_num(const char *s, double *x) {
  if (!*s || strpbrk(s, "xX")) return 0;
  char *e;
  errno = 0;
  double v = strtod(s, &e);
  if (e == s || *e || !isfinite(v)) return 0;
  *x = v;
  return 1;
}

/* Why s is not a finite number (for messages). */
const char *hd_scene_num_why(const char *s) {
  if (!*s) return "missing value: expected a number";
  char *e;
  double v = strtod(s, &e);
  if (!isfinite(v)) return "must be a finite number";
  /* `alpha = 0.9 # inelastic`: '#' starts a comment only at a line's start (libinih), and a
   * blank then ';' anywhere */
  if (e != s && strchr(e, '#'))
    return "not a number ('#' starts a comment only at the start of a line; after a value, "
           "write ' ; comment')";
  return "not a number";
}

/* The shortest of %.15g, %.16g, %.17g that reads back as exactly x (so the text round-trips
 * bit for bit, and 0.95 stays "0.95" rather than "0.94999999999999996"). */
void hd_scene_shortest(double x, char *buf, size_t n) {
  for (int prec = 15; prec <= 17; prec++) {
    snprintf(buf, n, "%.*g", prec, x);
    if (strtod(buf, NULL) == x) return;
  }
}

/* Whether x is in key k's range. */
static int in_range(const key_def *kd, double x) {
  return (kd->lo_open ? x > kd->lo : x >= kd->lo) && (kd->hi_open ? x < kd->hi : x <= kd->hi);
}

/* The generic "must be ..." of key k's range. */
void hd_scene_range_why(const key_def *kd, char *buf, size_t n) {
  char lo[40], hi[40];
  hd_scene_shortest(kd->lo, lo, sizeof lo);
  hd_scene_shortest(kd->hi, hi, sizeof hi);
  if (kd->hi == INFINITY)
    snprintf(buf, n, "must be %s %s", kd->lo_open ? ">" : ">=", lo);
  else
    snprintf(buf, n, "must be in %c%s, %s%c", kd->lo_open ? '(' : '[', lo, hi,
             kd->hi_open ? ')' : ']');
}

/* A number in key k's range (whole: a whole number too); else an error on key k of si. */
int hd_scene_get_ranged(ctx *c, int si, int k, const char *s, int whole, double *x) {
  const key_def *kd = &hd_scene_keys[k];
  double v;
  char why[120];
  if (!hd_scene_parse_num(s, &v)) return FAIL_AT(c, si, k, "%s", hd_scene_num_why(s));
  if (whole && v != floor(v)) return FAIL_AT(c, si, k, "must be a whole number");
  if (!in_range(kd, v)) {
    hd_scene_range_why(kd, why, sizeof why);
    return FAIL_AT(c, si, k, "%s", kd->why ? kd->why : why);
  }
  *x = v;
  return HD_OK;
}

/* Splits s at blanks into at most max tokens copied to tok (each < 64 chars). Returns the count,
 * or -1 if there are more than max or one is too long. */
int hd_scene_split(const char *s, char tok[][64], int max) {
  int n = 0;
  while (*s) {
    while (*s == ' ' || *s == '\t') s++;
    if (!*s) break;
    size_t len = strcspn(s, " \t");
    if (n == max || len >= 64) return -1;
    memcpy(tok[n], s, len);
    tok[n][len] = '\0';
    n++;
    s += len;
  }
  return n;
}

/* Parses the value of key k of section si into the scene. */
int hd_scene_set_value(ctx *c, int si, int k, const char *v) {
  const key_def *kd = &hd_scene_keys[k];
  void *p = hd_scene_field(c, si, k);
  double x;
  int rc = HD_OK;
  switch (kd->type) {
  case KT_CUSTOM:
    return kd->set(c, si, k, v);
  case KT_REAL:
  case KT_WHOLE:
    if ((rc = hd_scene_get_ranged(c, si, k, v, kd->type == KT_WHOLE, &x))) return rc;
    *(double *)p = x;
    break;
  case KT_LONG:
    if ((rc = hd_scene_get_ranged(c, si, k, v, 1, &x))) return rc;
    *(long *)p = (long)x;
    break;
  case KT_U64: {
    char *e;
    if (!*v || *v == '-' || *v == '+' || strpbrk(v, " \t"))
      return FAIL_AT(c, si, k, "expected a whole number >= 0");
    errno = 0;
    unsigned long long u = strtoull(v, &e, 10);
    if (*e || e == v) return FAIL_AT(c, si, k, "expected a whole number >= 0");
    if (errno == ERANGE) return FAIL_AT(c, si, k, "too large (max %llu)", ULLONG_MAX);
    *(unsigned long long *)p = u;
    break;
  }
  case KT_BOOL: {
    static const char *const yes[] = {"1", "true", "yes", "on"}, *const no[] = {"0", "false", "no",
                                                                                "off"};
    int i = 0;
    while (i < 4 && strcmp(v, yes[i]) && strcmp(v, no[i])) i++;
    if (i == 4) return FAIL_AT(c, si, k, "expected 1 or 0 (true/false, yes/no, on/off)");
    *(int *)p = !strcmp(v, yes[i]);
    break;
  }
  case KT_ENUM: {
    int i = 0;
    while (kd->names[i] && strcmp(v, kd->names[i])) i++;
    if (!kd->names[i]) {
      char list[200] = "";
      for (int j = 0; kd->names[j]; j++) {
        const char *sep = !j ? "" : kd->names[j + 1] ? ", " : " or ";
        size_t at = strlen(list);
        snprintf(list + at, sizeof list - at, "%s%s", sep, kd->names[j]);
      }
      return FAIL_AT(c, si, k, "expected %s", list);
    }
    *(int *)p = i;
    break;
  }
  }
  return kd->check ? kd->check(c, si, k) : HD_OK;
}
