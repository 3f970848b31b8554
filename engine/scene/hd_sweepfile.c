/* hd_sweepfile: see hd_sweepfile.h for the contract.
 *
 * Hand-written rather than libinih's: the file is read whole and parsed as len bytes, so that
 * a NUL byte is seen and named (libinih's line reader ends a line there and reads on), every
 * message has its line, and a value may be quoted ("linear 3"), which libinih does not know.
 * The syntax is the scene files' own (sections, KEY = VALUE, ; and # comments). */
#include "hd_sweepfile.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

void hd_sweepfile_free(hd_sweepfile *s) {
  if (!s) return;
  for (int k = 0; k < s->nax; k++) {
    for (int j = 0; j < s->ax[k].n; j++) free(s->ax[k].v[j]);
    free(s->ax[k].v);
    free(s->ax[k].key);
  }
  for (int j = 0; j < s->seeds.n; j++) free(s->seeds.v[j]);
  free(s->seeds.v);
  free(s->seeds.key);
  for (int k = 0; k < s->npoints; k++) free(s->points[k]);
  free(s->points);
  free(s->pt_line);
  free(s->scene);
  memset(s, 0, sizeof *s);
}

static char *trim(char *p) {
  while (isspace((unsigned char)*p)) p++;
  char *e = p + strlen(p);
  while (e > p && isspace((unsigned char)e[-1])) *--e = '\0';
  return p;
}

/* "name:LINE: [sec] key: why" into err; returns HD_EINPUT (HD_ENOMEM when why says so). */
static int bad(hd_error *err, const char *name, long line, const char *sec, const char *key,
               const char *fmt, ...) __attribute__((format(printf, 6, 7)));
static int bad(hd_error *err, const char *name, long line, const char *sec, const char *key,
               const char *fmt, ...) {
  char why[768];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(why, sizeof why, fmt, ap);
  va_end(ap);
  return hd_error_set(err, strcmp(why, "out of memory") ? HD_EINPUT : HD_ENOMEM,
                      "%s:%ld: [%.64s]%s%.128s: %s", name, line, sec, key ? " " : "",
                      key ? key : "", why);
}

int hd_sweep_split(const char *text, char **buf, const char **words, int max) {
  size_t n = strlen(text);
  *buf = malloc(n + 1);
  if (!*buf) return -1;
  char *o = *buf;
  int count = 0;
  const char *p = text;
  for (;;) {
    while (*p == ' ' || *p == '\t') p++;
    if (!*p) break;
    if (count == max) break;
    words[count++] = o;
    int q = 0;
    for (; *p && (q || (*p != ' ' && *p != '\t')); p++) {
      if (*p == '"')
        q = !q;
      else
        *o++ = *p;
    }
    *o++ = '\0';
    if (q) {
      free(*buf);
      *buf = NULL;
      return -1;
    }
  }
  return count;
}

int hd_sweep_format_set(char *out, size_t size, const char *key, const char *value) {
  int blank = strpbrk(value, " \t") != NULL || !*value;
  return snprintf(out, size, "%s=%s%s%s", key, blank ? "\"" : "", value, blank ? "\"" : "");
}

/* Appends the copy of v to a->v; 0 or -1 (out of memory). */
static int push(hd_sweep_axis *a, int *cap, const char *v) {
  if (a->n == *cap) {
    int c = *cap ? 2 * *cap : 8;
    char **p = realloc(a->v, (size_t)c * sizeof *p);
    if (!p) return -1;
    a->v = p;
    *cap = c;
  }
  char *d = strdup(v);
  if (!d) return -1;
  a->v[a->n++] = d;
  return 0;
}

/* A range of integers FROM:TO:STEP (the seeds: every value exact, up to 2^64 - 1). */
static int int_range(hd_sweep_axis *a, const char *val, const char *name, const char *sec,
                     hd_error *err) {
  unsigned long long v[3];
  const char *p = val;
  for (int k = 0; k < 3; k++) {
    char *end;
    while (*p == ' ' || *p == '\t') p++;
    if (!isdigit((unsigned char)*p))
      return bad(err, name, a->line, sec, a->key,
                 "'%s': not a range FROM:TO:STEP of non-negative integers", val);
    errno = 0;
    v[k] = strtoull(p, &end, 10);
    if (errno == ERANGE)
      return bad(err, name, a->line, sec, a->key, "'%s': a seed above %llu", val, ULLONG_MAX);
    while (*end == ' ' || *end == '\t') end++;
    if (k < 2 ? *end != ':' : *end != '\0')
      return bad(err, name, a->line, sec, a->key,
                 "'%s': not a range FROM:TO:STEP of non-negative integers", val);
    p = end + 1;
  }
  if (v[2] == 0 || v[1] < v[0])
    return bad(err, name, a->line, sec, a->key, "'%s': a range needs FROM <= TO and STEP > 0", val);
  unsigned long long n = (v[1] - v[0]) / v[2] + 1;
  if (n > HD_SWEEP_MAX_VALUES)
    return bad(err, name, a->line, sec, a->key, "'%s': more than %d values", val,
               HD_SWEEP_MAX_VALUES);
  int cap = 0;
  for (unsigned long long k = 0; k < n; k++) {
    char buf[32];
    snprintf(buf, sizeof buf, "%llu", v[0] + k * v[2]);
    if (push(a, &cap, buf)) return bad(err, name, a->line, sec, a->key, "out of memory");
  }
  return HD_OK;
}

