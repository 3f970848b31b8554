/* The "How to add ..." sections of docs/architecture.md, walked through: every file they name
 * exists, every C name they quote is in the sources, and each worked example does what the
 * text says (a scene key, a shape, a subcommand).  Run from the source tree (tests/run-tests
 * does); elsewhere the tests skip. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "haff.h"
#include "hd_scene.h"
#include "hd_scene_internal.h"

#include <math.h>

/* The whole file at path (malloc'd), or NULL. */
static char *slurp(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  size_t cap = 1 << 16, n = 0;
  char *s = malloc(cap);
  for (size_t got; s && (got = fread(s + n, 1, cap - 1 - n, f)) > 0;) {
    n += got;
    if (n == cap - 1) {
      char *t = realloc(s, cap *= 2);
      if (!t) free(s);
      s = t;
    }
  }
  fclose(f);
  if (s) s[n] = '\0';
  return s;
}

/* Whether the word w is in a source of a layer folder (as a whole word, or as a prefix when it
 * ends with '_'). */
static int in_sources(const char *w) {
  char cmd[512];
  snprintf(cmd, sizeof cmd, "grep -rq%s -e '%s' engine db run analysis mc cli tests",
           w[strlen(w) - 1] == '_' ? "" : "w", w);
  return system(cmd) == 0;
}

/* The "## How to add" sections of docs/architecture.md (from the first to the end), or NULL
 * (skip: not in the source tree), without "How to add a collisions column": its example column
 * (species_i) is one to add, not in the sources; tests/test_db.c walks it through
 * (every_collision_column_round_trips, schema_sql_collisions_is_the_column_table). */
static char *howto_text(void) {
  char *doc = slurp("docs/architecture.md");
  if (!doc) return NULL;
  char *h = strstr(doc, "\n## How to add");
  assert_non_null(h);
  char *t = strdup(h);
  free(doc);
  char *col = t ? strstr(t, "\n## How to add a collisions column") : NULL;
  if (col) {
    char *next = strstr(col + 1, "\n## ");
    memmove(col, next ? next : col + strlen(col), strlen(next ? next : col + strlen(col)) + 1);
  }
  return t;
}

/* Every `quoted` path in the sections exists, every C name in a `quoted` span is in the
 * sources (K_ID: the row X(ID, of SCENE_KEYS); placeholders (X, *) are not checked. */
static void howto_names_exist(void **state) {
  (void)state;
  char *t = howto_text();
  if (!t) skip();
  static const char *const sections[] = {"## How to add a scene key", "## How to add a shape",
                                         "## How to add a subcommand"};
  for (size_t k = 0; k < sizeof sections / sizeof *sections; k++)
    if (!strstr(t, sections[k])) fail_msg("docs/architecture.md: no section '%s'", sections[k]);
  int paths = 0, names = 0;
  for (char *p = strchr(t, '`'); p; p = strchr(p, '`')) {
    char *e = strchr(p + 1, '`');
    if (!e) break;
    *e = '\0';
    char *span = p + 1;
    p = e + 1;
    if (strchr(span, '*') || strstr(span, "_X") || strstr(span, "cmd_X")) continue;
    size_t n = strlen(span);
    int path =
        strchr(span, '/') && strcspn(span, " ") == n && n > 2 &&
        (!strcmp(span + n - 2, ".c") || !strcmp(span + n - 2, ".h") ||
         (n > 3 && !strcmp(span + n - 3, ".md")) || (n > 3 && !strcmp(span + n - 3, ".sh")) ||
         (n > 5 && !strcmp(span + n - 5, ".bash")));
    if (path) {
      if (access(span, F_OK)) fail_msg("docs/architecture.md names %s: no such file", span);
      paths++;
      continue;
    }
    /* the C names: words with '_' or of 3+ capitals */
    for (char *w = span; *w;) {
      if (!(isalpha((unsigned char)*w) || *w == '_') ||
          (w > span && isalnum((unsigned char)w[-1]))) {
        w++;
        continue;
      }
      size_t m = 0;
      int caps = 0, under = 0;
      while (isalnum((unsigned char)w[m]) || w[m] == '_') {
        caps += isupper((unsigned char)w[m]) != 0;
        under += w[m] == '_';
        m++;
      }
      char word[128];
      snprintf(word, sizeof word, "%.*s", (int)m, w);
      w += m;
      if (!(under || (caps == (int)m && m >= 3)) || !strcmp(word, "X")) continue;
      char want[160];
      if (!strncmp(word, "K_", 2))
        snprintf(want, sizeof want, "X(%s,", word + 2);
      else
        snprintf(want, sizeof want, "%s", word);
      if (!in_sources(want)) fail_msg("docs/architecture.md names %s: not in the sources", want);
      names++;
    }
  }
  assert_true(paths >= 10 && names >= 30); /* the sections were read */
  free(t);
}

