/* hd_scene_species: the species of a scene as one table.  [dimers] is species 0, [disks]
 * species 1 and each [species NAME] section 2, 3, ... in scene order: the numbering of the
 * engine (hd_body.species), of states.species and of the species table of the log.  A layer
 * above takes a species' kind, shape, count and restitutions from here, never from the
 * shorthand sections' own fields. */
#ifndef HD_SCENE_SPECIES_H
#define HD_SCENE_SPECIES_H

#include "hd_body.h"
#include "hd_scene.h"

/* One species of a scene. */
typedef struct hd_scene_sp {
  hd_kind kind;     /* what its section makes: HD_KIND_DIMER ([dimers]), HD_KIND_DISK ([disks]),
                     * HD_KIND_BODY ([species NAME], whatever its shape) */
  const char *name; /* "dimer", "disk" or the section's NAME (sc's storage) */
  long count;       /* bodies */
  long line;        /* the line of the section's header (0 for [dimers] and [disks]) */
  double alpha;     /* restitution within the species */
  hd_shape shape;   /* its shape: hd_shape_dimer, hd_shape_disk, or hd_shape_cluster of the
                     * section's disks with the fast tags */
} hd_scene_sp;

/* How many species sc has: 2 + its [species NAME] sections. */
int hd_scene_nspecies(const hd_scene *sc);

/* Species k of sc (0 .. hd_scene_nspecies - 1) into *out.  Returns 0, or -1 for k out of range
 * or a [species NAME] whose disks hd_shape_cluster refuses (a scene filled by hand: the loader
 * checks them). */
int hd_scene_species_get(const hd_scene *sc, int k, hd_scene_sp *out);

/* The restitution of a pair of bodies of species i and j of sc: the species' own alpha when
 * i = j, [disks] alpha_dimer for the pair of species 0 and 1, else sc->alpha_pair[i][j] (filled by
 * the loader). */
double hd_scene_pair_alpha(const hd_scene *sc, int i, int j);

/* Whether n disks (centres x, y, diameters d; n <= HD_MAX_BODY_DISKS) are one body, as a
 * [species] must be: every disk reached from disk 0 through touching or overlapping pairs
 * (centres at most (d_i + d_j)/2 apart, up to a relative 1e-12).  Returns -1 when they are,
 * else the index of a disk not reached (HD_MAX_BODY_DISKS when n is above it). */
int hd_scene_disks_unconnected(int n, const double *x, const double *y, const double *d);

#endif
