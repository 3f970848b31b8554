/* hd_model: what the runner (hd_run.c) needs from a simulation model, so that the 2D engine
 * (hd_sim) and the 1D rod ring share one driver: logging, samples, snapshots, checkpoints,
 * signals, resume and progress.  A model is chosen by the scene (hd_model_for_scene). */
#ifndef HD_MODEL_H
#define HD_MODEL_H

#include <stddef.h>
#include <stdint.h>

#include "hd_db.h"
#include "hd_error.h"
#include "hd_scene.h"

/* The operations of a model.  `m` is the model's own state. */
typedef struct hd_model_ops {
  const char *name; /* "bodies2d", "rods" */
  /* Builds the initial state of the scene (HD_EINPUT for a scene that cannot be set up). */
  int (*alloc)(void **m, const hd_scene *sc, hd_error *err);
  /* Builds the state saved in a checkpoint blob of a run of the same scene (exact). */
  int (*alloc_restore)(void **m, const hd_scene *sc, const void *blob, size_t n, hd_error *err);
  void (*free)(void *m);
  /* Processes events up to the next collision and describes it in *row (all but seq);
   * HD_OK, or HD_SIM_STOPTIME / HD_SIM_IDLE (hd_sim.h), HD_ECOLLAPSE, HD_EPHYS. */
  int (*next)(void *m, double t_stop, hd_collision_row *row, hd_error *err);
  /* Exact state as a malloc'd blob. */
  int (*checkpoint)(const void *m, void **blob, size_t *n, hd_error *err);
  double (*time)(const void *m);        /* absolute time */
  double (*cpd)(const void *m);         /* collisions per particle */
  int64_t (*events)(const void *m);     /* events processed */
  double (*temperature)(const void *m); /* kinetic temperature for the progress line */
  /* A samples row at the current time (t, collisions, cpd, energies per particle). */
  void (*sample)(const void *m, hd_sample_row *row);
  /* Writes one states row per body at the current time under label. */
  int (*log_states)(const void *m, hd_db *db, int64_t run, const char *label, hd_error *err);
  /* The box (for runs.box_x/box_y; ly = 0 for 1D). */
  void (*box)(const void *m, double *lx, double *ly);
  /* One record per body at the current time into out[0 .. bodies-1] (any order; rec.body says
   * which), for a frame; HD_OK or HD_ENOMEM. */
  int (*states)(const void *m, hd_state_rec *out, hd_error *err);
  /* NULL, or: writes the species table of run (db/schema.sql, table species) at its start. */
  int (*log_species)(const void *m, hd_db *db, int64_t run, hd_error *err);
  /* NULL, or: writes the sample_species rows that go with a samples row at the current time. */
  int (*log_species_sample)(const void *m, hd_db *db, int64_t run, hd_error *err);
} hd_model_ops;

/* The model that runs scene sc. */
const hd_model_ops *hd_model_for_scene(const hd_scene *sc);

/* The 2D bodies engine (hd_sim) as a model: run/hd_model_sim.c. */
extern const hd_model_ops hd_model_bodies2d;

#endif
