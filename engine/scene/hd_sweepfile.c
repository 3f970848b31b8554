/* hd_sweepfile: see hd_sweepfile.h for the contract.
 *
 * The lines are read by libinih (ini_parse_stream, the scene files' reader), with what libinih
 * does not do done around it:
 *   - a NUL byte: libinih's lines are C strings, so a NUL would end a line and the rest be read
 *     on silently; the text is searched for one first, and the line holding it is refused by
 *     name and line (after the lines before it, in file order as every other refusal);
 *   - line numbers and [section] lines: libinih tells its handler neither, so its reader here
 *     hands over one physical line per call, counts them, and checks every line before libinih
 *     sees it (hd_sweepfile.h's syntax; a [section] known and alone on its line);
 *   - quoted values ("linear 3"): libinih's inline comments are turned off for the parse (a ';'
 *     inside quotes is a value), and the handler cuts a comment from libinih's raw value itself,
 *     outside quotes; LISTs and points are split here (hd_sweep_split);
 *   - long lines: an axis may list HD_SWEEP_MAX_VALUES values, so libinih's line buffer is put
 *     on the heap and made as long as the longest line.
 * libinih's settings are process globals (ini_max_line, ...): they are set for one parse and
 * restored after it, so a sweep file and a scene must not be parsed by two threads at once. */
#include "hd_sweepfile.h"

#include <ctype.h>
#include <errno.h>
#include <ini.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
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

