/* haff command-line front end: the one table of subcommands (haff_commands, cli/haff_commands.c)
 * and every subcommand's entry point and option spec, declared here only.  `haff X` (`haff mc X`)
 * is in cli/cmd_X.c, cli/analysis/cmd_X.c or cli/mc/cmd_mc_X.c ('-' in X written '_'): a function
 * int hd_cmd_X(int argc, char **argv) (hd_cmd_mc_X) with argv[0] the subcommand's name, and its
 * option spec hd_cmd_X_spec.  It returns
 * the process exit code (0 ok, 1 failed run, 2 bad usage or input) and never calls exit().  Its
 * options are a table (hd_opt.h) in its hd_optspec, from which its --help, the man page and the
 * bash completion come. */
#ifndef HAFF_CLI_H
#define HAFF_CLI_H

#include <stdio.h>

#include "hd_opt.h"

/* One subcommand of bin/haff, or a group of them (`haff mc PROGRAM`). */
typedef struct haff_command {
  const char *name;                   /* as typed: "run", "haff-fit", "mc", "fmean" */
  const char *group;                  /* NULL: a command of haff; else the group it belongs to
                                       * ("mc": typed `haff mc fmean`) */
  int (*main)(int argc, char **argv); /* entry point, argv[0] == name; NULL for a group, whose
                                       * programs are the entries naming it as their group */
  const char *summary;                /* one line for `haff --help` (`haff GROUP --help`) */
  const hd_optspec *spec;             /* its options and help; NULL for a group */
} haff_command;

/* Output streams that remember why a write failed (cli/haff_out.c), so that every "write
 * error" names its reason even when the failed write was an earlier, automatic flush of the
 * buffer.  haff_stdout_wrap: stdout becomes such a stream (bin/haff's main, first); it has no
 * file descriptor of its own (fileno(stdout) is -1, freopen fails on it): a child process that
 * must not write to stdout gets /dev/null by dup2 onto STDOUT_FILENO. */
void haff_stdout_wrap(void);
/* path opened for writing (created, truncated) as such a stream; NULL with errno set. */
FILE *haff_fopen_out(const char *path);
/* Closes f (stdout: flushes it): 0, or 1 after one line "haff CMD: NAME: write error: REASON"
 * on stderr (name NULL: "stdout"; cmd NULL: "haff: ..."). */
int haff_close_out(FILE *f, const char *cmd, const char *name);

/* Every subcommand, in the order of `haff --help`; ends with an entry whose name is NULL. */
extern const haff_command haff_commands[];

/* The version string stored in runs.version (the build's commit: hd_build.h, runs.git_commit). */
#define HAFF_VERSION "0.1.0"

/* The process's whole command line as typed (main's argc and a copy of its argv, which option
 * parsing permutes), set by main (cli/haff.c) before it dispatches, for runs.command; argv NULL
 * when a subcommand's main is called directly (tests). */
extern int haff_argc;
extern char **haff_argv;

/* cli/cmd_run.c: haff run SCENE, haff resume DB */
int hd_cmd_run(int argc, char **argv);
int hd_cmd_resume(int argc, char **argv);
extern const hd_optspec hd_cmd_run_spec, hd_cmd_resume_spec;
/* cli/cmd_merge.c, cli/cmd_sweep.c, cli/cmd_movie.c */
int hd_cmd_merge(int argc, char **argv);
int hd_cmd_sweep(int argc, char **argv);
int hd_cmd_movie(int argc, char **argv);
extern const hd_optspec hd_cmd_merge_spec, hd_cmd_sweep_spec, hd_cmd_movie_spec;
/* cli/cmd_export.c: haff export xyz DB (its spec's options follow the format word) */
int hd_cmd_export(int argc, char **argv);
extern const hd_optspec hd_cmd_export_spec;
/* cli/mc/cmd_mc_fmean.c, cmd_mc_eps.c, cmd_mc_rate.c: haff mc fmean, eps, rate */
int hd_cmd_mc_fmean(int argc, char **argv);
int hd_cmd_mc_eps(int argc, char **argv);
int hd_cmd_mc_rate(int argc, char **argv);
extern const hd_optspec hd_cmd_mc_fmean_spec, hd_cmd_mc_eps_spec, hd_cmd_mc_rate_spec;
struct hd_shape;
/* The body of --disks ('x y d m; x y d m; ...', 1 to HD_MAX_BODY_DISKS disks) into *shape
 * (cli/mc/cmd_mc_fmean.c).  Returns 0, or 2 after one line on stderr naming cmd. */
int hd_mc_parse_disks(const char *cmd, const char *spec, struct hd_shape *shape);
/* cli/analysis/cmd_*.c (docs/analysis.md); each returns 0 ok, 1 failure (database unreadable,
 * write error), 2 bad usage or input */
int hd_cmd_haff_fit(int argc, char **argv); /* haff haff-fit DB: eq. (31) per run / group */
int hd_cmd_table1(int argc, char **argv);   /* haff table1 DB: Table I */
int hd_cmd_table2(int argc, char **argv);   /* haff table2 DB: Table II */
int hd_cmd_energy(int argc, char **argv);   /* haff energy DB: Figs. 2 and 3 data */
int hd_cmd_angles(int argc, char **argv);   /* haff angles DB: Fig. 5 data, <f> */
int hd_cmd_veldist(int argc, char **argv);  /* haff veldist DB: Fig. 6 data, shape stats */
extern const hd_optspec hd_cmd_haff_fit_spec, hd_cmd_table1_spec, hd_cmd_table2_spec,
    hd_cmd_energy_spec, hd_cmd_angles_spec, hd_cmd_veldist_spec;
/* cli/analysis/cmd_rods_*.c (docs/rods.md) */
int hd_cmd_rods_energy(int argc, char **argv);   /* rods Figs. 1, 2, 9-11 data */
int hd_cmd_rods_density(int argc, char **argv);  /* rods Figs. 3, 4, 6 data */
int hd_cmd_rods_phase(int argc, char **argv);    /* rods Fig. 5 data: phase space */
int hd_cmd_rods_gofr(int argc, char **argv);     /* rods Fig. 8 data: g(x) */
int hd_cmd_rods_veldist(int argc, char **argv);  /* rods Fig. 7 data: cluster velocities */
int hd_cmd_rods_clusters(int argc, char **argv); /* rods clusters per snapshot */
int hd_cmd_rods_collapse(int argc, char **argv); /* rods (N, eps) collapse scan */
extern const hd_optspec hd_cmd_rods_energy_spec, hd_cmd_rods_density_spec, hd_cmd_rods_phase_spec,
    hd_cmd_rods_gofr_spec, hd_cmd_rods_veldist_spec, hd_cmd_rods_clusters_spec,
    hd_cmd_rods_collapse_spec;

#endif
