/* cli_species: `--by-species` of `haff haff-fit` and `haff energy` (docs/analysis.md,
 * "Mixtures: the temperature ratio"). */
#ifndef HD_CLI_SPECIES_H
#define HD_CLI_SPECIES_H

#include "cli_common.h"

/* haff-fit --by-species on the parsed arguments a: one TSV row per species of each ensemble.
 * Returns the exit code (0; 1 for a failure to read or write; 2 for bad input). */
int hd_cli_species_fit(const hd_cli_args *a, const char *cmd);

/* energy --by-species: one block per species of each ensemble, the per-species energies and
 * T_i/T against time, averaged over the ensemble's runs sample by sample.  Exit code. */
int hd_cli_species_energy(const hd_cli_args *a, const char *cmd);

#endif
