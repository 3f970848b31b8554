/* The analysis subcommands of bin/haff (docs/analysis.md).  Each returns the exit code: 0 ok,
 * 1 failure (database unreadable, write error), 2 bad usage or input; --help prints usage. */
#ifndef HD_ANA_CLI_H
#define HD_ANA_CLI_H

int haff_fit_main(int argc, char **argv);     /* haff haff-fit DB: eq. (31) per run / group */
int haff_table1_main(int argc, char **argv);  /* haff table1 DB: Table I */
int haff_table2_main(int argc, char **argv);  /* haff table2 DB: Table II */
int haff_energy_main(int argc, char **argv);  /* haff energy DB: Figs. 2 and 3 data */
int haff_angles_main(int argc, char **argv);  /* haff angles DB: Fig. 5 data, <f> */
int haff_veldist_main(int argc, char **argv); /* haff veldist DB: Fig. 6 data, shape stats */
/* analysis/rods_cli.c (docs/rods.md) */
int haff_rods_energy_main(int argc, char **argv);   /* rods Figs. 1, 2, 9-11 data */
int haff_rods_density_main(int argc, char **argv);  /* rods Figs. 3, 4, 6 data */
int haff_rods_phase_main(int argc, char **argv);    /* rods Fig. 5 data: phase space */
int haff_rods_gofr_main(int argc, char **argv);     /* rods Fig. 8 data: g(x) */
int haff_rods_veldist_main(int argc, char **argv);  /* rods Fig. 7 data: cluster velocities */
int haff_rods_clusters_main(int argc, char **argv); /* rods clusters per snapshot */
int haff_rods_collapse_main(int argc, char **argv); /* rods (N, eps) collapse scan */

#endif
