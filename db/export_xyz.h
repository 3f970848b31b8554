/* export_xyz: extended XYZ of a run's states and frames (db/export_xyz.c has the format). */
#ifndef HD_EXPORT_XYZ_H
#define HD_EXPORT_XYZ_H

#include "hd_body.h"
#include "hd_db.h"
#include "hd_scene.h"

/* The geometry of a run that the exports need (hd_export_read_run), read from its scene text
 * (the engine's loader), runs.box_x/box_y and its species table. */
typedef struct hd_export_geom {
  double lx, ly;      /* box edges (a ring of rods: its length, and 1) */
  hd_shape dimer;     /* [dimers] d, a, m */
  hd_shape disk;      /* [disks] sigma, mass */
  int wall_x, wall_y; /* [walls] close x (left right), y (bottom top) */
  double rod_gamma;   /* [rods] gamma (masses 1 + gamma, 1 + 1/gamma alternate) */
  int rods;           /* a rods run */
  int nsp;            /* species of the run's species table (schema version 3), 0 if none */
  hd_shape sp[HD_MAX_SPECIES];        /* their shapes: the engine's (hd_db_read_species) */
  int64_t first[HD_MAX_SPECIES + 1];  /* bodies first[s] .. first[s + 1] - 1 are of species s */
  int ntypes;                         /* the types (hd_export_body_type): the species table's
                                       * rows in idx order, else ("rod") or ("dimer", "disk") */
  char type_name[HD_MAX_SPECIES][64]; /* species.name ('dimer', 'disk', NAME) or 'rod' */
  char type_elem[HD_MAX_SPECIES][4];  /* the element symbol of the type in XYZ: N dimer, Ar disk,
                                       * C rod, O F Ne Na Mg Al ... the named species by idx */
} hd_export_geom;

/* One frame of a run handed to an hd_export_emit: n bodies (body numbers, kinds HD_KIND_DISK,
 * HD_KIND_DIMER, HD_KIND_ROD or HD_KIND_BODY, and states), valid during the call. */
typedef struct hd_export_frame {
  const char *label;     /* initial, frames, velocities, checkpoint, final */
  double t, cpd;         /* its time and cpd (cpd valid when has_cpd) */
  int has_cpd;           /* 0 when the stored cpd is NULL */
  long n;                /* bodies */
  const long long *body; /* body numbers */
  const int *kind;       /* their kinds */
  const hd_kin *kin;     /* their states (a rod: x, v in x, vx; bath temperature in omega) */
} hd_export_frame;

/* Called once per frame; returns 0 or an exit code (having said why on stderr). */
typedef int (*hd_export_emit)(void *ctx, const hd_export_geom *g, const hd_export_frame *f);

/* Finds run *run of db (the newest when *run <= 0; *run is set to it) and reads its geometry
 * into *g.  Returns 0, or an exit code with one line on stderr ("haff export: ..."). */
int hd_export_read_run(hd_db *db, int64_t *run, hd_export_geom *g);

/* Hands every frame of run/label (initial, final, checkpoint, velocities, frames, all) to emit,
 * in time order (at equal t: initial, frames, velocities, checkpoint, final): one per (label, t)
 * of the states table, one per frames row.  Returns 0, or emit's code, or an exit code with
 * one line on stderr: 1 (cannot read), 2 (no such frames, a damaged file). */
int hd_export_frames(hd_db *db, int64_t run, const char *label, const hd_export_geom *g,
                     hd_export_emit emit, void *ctx);

/* The shape of body `body` of kind `kind` (not a rod): its species' in the run's species table,
 * or for a run without one the scene's [dimers] or [disks]. */
const hd_shape *hd_export_body_shape(const hd_export_geom *g, long long body, int kind);
/* Disks of body `body` of kind `kind` (a rod: 1). */
int hd_export_body_disks(const hd_export_geom *g, long long body, int kind);
/* The type (0 .. g->ntypes - 1) of body `body` of kind `kind`. */
int hd_export_body_type(const hd_export_geom *g, long long body, int kind);
/* The mass of rod `body` (engine/rods/rods.c: 1 + gamma, 1 + 1/gamma alternate). */
double hd_export_rod_mass(const hd_export_geom *g, long long body);

/* Writes the states and frames of run `run` of db (the newest run if run <= 0) with label
 * initial, final, checkpoint, velocities, frames or all, as extended XYZ, to outpath (NULL or
 * "-": stdout, which is flushed and checked; a regular file is written as outpath.tmp, renamed to
 * outpath on success and removed on failure, so a failed export leaves no outpath).  Messages go
 * to stderr, prefixed "haff export: ".
 * Returns 0, or the exit code of the failure: 1 (cannot read or write), 2 (no such run). */
int hd_xyz_export(hd_db *db, int64_t run, const char *label, const char *outpath);

#endif