/* The scene key example: `[walls] alpha` is read into wall_alpha, refused out of range with
 * file:line:key, and has its row in docs/scene-keys.md. */
static void howto_scene_key(void **state) {
  (void)state;
  char *keys = slurp("docs/scene-keys.md");
  if (!keys) skip();
  assert_non_null(strstr(keys, "body–wall restitution"));
  free(keys);
  static const char good[] = "[disks]\ncount = 10\n[system]\narea_fraction = 0.1\n"
                             "[walls]\nsides = left right\nalpha = 0.9\n[run]\nstop_cpd = 1\n";
  hd_scene sc;
  hd_error e;
  assert_int_equal(hd_scene_load_string(&sc, good, "w.ini", NULL, 0, &e), HD_OK);
  assert_true(sc.wall_alpha == 0.9);
  assert_non_null(strstr(sc.text, "alpha = 0.9"));
  hd_scene_free(&sc);
  char bad[sizeof good + 4];
  snprintf(bad, sizeof bad, "%s", good);
  memcpy(strstr(bad, "alpha = 0.9"), "alpha = 1.5", 11);
  assert_int_equal(hd_scene_load_string(&sc, bad, "w.ini", NULL, 0, &e), HD_EINPUT);
  assert_string_equal(e.msg, "w.ini:7: [walls] alpha = 1.5: must be in [0, 1]");
}

/* The shape example: `shape = bent 90` makes a species of three disks and is written back. */
static void howto_shape(void **state) {
  (void)state;
  static const char text[] = "[species v]\ncount = 4\nshape = bent 90\n[system]\n"
                             "area_fraction = 0.05\n[run]\nstop_cpd = 1\n";
  hd_scene sc;
  hd_error e;
  assert_int_equal(hd_scene_load_string(&sc, text, "b.ini", NULL, 0, &e), HD_OK);
  assert_int_equal(sc.n_named, 1);
  assert_int_equal(sc.named[0].ndisk, 3);
  assert_non_null(strstr(sc.text, "shape = bent 90"));
  hd_scene_free(&sc);
}

/* Loads `shape = SHAPE` (with d = 1, m = 1) as the species t of a small scene, file "f.ini"
 * (the shape on line 3). */
static int load_shape(hd_scene *sc, const char *shape, hd_error *e) {
  char text[512];
  snprintf(text, sizeof text,
           "[species t]\ncount = 4\nshape = %s\n[system]\narea_fraction = 0.05\n[run]\n"
           "stop_cpd = 1\n",
           shape);
  return hd_scene_load_string(sc, text, "f.ini", NULL, 0, e);
}

/* Whether every form's syntax is in s, in the table's order, each between two `quote`s (the
 * messages: "", the docs' key table: "`"). */
static int lists_forms(const char *s, const char *quote) {
  for (const hd_scene_form *f = hd_scene_forms; f->name; f++) {
    char syn[128], want[140];
    hd_scene_form_syntax(f, syn, sizeof syn);
    snprintf(want, sizeof want, "%s%s%s", quote, syn, quote);
    if (!(s = strstr(s, want))) return 0;
    s += strlen(want);
  }
  return 1;
}

/* A value of q inside its range. */
static double inside(const hd_scene_form_param *q) {
  if (isinf(q->hi)) return q->lo + 0.5;
  return q->whole ? floor((q->lo + q->hi) / 2) : (q->lo + q->hi) / 2;
}

/* The shape text "NAME v0 v1 ...", with number i replaced by bad (i = -1: none), and S when
 * s > 0. */
static void form_text(const hd_scene_form *f, int i, double bad, double s, char *buf, size_t n) {
  size_t at = (size_t)snprintf(buf, n, "%s", f->name);
  for (int j = 0; j < f->nparam; j++)
    at += (size_t)snprintf(buf + at, n - at, " %.17g", j == i ? bad : inside(&f->param[j]));
  if (s > 0) snprintf(buf + at, n - at, " %.17g", s);
}

