/* hd_scene_species: the species of a scene as one table (hd_scene_species.h). */
#include "hd_scene_species.h"

#include <string.h>

int hd_scene_nspecies(const hd_scene *sc) {
  return 2 + sc->n_named;
}

int hd_scene_species_get(const hd_scene *sc, int k, hd_scene_sp *out) {
  memset(out, 0, sizeof *out);
  if (k == 0) {
    out->kind = HD_KIND_DIMER, out->name = "dimer", out->count = sc->n_dimers;
    out->alpha = sc->dimer_alpha;
    hd_shape_dimer(&out->shape, sc->dimer_d, sc->dimer_a, sc->dimer_m);
    return 0;
  }
  if (k == 1) {
    out->kind = HD_KIND_DISK, out->name = "disk", out->count = sc->n_disks;
    out->alpha = sc->disk_alpha;
    hd_shape_disk(&out->shape, sc->disk_sigma, sc->disk_mass);
    return 0;
  }
  if (k < 0 || k >= hd_scene_nspecies(sc)) return -1;
  const hd_scene_species *sp = &sc->named[k - 2];
  out->kind = HD_KIND_BODY, out->name = sp->name, out->count = sp->count, out->line = sp->line;
  out->alpha = sp->alpha;
  return hd_shape_cluster(&out->shape, sp->ndisk, sp->x, sp->y, sp->d, sp->m, 1);
}

double hd_scene_pair_alpha(const hd_scene *sc, int i, int j) {
  if (i == j) return i == 0 ? sc->dimer_alpha : i == 1 ? sc->disk_alpha : sc->named[i - 2].alpha;
  if (i + j == 1) return sc->disk_alpha_dimer;
  return sc->alpha_pair[i][j];
}
