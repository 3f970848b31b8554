/* The one option parser (cli/hd_opt.c) on a table of every kind of value: numbers read or
 * refused with one line naming the option, the value and the rule (bad number, out of range,
 * inf, nan, overflow), a missing value, an unknown option, an option given twice, "--", short
 * clusters, enums, lists, paths, options that do not apply, positional counts, and the help
 * text made from the table.  Every check is exact: no random input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hd_opt.h"

/* The values of the test table. */
typedef struct targs {
  int quiet, count, mode, bare;
  long big;
  long long id;
  double ratio, any, unit;
  const char *name, *db, *seed;
  const char *set_v[2];
  hd_optlist sets;
} targs;

static const hd_optdef topts[] = {
    HD_OPT_FLAG("quiet", 'q', targs, quiet, "say less"),
    HD_OPT_INT("count", 'c', targs, count, 1, 100, 0, "N", "a count in [1, 100]"),
    HD_OPT_INT("big", 0, targs, big, 0, LONG_MAX, HD_OPTF_EXP, "N", "whole, 1e6 allowed"),
    HD_OPT_INT("id", 0, targs, id, 1, LLONG_MAX, 0, "ID", "an id"),
    HD_OPT_DBL("ratio", 'r', targs, ratio, 0, INFINITY, HD_OPTF_GT | HD_OPTF_FINITE, "X",
               "a ratio > 0\nsecond line"),
    HD_OPT_DBL("any", 0, targs, any, -INFINITY, INFINITY, 0, "X", "any number, inf too"),
    HD_OPT_DBL("unit", 0, targs, unit, 0, 1, HD_OPTF_LT, "X", "in [0, 1)"),
    HD_OPT_ENUM("mode", 'm', targs, mode, "a|b|c", "M", "a, b or c"),
    HD_OPT_STR("name", 'n', targs, name, "S", "any text"),
    HD_OPT_PATH("db", 0, targs, db, HD_OPTF_NOT_STDOUT, "DB", "a database"),
    HD_OPT_LIST("set", 0, targs, sets, "K=V", "repeatable"),
    {.name = "seed",
     .kind = HD_ARG_STRING,
     .off = offsetof(targs, seed),
     .flags = HD_OPTF_ONCE,
     .meta = "N",
     .help = "once only"},
    {.name = "bare", .kind = HD_ARG_FLAG, .off = offsetof(targs, bare), .set = 2, .help = NULL},
    {0}};

static const hd_optspec tspec = {.cmd = "test",
                                 .head = "usage: test FILE [options]\n",
                                 .tail = "the end\n",
                                 .opts = topts,
                                 .allowed = 1,
                                 .npos_min = 1,
                                 .npos_max = 1,
                                 .pos = "one file"};

static char err_text[4096], out_text[16384];
static hd_optres res;

/* Runs hd_opt_parse(spec) on "test" + the NULL-terminated args into *a (defaults set here),
 * with stderr in err_text and stdout in out_text.  Returns what the parser returned.  argv is
 * static: res.pos points into it after the call (a local array left it dangling, and
 * values_are_stored read res.pos[0] from a dead stack frame). */
static int run_spec(const hd_optspec *spec, targs *a, const char *const *args) {
  static char *argv[32];
  int argc = 0;
  argv[argc++] = (char *)"test";
  for (; *args; args++) argv[argc++] = (char *)*args;
  argv[argc] = NULL;
  memset(a, 0, sizeof *a);
  a->count = 10, a->ratio = 1, a->mode = -1, a->id = -1;
  a->sets = (hd_optlist){a->set_v, 0, 2};
  fflush(stdout), fflush(stderr);
  FILE *e = tmpfile(), *o = tmpfile();
  assert_non_null(e);
  assert_non_null(o);
  int save_e = dup(2), save_o = dup(1);
  dup2(fileno(e), 2), dup2(fileno(o), 1);
  int rc = hd_opt_parse(spec, argc, argv, a, &res);
  fflush(stdout), fflush(stderr);
  dup2(save_e, 2), dup2(save_o, 1);
  close(save_e), close(save_o);
  rewind(e), rewind(o);
  err_text[fread(err_text, 1, sizeof err_text - 1, e)] = 0;
  out_text[fread(out_text, 1, sizeof out_text - 1, o)] = 0;
  fclose(e), fclose(o);
  return rc;
}

