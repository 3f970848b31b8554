/* hd_scene_parse: reading a scene's text: its lines, `[section]` headers and `key = value`
 * lines (libinih), and the `--set SECTION.KEY=VALUE` overrides; each key is found in SCENE_KEYS
 * (hd_scene_keys.h) and its value handed to hd_scene_set_value.
 *
 * Line numbers: libinih's handler is not told the line, so the scene is fed to ini_parse_stream
 * through our own reader, which hands over one physical line per call and counts them; the
 * handler then knows the line it is called for.  The reader also
 *   - strips leading blanks, so that an indented key is never taken for a libinih "multi-line
 *     continuation" of the previous key;
 *   - checks every `[section]` header itself (libinih does not report headers to the handler),
 *     so that an unknown or empty section is still an error, and text after `]` is refused;
 *   - refuses lines longer than HD_SCENE_MAX_LINE.
 * Every key is remembered with where it was set (file line or --set), so that checks made after
 * the whole scene is read still name the right line. */
#include "hd_scene_internal.h"

#include <ctype.h>
#include <ini.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Whether s is a valid species name: [A-Za-z0-9_]{1,31}. */
static int good_name(const char *s) {
  size_t n = strlen(s);
  if (n == 0 || n >= HD_SPECIES_NAME_MAX) return 0;
  for (size_t i = 0; i < n; i++)
    if (!isalnum((unsigned char)s[i]) && s[i] != '_') return 0;
  return 1;
}

int hd_scene_find_sec(const char *s) {
  for (int i = 0; i < N_SEC; i++)
    if (i != S_SPECIES && !strcmp(s, hd_scene_sec_name[i])) return i;
  return -1;
}

/* The NAME of a section "species NAME" (blanks between), or NULL when s is not one. */
static const char *species_part(const char *s) {
  if (strncmp(s, "species", 7) || (s[7] != ' ' && s[7] != '\t')) return NULL;
  s += 7;
  while (*s == ' ' || *s == '\t') s++;
  return s;
}

/* The instance of named species `name`, or -1. */
int hd_scene_find_species(const ctx *c, const char *name) {
  for (int j = 0; j < c->sc->n_named; j++)
    if (!strcmp(c->sc->named[j].name, name)) return N_SEC + j;
  return -1;
}

static int unknown_section(ctx *c, const char *s) {
  char at[600];
  hd_scene_where(c, c->cur, at, sizeof at);
  if (!strcmp(s, "species"))
    return hd_scene_cfail(c, HD_EINPUT,
                          "%s: [species]: a species section needs a name: [species NAME]", at);
  return hd_scene_cfail(
      c, HD_EINPUT,
      "%s: [%.60s]: unknown section (known: system dimers disks species NAME walls init "
      "run log rods)",
      at, s);
}

static void mark_section(ctx *c, int si) {
  if (!c->present[si]) c->sec_at[si] = c->cur;
  c->present[si] = 1;
}

/* The section instance of a [section] name (a new [species NAME] is created when `create`), or
 * -1 with the error set. */
static int section_index(ctx *c, const char *s, int create) {
  int si = hd_scene_find_sec(s);
  if (si >= 0) return si;
  const char *name = species_part(s);
  if (!name) return unknown_section(c, s), -1;
  char at[600];
  hd_scene_where(c, c->cur, at, sizeof at);
  if (!good_name(name))
    return hd_scene_cfail(c, HD_EINPUT,
                          "%s: [species %.40s]: a species name is 1 to %d letters, digits or _", at,
                          name, HD_SPECIES_NAME_MAX - 1),
           -1;
  if (!strcmp(name, "dimer") || !strcmp(name, "disk") || !strcmp(name, "dimers") ||
      !strcmp(name, "disks"))
    return hd_scene_cfail(
               c, HD_EINPUT,
               "%s: [species %s]: reserved name (the [dimers] and [disks] sections are those "
               "species)",
               at, name),
           -1;
  si = hd_scene_find_species(c, name);
  if (si >= 0 || !create) return si;
  hd_scene *sc = c->sc;
  if (sc->n_named == HD_MAX_SPECIES - 2)
    return hd_scene_cfail(
               c, HD_EINPUT,
               "%s: [species %s]: more than %d [species] sections (HD_MAX_SPECIES %d counts "
               "[dimers] and [disks])",
               at, name, HD_MAX_SPECIES - 2, HD_MAX_SPECIES),
           -1;
  si = N_SEC + sc->n_named;
  hd_scene_species *sp = &sc->named[sc->n_named++];
  memset(sp, 0, sizeof *sp);
  strcpy(sp->name, name);
  sp->line = c->cur.over ? 0 : c->cur.line;
  for (int k = 0; k < N_KEY; k++)
    if (hd_scene_keys[k].sec == S_SPECIES && hd_scene_keys[k].type == KT_REAL)
      *(double *)hd_scene_field(c, si, k) = hd_scene_keys[k].def;
  sp_parse *p = &c->sp[si - N_SEC];
  memset(p, 0, sizeof *p);
  p->d = hd_scene_keys[K_PD].def;
  p->m = hd_scene_keys[K_PM].def;
  p->s = NAN;
  return si;
}

