/* bin/haff: dispatches to the subcommands listed in commands[] below. */
#include "haff.h"
#include "hd_ana_cli.h" /* the analysis subcommands */

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

int haff_run_main(int argc, char **argv);
int haff_resume_main(int argc, char **argv);
int haff_mc_main(int argc, char **argv);
int haff_export_main(int argc, char **argv);
int haff_merge_main(int argc, char **argv);
int haff_sweep_main(int argc, char **argv);
int haff_movie_main(int argc, char **argv);

static const haff_command commands[] = {
    {"run", haff_run_main, "run a scene and append one run to a database"},
    {"resume", haff_resume_main, "continue an interrupted run from its last checkpoint"},
    {"mc", haff_mc_main, "Monte Carlo: `mc fmean` (<f>, D_e) and `mc eps` (rod restitution)"},
    {"export", haff_export_main, "export xyz DB: extended XYZ snapshots for OVITO and VMD"},
    {"merge", haff_merge_main, "merge OUT IN...: the runs of many databases into one"},
    {"sweep", haff_sweep_main, "a study: a grid of runs, locally (--jobs) or on Slurm, merged"},
    {"movie", haff_movie_main, "movie DB -o run.mp4|run.gif: the run's frames, drawn by gnuplot"},
    {"haff-fit", haff_fit_main, "fit eq. (31) (D_e, nu0_eff) per run or per (alpha, a/d) group"},
    {"table1", haff_table1_main, "Table I: D_e and nu0_eff/nu0 per (alpha, a/d), TSV or --md"},
    {"table2", haff_table2_main, "Table II: K = E_tr/E_rot = a0 + a1 tau with 99% intervals"},
    {"energy", haff_energy_main, "Figs. 2-3 data: E, (1-alpha^2) cpd, nu0_eff t per group"},
    {"angles", haff_angles_main, "Fig. 5 data: contact-angle histograms per block; --fmean"},
    {"veldist", haff_veldist_main, "Fig. 6 data: scaled velocity histograms; --stats a2, KS"},
    {"rods-energy", haff_rods_energy_main, "rods Figs. 1-2, 9-11: energy, collisions vs t, theory"},
    {"rods-density", haff_rods_density_main, "rods Figs. 3, 4, 6: coarse-grained density, local E"},
    {"rods-phase", haff_rods_phase_main, "rods Fig. 5: phase space (x, v, T_B) at a time"},
    {"rods-gofr", haff_rods_gofr_main, "rods Fig. 8: pair correlation g(x) at a time"},
    {"rods-veldist", haff_rods_veldist_main,
     "rods Fig. 7: velocities of all rods and of a cluster"},
    {"rods-clusters", haff_rods_clusters_main, "rods: clusters per snapshot (count, largest)"},
    {"rods-collapse", haff_rods_collapse_main, "rods: (N, eps) scan of collapse vs McNamara-Young"},
};
static const size_t n_commands = sizeof commands / sizeof commands[0];

int haff_wants_help(int argc, char **argv) {
  for (int i = 1; i < argc; i++)
    if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help")) return 1;
  return 0;
}

static void usage(FILE *out) {
  fprintf(out, "usage: haff COMMAND [ARGS...]   (haff COMMAND --help for each)\n\ncommands:\n");
  for (size_t i = 0; i < n_commands; i++)
    fprintf(out, "  %-12s %s\n", commands[i].name, commands[i].summary);
  fprintf(out,
          "\noptions: -h, --help (this text), -V, --version (the version, as in runs.version)\n");
  fprintf(out, "\nexit status: 0 ok, 1 failed run (collapse, interrupted, resource), 2 bad usage "
               "or input\n");
}

/* The exit code of a command that returned rc, once what it wrote on stdout is out: a write
 * error (a full disk, /dev/full, a closed pipe) turns a success into 1, with one line naming the
 * command.  A command that failed already said why; its code stays. */
static int stdout_flushed(const char *cmd, int rc) {
  errno = 0;
  int bad = fflush(stdout) != 0;
  bad |= ferror(stdout) != 0;
  if (bad && rc == 0) {
    fprintf(stderr, "haff%s%s: stdout: write error%s%s\n", cmd ? " " : "", cmd ? cmd : "",
            errno ? ": " : "", errno ? strerror(errno) : "");
    return 1;
  }
  return rc;
}

int main(int argc, char **argv) {
  /* a file size limit (ulimit -f) then fails the write with EFBIG, which the run reports and
   * survives like a full disk, instead of killing the process with the run left 'running' */
  signal(SIGXFSZ, SIG_IGN);
  if (argc < 2) {
    usage(stderr);
    return 2;
  }
  if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "help")) {
    usage(stdout);
    return stdout_flushed(NULL, 0);
  }
  if (!strcmp(argv[1], "--version") || !strcmp(argv[1], "-V")) {
    printf("haff %s\n", HAFF_VERSION);
    return stdout_flushed(NULL, 0);
  }
  for (size_t i = 0; i < n_commands; i++)
    if (!strcmp(argv[1], commands[i].name))
      return stdout_flushed(commands[i].name, commands[i].main(argc - 1, argv + 1));
  fprintf(stderr, "haff: unknown command '%s' (haff --help lists them)\n", argv[1]);
  return 2;
}
