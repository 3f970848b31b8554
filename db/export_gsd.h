/* export_gsd: a run's states and frames as a GSD file of the hoomd schema (db/export_gsd.c has
 * the layout and the schema as written). */
#ifndef HD_EXPORT_GSD_H
#define HD_EXPORT_GSD_H

#include "hd_db.h"

/* Writes the states and frames of run `run` of db (the newest run if run <= 0) with label
 * initial, final, checkpoint, velocities, frames or all (the frames of `haff export xyz`, in the
 * same order) as a GSD file to outpath (a file: GSD is written with a seek back to its header),
 * through outpath.tmp renamed at the end, so that a failed export leaves no file.  application
 * goes into the header (e.g. "haff 0.1.0").  Messages go to stderr, prefixed "haff export: ".
 * Returns 0, or the exit code of the failure: 1 (cannot read or write), 2 (no such run). */
int hd_gsd_export(hd_db *db, int64_t run, const char *label, const char *outpath,
                  const char *application);

#endif
