/* hd_species: mixtures analysed per species (`haff haff-fit --by-species`, `haff energy
 * --by-species`; docs/analysis.md, "Mixtures: the temperature ratio").  Runs are grouped into
 * ensembles of the same species (hd_ana_mix_same); per species, its translational temperature
 * over the mixture's, T_i / T with T = sum_j x_j T_j (x_j = N_j / N; in 2D a body's e_tr is
 * its T), averaged over the samples of each run's HCS window (hd_run_fit), then over the runs
 * (runs of one ensemble also have the same roughness, shapes and walls: hd_ana_same_physics);
 * and the Garzo-Dufty value of the Maxwellian approximation for a mixture of smooth disks
 * (hd_mixture_hcs). */
#ifndef HD_SPECIES_H
#define HD_SPECIES_H

#include <sqlite3.h>
#include <stddef.h>

#include "hd_anaspecies.h"
#include "hd_error.h"
#include "hd_runfit.h"

/* Blocks of one run's window for an error without a second run (batch means). */
#define HD_SPECIES_BLOCKS 8

/* One species of an ensemble. */
typedef struct hd_species_row {
  double T_ratio;        /* <T_i / T> over the window's samples, mean over the runs */
  double T_ratio_err;    /* its standard error: over the runs (sd / sqrt R, R >= 2), else over
                          * HD_SPECIES_BLOCKS blocks of the one run's window (NaN with fewer than
                          * 2 samples per block) */
  double T_ratio_theory; /* hd_mixture_hcs at d = 2 (NaN where it does not apply: why) */
  double K, K_err;       /* rotating species: <e_tr / e_rot> over the window, the same way (NaN
                          * otherwise) */
} hd_species_row;

/* One ensemble of runs and its species. */
typedef struct hd_species_group {
  hd_ana_mix mix;                    /* the species (of its first run) */
  size_t n;                          /* runs in the group */
  size_t *idx;                       /* their indices in the fits given to hd_species_groups */
  size_t used;                       /* runs that had per-species samples in their window */
  int err_runs;                      /* 1: the errors are over runs; 0: over blocks of one run */
  double cpd_start, cpd_end;         /* the mean window */
  hd_species_row row[HD_ANA_SP_MAX]; /* one per mix.sp */
  char why[160];                     /* why T_ratio_theory is empty ("" when it is given) */
} hd_species_group;

/* Groups fits[0..n) (runs of rods left out) into ensembles and fills each group's rows from
 * the per-species samples in each run's window [t_start, t_end] (a run without any is left
 * out of the means and `used`).  *g malloc'd, *ng groups (hd_species_groups_free).  HD_OK,
 * HD_EIO / HD_ENOMEM / HD_EINPUT (a stored scene the loader refuses). */
int hd_species_groups(sqlite3 *db, const hd_run_fit *fits, size_t n, hd_species_group **g,
                      size_t *ng, hd_error *err);
void hd_species_groups_free(hd_species_group *g, size_t ng);

/* T_i / T of the Maxwellian-approximation HCS (hd_mixture_hcs, d = 2, Enskog chi_ij of
 * hd_mixture_chi2d at the mixture's area fraction) for mix's species into ratio[0..k).
 * Returns 1, or 0 with why set (and ratio NaN) when it does not apply: a species of rotating
 * or multi-disk bodies, walls, no box, no species. */
int hd_species_theory(const hd_ana_mix *mix, double *ratio, char *why, size_t whylen);

#endif