/* A range of reals FROM:TO:STEP; integers (|v| < 2^53) written exactly, others to 12 digits. */
static int real_range(hd_sweep_axis *a, const char *val, const char *name, const char *sec,
                      hd_error *err) {
  double v[3];
  const char *p = val;
  for (int k = 0; k < 3; k++) {
    char *end;
    errno = 0;
    v[k] = strtod(p, &end);
    while (*end == ' ' || *end == '\t') end++;
    if (end == p || errno || !isfinite(v[k]) || (k < 2 ? *end != ':' : *end != '\0'))
      return bad(err, name, a->line, sec, a->key, "'%s': not a range FROM:TO:STEP", val);
    p = end + 1;
  }
  if (!(v[2] > 0) || v[1] < v[0])
    return bad(err, name, a->line, sec, a->key, "'%s': a range needs FROM <= TO and STEP > 0", val);
  double n = floor((v[1] - v[0]) / v[2] + 1e-9) + 1;
  if (!(n <= HD_SWEEP_MAX_VALUES))
    return bad(err, name, a->line, sec, a->key, "'%s': more than %d values", val,
               HD_SWEEP_MAX_VALUES);
  int cap = 0;
  for (int k = 0; k < (int)n; k++) {
    char buf[64];
    double x = v[0] + k * v[2];
    if (x == floor(x) && fabs(x) < 9007199254740992.0)
      snprintf(buf, sizeof buf, "%.0f", x);
    else
      snprintf(buf, sizeof buf, "%.12g", x);
    if (push(a, &cap, buf)) return bad(err, name, a->line, sec, a->key, "out of memory");
  }
  return HD_OK;
}

/* qsort's order of two strings given by pointer. */
static int cmp_str(const void *x, const void *y) {
  return strcmp(*(const char *const *)x, *(const char *const *)y);
}

/* Parses a LIST (values, or FROM:TO:STEP) into a->v; seeds: integers. */
static int parse_list(hd_sweep_axis *a, const char *sec, char *val, int seeds, const char *name,
                      hd_error *err) {
  if (strchr(val, ':') && !strchr(val, '"'))
    return seeds ? int_range(a, val, name, sec, err) : real_range(a, val, name, sec, err);
  const char *w[64];
  char *buf = NULL;
  int cap = 0, rc = HD_OK;
  const char *p = val;
  /* word by word (a line may hold far more values than fit in w at once) */
  while (!rc && *p) {
    while (*p == ' ' || *p == '\t') p++;
    if (!*p) break;
    const char *q = p;
    int quoted = 0;
    for (; *q && (quoted || (*q != ' ' && *q != '\t')); q++)
      if (*q == '"') quoted = !quoted;
    char *one = strndup(p, (size_t)(q - p));
    if (!one) return bad(err, name, a->line, sec, a->key, "out of memory");
    int n = hd_sweep_split(one, &buf, w, 1);
    if (n != 1)
      rc = bad(err, name, a->line, sec, a->key, "%s: an unclosed quote", one);
    else if (!w[0][0])
      rc = bad(err, name, a->line, sec, a->key, "an empty value (\"\")");
    else if (a->n >= HD_SWEEP_MAX_VALUES)
      rc = bad(err, name, a->line, sec, a->key, "more than %d values", HD_SWEEP_MAX_VALUES);
    else if (push(a, &cap, w[0]))
      rc = bad(err, name, a->line, sec, a->key, "out of memory");
    free(buf);
    buf = NULL;
    free(one);
    p = q;
  }
  if (rc) return rc;
  if (a->n == 0) return bad(err, name, a->line, sec, a->key, "no values");
  for (int k = 0; k < a->n; k++) {
    if (seeds) {
      const char *v = a->v[k];
      char *end;
      errno = 0;
      (void)strtoull(v, &end, 10);
      if (strspn(v, "0123456789") != strlen(v))
        return bad(err, name, a->line, sec, a->key, "'%s': not a non-negative integer seed", v);
      if (errno == ERANGE)
        return bad(err, name, a->line, sec, a->key, "'%s': a seed above %llu", v, ULLONG_MAX);
    }
  }
  /* none twice: sorted copies side by side (a range may give HD_SWEEP_MAX_VALUES values; the
   * pairwise check took minutes there, found by make fuzz) */
  if (a->n < 2) return HD_OK;
  const char **c = malloc((size_t)a->n * sizeof *c);
  if (!c) return bad(err, name, a->line, sec, a->key, "out of memory");
  for (int k = 0; k < a->n; k++) c[k] = a->v[k];
  qsort(c, (size_t)a->n, sizeof *c, cmp_str);
  for (int k = 1; k < a->n; k++)
    if (!strcmp(c[k - 1], c[k])) {
      rc = bad(err, name, a->line, sec, a->key, "value '%s' given twice", c[k]);
      break;
    }
  free(c);
  return rc;
}

