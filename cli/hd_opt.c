/* hd_opt: one option parser for every subcommand, from its table (hd_opt.h). */
#include "hd_opt.h"
#include "hd_path.h"

#include "hd_error.h"

#include <errno.h>
#include <getopt.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

enum { MAX_OPTS = 64, VAL0 = 256 /* getopt_long's val of opts[k]: VAL0 + k */ };

/* How the option is named in messages: "--name", or "-o" for a short-only option. */
static const char *opt_name(const hd_optdef *d, char *buf, size_t n) {
  if (d->flags & HD_OPTF_SHORT)
    snprintf(buf, n, "-%c", d->letter);
  else
    snprintf(buf, n, "--%s", d->name);
  return buf;
}

/* "haff CMD: OPT 'S': expected WHAT" and 2. */
static int expected(const char *cmd, const hd_optdef *d, const char *s, const char *what) {
  char nb[64];
  fprintf(stderr, "haff %s: %s '%s': expected %s\n", cmd, opt_name(d, nb, sizeof nb), s, what);
  return 2;
}

/* What a DOUBLE option accepts, as words: "a number > 0", "a number in [0, 1)". */
static void double_range(const hd_optdef *d, char *buf, size_t n) {
  const char *num = d->flags & HD_OPTF_FINITE ? "a finite number" : "a number";
  int has_lo = d->lo > -INFINITY, has_hi = d->hi < INFINITY;
  if (has_lo && has_hi)
    snprintf(buf, n, "%s in %c%g, %g%c", num, d->flags & HD_OPTF_GT ? '(' : '[', d->lo, d->hi,
             d->flags & HD_OPTF_LT ? ')' : ']');
  else if (has_lo)
    snprintf(buf, n, "%s %s %g", num, d->flags & HD_OPTF_GT ? ">" : ">=", d->lo);
  else if (has_hi)
    snprintf(buf, n, "%s %s %g", num, d->flags & HD_OPTF_LT ? "<" : "<=", d->hi);
  else
    snprintf(buf, n, "%s", num);
}

int hd_opt_number(const char *cmd, const hd_optdef *d, const char *s, double *x, long long *i) {
  char what[128];
  char *end;
  if (d->kind == HD_ARG_INT) {
    if (d->ihi == LLONG_MAX)
      snprintf(what, sizeof what, "a whole number >= %lld", d->ilo);
    else
      snprintf(what, sizeof what, "a whole number in [%lld, %lld]", d->ilo, d->ihi);
    errno = 0;
    long long v = strtoll(s, &end, 10);
    int ok = end != s && !*end && errno == 0;
    if (!ok && (d->flags & HD_OPTF_EXP)) { /* 1e6: whole and exact as a double */
      errno = 0;
      double w = strtod(s, &end);
      ok = end != s && !*end && errno == 0 && w == floor(w) && fabs(w) <= 9007199254740992.0;
      v = ok ? (long long)w : 0;
    }
    if (!ok || v < d->ilo || v > d->ihi) return expected(cmd, d, s, what);
    *i = v;
    return 0;
  }
  double_range(d, what, sizeof what);
  errno = 0;
  double v = strtod(s, &end);
  int ok = end != s && !*end && errno == 0 && !isnan(v);
  if (ok && (d->flags & HD_OPTF_FINITE)) ok = isfinite(v);
  if (ok)
    ok = (d->flags & HD_OPTF_GT ? v > d->lo : v >= d->lo) &&
         (d->flags & HD_OPTF_LT ? v < d->hi : v <= d->hi);
  if (!ok) return expected(cmd, d, s, what);
  *x = v;
  return 0;
}

/* Whether option d applies to spec (a table shared by several subcommands). */
static int applies(const hd_optspec *spec, const hd_optdef *d) {
  return !spec->allowed || !d->set || (spec->allowed & d->set);
}

/* The enum word s of d: its index, or -1. */
static int enum_index(const hd_optdef *d, const char *s) {
  int k = 0;
  size_t len = strlen(s);
  for (const char *p = d->choices; p; k++) {
    const char *bar = strchr(p, '|');
    size_t n = bar ? (size_t)(bar - p) : strlen(p);
    if (n == len && !strncmp(p, s, n)) return k;
    p = bar ? bar + 1 : NULL;
  }
  return -1;
}

