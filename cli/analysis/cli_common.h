/* cli_common: the command-line plumbing shared by the analysis subcommands (cmd_*.c):
 * option parsing, output files and loading the per-run fits.  CLI code: may print to stderr. */
#ifndef HD_CLI_COMMON_H
#define HD_CLI_COMMON_H

#include <sqlite3.h>
#include <stdint.h>
#include <stdio.h>

#include "hd_opt.h"
#include "hd_runfit.h"

/* Options an analysis subcommand may accept (bits of hd_optspec.allowed, hd_optdef.set). */
enum {
  HD_OPT_RUN = 1,      /* --run ID */
  HD_OPT_ALL = 2,      /* --all */
  HD_OPT_FIT = 4,      /* --no-detect --thr X --min-coll N --cpd-max X --cpd-skip X --s-end X
                        * --s-flag X --min-window X */
  HD_OPT_MD = 8,       /* --md --keep-flagged (the tables) */
  HD_OPT_GROUP = 16,   /* --alpha-group */
  HD_OPT_BLOCK = 32,   /* --block N --fmean */
  HD_OPT_BINS = 64,    /* --bins N */
  HD_OPT_STATS = 128,  /* --stats --label L --range X */
  HD_OPT_KCI = 256,    /* --k-ci ac|ols|runs --cpd-min-k X (the K fit's options) */
  HD_OPT_SPECIES = 512 /* --by-species (haff-fit, energy: cli_species.c) */
};

/* Parsed arguments. */
typedef struct hd_cli_args {
  const char *cmd;   /* the subcommand, for messages (set by hd_cli_parse) */
  const char *db;    /* the database (positional) */
  const char *out;   /* -o FILE, NULL for stdout */
  int64_t run;       /* --run ID, -1 when absent */
  int all;           /* --all */
  int md;            /* --md: Markdown table */
  int keep_flagged;  /* --keep-flagged: tables keep the groups flagged inhomogeneous */
  int pool;          /* --pool: veldist pools the snapshots of the runs' HCS windows */
  int group;         /* --alpha-group */
  hd_fit_opts fit;   /* fit options */
  long block;        /* --block N [10000] */
  int fmean;         /* --fmean */
  int bins;          /* --bins N [36 angles, 40 velocities] */
  int stats;         /* --stats */
  const char *label; /* --label [velocities] */
  double range;      /* --range X [5]: histogram of scaled velocities on [-X, X] */
  hd_kmode kmode;    /* --k-ci [ac] */
  int by_species;    /* --by-species: one row per species of each ensemble (cli_species.c) */
} hd_cli_args;

/* The options of every analysis subcommand (a spec's `allowed` says which apply): the table
 * of hd_opt_parse, with hd_cli_args as dest.  Each subcommand's hd_optspec points to it. */
extern const hd_optdef hd_cli_opts[];

/* The first fields of an analysis subcommand's hd_optspec: its name CMD, the options it reads
 * (ALLOWED, of hd_cli_opts) and its one positional argument, the database. */
#define HD_CLI_SPEC(CMD, ALLOWED)                                                                  \
  HD_OPT_SPEC(CMD, hd_cli_opts, ALLOWED, 1, 1, "one database argument")

/* Parses argv (argv[0] the subcommand) by spec (opts hd_cli_opts, one positional: the
 * database) into *a, after setting its defaults.  Returns 0 to go on, 2 after printing one
 * line on stderr for bad usage, or -1 after printing help (the caller returns 0). */
int hd_cli_parse(const hd_optspec *spec, int argc, char **argv, hd_cli_args *a);

/* Opens a->out for writing (stdout when NULL or "-").  Returns NULL after printing the error. */
FILE *hd_cli_out(const hd_cli_args *a);

/* Closes what hd_cli_out opened (not stdout).  Returns 0, or 1 after printing a write error. */
int hd_cli_close(FILE *f, const hd_cli_args *a);

/* Opens the database and fits the selected runs (--run ID or every finished run).  Prints the
 * error and returns its exit code (1 or 2) on failure; 0 with *fits malloc'd on success.  Says
 * on stderr how many windows were stored with the runs and how many computed (and why). */
int hd_cli_fits(const hd_cli_args *a, const char *cmd, sqlite3 **db, hd_run_fit **fits, size_t *n);

