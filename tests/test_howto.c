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
      cmocka_unit_test(howto_subcommand_files),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