/* "a, b or c" from "a|b|c". */
static void enum_words(const hd_optdef *d, char *buf, size_t n) {
  size_t o = 0;
  for (const char *p = d->choices; p && o < n;) {
    const char *bar = strchr(p, '|');
    size_t len = bar ? (size_t)(bar - p) : strlen(p);
    const char *sep = p == d->choices ? "" : bar ? ", " : " or ";
    o += (size_t)snprintf(buf + o, n - o, "%s%.*s", sep, (int)len, p);
    p = bar ? bar + 1 : NULL;
  }
}

/* Stores the value s of option d in dest.  0, or 2 after the message. */
static int store(const hd_optspec *spec, const hd_optdef *d, const char *s, char *dest) {
  char *at = dest + d->off, nb[64], what[256];
  switch (d->kind) {
  case HD_ARG_FLAG: {
    int v = !(d->flags & HD_OPTF_CLEAR);
    memcpy(at, &v, sizeof v);
    return 0;
  }
  case HD_ARG_INT: {
    long long v;
    if (hd_opt_number(spec->cmd, d, s, NULL, &v)) return 2;
    if (d->size == sizeof(int)) {
      int w = (int)v;
      memcpy(at, &w, sizeof w);
    } else {
      memcpy(at, &v, sizeof v);
    }
    return 0;
  }
  case HD_ARG_DOUBLE: {
    double v;
    if (hd_opt_number(spec->cmd, d, s, &v, NULL)) return 2;
    memcpy(at, &v, sizeof v);
    return 0;
  }
  case HD_ARG_PATH:
    if (!*s) return expected(spec->cmd, d, s, "a file name");
    if ((d->flags & HD_OPTF_NOT_STDOUT) && !strcmp(s, "-")) {
      fprintf(stderr, "haff %s: %s -: a database cannot be written to stdout; give a file name\n",
              spec->cmd, opt_name(d, nb, sizeof nb));
      return 2;
    }
    /* fall through */
  case HD_ARG_STRING:
    memcpy(at, &s, sizeof s);
    return 0;
  case HD_ARG_ENUM: {
    int k = enum_index(d, s);
    if (k < 0) {
      enum_words(d, what, sizeof what);
      return expected(spec->cmd, d, s, what);
    }
    memcpy(at, &k, sizeof k);
    return 0;
  }
  case HD_ARG_LIST: {
    hd_optlist *l = (hd_optlist *)(void *)at;
    if (l->n >= l->max) {
      fprintf(stderr, "haff %s: more than %d %s options\n", spec->cmd, l->max,
              opt_name(d, nb, sizeof nb));
      return 2;
    }
    l->v[l->n++] = s;
    return 0;
  }
  }
  return 2;
}

int hd_opt_index(const hd_optspec *spec, const char *name) {
  for (int k = 0; spec->opts[k].name; k++)
    if (!strcmp(spec->opts[k].name, name)) return k;
  return -1;
}

/* getopt_long's tables from spec: lo (the long options, val VAL0 + index, and help) and
 * shorts (":h" and the letters).  Returns the number of options, or -1 after one line when the
 * table has more than MAX_OPTS. */
static int getopt_tables(const hd_optspec *spec, struct option *lo, char *shorts) {
  size_t ns = 0;
  int n = 0, nl = 0;
  shorts[ns++] = ':'; /* first: a missing value is told from an unknown option */
  shorts[ns++] = 'h';
  for (; spec->opts[n].name; n++) {
    const hd_optdef *d = &spec->opts[n];
    int has_arg = d->kind == HD_ARG_FLAG ? no_argument : required_argument;
    if (n == MAX_OPTS) {
      fprintf(stderr, "haff %s: more than %d options in its table\n", spec->cmd, MAX_OPTS);
      return -1;
    }
    if (!(d->flags & HD_OPTF_SHORT)) lo[nl++] = (struct option){d->name, has_arg, NULL, VAL0 + n};
    if (d->letter) {
      shorts[ns++] = d->letter;
      if (has_arg == required_argument) shorts[ns++] = ':';
    }
  }
  shorts[ns] = '\0';
  lo[nl++] = (struct option){"help", no_argument, NULL, 'h'};
  lo[nl] = (struct option){NULL, 0, NULL, 0};
  return n;
}