/* One KEY = VALUE of section sec at line (key and val trimmed, the comment cut). */
static int one_key(hd_sweepfile *s, const char *sec, const char *key, char *val, long line,
                   const char *name, hd_error *err) {
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

/* One parse: the text, the line being read, its section, the first refusal (parsing stops). */
typedef struct sweep_ctx {
  hd_sweepfile *s;
  const char *p, *end; /* text not yet read; end: the start of the line with a NUL byte, or the
                          end of the text */
  long line;           /* the line read last (1-based) */
  char sec[64];        /* its section ("" before the first) */
  const char *name;
  hd_error *err;
  int rc;
} sweep_ctx;

/* A key = value line (libinih's handler): the value is libinih's raw one (blanks trimmed, no
 * comment removed: libinih's inline comments are off, it does not know quotes), from which a
 * comment is cut here, outside quotes. */
static int on_key(void *user, const char *section, const char *name, const char *value) {
  (void)section; /* c->sec, checked by the reader (libinih truncates long names) */
  sweep_ctx *c = user;
  if (c->rc) return 1;
  hd_sweepfile *s = c->s;
  const char *sec = c->sec, *key = name;
  long line = c->line;
  const char *nm = c->name;
  hd_error *err = c->err;
  char *val = strdup(value);
  if (!val) return c->rc = bad(err, nm, line, sec, key, "out of memory"), 1;
  int q = 0; /* an inline comment: ; or # at the value's start or after a blank, outside quotes */
  for (char *p = val; *p; p++) {
    if (*p == '"') q = !q;
    if (!q && (*p == ';' || *p == '#') && (p == val || isspace((unsigned char)p[-1]))) {
      *p = '\0';
      break;
    }
  }
  c->rc = one_key(s, sec, key, trim(val), line, nm, err);
  free(val);
  return 1;
}

/* fgets-like reader for ini_parse_stream: one physical line per call, counted, checked before
 * libinih sees it: no control character, a [section] line known and alone on its line, any
 * other line blank, a comment or KEY = VALUE with '=' (libinih also takes ':').  Leading blanks
 * are dropped (libinih would take an indented line for a continuation of the previous value).
 * NULL at the end or at the first refusal (in c->rc). */
static char *reader(char *str, int num, void *stream) {
  sweep_ctx *c = stream;
  if (c->rc || c->p >= c->end) return NULL;
  const char *s = c->p;
  const char *nl = memchr(s, '\n', (size_t)(c->end - s));
  size_t n = nl ? (size_t)(nl - s) : (size_t)(c->end - s);
  c->p = nl ? nl + 1 : c->end;
  c->line++;
  for (size_t k = 0; k < n; k++)
    if (((unsigned char)s[k] < 0x20 && s[k] != '\t' && s[k] != '\r') || s[k] == 0x7f) {
      c->rc =
          bad(c->err, c->name, c->line, c->sec, NULL,
              "a control character (byte 0x%02x): not a text line", (unsigned)(unsigned char)s[k]);
      return NULL;
    }
  while (n > 0 && isspace((unsigned char)*s)) s++, n--;
  if (n + 2 > (size_t)num) { /* cannot happen: ini_max_line is set to the longest line */
    c->rc = bad(c->err, c->name, c->line, c->sec, NULL, "line too long");
    return NULL;
  }
  memcpy(str, s, n);
  str[n] = '\n';
  str[n + 1] = '\0';
  char *p = malloc(n + 1);
  if (!p) {
    c->rc = bad(c->err, c->name, c->line, c->sec, NULL, "out of memory");
    return NULL;
  }
  memcpy(p, s, n);
  p[n] = '\0';
  char *t = trim(p);
  if (*t == '[') {
    char *close = strchr(t, ']');
    if (!close || *trim(close + 1))
      c->rc = bad(c->err, c->name, c->line, t, NULL, "not a [section] line");
    else {
      *close = '\0';
      snprintf(c->sec, sizeof c->sec, "%s", trim(t + 1));
      if (strcmp(c->sec, "sweep") && strcmp(c->sec, "axes") && strcmp(c->sec, "points"))
        c->rc =
            bad(c->err, c->name, c->line, c->sec, NULL, "unknown section (sweep, axes, points)");
    }
  } else if (*t && *t != ';' && *t != '#' && *(t + strcspn(t, "=:")) != '=') {
    c->rc = bad(c->err, c->name, c->line, c->sec, NULL, "'%s': not KEY = VALUE", t);
  }
  free(p);
  return c->rc ? NULL : str;
}

int hd_sweepfile_parse(hd_sweepfile *s, const char *text, size_t len, const char *name,
                       hd_error *err) {
  memset(s, 0, sizeof *s);
  if (!name) name = "sweep";
  if (len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3)) text += 3, len -= 3; /* a UTF-8 BOM */
  sweep_ctx c = {.s = s, .p = text, .end = text + len, .name = name, .err = err};
  /* a NUL byte ends libinih's lines without a word: the text is read up to the line that holds
   * the first one, which is refused there (after any refusal of the lines before it) */
  const char *nul = memchr(text, '\0', len);
  long nul_line = 0;
  size_t longest = 0;
  for (const char *p = text; p < text + len;) {
    const char *nl = memchr(p, '\n', (size_t)(text + len - p));
    const char *e = nl ? nl : text + len;
    nul_line++;
    if (nul && nul < e + 1) {
      c.end = p;
      break;
    }
    if ((size_t)(e - p) > longest) longest = (size_t)(e - p);
    p = e + 1;
  }
  /* libinih's settings for this parse (its globals; the scene parser's are restored after):
   * the line buffer on the heap and as long as the longest line, no inline comments (a quoted
   * value may hold ';'), no continuation lines */
  int max_line = ini_max_line, initial = ini_initial_alloc;
  bool stack = ini_use_stack, inline_comments = ini_allow_inline_comments,
       multiline = ini_allow_multiline;
  if (longest > (size_t)HD_SWEEP_MAX_BYTES) longest = (size_t)HD_SWEEP_MAX_BYTES;
  ini_max_line = ini_initial_alloc = (int)longest + 3;
  ini_use_stack = false;
  ini_allow_inline_comments = false;
  ini_allow_multiline = false;
  int r = ini_parse_stream(reader, &c, on_key, &c);
  ini_max_line = max_line, ini_initial_alloc = initial;
  ini_use_stack = stack, ini_allow_inline_comments = inline_comments;
  ini_allow_multiline = multiline;
  int rc = c.rc;
  if (!rc && r < 0)
    rc = bad(err, name, c.line, c.sec, NULL, "out of memory");
  else if (!rc && r > 0) /* the reader let only well-formed lines through */
    rc = bad(err, name, r, c.sec, NULL, "not a sweep file line");
  if (!rc && nul) rc = bad(err, name, nul_line, c.sec, NULL, "a NUL byte: not a text file");
  long line = c.line;
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
