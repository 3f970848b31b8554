/* hd_opt: the one command-line option parser of haff's subcommands.  Each subcommand declares
 * its options in a table (hd_optdef: long name, short letter, kind of value, range, where it is
 * stored, help line); hd_opt_parse reads argv with getopt_long from that table, checks every
 * value with one number parser, and prints --help from the same table, so that the help text,
 * the man page and the bash completion (both made from --help) cannot drift from what is
 * parsed.  CLI code: it prints its messages on stderr ("haff CMD: ...") and never exits. */
#ifndef HD_OPT_H
#define HD_OPT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* The kind of an option's value. */
typedef enum hd_arg {
  HD_ARG_FLAG,   /* no value: stores int 1 (0 with HD_OPTF_CLEAR) */
  HD_ARG_INT,    /* a whole number in [ilo, ihi], stored in an int, long or long long (size) */
  HD_ARG_DOUBLE, /* a number in the range lo..hi (see HD_OPTF_*), stored in a double */
  HD_ARG_STRING, /* any text: stores the const char * (argv's own) */
  HD_ARG_PATH,   /* a file name: as STRING; refused empty, and "-" with HD_OPTF_NOT_STDOUT */
  HD_ARG_ENUM,   /* one word of choices ("ac|ols|runs"): stores its index as an int */
  HD_ARG_LIST    /* a repeatable text: appended to an hd_optlist */
} hd_arg;

/* Rules of a value (bits of hd_optdef.flags). */
enum {
  HD_OPTF_GT = 1,          /* DOUBLE: > lo, not >= lo */
  HD_OPTF_LT = 2,          /* DOUBLE: < hi, not <= hi */
  HD_OPTF_FINITE = 4,      /* DOUBLE: inf refused (nan always is) */
  HD_OPTF_EXP = 8,         /* INT: whole numbers written as 1e6 accepted too (exact below 2^53) */
  HD_OPTF_CLEAR = 16,      /* FLAG: stores 0 (a --no-X flag) */
  HD_OPTF_NOT_STDOUT = 32, /* PATH: "-" refused (a database is a file, not a stream) */
  HD_OPTF_SHORT = 64,      /* only the short form (-o): name is its name in messages and help */
  HD_OPTF_ONCE = 128,      /* given twice is an error ("--seed given twice: give one"); so is
                            * every HD_OPTF_OUTPUT, HD_OPTF_INPUT and HD_ARG_PATH option */
  HD_OPTF_OUTPUT = 256,    /* STRING, PATH: a file the command writes ("-": stdout); refused by
                            * hd_opt_parse when it would overwrite an input (hd_path_overwrites) */
  HD_OPTF_INPUT = 512,     /* STRING, PATH: a file the command reads, besides its positional
                            * arguments (which are inputs unless hd_optspec.out_pos says) */
  HD_OPTF_DB = 1024        /* with HD_OPTF_OUTPUT: a database the command writes into (kept and
                            * added to); any other output is replaced whole, so an existing
                            * SQLite file there is refused */
};

/* The values of an HD_ARG_LIST option, in the order given. */
typedef struct hd_optlist {
  const char **v; /* room for max values (the caller's array) */
  int n;          /* how many were given */
  int max;        /* capacity of v: one more is an error */
} hd_optlist;

/* One option of a subcommand.  A table ends with an entry whose name is NULL. */
typedef struct hd_optdef {
  const char *name;    /* long name without "--", e.g. "cpd-skip" */
  char letter;         /* short form ('o' for -o), 0 for none */
  hd_arg kind;         /* what the value is */
  size_t off;          /* where it is stored: offset in the caller's struct (dest of parse) */
  size_t size;         /* HD_ARG_INT: sizeof the field (int, long or long long) */
  double lo, hi;       /* HD_ARG_DOUBLE: the range (inclusive unless HD_OPTF_GT/LT) */
  long long ilo, ihi;  /* HD_ARG_INT: the range, inclusive */
  unsigned flags;      /* HD_OPTF_* */
  const char *choices; /* HD_ARG_ENUM: the words, '|'-separated */
  const char *meta;    /* the value's name in the help ("ID", "X"); NULL for a flag */
  const char *help;    /* the help line(s), '\n' between lines; NULL: not listed in --help */
  unsigned set;        /* which subcommands sharing the table accept it (hd_optspec.allowed);
                        * 0: every one */
} hd_optdef;

/* A subcommand's command line: its options and the text of its --help. */
typedef struct hd_optspec {
  const char *cmd;        /* as in messages, "haff CMD: ...": "run", "mc fmean" */
  const char *head;       /* --help text before the options (usage lines, description) */
  const char *tail;       /* --help text after the options, or NULL */
  const hd_optdef *opts;  /* the table */
  unsigned allowed;       /* which options of a shared table apply (hd_optdef.set); 0: all */
  int npos_min, npos_max; /* how many positional arguments (npos_max < 0: any number) */
  const char *pos;        /* what they are, for "expected PHRASE": "one database" */
  int out_pos;            /* 1 + the index of the positional argument that is an output (merge's
                           * OUT.db), checked like an HD_OPTF_OUTPUT option; 0: every
                           * positional argument is an input */
  const char *const *help_for; /* this subcommand's own help of options of a shared table:
                                * pairs (name, help), then NULL; NULL: the table's help */
} hd_optspec;

/* What hd_opt_parse found besides the stored values. */
typedef struct hd_optres {
  unsigned char given[64]; /* given[k]: how many times opts[k] was given (saturates at 255) */
  char **pos;              /* the positional arguments (inside argv) */
  int npos;                /* how many */
} hd_optres;

