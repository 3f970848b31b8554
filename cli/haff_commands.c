/* The one table of haff's subcommands: `haff --help`, the dispatch (cli/haff.c), and through
 * --help the man page (cli/haff-man.sh) and the bash completion come from it. */
#include <stddef.h>

#include "haff.h"

int haff_argc;
char **haff_argv;

const haff_command haff_commands[] = {
    {"run", NULL, haff_run_main, "run a scene and append one run to a database", &haff_run_spec},
    {"resume", NULL, haff_resume_main, "continue an interrupted run from its last checkpoint",
     &haff_resume_spec},
    {"mc", NULL, NULL,
     "Monte Carlo: `mc fmean` (<f>, D_e), `mc eps` (rod restitution), `mc rate` (collision "
     "frequency)",
     NULL},
    {"fmean", "mc", hd_mc_fmean_main, "<f> and D_e = D/<f> for an elongation a/d",
     &hd_mc_fmean_spec},
    {"eps", "mc", hd_mc_eps_main,
     "sample or tabulate p_beta(eps), the rods' stochastic restitution", &hd_mc_eps_spec},
    {"rate", "mc", hd_mc_rate_main,
     "the low-density collision frequency of dimers / any shape over eq. (29)'s nu0",
     &hd_mc_rate_spec},
    {"export", NULL, haff_export_main,
     "export xyz|gsd DB: extended XYZ (ASE, OVITO) or GSD (HOOMD, OVITO) trajectories",
     &haff_export_spec},
    {"merge", NULL, haff_merge_main, "merge OUT IN...: the runs of many databases into one",
     &haff_merge_spec},
    {"sweep", NULL, haff_sweep_main,
     "a study: a grid of runs, locally (--jobs) or on Slurm, merged", &haff_sweep_spec},
    {"movie", NULL, haff_movie_main,
     "movie DB -o run.mp4|run.gif: the run's frames, drawn by gnuplot", &haff_movie_spec},
    {"haff-fit", NULL, haff_fit_main,
     "fit eq. (31) (D_e, nu0_eff) per run or per (alpha, a/d) group", &haff_fit_spec},
    {"table1", NULL, haff_table1_main, "Table I: D_e and nu0_eff/nu0 per (alpha, a/d), TSV or --md",
     &haff_table1_spec},
    {"table2", NULL, haff_table2_main, "Table II: K = E_tr/E_rot = a0 + a1 tau with 99% intervals",
     &haff_table2_spec},
    {"energy", NULL, haff_energy_main, "Figs. 2-3 data: E, (1-alpha^2) cpd, nu0_eff t per group",
     &haff_energy_spec},
    {"angles", NULL, haff_angles_main, "Fig. 5 data: contact-angle histograms per block; --fmean",
     &haff_angles_spec},
    {"veldist", NULL, haff_veldist_main, "Fig. 6 data: scaled velocity histograms; --stats a2, KS",
     &haff_veldist_spec},
    {"rods-energy", NULL, haff_rods_energy_main,
     "rods Figs. 1-2, 9-11: energy, collisions vs t, theory", &haff_rods_energy_spec},
    {"rods-density", NULL, haff_rods_density_main,
     "rods Figs. 3, 4, 6: coarse-grained density, local E", &haff_rods_density_spec},
    {"rods-phase", NULL, haff_rods_phase_main, "rods Fig. 5: phase space (x, v, T_B) at a time",
     &haff_rods_phase_spec},
    {"rods-gofr", NULL, haff_rods_gofr_main, "rods Fig. 8: pair correlation g(x) at a time",
     &haff_rods_gofr_spec},
    {"rods-veldist", NULL, haff_rods_veldist_main,
     "rods Fig. 7: velocities of all rods and of a cluster", &haff_rods_veldist_spec},
    {"rods-clusters", NULL, haff_rods_clusters_main, "rods: clusters per snapshot (count, largest)",
     &haff_rods_clusters_spec},
    {"rods-collapse", NULL, haff_rods_collapse_main,
     "rods: (N, eps) scan of collapse vs McNamara-Young", &haff_rods_collapse_spec},
    {NULL, NULL, NULL, NULL, NULL}};
