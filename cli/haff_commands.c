/* The one table of haff's subcommands: `haff --help`, the dispatch (cli/haff.c), and through
 * --help the man page (cli/haff-man.sh) and the bash completion come from it. */
#include <stddef.h>

#include "haff.h"

int haff_argc;
char **haff_argv;

const haff_command haff_commands[] = {
    {"run", NULL, hd_cmd_run, "run a scene and append one run to a database", &hd_cmd_run_spec},
    {"resume", NULL, hd_cmd_resume, "continue an interrupted run from its last checkpoint",
     &hd_cmd_resume_spec},
    {"mc", NULL, NULL,
     "Monte Carlo: `mc fmean` (<f>, D_e), `mc eps` (rod restitution), `mc rate` (collision "
     "frequency)",
     NULL},
    {"fmean", "mc", hd_cmd_mc_fmean, "<f> and D_e = D/<f> for an elongation a/d",
     &hd_cmd_mc_fmean_spec},
    {"eps", "mc", hd_cmd_mc_eps, "sample or tabulate p_beta(eps), the rods' stochastic restitution",
     &hd_cmd_mc_eps_spec},
    {"rate", "mc", hd_cmd_mc_rate,
     "the low-density collision frequency of dimers / any shape over eq. (29)'s nu0",
     &hd_cmd_mc_rate_spec},
    {"export", NULL, hd_cmd_export,
     "export xyz|gsd DB: extended XYZ (ASE, OVITO) or GSD (HOOMD, OVITO) trajectories",
     &hd_cmd_export_spec},
    {"merge", NULL, hd_cmd_merge, "merge OUT IN...: the runs of many databases into one",
     &hd_cmd_merge_spec},
    {"sweep", NULL, hd_cmd_sweep, "a study: a grid of runs, locally (--jobs) or on Slurm, merged",
     &hd_cmd_sweep_spec},
    {"movie", NULL, hd_cmd_movie, "movie DB -o run.mp4|run.gif: the run's frames, drawn by gnuplot",
     &hd_cmd_movie_spec},
    {"haff-fit", NULL, hd_cmd_haff_fit,
     "fit eq. (31) (D_e, nu0_eff) per run or per (alpha, a/d) group", &hd_cmd_haff_fit_spec},
    {"table1", NULL, hd_cmd_table1, "Table I: D_e and nu0_eff/nu0 per (alpha, a/d), TSV or --md",
     &hd_cmd_table1_spec},
    {"table2", NULL, hd_cmd_table2, "Table II: K = E_tr/E_rot = a0 + a1 tau with 99% intervals",
     &hd_cmd_table2_spec},
    {"energy", NULL, hd_cmd_energy, "Figs. 2-3 data: E, (1-alpha^2) cpd, nu0_eff t per group",
     &hd_cmd_energy_spec},
    {"angles", NULL, hd_cmd_angles, "Fig. 5 data: contact-angle histograms per block; --fmean",
     &hd_cmd_angles_spec},
    {"veldist", NULL, hd_cmd_veldist, "Fig. 6 data: scaled velocity histograms; --stats a2, KS",
     &hd_cmd_veldist_spec},
    {"rods-energy", NULL, hd_cmd_rods_energy,
     "rods Figs. 1-2, 9-11: energy, collisions vs t, theory", &hd_cmd_rods_energy_spec},
    {"rods-density", NULL, hd_cmd_rods_density,
     "rods Figs. 3, 4, 6: coarse-grained density, local E", &hd_cmd_rods_density_spec},
    {"rods-phase", NULL, hd_cmd_rods_phase, "rods Fig. 5: phase space (x, v, T_B) at a time",
     &hd_cmd_rods_phase_spec},
    {"rods-gofr", NULL, hd_cmd_rods_gofr, "rods Fig. 8: pair correlation g(x) at a time",
     &hd_cmd_rods_gofr_spec},
    {"rods-veldist", NULL, hd_cmd_rods_veldist,
     "rods Fig. 7: velocities of all rods and of a cluster", &hd_cmd_rods_veldist_spec},
    {"rods-clusters", NULL, hd_cmd_rods_clusters, "rods: clusters per snapshot (count, largest)",
     &hd_cmd_rods_clusters_spec},
    {"rods-collapse", NULL, hd_cmd_rods_collapse,
     "rods: (N, eps) scan of collapse vs McNamara-Young", &hd_cmd_rods_collapse_spec},
    {NULL, NULL, NULL, NULL, NULL}};
