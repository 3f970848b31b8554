/* The table of subcommands (cli/haff_commands.c) and each one's option table against what users
 * see: every option of every subcommand is in its --help (the text hd_opt_help makes from the
 * table, and the binary prints that very text), in its section of the man page and in the bash
 * completion; each command is in `haff --help` (a group's programs in `haff GROUP --help`); no
 * table names an option or a letter twice.  Linked with the CLI's objects (not cli/haff.c). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "haff.h"
#include "test_cli_util.h"

static char root[4096]; /* the source tree (the tests run from it) */

/* The text of dir/out.txt, malloc'd. */
static char *slurp_out(void) {
  char p[400];
  snprintf(p, sizeof p, "%s/out.txt", dir);
  FILE *f = fopen(p, "rb");
  assert_non_null(f);
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *s = malloc((size_t)n + 1);
  assert_non_null(s);
  s[fread(s, 1, (size_t)n, f)] = 0;
  fclose(f);
  return s;
}

/* The words typed before the options: "run", "mc fmean". */
static void words_of(const haff_command *c, char *buf, size_t n) {
  if (c->group)
    snprintf(buf, n, "%s %s", c->group, c->name);
  else
    snprintf(buf, n, "%s", c->name);
}

/* How option d is typed: "--name", or "-o" for a short-only one. */
static void typed(const hd_optdef *d, char *buf, size_t n) {
  if (d->flags & HD_OPTF_SHORT)
    snprintf(buf, n, "-%c", d->letter);
  else
    snprintf(buf, n, "--%s", d->name);
}

/* Whether option d is one of spec's (listed in its help). */
static int listed(const hd_optspec *spec, const hd_optdef *d) {
  return d->help && (!spec->allowed || !d->set || (spec->allowed & d->set));
}

static void tables_are_well_formed(void **state) {
  (void)state;
  int ncmd = 0;
  for (const haff_command *c = haff_commands; c->name; c++, ncmd++) {
    if (c->group) { /* a program: its group is a command of haff without a main */
      const haff_command *g = haff_commands;
      while (g->name && (g->group || strcmp(g->name, c->group))) g++;
      assert_non_null(g->name);
      assert_null(g->main);
    }
    assert_non_null(c->summary);
    if (!c->spec) continue;
    char w[64];
    words_of(c, w, sizeof w);
    assert_string_equal(c->spec->cmd, w); /* messages say "haff WORDS: ..." */
    const hd_optdef *o = c->spec->opts;
    for (int i = 0; o[i].name; i++) {
      if (!listed(c->spec, &o[i]) && !o[i].set) fail_msg("haff %s: --%s has no help", w, o[i].name);
      for (int j = 0; j < i; j++) {
        if (!strcmp(o[i].name, o[j].name)) fail_msg("haff %s: --%s twice", w, o[i].name);
        if (o[i].letter && o[i].letter == o[j].letter)
          fail_msg("haff %s: -%c twice", w, o[i].letter);
      }
      if (o[i].letter == 'h') fail_msg("haff %s: -h is --help", w);
      /* where the value goes: an int or a 64-bit field, an enum's words */
      if (o[i].kind == HD_ARG_INT && o[i].size != sizeof(int) && o[i].size != sizeof(long long))
        fail_msg("haff %s: --%s: size %zu", w, o[i].name, o[i].size);
      if (o[i].kind == HD_ARG_INT && !(o[i].ilo <= o[i].ihi))
        fail_msg("--%s: empty range", o[i].name);
      if (o[i].kind == HD_ARG_DOUBLE && !(o[i].lo <= o[i].hi))
        fail_msg("--%s: empty range", o[i].name);
      if ((o[i].kind == HD_ARG_ENUM) != (o[i].choices != NULL))
        fail_msg("haff %s: --%s: choices", w, o[i].name);
    }
  }
  assert_true(ncmd >= 22);
}

/* Every option of the table is in the help made from it; the binary prints the same text. */
static void help_lists_every_option(void **state) {
  (void)state;
  for (const haff_command *c = haff_commands; c->name; c++) {
    if (!c->spec) continue;
    char *help = NULL, w[64];
    size_t hn = 0;
    FILE *m = open_memstream(&help, &hn);
    assert_non_null(m);
    hd_opt_help(c->spec, m);
    fclose(m);
    words_of(c, w, sizeof w);
    for (const hd_optdef *d = c->spec->opts; d->name; d++) {
      if (!listed(c->spec, d)) continue;
      char t[64];
      typed(d, t, sizeof t);
      if (!strstr(help, t)) fail_msg("haff %s --help: no %s", w, t);
    }
    if (haff) {
      assert_int_equal(sh("%s %s --help > out.txt", haff, w), 0);
      char *out = slurp_out();
      if (strcmp(out, help)) fail_msg("haff %s --help is not the text of its table", w);
      free(out);
    }
    free(help);
  }
}

