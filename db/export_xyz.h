/* export_xyz: extended XYZ of a run's states and frames (db/export_xyz.c has the format). */
#ifndef HD_EXPORT_XYZ_H
#define HD_EXPORT_XYZ_H

#include "hd_db.h"

/* Writes the states and frames of run `run` of db (the newest run if run <= 0) with label
 * initial, final, checkpoint, velocities, frames or all, as extended XYZ, to outpath (NULL or
 * "-": stdout, which is flushed and checked).  Messages go to stderr, prefixed "haff export: ".
 * Returns 0, or the exit code of the failure: 1 (cannot read or write), 2 (no such run). */
int hd_xyz_export(hd_db *db, int64_t run, const char *label, const char *outpath);

#endif