/* One line (NUL-terminated copy, no \n) of the file: its section *sec updated. */
static int one_line(hd_sweepfile *s, char *buf, long line, char *sec, size_t secsize,
                    const char *name, hd_error *err) {
  for (const char *c = buf; *c; c++)
    if (((unsigned char)*c < 0x20 && *c != '\t' && *c != '\r') || *c == 0x7f)
      return bad(err, name, line, sec, NULL, "a control character (byte 0x%02x): not a text line",
                 (unsigned)(unsigned char)*c);
  char *p = trim(buf);
  if (!*p || *p == ';' || *p == '#') return HD_OK;
  if (*p == '[') {
    char *close = strchr(p, ']');
    if (!close || *trim(close + 1)) return bad(err, name, line, p, NULL, "not a [section] line");
    *close = '\0';
    snprintf(sec, secsize, "%s", trim(p + 1));
    if (strcmp(sec, "sweep") && strcmp(sec, "axes") && strcmp(sec, "points"))
      return bad(err, name, line, sec, NULL, "unknown section (sweep, axes, points)");
    return HD_OK;
  }
  char *eq = strchr(p, '=');
  if (!eq) return bad(err, name, line, sec, NULL, "'%s': not KEY = VALUE", p);
  *eq = '\0';
  char *key = trim(p), *val = eq + 1;
  int q = 0; /* an inline comment: ; or # after a blank, outside quotes */
  for (char *c = val; *c; c++) {
    if (*c == '"') q = !q;
    if (!q && (*c == ';' || *c == '#') && c > val && isspace((unsigned char)c[-1])) {
      *c = '\0';
      break;
    }
  }
  val = trim(val);
  if (!sec[0]) return bad(err, name, line, "", key, "a key before any [section]");
  if (!strcmp(sec, "sweep")) {
    if (!strcmp(key, "scene")) {
      if (s->scene_line)
        return bad(err, name, line, sec, key, "duplicate key (first set at line %ld)",
                   s->scene_line);
      s->scene_line = line;
      if (!val[0]) return bad(err, name, line, sec, key, "no file named");
      s->scene = strdup(val);
      return s->scene ? HD_OK : bad(err, name, line, sec, key, "out of memory");
    }
    if (!strcmp(key, "seeds")) {
      if (s->seeds.line)
        return bad(err, name, line, sec, key, "duplicate key (first set at line %ld)",
                   s->seeds.line);
      s->seeds.line = line;
      s->seeds.key = strdup("seeds");
      if (!s->seeds.key) return bad(err, name, line, sec, key, "out of memory");
      return parse_list(&s->seeds, sec, val, 1, name, err);
    }
    return bad(err, name, line, sec, key, "unknown key (scene, seeds)");
  }
  if (!strcmp(sec, "axes")) {
    if (s->nax == HD_SWEEP_MAX_AXES)
      return bad(err, name, line, sec, key, "more than %d axes", HD_SWEEP_MAX_AXES);
    if (!strchr(key, '.') || strpbrk(key, " \t\"="))
      return bad(err, name, line, sec, key, "an axis is SECTION.KEY of the scene");
    for (int k = 0; k < s->nax; k++)
      if (!strcmp(s->ax[k].key, key))
        return bad(err, name, line, sec, key, "duplicate axis (first at line %ld)", s->ax[k].line);
    if (!strcmp(key, "system.seed"))
      return bad(err, name, line, sec, key, "seeds are [sweep] seeds");
    hd_sweep_axis *a = &s->ax[s->nax];
    a->key = strdup(key);
    if (!a->key) return bad(err, name, line, sec, key, "out of memory");
    s->nax++;
    a->line = line;
    return parse_list(a, sec, val, 0, name, err);
  }
  /* points */
  if (strcmp(key, "point")) return bad(err, name, line, sec, key, "unknown key (point)");
  if (!val[0]) return bad(err, name, line, sec, key, "no overrides");
  char **p2 = realloc(s->points, (size_t)(s->npoints + 1) * sizeof *p2);
  if (p2) s->points = p2;
  long *l2 = p2 ? realloc(s->pt_line, (size_t)(s->npoints + 1) * sizeof *l2) : NULL;
  if (l2) s->pt_line = l2;
  char *copy = l2 ? strdup(val) : NULL;
  if (!copy) return bad(err, name, line, sec, key, "out of memory");
  s->points[s->npoints] = copy;
  s->pt_line[s->npoints++] = line;
  int quotes = 0; /* hd_sweep_split's quotes toggle: balanced when even */
  for (const char *c = val; *c; c++) quotes += *c == '"';
  if (quotes % 2) return bad(err, name, line, sec, key, "an unclosed quote");
  return HD_OK;
}

