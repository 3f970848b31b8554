/* hd_anaspecies: what the per-species analysis (`haff haff-fit --by-species`, analysis/
 * hd_species.c) reads of a run: its species as the engine numbers them (0 [dimers], 1 [disks],
 * 2, 3, ... each [species NAME]) with their bodies' mass, size and restitutions, from the
 * stored scene; and the energies per body of each species with every sample (sample_species,
 * schema version 3). */
#ifndef HD_ANASPECIES_H
#define HD_ANASPECIES_H

#include <sqlite3.h>
#include <stddef.h>
#include <stdint.h>

#include "hd_error.h"

/* Most species of a run (HD_MAX_SPECIES of the scene). */
#define HD_ANA_SP_MAX 8

/* One species of a run that has bodies. */
typedef struct hd_ana_sp {
  int idx;       /* the engine's species index (species.idx, sample_species.species) */
  char name[32]; /* 'dimers', 'disks' or the [species NAME] (run_species.species) */
  long count;    /* its bodies */
  double mass;   /* a body's mass */
  double sigma;  /* a body's diameter when it is one disk (a [dimers] of a = 0 counts: one disk
                  * of diameter d and mass 2m); NaN for a body of several disks */
  int rotates;   /* 1 if its bodies have a moment of inertia (E_rot, K = E_tr/E_rot exist) */
} hd_ana_sp;

/* The species of one run. */
typedef struct hd_ana_mix {
  int k;                                       /* species with bodies, in engine order */
  hd_ana_sp sp[HD_ANA_SP_MAX];                 /* them */
  double alpha[HD_ANA_SP_MAX * HD_ANA_SP_MAX]; /* restitution of the pair (i, j) of sp[], i * k
                                                * + j: the scene's alpha and alpha_OTHER */
  double area; /* the box's area (runs.box_x * box_y, else the scene's; NaN without one) */
  int walls;   /* [walls] sides given */
  int rods;    /* a rods run (k = 0: no species analysis) */
} hd_ana_mix;

/* Reads run's species from its stored scene (the engine's loader, hd_scene_read_stored) and
 * box.  HD_OK; HD_EINPUT for no such run or a scene the loader refuses ("run N: runs.scene:
 * LINE: ..."); HD_EIO when the database cannot be read. */
int hd_ana_mix_read(sqlite3 *db, int64_t run, hd_ana_mix *mix, hd_error *err);

/* Whether two runs' species are the same ensemble: the same species (index, name, count, mass,
 * diameter), restitutions, box area (all equal to 1e-9 relative) and walls. */
int hd_ana_mix_same(const hd_ana_mix *a, const hd_ana_mix *b);

/* Energies per body of each of a run's k species at every sample time, by t: frame f holds
 * e_tr[f * k + s] and e_rot[f * k + s] of mix->sp[s] at time t[f]. */
typedef struct hd_ana_spseries {
  size_t n, k;
  double *t, *e_tr, *e_rot; /* malloc'd; hd_ana_spseries_free */
} hd_ana_spseries;

/* Reads run's per-species energies: the one reader of them, for every analysis.  From
 * sample_species, their only store from schema version 5 on (and every species' rows from
 * version 3); a run without rows there (a file before version 3, read as it is) falls back to
 * the samples columns e_tr_dimer, e_rot_dimer, e_tr_disk, and a run of one species to e_tr,
 * e_rot.  A
 * time at which some species has no row is left out.  HD_OK (n = 0 when there is nothing),
 * HD_EIO, HD_ENOMEM. */
int hd_ana_spseries_read(sqlite3 *db, int64_t run, const hd_ana_mix *mix, hd_ana_spseries *s,
                         hd_error *err);
void hd_ana_spseries_free(hd_ana_spseries *s);

#endif