static int run(targs *a, const char *const *args) {
  return run_spec(&tspec, a, args);
}

/* rc 2 and one line on stderr holding want. */
static void refused(const char *const *args, const char *want) {
  targs a;
  int rc = run(&a, args);
  if (rc != 2 || !strstr(err_text, want) || strchr(err_text, '\n') != strrchr(err_text, '\n'))
    fail_msg("%s ...: rc %d, stderr '%s' (wanted 2 and '%s')", args[0], rc, err_text, want);
}

static void values_are_stored(void **state) {
  (void)state;
  targs a;
  const char *args[] = {"f.txt",  "--count", "5",     "--big=1e6", "--id",   "9223372036854775807",
                        "-r",     "0.25",    "--any", "-inf",      "--unit", "0",
                        "--mode", "c",       "-n",    "x y",       "--db",   "a.db",
                        "-q",     NULL};
  assert_int_equal(run(&a, args), 0);
  assert_string_equal(err_text, "");
  assert_int_equal(a.count, 5);
  assert_int_equal(a.big, 1000000);
  assert_true(a.id == LLONG_MAX);
  assert_true(a.ratio == 0.25);
  assert_true(isinf(a.any) && a.any < 0);
  assert_true(a.unit == 0);
  assert_int_equal(a.mode, 2);
  assert_string_equal(a.name, "x y");
  assert_string_equal(a.db, "a.db");
  assert_int_equal(a.quiet, 1);
  assert_int_equal(res.npos, 1);
  assert_string_equal(res.pos[0], "f.txt");
  assert_int_equal(res.given[hd_opt_index(&tspec, "count")], 1);
  assert_int_equal(res.given[hd_opt_index(&tspec, "seed")], 0);
  /* nothing given: the defaults stay */
  const char *none[] = {"f.txt", NULL};
  assert_int_equal(run(&a, none), 0);
  assert_int_equal(a.count, 10);
  assert_true(a.ratio == 1);
  assert_int_equal(a.mode, -1);
  /* a short cluster: a flag and a value in one word, and the value glued on */
  const char *cluster[] = {"-qc7", "f.txt", "-mb", NULL};
  assert_int_equal(run(&a, cluster), 0);
  assert_int_equal(a.quiet, 1);
  assert_int_equal(a.count, 7);
  assert_int_equal(a.mode, 1);
}

/* Refuses "f OPT VALUE" for each case (exit 2, one line on stderr holding want). */
typedef struct {
  const char *opt, *value, *want;
} refusal;

static void refused_all(const refusal *cases, size_t n) {
  for (size_t k = 0; k < n; k++) {
    const char *args[] = {"f", cases[k].opt, cases[k].value, NULL};
    refused(args, cases[k].want);
  }
}

static void bad_numbers_name_option_value_and_rule(void **state) {
  (void)state;
  static const refusal cases[] = {
      {"--count", "x", "haff test: --count 'x': expected a whole number in [1, 100]"},
      {"--count", "2.5", "--count '2.5': expected a whole number in [1, 100]"},
      {"--count", "1e1", "--count '1e1'"}, /* no HD_OPTF_EXP: digits only */
      {"--count", "", "--count '': expected"},
      {"--ratio", "abc", "haff test: --ratio 'abc': expected a finite number > 0"},
      {"--any", "nan", "--any 'nan': expected a number"},
      {"--any", "1e400", "--any '1e400'"}, /* overflow (ERANGE) */
      {"--big", "1.5", "--big '1.5': expected a whole number >= 0"},
      {"--big", "1e300", "--big '1e300'"}, /* whole, but past what a double holds exactly */
      {"--id", "99999999999999999999", "--id '99999999999999999999': expected a whole number >= 1"},
      {"--mode", "d", "haff test: --mode 'd': expected a, b or c"}};
  refused_all(cases, sizeof cases / sizeof cases[0]);
}