/* `haff --help` lists the commands, `haff mc --help` the programs of mc. */
static void command_lists(void **state) {
  (void)state;
  if (!haff) skip();
  for (const haff_command *c = haff_commands; c->name; c++) {
    if (c->group)
      assert_int_equal(sh("%s %s --help > out.txt", haff, c->group), 0);
    else
      assert_int_equal(sh("%s --help > out.txt", haff), 0);
    char *out = slurp_out(), want[256];
    snprintf(want, sizeof want, "\n  %-*s %s\n", c->group ? 8 : 12, c->name, c->summary);
    if (!strstr(out, want)) fail_msg("'%s' is not listed as '%s'", c->name, want);
    free(out);
  }
}

/* Each option is in its command's section of the man page (made by cli/haff-man.sh) and in what
 * the bash completion offers after "haff WORDS --". */
static void man_page_and_completion(void **state) {
  (void)state;
  if (!haff) skip();
  char p[4200];
  snprintf(p, sizeof p, "%s/build/haff.1", root);
  FILE *f = fopen(p, "rb");
  if (!f) fail_msg("%s: not built (make all)", p);
  char *man = calloc(1, 1 << 20);
  assert_non_null(man);
  size_t k = fread(man, 1, (1 << 20) - 1, f);
  man[k] = 0;
  fclose(f);
  for (const haff_command *c = haff_commands; c->name; c++) {
    if (!c->spec) continue;
    char w[64], sec[96];
    words_of(c, w, sizeof w);
    snprintf(sec, sizeof sec, "\n.SS haff %s\n", w);
    char *s = strstr(man, sec);
    if (!s) fail_msg("the man page has no section for haff %s", w);
    s += strlen(sec);
    char *e = strstr(s, "\n.SS ");
    if (!e) e = s + strlen(s);
    char save = *e;
    *e = 0;
    assert_int_equal(sh("bash -c 'source %s/cli/haff-completion.bash; COMP_WORDS=(%s %s --); "
                        "COMP_CWORD=${#COMP_WORDS[@]}; COMP_CWORD=$((COMP_CWORD - 1)); _haff; "
                        "printf \"%%s\\n\" \"${COMPREPLY[@]}\"' > out.txt",
                        root, haff, w),
                     0);
    char *out = slurp_out(), *comp = malloc(strlen(out) + 2);
    assert_non_null(comp);
    comp[0] = '\n'; /* each offered word on a line of its own, "\n--name\n" */
    strcpy(comp + 1, out);
    free(out);
    for (const hd_optdef *d = c->spec->opts; d->name; d++) {
      if (!listed(c->spec, d)) continue;
      char t[64], roff[96], cw[80];
      typed(d, t, sizeof t);
      size_t o = 0; /* troff: each '-' as "\-" */
      for (const char *q = t; *q && o + 3 < sizeof roff; q++) {
        if (*q == '-') roff[o++] = '\\';
        roff[o++] = *q;
      }
      roff[o] = 0;
      if (!strstr(s, roff)) fail_msg("man page, haff %s: no %s", w, t);
      if (d->flags & HD_OPTF_SHORT) continue; /* the completion offers long options */
      snprintf(cw, sizeof cw, "\n%s\n", t);
      if (!strstr(comp, cw)) fail_msg("completion, haff %s: no %s", w, t);
    }
    free(comp);
    *e = save;
  }
  free(man);
}

static int setup(void **state) {
  (void)state;
  if (!getcwd(root, sizeof root)) return -1;
  haff = getenv("HAFF_BIN");
  if (getenv("HAFF_SANITIZE") && getenv("HAFF_SANITIZE")[0] == '1') haff = NULL;
  return test_cli_mkdtemp("tables");
}

static int teardown(void **state) {
  (void)state;
  return test_cli_rmdir();
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(tables_are_well_formed),
      cmocka_unit_test(help_lists_every_option),
      cmocka_unit_test(command_lists),
      cmocka_unit_test(man_page_and_completion),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