/* How to add a shape: a short form is a row of hd_scene_forms (and its builder), and that row
 * drives everything else.  Walked through for every row: (1) no other list of forms is left
 * (the SH_ enum is gone), (2) the help text: the messages of an unknown form and of a species
 * without a shape list every form, and docs/scene-keys.md has the form in the `shape` row and
 * its `.help` line in the list of short forms, (3) the error ranges: a number just outside its
 * range is refused with "NAME must be ..." naming the range's ends, a word too many is refused,
 * (4) the form with numbers inside the ranges, with and without S, makes the builder's disks
 * bit for bit and round-trips through the canonical text (hd_scene_put_shape, then parsed again).
 */
static void howto_shape_forms(void **state) {
  (void)state;
  char *keys = slurp("docs/scene-keys.md");
  if (!keys) skip();
  /* (1) */
  int grc = system("grep -rqE '\\bSH_[A-Z]+' engine/scene");
  assert_true(WIFEXITED(grc) && WEXITSTATUS(grc) == 1); /* 1: no match (2 would be grep failing) */
  /* (2) */
  hd_scene sc;
  hd_error e;
  assert_int_equal(load_shape(&sc, "nosuchform", &e), HD_EINPUT);
  assert_true(lists_forms(e.msg, ""));
  assert_int_equal(hd_scene_load_string(&sc, "[species t]\ncount = 4\n[run]\nstop_cpd = 1\n",
                                        "f.ini", NULL, 0, &e),
                   HD_EINPUT);
  assert_non_null(strstr(e.msg, "missing: give shape = "));
  assert_true(lists_forms(e.msg, ""));
  char *row = strstr(keys, "| `shape` |");
  assert_non_null(row);
  char *eol = strchr(row, '\n');
  assert_non_null(eol);
  *eol = '\0';
  assert_true(lists_forms(row, "`"));
  char *list = strstr(row + strlen(row) + 1, "Short forms of `shape`");
  assert_non_null(list);
  char *w = list; /* the list with each line break and its indent made one blank */
  for (const char *r = list; *r; r++) {
    if (*r == '\n' && r[1] == ' ') {
      *w++ = ' ';
      while (r[1] == ' ') r++;
    } else {
      *w++ = *r;
    }
  }
  *w = '\0';
  int nform = 0;
  for (const hd_scene_form *f = hd_scene_forms; f->name; f++, nform++) {
    char syn[128], line[512];
    hd_scene_form_syntax(f, syn, sizeof syn);
    snprintf(line, sizeof line, "- `%s`: %s", syn, f->help);
    if (!strstr(list, line)) fail_msg("docs/scene-keys.md: no line '%s'", line);
  }
  assert_true(nform >= 5);
  free(keys);
  for (const hd_scene_form *f = hd_scene_forms; f->name; f++) {
    char text[256], msg[512];
    /* (3) */
    for (int i = 0; i < f->nparam; i++) {
      const hd_scene_form_param *q = &f->param[i];
      double out[3] = {q->lo_open ? q->lo : q->lo - 1, q->hi_open ? q->hi : q->hi + 1,
                       q->whole ? q->lo + 0.5 : NAN};
      for (int o = 0; o < 3; o++) {
        if (isnan(out[o]) || isinf(out[o])) continue;
        form_text(f, i, out[o], 0, text, sizeof text);
        assert_int_equal(load_shape(&sc, text, &e), HD_EINPUT);
        snprintf(msg, sizeof msg, "f.ini:3: [species t] shape = %s: %s must be ", text, q->name);
        if (strncmp(e.msg, msg, strlen(msg))) fail_msg("%s: '%s'", text, e.msg);
        char lo[40], hi[40];
        snprintf(lo, sizeof lo, "%g", q->lo);
        snprintf(hi, sizeof hi, "%g", q->hi);
        if (!strstr(e.msg + strlen(msg), lo) || (!isinf(q->hi) && !strstr(e.msg + strlen(msg), hi)))
          fail_msg("%s: '%s' does not name the range", text, e.msg);
        if (q->note && !strstr(e.msg, q->note)) fail_msg("%s: '%s': no note", text, e.msg);
      }
    }
    if (f->spacing) { /* S = 0 */
      form_text(f, -1, 0, 0, text, sizeof text);
      strcat(text, " 0");
      assert_int_equal(load_shape(&sc, text, &e), HD_EINPUT);
      snprintf(msg, sizeof msg, "f.ini:3: [species t] shape = %s: %s must be > 0", text,
               hd_scene_form_spacing.name);
      assert_string_equal(e.msg, msg);
    }
    form_text(f, -1, 0, f->spacing ? 0.9 : 0, text, sizeof text); /* every word it takes, */
    strcat(text, " 1");                                           /* and exactly one more */
    assert_int_equal(load_shape(&sc, text, &e), HD_EINPUT);
    assert_true(lists_forms(e.msg, ""));
    /* (4) */
    for (int with_s = 0; with_s < 1 + f->spacing; with_s++) {
      double s = with_s ? 0.9 : 0, v[HD_SCENE_FORM_MAX_PARAM];
      double x[HD_MAX_BODY_DISKS], y[HD_MAX_BODY_DISKS];
      for (int i = 0; i < f->nparam; i++) v[i] = inside(&f->param[i]);
      int n = f->build(v, with_s ? s : 1, x, y);
      form_text(f, -1, 0, s, text, sizeof text);
      if (load_shape(&sc, text, &e)) fail_msg("shape = %s: %s", text, e.msg);
      assert_int_equal(sc.named[0].ndisk, n);
      for (int k = 0; k < n; k++) {
        assert_memory_equal(&sc.named[0].x[k], &x[k], sizeof x[k]);
        assert_memory_equal(&sc.named[0].y[k], &y[k], sizeof y[k]);
        assert_true(sc.named[0].d[k] == 1 && sc.named[0].m[k] == 1);
      }
      char written[128];
      const char *at = strstr(sc.text, "shape = ");
      assert_non_null(at);
      snprintf(written, sizeof written, "%.*s", (int)strcspn(at, "\n"), at);
      snprintf(msg, sizeof msg, "shape = %s", f->name);
      assert_int_equal(strncmp(written, msg, strlen(msg)), 0);
      hd_scene again;
      assert_int_equal(hd_scene_load_stored(&again, sc.text, "runs.scene", &e), HD_OK);
      assert_string_equal(again.text, sc.text);
      assert_int_equal(again.named[0].ndisk, n);
      assert_memory_equal(again.named[0].x, sc.named[0].x, (size_t)n * sizeof(double));
      assert_memory_equal(again.named[0].y, sc.named[0].y, (size_t)n * sizeof(double));
      hd_scene_free(&again);
      hd_scene_free(&sc);
    }
  }
}