/* "stored", "computed" or "whole" for hd_run_fit.window (HD_WINDOW_*). */
const char *hd_cli_window_name(int window);

/* The runs an analysis of groups works on (hd_cli_groups). */
typedef struct hd_cli_set {
  sqlite3 *db;      /* the database, open */
  hd_run_fit *fits; /* the fitted runs (hd_cli_fits), n of them */
  size_t n;
  hd_group *g; /* the fits grouped into ensembles (hd_group_runs), ng of them */
  size_t ng;
} hd_cli_set;

/* hd_cli_parse by spec, hd_cli_fits, then the fits grouped into ensembles (hd_group_runs; warns
 * on stderr when two share an (alpha, a/d) label) into *s.  Returns as hd_cli_parse (-1 after
 * --help) or hd_cli_fits (nothing left open on failure); on 0 free with hd_cli_groups_free. */
int hd_cli_groups(const hd_optspec *spec, int argc, char **argv, hd_cli_args *a, hd_cli_set *s);

/* The start of table1 and table2: hd_cli_groups, then the groups of the papers' case
 * (hd_cli_table_groups: none is bad input, "haff CMD: none" on stderr, exit 2), then the
 * output opened (hd_cli_out).  Returns as hd_cli_groups; on 0 *out is open and s holds the
 * groups (the caller frees both). */
int hd_cli_table_start(const hd_optspec *spec, int argc, char **argv, int with_disks,
                       const char *none, hd_cli_args *a, hd_cli_set *s, FILE **out);

/* A group's name for the notes: "alpha A a/d X", "alpha A" when a/d does not apply (bodies
 * that are not dimers or disks), "alpha (several)" for a gas of several restitutions: never
 * "nan".  Returned by value: usable as a printf argument. */
typedef struct hd_cli_name {
  char s[64];
} hd_cli_name;
hd_cli_name hd_cli_group_name(const hd_group *g);

/* Prints a warning on stderr for each group whose (alpha, a/d) label an earlier group has (and
 * what they differ in: hd_group_differ), and a note for each group of rough bodies. */
void hd_cli_groups_warn(const char *cmd, const hd_group *g, size_t ng);

/* Frees what hd_cli_groups returned and closes the database. */
void hd_cli_groups_free(hd_cli_set *s);

/* The start of a subcommand on one run: hd_cli_parse, then --run ID is required, the database
 * is opened and the run's info read into *info.  Returns as hd_cli_parse (-1 after --help), or
 * the exit code after printing one line; on 0 *db is open (the caller closes it). */
int hd_cli_one_run(const hd_optspec *spec, int argc, char **argv, hd_cli_args *a, sqlite3 **db,
                   hd_run_info *info);

/* Whether group g is in the papers' tables: one species in a periodic box, dimers (and disks
 * when with_disks: Table I's reference; Table II's K needs rotation). */
int hd_cli_in_table(const hd_group *g, int with_disks);

/* How many of the groups g[0..ng) are in the table; says on stderr which are left out for not
 * being the papers' case (a mixture, walls) and where they are fitted. */
size_t hd_cli_table_groups(const char *cmd, const hd_group *g, size_t ng, int with_disks);

/* Whether a table leaves group g out for being flagged (inhomogeneous, short, outliers; not with
 * keep); says so on stderr, and that a group without state measures could not be checked. */
int hd_cli_flagged_out(const char *cmd, const hd_group *g, const hd_group_fit *q, int keep);

/* Says on stderr how many of group g's runs q left out for a short window, and how many it
 * rejected as outliers (none: nothing). */
void hd_cli_short_note(const char *cmd, const hd_group *g, const hd_group_fit *q);

/* x printed with the printf format fmt (one double conversion), or, when x is NaN, "" (tsv) or
 * "—" (md = 1): a missing or unmeasured value is never printed as nan.  The text lives in one of
 * 64 rotating static buffers: valid until 63 more calls. */
const char *hd_cli_num(const char *fmt, double x, int md);

/* Says on stderr why a group fitted from one run has no error (hd_ensemble_mean). */
void hd_cli_one_run_note(const char *cmd, const hd_group *g, size_t m);

/* Prints the error of a failed library call as "haff CMD: msg" and returns its exit code. */
int hd_cli_fail(const char *cmd, const hd_error *err);

#endif