/* Parses argv[1..argc) (argv[0] the subcommand's name; GNU getopt_long, which moves the
 * positional arguments after the options; "--" ends the options) by spec, storing each value
 * in dest (the struct the table's offsets refer to; its defaults set by the caller).  A value
 * given twice: the last one counts (res->given says how often), except an option of
 * HD_OPTF_ONCE, an output, an input or a path (refused).  -h and --help print the help
 * (hd_opt_help) on stdout.  Returns 0 to go on, -1 after printing the help (the caller returns
 * 0), or 2 after one line on stderr naming the option, the value and why (bad number, out of
 * range, unknown option, missing value, an option that does not apply to this subcommand
 * (said after its value is checked), a wrong count of positional arguments). */
int hd_opt_parse(const hd_optspec *spec, int argc, char **argv, void *dest, hd_optres *res);

/* The one rule for outputs that must not be inputs, applied by hd_opt_parse after the values
 * are read and before the command opens anything: every output (an HD_OPTF_OUTPUT option given,
 * not "-"; the positional argument out_pos) is compared by hd_path_overwrites with every input
 * (the other positional arguments, the HD_OPTF_INPUT options given) and with every other
 * output; its folder must exist (hd_path_folder_missing); and an output that is not a database
 * (no HD_OPTF_DB; out_pos is one) must not be an existing SQLite file (hd_path_is_sqlite: a
 * text or movie written over a database would destroy its runs).  Returns 0, or 2 after one
 * line on stderr, e.g. "haff energy: -o x.db would overwrite the input x.db (the same file):
 * nothing written", "haff run: -o no/x.db: the folder no does not exist: nothing written". */
int hd_opt_check_outputs(const hd_optspec *spec, const hd_optres *res, const void *dest);

/* The one number parser: reads s as the value of option d by its range and rules, into *x
 * (kind HD_ARG_DOUBLE) or *i (HD_ARG_INT).  Returns 0, or 2 after printing one line on stderr
 * that names the option, the value and what was expected, e.g.
 * "haff haff-fit: --cpd-skip 'x': expected a number >= 0". */
int hd_opt_number(const char *cmd, const hd_optdef *d, const char *s, double *x, long long *i);

/* Writes spec's --help text to out: head, one line per listed option ("  --name META  help",
 * with its short form), tail. */
void hd_opt_help(const hd_optspec *spec, FILE *out);

/* Index of the option named name in spec's table, -1 if none. */
int hd_opt_index(const hd_optspec *spec, const char *name);

/* If option `opt` was given, refuses each option of the space-separated names `others` that
 * was given too: prints "haff CMD: --X does not apply WHY (see --help)" and returns 2; else 0.
 * opt NULL: refuses the others unconditionally (why then says when). */
int hd_opt_refuse(const hd_optspec *spec, const hd_optres *res, const char *opt, const char *others,
                  const char *why);

/* The first fields of an hd_optspec, in one line: cmd, opts, allowed, npos_min, npos_max, pos. */
#define HD_OPT_SPEC(CMD, OPTS, ALLOWED, NMIN, NMAX, POS)                                           \
  .cmd = CMD, .opts = OPTS, .allowed = ALLOWED, .npos_min = NMIN, .npos_max = NMAX, .pos = POS

/* Table entries, for readability: T the struct of dest, F its field; the last arguments are
 * the help text H and, after it, any more designators of the entry (e.g. .set = X). */
#define HD_OPT_FLAG(N, L, T, F, ...)                                                               \
  { .name = N, .letter = L, .kind = HD_ARG_FLAG, .off = offsetof(T, F), .help = __VA_ARGS__ }
#define HD_OPT_INT(N, L, T, F, LO, HI, FL, M, ...)                                                 \
  {                                                                                                \
    .name = N, .letter = L, .kind = HD_ARG_INT, .off = offsetof(T, F),                             \
    .size = sizeof(((T *)0)->F), .ilo = LO, .ihi = HI, .flags = FL, .meta = M, .help = __VA_ARGS__ \
  }
#define HD_OPT_DBL(N, L, T, F, LO, HI, FL, M, ...)                                                 \
  {                                                                                                \
    .name = N, .letter = L, .kind = HD_ARG_DOUBLE, .off = offsetof(T, F), .lo = LO, .hi = HI,      \
    .flags = FL, .meta = M, .help = __VA_ARGS__                                                    \
  }
#define HD_OPT_STR(N, L, T, F, M, ...)                                                             \
  {                                                                                                \
    .name = N, .letter = L, .kind = HD_ARG_STRING, .off = offsetof(T, F), .meta = M,               \
    .help = __VA_ARGS__                                                                            \
  }
#define HD_OPT_PATH(N, L, T, F, FL, M, ...)                                                        \
  {                                                                                                \
    .name = N, .letter = L, .kind = HD_ARG_PATH, .off = offsetof(T, F), .flags = FL, .meta = M,    \
    .help = __VA_ARGS__                                                                            \
  }
#define HD_OPT_ENUM(N, L, T, F, C, M, ...)                                                         \
  {                                                                                                \
    .name = N, .letter = L, .kind = HD_ARG_ENUM, .off = offsetof(T, F), .choices = C, .meta = M,   \
    .help = __VA_ARGS__                                                                            \
  }
#define HD_OPT_LIST(N, L, T, F, M, ...)                                                            \
  {                                                                                                \
    .name = N, .letter = L, .kind = HD_ARG_LIST, .off = offsetof(T, F), .meta = M,                 \
    .help = __VA_ARGS__                                                                            \
  }

#endif