/* Handles `name = value` in section `section` at c->cur. */
static int handle(ctx *c, const char *section, const char *name, const char *value) {
  char at[600], v[96], label[64];
  if (!*section) {
    hd_scene_where(c, c->cur, at, sizeof at);
    hd_scene_shorten(value, v, sizeof v);
    return hd_scene_cfail(c, HD_EINPUT, "%s: %.60s = %s: key outside any [section]", at, name, v);
  }
  int si = section_index(c, section, 0);
  if (si < 0) return c->failed ? c->code : unknown_section(c, section);
  int s = hd_scene_sec_of(si);
  hd_scene_sec_label(c, si, label, sizeof label);
  int k = 0;
  while (k < N_KEY && !(hd_scene_keys[k].sec == s && !strcmp(hd_scene_keys[k].name, name))) k++;
  if (k == N_KEY && s == S_SPECIES && !strncmp(name, "alpha_", 6) && name[6]) k = K_PALPHAX;
  if (k == N_KEY && s == S_SPECIES && !strncmp(name, "beta_", 5) && name[5]) k = K_PBETAX;
  if (k == N_KEY) {
    char known[300] = "";
    for (int j = 0; j < N_KEY; j++)
      if (hd_scene_keys[j].sec == s) {
        strcat(known, " ");
        strcat(known, hd_scene_keys[j].name);
      }
    char nm[64];
    hd_scene_shorten(name, nm, sizeof nm);
    return hd_scene_fail(c, HD_EINPUT, c->cur, si, nm, value, "unknown key (keys of [%s]:%s)",
                         s == S_SPECIES ? "species NAME" : hd_scene_sec_name[s], known);
  }
  loc *prev = &c->key_at[si][k];
  char *val = c->key_val[si][k];
  if (k == K_PALPHAX || k == K_PBETAX) { /* one slot per OTHER and kind */
    sp_parse *p = &c->sp[si - N_SEC];
    int beta = k == K_PBETAX, same = 0;
    const char *other = name + (beta ? 5 : 6), *kind = beta ? "beta" : "alpha";
    if (!good_name(other))
      return hd_scene_fail(c, HD_EINPUT, c->cur, si, name, value,
                           "OTHER of %s_OTHER must be a species name (letters, digits, _)", kind);
    int j = 0;
    while (j < p->npair && (strcmp(p->pair[j].other, other) || p->pair[j].beta != beta))
      same += p->pair[j++].beta == beta;
    if (j == p->npair) {
      if (same == HD_MAX_SPECIES)
        return hd_scene_fail(c, HD_EINPUT, c->cur, si, name, value,
                             "more %s_OTHER keys than species", kind);
      memset(&p->pair[j], 0, sizeof p->pair[j]);
      strcpy(p->pair[j].other, other);
      p->pair[j].beta = beta;
      p->npair++;
    } else if (j != p->npair - 1) { /* hd_scene_set_alpha_other reads the last: make it so */
      sp_pair t = p->pair[j];
      memmove(&p->pair[j], &p->pair[j + 1], (size_t)(p->npair - 1 - j) * sizeof t);
      p->pair[p->npair - 1] = t;
    }
    prev = &p->pair[p->npair - 1].at;
    val = p->pair[p->npair - 1].val;
  }
  if (!c->cur.over && prev->line > 0)
    return hd_scene_fail(c, HD_EINPUT, c->cur, si, name, value,
                         "duplicate key (first set at line %ld)", prev->line);
  if (c->cur.over && prev->over > 0)
    return hd_scene_fail(c, HD_EINPUT, c->cur, si, name, value,
                         "duplicate key (also set by --set %s)", c->over[prev->over - 1]);
  *prev = c->cur;
  hd_scene_shorten(value, val, 96);
  /* a file's value that a --set replaces is not read: the override mends a bad line */
  for (int i = 0; !c->cur.over && i < c->n_over; i++)
    if (hd_scene_override_sets(c->over[i], label, name)) return HD_OK;
  return hd_scene_set_value(c, si, k, value);
}