static void out_of_range_is_refused_at_both_ends(void **state) {
  (void)state;
  static const refusal cases[] = {
      {"--count", "0", "--count '0': expected a whole number in [1, 100]"},
      {"--count", "101", "--count '101'"},
      {"--count", "4294967297", "--count '4294967297'"}, /* past an int: not cast to 1 */
      {"--ratio", "0", "--ratio '0': expected a finite number > 0"}, /* > 0: 0 itself is out */
      {"--ratio", "inf", "--ratio 'inf'"},
      {"--unit", "1", "--unit '1': expected a number in [0, 1)"},
      {"--unit", "-1e-300", "--unit '-1e-300'"}};
  refused_all(cases, sizeof cases / sizeof cases[0]);
  targs a;
  const char *edge[] = {"f", "--count", "100", "--unit", "0.9999999999999999", NULL};
  assert_int_equal(run(&a, edge), 0);
  assert_int_equal(a.count, 100);
}

static void missing_value_and_unknown_option(void **state) {
  (void)state;
  const char *a1[] = {"f", "--count", NULL};
  refused(a1, "haff test: option '--count' needs a value (see haff test --help)");
  const char *a2[] = {"f", "-c", NULL};
  refused(a2, "option '--count' needs a value");
  const char *a3[] = {"f", "--bogus", NULL};
  refused(a3, "haff test: unknown option or missing value '--bogus' (see haff test --help)");
  const char *a4[] = {"f", "-z", NULL};
  refused(a4, "unknown option or missing value '-z'");
  const char *a5[] = {"f", "-qz", NULL}; /* inside a cluster: the letter at fault */
  refused(a5, "'-z'");
  const char *a6[] = {"f", "--quiet=1", NULL}; /* a flag takes no value */
  refused(a6, "'--quiet=1'");
}

static void repeated_options(void **state) {
  (void)state;
  targs a;
  /* the last value counts, and given[] says how often */
  const char *a1[] = {"f", "--count", "3", "--count", "4", NULL};
  assert_int_equal(run(&a, a1), 0);
  assert_int_equal(a.count, 4);
  assert_int_equal(res.given[hd_opt_index(&tspec, "count")], 2);
  /* a bad value is refused even when a good one came first */
  const char *a2[] = {"f", "--count", "3", "--count", "x", NULL};
  refused(a2, "--count 'x'");
  /* HD_OPTF_ONCE */
  const char *a3[] = {"f", "--seed", "1", "--seed", "2", NULL};
  refused(a3, "haff test: --seed given twice: give one");
  /* a list keeps every value, in order, up to its room */
  const char *a4[] = {"f", "--set", "a=1", "--set", "b=2", NULL};
  assert_int_equal(run(&a, a4), 0);
  assert_int_equal(a.sets.n, 2);
  assert_string_equal(a.set_v[0], "a=1");
  assert_string_equal(a.set_v[1], "b=2");
  const char *a5[] = {"f", "--set", "a=1", "--set", "b=2", "--set", "c=3", NULL};
  refused(a5, "haff test: more than 2 --set options");
}

static void double_dash_ends_the_options(void **state) {
  (void)state;
  targs a;
  const char *a1[] = {"--count", "3", "--", "--count", NULL};
  assert_int_equal(run(&a, a1), 0);
  assert_int_equal(a.count, 3);
  assert_int_equal(res.npos, 1);
  assert_string_equal(res.pos[0], "--count");
  const char *a2[] = {"--", "-", NULL}; /* "-" is a positional argument */
  assert_int_equal(run(&a, a2), 0);
  assert_string_equal(res.pos[0], "-");
  /* options after the positional argument are read too (GNU permutation) */
  const char *a3[] = {"f", "-q", NULL};
  assert_int_equal(run(&a, a3), 0);
  assert_int_equal(a.quiet, 1);
  assert_string_equal(res.pos[0], "f");
}