int hd_sweepfile_parse(hd_sweepfile *s, const char *text, size_t len, const char *name,
                       hd_error *err) {
  memset(s, 0, sizeof *s);
  if (!name) name = "sweep";
  size_t at = 0;
  if (len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3)) at = 3; /* a UTF-8 byte order mark */
  char sec[64] = "";
  long line = 0;
  int rc = HD_OK;
  char *buf = NULL;
  size_t cap = 0;
  while (!rc && at < len) {
    line++;
    const char *nl = memchr(text + at, '\n', len - at);
    size_t n = nl ? (size_t)(nl - (text + at)) : len - at;
    if (memchr(text + at, '\0', n)) {
      rc = bad(err, name, line, sec, NULL, "a NUL byte: not a text file");
      break;
    }
    if (n + 1 > cap) {
      char *b = realloc(buf, n + 1);
      if (!b) {
        rc = bad(err, name, line, sec, NULL, "out of memory");
        break;
      }
      buf = b;
      cap = n + 1;
    }
    memcpy(buf, text + at, n);
    buf[n] = '\0';
    rc = one_line(s, buf, line, sec, sizeof sec, name, err);
    at += n + (nl ? 1 : 0);
  }
  free(buf);
  if (!rc && !s->scene_line) rc = bad(err, name, line, "sweep", "scene", "missing: the base scene");
  if (!rc && s->nax && s->npoints)
    rc = bad(err, name, s->pt_line[0], "points", "point",
             "a sweep has [axes] or [points], not both");
  if (rc) hd_sweepfile_free(s);
  return rc;
}

int hd_sweepfile_read(hd_sweepfile *s, const char *path, hd_error *err) {
  memset(s, 0, sizeof *s);
  struct stat sb;
  if (stat(path, &sb) != 0) return hd_error_set(err, HD_EINPUT, "%s: %s", path, strerror(errno));
  if (S_ISDIR(sb.st_mode))
    return hd_error_set(err, HD_EINPUT, "%s: a directory, not a sweep file", path);
  FILE *f = fopen(path, "rb");
  if (!f) return hd_error_set(err, HD_EINPUT, "%s: %s", path, strerror(errno));
  size_t cap = 65536, len = 0;
  char *text = malloc(cap);
  int rc = text ? HD_OK : hd_error_set(err, HD_ENOMEM, "%s: out of memory", path);
  while (!rc) {
    if (len == cap) {
      if ((long)cap >= HD_SWEEP_MAX_BYTES) {
        rc = hd_error_set(err, HD_EINPUT, "%s: larger than %ld bytes: not a sweep file", path,
                          (long)HD_SWEEP_MAX_BYTES);
        break;
      }
      char *t = realloc(text, 2 * cap);
      if (!t) {
        rc = hd_error_set(err, HD_ENOMEM, "%s: out of memory", path);
        break;
      }
      text = t;
      cap *= 2;
    }
    size_t got = fread(text + len, 1, cap - len, f);
    len += got;
    if (got == 0) {
      if (ferror(f)) rc = hd_error_set(err, HD_EINPUT, "%s: %s", path, strerror(errno));
      break;
    }
  }
  fclose(f);
  if (!rc) rc = hd_sweepfile_parse(s, text, len, path, err);
  free(text);
  return rc;
}