static int on_key(void *user, const char *section, const char *name, const char *value) {
  ctx *c = user;
  if (c->failed) return 0;
  return handle(c, section, name, value) == HD_OK;
}

/* Checks a `[section]` line (leading blanks already gone). */
static int section_line(ctx *c, const char *line) {
  const char *close = strchr(line, ']');
  char at[600];
  hd_scene_where(c, c->cur, at, sizeof at);
  if (!close) {
    return hd_scene_cfail(c, HD_EINPUT, "%s: malformed section header: no ']'", at);
  }
  const char *r = close + 1;
  while (*r == ' ' || *r == '\t') r++;
  if (*r && *r != '\n' && *r != '\r' && *r != ';' && *r != '#') {
    return hd_scene_cfail(c, HD_EINPUT,
                          "%s: text after the [section] header: put each key on its own line", at);
  }
  char name[64];
  size_t len = (size_t)(close - line - 1);
  if (len >= sizeof name) len = sizeof name - 1;
  memcpy(name, line + 1, len);
  name[len] = '\0';
  int si = section_index(c, name, 1);
  if (si < 0) return c->code;
  mark_section(c, si);
  c->cur_si = si;
  return HD_OK;
}

/* fgets-like reader for ini_parse_stream: one physical line per call, counted. */
static char *reader(char *str, int num, void *stream) {
  ctx *c = stream;
  if (c->failed || c->p >= c->end) return NULL;
  const char *s = c->p;
  const char *nl = memchr(s, '\n', (size_t)(c->end - s));
  const char *stop = nl ? nl + 1 : c->end;
  c->p = stop;
  c->cur.line = ++c->lineno;
  c->cur.over = 0;
  /* every blank libinih skips at a line's start (\r \v \f too): "\v[disks]" was parsed as a
   * section by libinih but not seen as one here, so its keys took effect while the section was
   * left out of the canonical text (and a resume ran without them).  On the first line, byte
   * order marks among the blanks too: libinih skips one at the start of what it is handed,
   * so "\t<BOM>[system]" (found by make fuzz) was its section but not ours.  Handing it the
   * line without any of them keeps the two views the same. */
  for (;;) {
    if (c->lineno == 1 && stop - s >= 3 && !memcmp(s, "\xEF\xBB\xBF", 3))
      s += 3;
    else if (s < stop && (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\v' || *s == '\f'))
      s++;
    else
      break;
  }
  size_t len = (size_t)(stop - s);
  size_t body = len; /* the line without its end (\n or \r\n): what HD_SCENE_MAX_LINE bounds */
  if (body > 0 && s[body - 1] == '\n') body--;
  if (body > 0 && s[body - 1] == '\r') body--;
  if (len + 1 > (size_t)num || body > HD_SCENE_MAX_LINE) {
    char at[600];
    hd_scene_where(c, c->cur, at, sizeof at);
    hd_scene_cfail(c, HD_EINPUT, "%s: line too long (max %d bytes)", at, HD_SCENE_MAX_LINE);
    return NULL;
  }
  memcpy(str, s, len);
  str[len] = '\0';
  if (str[0] == '[' && section_line(c, str)) return NULL;
  /* in `disks = ...` a blank before ';' would start a libinih comment and drop the disks after
   * it without a word */
  if (c->cur_si >= N_SEC && !strncmp(str, "disks", 5) && strchr(" \t=:", str[5]) &&
      (strstr(str, " ;") || strstr(str, "\t;"))) {
    char at[600];
    hd_scene_where(c, c->cur, at, sizeof at);
    hd_scene_cfail(
        c, HD_EINPUT,
        "%s: [species %s] disks: a blank before ';' starts a comment: write x y d m; x y d m", at,
        c->sc->named[c->cur_si - N_SEC].name);
    return NULL;
  }
  return str;
}

/* Parses the scene text (c->p .. c->end). */
int hd_scene_parse_text(ctx *c) {
  int saved = ini_max_line;
  ini_max_line = HD_SCENE_MAX_LINE + 3;
  c->cur_si = -1;
  int r = ini_parse_stream(reader, c, on_key, c);
  ini_max_line = saved;
  if (c->failed) return c->code;
  if (r != 0) {
    if (r < 0) return hd_scene_cfail(c, HD_ENOMEM, "%s: out of memory while parsing", c->name);
    return hd_scene_cfail(c, HD_EINPUT,
                          "%s:%d: malformed line: expected [section], key = value or a comment",
                          c->name, r);
  }
  return HD_OK;
}

char *hd_scene_trim(char *s) {
  while (*s == ' ' || *s == '\t') s++;
  char *e = s + strlen(s);
  while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r' || e[-1] == '\n')) *--e = '\0';
  return s;
}

/* Splits the override in buf ("SECTION.KEY=VALUE", changed in place) into its trimmed parts;
 * "species.NAME.KEY=VALUE" gives the section "species NAME", written to secbuf.  0 if it has no
 * '=' or no '.' before it (or, for species, no second '.'). */
static int split_override(char *buf, char *secbuf, size_t n, char **sec, char **key, char **val) {
  char *eq = strchr(buf, '=');
  char *dot = eq ? memchr(buf, '.', (size_t)(eq - buf)) : NULL;
  if (!eq || !dot) return 0;
  *dot = *eq = '\0';
  *sec = hd_scene_trim(buf), *key = hd_scene_trim(dot + 1), *val = hd_scene_trim(eq + 1);
  if (!strcmp(*sec, "species")) {
    char *dot2 = strchr(*key, '.');
    if (!dot2) return 0;
    *dot2 = '\0';
    snprintf(secbuf, n, "species %s", hd_scene_trim(*key));
    *sec = secbuf;
    *key = hd_scene_trim(dot2 + 1);
  }
  return 1;
}

int hd_scene_override_sets(const char *over, const char *section, const char *key) {
  char buf[HD_SCENE_MAX_LINE + 1], secbuf[HD_SCENE_MAX_LINE + 16], *sec, *k, *val;
  if (strlen(over) > HD_SCENE_MAX_LINE) return 0;
  strcpy(buf, over);
  return split_override(buf, secbuf, sizeof secbuf, &sec, &k, &val) && !strcmp(sec, section) &&
         !strcmp(k, key);
}

/* Applies override i ("SECTION.KEY=VALUE"). */
int hd_scene_apply_override(ctx *c, int i) {
  char buf[HD_SCENE_MAX_LINE + 1], secbuf[HD_SCENE_MAX_LINE + 16], at[600];
  c->cur.line = 0;
  c->cur.over = i + 1;
  hd_scene_where(c, c->cur, at, sizeof at);
  if (strlen(c->over[i]) > HD_SCENE_MAX_LINE) {
    return hd_scene_cfail(c, HD_EINPUT, "--set: value too long (max %d bytes)", HD_SCENE_MAX_LINE);
  }
  strcpy(buf, c->over[i]);
  char *sec, *key, *val;
  if (!split_override(buf, secbuf, sizeof secbuf, &sec, &key, &val))
    return hd_scene_cfail(c, HD_EINPUT, "%s: expected SECTION.KEY=VALUE (species.NAME.KEY=VALUE)",
                          at);
  int si = section_index(c, sec, 1);
  if (si < 0) return c->code;
  mark_section(c, si);
  return handle(c, sec, key, val);
}