static void positional_count(void **state) {
  (void)state;
  const char *a1[] = {"--quiet", NULL};
  refused(a1, "haff test: expected one file (see haff test --help)");
  const char *a2[] = {"f", "g", NULL};
  refused(a2, "expected one file");
  hd_optspec none = tspec;
  none.npos_min = none.npos_max = 0;
  targs a;
  const char *a3[] = {"g", NULL};
  assert_int_equal(run_spec(&none, &a, a3), 2);
  assert_non_null(strstr(err_text, "haff test: unexpected argument 'g'"));
}

static void paths_and_options_that_do_not_apply(void **state) {
  (void)state;
  const char *a1[] = {"f", "--db", "-", NULL};
  refused(a1, "haff test: --db -: a database cannot be written to stdout; give a file name");
  const char *a2[] = {"f", "--db", "", NULL};
  refused(a2, "--db '': expected a file name");
  /* bare belongs to set 2, the spec allows set 1 only */
  const char *a3[] = {"f", "--bare", NULL};
  refused(a3, "haff test: option '--bare' does not apply here (see --help)");
  hd_optspec both = tspec;
  both.allowed = 3;
  targs a;
  assert_int_equal(run_spec(&both, &a, a3), 0);
  assert_int_equal(a.bare, 1);
}

static void help_comes_from_the_table(void **state) {
  (void)state;
  targs a;
  const char *a1[] = {"f", "--help", NULL};
  assert_int_equal(run(&a, a1), -1);
  const char *a2[] = {"-h", NULL}; /* no positional needed for help */
  assert_int_equal(run(&a, a2), -1);
  assert_true(!strncmp(out_text, "usage: test FILE [options]\n", 27));
  assert_non_null(strstr(out_text, "\nthe end\n"));
  assert_non_null(strstr(out_text, "  -q, --quiet      say less\n"));
  assert_non_null(strstr(out_text, "  -c, --count N    a count in [1, 100]\n"));
  assert_non_null(
      strstr(out_text, "  -r, --ratio X    a ratio > 0\n                   second line\n"));
  for (const hd_optdef *d = topts; d->name; d++) {
    char want[64];
    snprintf(want, sizeof want, "--%s", d->name);
    if (d->help && !d->set)
      assert_non_null(strstr(out_text, want));
    else
      assert_null(strstr(out_text, want)); /* hidden, or not of this subcommand */
  }
}

static void refuse_and_number(void **state) {
  (void)state;
  targs a;
  const char *a1[] = {"f", "--name", "x", "--mode", "a", NULL};
  assert_int_equal(run(&a, a1), 0);
  assert_int_equal(hd_opt_refuse(&tspec, &res, "quiet", "name", "with --quiet"), 0); /* not given */
  fflush(stderr);
  FILE *e = tmpfile();
  int save = dup(2);
  dup2(fileno(e), 2);
  int r1 = hd_opt_refuse(&tspec, &res, "name", "count mode", "with --name");
  int r2 = hd_opt_refuse(&tspec, &res, NULL, "quiet count", "here");
  fflush(stderr);
  dup2(save, 2), close(save);
  rewind(e);
  char buf[512];
  buf[fread(buf, 1, sizeof buf - 1, e)] = 0;
  fclose(e);
  assert_int_equal(r1, 2);
  assert_int_equal(r2, 0);
  assert_string_equal(buf, "haff test: --mode does not apply with --name (see --help)\n");
  double x = 0;
  long long i = 0;
  assert_int_equal(hd_opt_number("t", &topts[4], "2.5", &x, NULL), 0);
  assert_true(x == 2.5);
  assert_int_equal(hd_opt_number("t", &topts[2], "3e3", NULL, &i), 0);
  assert_true(i == 3000);
  assert_int_equal(hd_opt_index(&tspec, "nope"), -1);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(values_are_stored),
      cmocka_unit_test(bad_numbers_name_option_value_and_rule),
      cmocka_unit_test(out_of_range_is_refused_at_both_ends),
      cmocka_unit_test(missing_value_and_unknown_option),
      cmocka_unit_test(repeated_options),
      cmocka_unit_test(double_dash_ends_the_options),
      cmocka_unit_test(positional_count),
      cmocka_unit_test(paths_and_options_that_do_not_apply),
      cmocka_unit_test(help_comes_from_the_table),
      cmocka_unit_test(refuse_and_number),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
