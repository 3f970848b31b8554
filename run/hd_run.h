/* hd_run: drives a simulation to its stop condition and logs it to the database — collisions,
 * samples, velocity snapshots, checkpoints — with SIGINT/SIGTERM handling, a progress line and
 * `resume`.  The one place where a simulation model (hd_model.h: the 2D engine hd_sim, the rod
 * ring) and the store (hd_db) meet. */
#ifndef HD_RUN_H
#define HD_RUN_H

#include <stddef.h>
#include <stdint.h>

#include "hd_error.h"
#include "hd_scene.h"

/* How a run is driven. */
typedef struct hd_run_opts {
  const char *db_path;     /* database to append the run to (created if missing) */
  int quiet;               /* no progress line */
  const char *version;     /* written to runs.version */
  const char *command;     /* hd_run_new: the command line, written to runs.command (NULL: none);
                              runs.git_commit, git_dirty, compiler and cflags are this library's
                              build (hd_build.h) */
  const char *sweep_point; /* hd_run_new: written to runs.sweep_point (NULL: none) */
  char *note;              /* NULL, or note_size bytes that get "" or why a run that ended well
                              ended before its stop condition (also in runs.message) */
  size_t note_size;
  double progress_every; /* when stderr is not a terminal (a batch log): one progress line every
                            this many seconds; 0 takes HD_RUN_PROGRESS_EVERY, < 0 none.  On a
                            terminal the line is redrawn in place twice a second instead. */
} hd_run_opts;

/* Seconds between progress lines in a log (stderr not a terminal) by default. */
#define HD_RUN_PROGRESS_EVERY 60.0

/* Runs scene sc as a new run in the database; *run gets its id (0 if none was created).  A run
 * that ends done, collapsed or interrupted stores its HCS window (hd_db_run_hcs) before its
 * status.
 * Returns HD_OK (done), HD_EINTR (signal: checkpointed, status 'interrupted'), HD_ECOLLAPSE
 * (status 'collapsed'), HD_EIO (database: status 'failed' when it could still be written),
 * HD_EINPUT (the scene cannot be set up: nothing is written), HD_EPHYS (verification). */
int hd_run_new(const hd_scene *sc, const hd_run_opts *o, int64_t *run, hd_error *err);

/* Continues run want_run (<= 0: the newest resumable) from its last checkpoint, exactly as if
 * it had never stopped.  Returns as hd_run_new. */
int hd_run_resume(int64_t want_run, const hd_run_opts *o, int64_t *run, hd_error *err);

#endif