/* The subcommand rule: every command of haff_commands is hd_cmd_X (haff mc X: hd_cmd_mc_X)
 * with its options hd_cmd_X_spec, defined in cmd_X.c of cli/, cli/analysis/ or cli/mc/ (haff
 * resume shares cli/cmd_run.c with haff run) and declared in cli/haff.h. */
static void howto_subcommand_files(void **state) {
  (void)state;
  char *h = slurp("cli/haff.h");
  if (!h) skip();
  int n = 0;
  for (const haff_command *c = haff_commands; c->name; c++) {
    if (!c->main) continue;
    char x[64], entry[160], spec[96], path[160];
    snprintf(x, sizeof x, "%s%s%s", c->group ? c->group : "", c->group ? "_" : "", c->name);
    for (char *q = x; *q; q++)
      if (*q == '-') *q = '_';
    snprintf(entry, sizeof entry, "int hd_cmd_%s(int argc, char **argv)", x);
    snprintf(spec, sizeof spec, "hd_cmd_%s_spec", x);
    const char *dirs[] = {"cli", "cli/analysis", "cli/mc"};
    char *src = NULL;
    for (size_t d = 0; d < 3 && !src; d++) {
      snprintf(path, sizeof path, "%s/cmd_%s.c", dirs[d], strcmp(x, "resume") ? x : "run");
      src = slurp(path);
    }
    if (!src) fail_msg("haff %s: no cmd_%s.c in cli/, cli/analysis/ or cli/mc/", c->name, x);
    if (!strstr(src, entry)) fail_msg("%s: no '%s'", path, entry);
    if (!strstr(src, spec)) fail_msg("%s: no %s", path, spec);
    entry[strlen(entry) - strlen("(int argc, char **argv)")] = '\0';
    if (!strstr(h, entry + 4)) fail_msg("cli/haff.h: no %s", entry + 4);
    free(src);
    n++;
  }
  assert_true(n >= 20);
  free(h);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(howto_names_exist),
      cmocka_unit_test(howto_scene_key),
      cmocka_unit_test(howto_shape),
      cmocka_unit_test(howto_shape_forms),
      cmocka_unit_test(howto_subcommand_files),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