int hd_opt_parse(const hd_optspec *spec, int argc, char **argv, void *dest, hd_optres *res) {
  struct option lo[MAX_OPTS + 2];
  char shorts[3 * MAX_OPTS + 4];
  memset(res, 0, sizeof *res);
  int n = getopt_tables(spec, lo, shorts);
  if (n < 0) return 2;
  optind = 0; /* full re-initialisation: a subcommand may run more than once per process */
  opterr = 0; /* our one line, not getopt's as well */
  int c;
  char nb[64], buf[8];
  while ((c = getopt_long(argc, argv, shorts, lo, NULL)) != -1) {
    if (c == 'h') {
      hd_opt_help(spec, stdout);
      return -1;
    }
    int k = c >= VAL0 ? c - VAL0 : -1;
    if (c == ':') { /* a value missing: optopt is the option's val or letter */
      k = optopt >= VAL0 ? optopt - VAL0 : -1;
      for (int j = 0; k < 0 && j < n; j++)
        if (spec->opts[j].letter == optopt) k = j;
      fprintf(stderr, "haff %s: option '%s' needs a value (see haff %s --help)\n", spec->cmd,
              k >= 0 ? opt_name(&spec->opts[k], nb, sizeof nb) : "?", spec->cmd);
      return 2;
    }
    for (int j = 0; k < 0 && j < n; j++)
      if (spec->opts[j].letter == c) k = j;
    if (k < 0) { /* '?': unknown, or ambiguous */
      fprintf(stderr, "haff %s: unknown option or missing value '%s' (see haff %s --help)\n",
              spec->cmd, hd_opt_culprit(argv, lo, buf, sizeof buf), spec->cmd);
      return 2;
    }
    const hd_optdef *d = &spec->opts[k];
    /* an output, an input or any file name given twice: which one was meant? (the last one
     * counted: `run -o a.db -o b.db` wrote b.db alone) */
    int once =
        (d->flags & (HD_OPTF_ONCE | HD_OPTF_OUTPUT | HD_OPTF_INPUT)) || d->kind == HD_ARG_PATH;
    if (res->given[k] && once) {
      fprintf(stderr, "haff %s: %s given twice: give one\n", spec->cmd, opt_name(d, nb, sizeof nb));
      return 2;
    }
    if (store(spec, d, optarg, dest)) return 2; /* a bad value is named first */
    if (!applies(spec, d)) {
      fprintf(stderr, "haff %s: option '%s' does not apply here (see --help)\n", spec->cmd,
              opt_name(d, nb, sizeof nb));
      return 2;
    }
    if (res->given[k] < 255) res->given[k]++;
  }
  res->pos = argv + optind;
  res->npos = argc - optind;
  if (res->npos < spec->npos_min || (spec->npos_max >= 0 && res->npos > spec->npos_max)) {
    if (spec->npos_max == 0)
      fprintf(stderr, "haff %s: unexpected argument '%s' (see haff %s --help)\n", spec->cmd,
              res->pos[0], spec->cmd);
    else
      fprintf(stderr, "haff %s: expected %s (see haff %s --help)\n", spec->cmd, spec->pos,
              spec->cmd);
    return 2;
  }
  return hd_opt_check_outputs(spec, res, dest);
}

/* The value of string option d (NULL when not given or "-", stdout). */
static const char *path_value(const hd_optres *res, const hd_optspec *spec, int k,
                              const void *dest) {
  const hd_optdef *d = &spec->opts[k];
  if (!res->given[k] || (d->kind != HD_ARG_STRING && d->kind != HD_ARG_PATH)) return NULL;
  const char *v;
  memcpy(&v, (const char *)dest + d->off, sizeof v);
  return v && strcmp(v, "-") ? v : NULL;
}

int hd_opt_check_outputs(const hd_optspec *spec, const hd_optres *res, const void *dest) {
  enum { MAXF = MAX_OPTS + 64 };
  const char *out[MAXF], *oname[MAXF], *in[MAXF];
  int isdb[MAXF];
  char names[MAX_OPTS][64];
  int no = 0, ni = 0;
  for (int k = 0; spec->opts[k].name && k < MAX_OPTS; k++) {
    const hd_optdef *d = &spec->opts[k];
    const char *v = path_value(res, spec, k, dest);
    if (!v) continue;
    if ((d->flags & HD_OPTF_OUTPUT) && no < MAXF)
      isdb[no] = (d->flags & HD_OPTF_DB) != 0, oname[no] = opt_name(d, names[k], sizeof names[k]),
      out[no++] = v;
    else if ((d->flags & HD_OPTF_INPUT) && ni < MAXF)
      in[ni++] = v;
  }
  for (int j = 0; j < res->npos; j++) {
    if (j == spec->out_pos - 1 && no < MAXF)
      isdb[no] = 1, oname[no] = "the output", out[no++] = res->pos[j];
    else if (j != spec->out_pos - 1 && ni < MAXF)
      in[ni++] = res->pos[j];
  }
  for (int o = 0; o < no; o++) {
    for (int i = 0; i < ni; i++)
      if (hd_path_overwrites(out[o], in[i])) {
        fprintf(stderr,
                "haff %s: %s %s would overwrite the input %s (the same file, or its SQLite "
                "log): refused, nothing written\n",
                spec->cmd, oname[o], out[o], in[i]);
        return 2;
      }
    for (int p = 0; p < o; p++)
      if (hd_path_overwrites(out[o], out[p]) || hd_path_overwrites(out[p], out[o])) {
        fprintf(stderr, "haff %s: %s %s and %s %s are the same file: give two\n", spec->cmd,
                oname[p], out[p], oname[o], out[o]);
        return 2;
      }
  }
  for (int o = 0; o < no; o++) { /* then each output alone */
    char folder[512];
    int miss = hd_path_folder_missing(out[o], folder, sizeof folder);
    if (miss) {
      fprintf(stderr, "haff %s: %s %s: the folder %s %s: nothing written\n", spec->cmd, oname[o],
              out[o], folder, miss == 1 ? "does not exist" : "is not a folder");
      return 2;
    }
    if (!isdb[o] && hd_path_is_sqlite(out[o])) {
      fprintf(stderr,
              "haff %s: %s %s is an SQLite database, which this output would replace: refused, "
              "nothing written (remove it first, or name another file)\n",
              spec->cmd, oname[o], out[o]);
      return 2;
    }
  }
  return 0;
}

void hd_opt_help(const hd_optspec *spec, FILE *out) {
  if (spec->head) fputs(spec->head, out);
  char left[128];
  for (const hd_optdef *d = spec->opts; d->name; d++) {
    if (!d->help || !applies(spec, d)) continue;
    int o;
    if (d->flags & HD_OPTF_SHORT)
      o = snprintf(left, sizeof left, "  -%c", d->letter);
    else if (d->letter)
      o = snprintf(left, sizeof left, "  -%c, --%s", d->letter, d->name);
    else
      o = snprintf(left, sizeof left, "  --%s", d->name);
    if (d->meta) snprintf(left + o, sizeof left - (size_t)o, " %s", d->meta);
    fprintf(out, "%-*s", 19, left);
    if (strlen(left) >= 19) fputs("  ", out);
    const char *help = d->help;
    for (const char *const *h = spec->help_for; h && h[0] && h[1]; h += 2)
      if (!strcmp(h[0], d->name)) help = h[1];
    for (const char *p = help; *p;) { /* continuation lines under the first */
      size_t len = strcspn(p, "\n");
      fprintf(out, "%.*s\n", (int)len, p);
      p += len;
      if (*p) fprintf(out, "%-19s", ""), p++;
    }
  }
  if (spec->tail) fputs(spec->tail, out);
}

int hd_opt_refuse(const hd_optspec *spec, const hd_optres *res, const char *opt, const char *others,
                  const char *why) {
  if (opt) {
    int m = hd_opt_index(spec, opt);
    if (m < 0 || !res->given[m]) return 0;
  }
  for (int k = 0; spec->opts[k].name; k++) {
    if (!res->given[k] || (opt && !strcmp(spec->opts[k].name, opt))) continue;
    const char *name = spec->opts[k].name;
    size_t len = strlen(name);
    for (const char *p = others; *p;) {
      size_t w = strcspn(p, " ");
      if (w == len && !strncmp(p, name, len)) {
        fprintf(stderr, "haff %s: --%s does not apply %s (see --help)\n", spec->cmd, name, why);
        return 2;
      }
      p += w;
      p += strspn(p, " ");
    }
  }
  return 0;
}
