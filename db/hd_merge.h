/* hd_merge: merges haff databases into one (`haff merge OUT IN...`).  Every run of every input
 * is appended to OUT with a new id (the input's ids shifted past OUT's largest) and the rows of
 * every table with a `run` column follow it (collisions, sample_rows, sample_species, states,
 * checkpoints, and any table of the user's such as plots_runs, created in OUT from the input's
 * definition when OUT lacks it).  OUT is of this haff's schema version (an older OUT is brought
 * to it); an input of schema version 0 to 4 has its table samples converted as OUT's would be
 * (hd_db_samples_convert: the per-species columns become sample_species rows).  Each run's
 * provenance row (host, Slurm job and task) is carried over with the file and id it came from
 * (db/schema.sql, table provenance).
 *
 * Refused, as bad input, before OUT is touched: a file given twice (also as OUT, by any link, or
 * as its SQLite log), an OUT name that SQLite or the command line reads otherwise ("-",
 * ":memory:", "file:..."; "./NAME" is the file), a write-protected OUT, a file that is not a
 * haff database, is of a newer schema version or fails PRAGMA integrity_check, OUT or an input
 * being written by a run (its DB.lock held), and a run whose identity (scene text, seed,
 * commit: runs.git_commit, "unknown" when NULL or not kept) is already in OUT or in an input merged
 * before it.  No SQL is built from a name found in a file: haff's per-run tables (hd_db_run_tables)
 * are copied with the columns of haff's own schema that the input has; a user's table with a run
 * column only when its name and its columns' are plain identifiers (else the merge is refused),
 * created in OUT from its columns and their affinities (its definition's text is never run). SIGINT
 * and SIGTERM stop the merge (HD_EINTR) with its temporary file removed.  OUT keeps its file mode.
 * Atomic: the merge is built in a temporary file beside OUT (a copy of OUT when it exists) that is
 * renamed over OUT at the end, so a merge that fails or is killed leaves OUT as it was. */
#ifndef HD_MERGE_H
#define HD_MERGE_H

#include <stdint.h>

#include "hd_error.h"

/* Merges the n_in databases in[] into out (created when missing).  *runs gets the number of
 * runs appended (may be NULL).  Returns HD_OK, HD_EINPUT (see above; err names the file, and
 * the run for a duplicate), HD_EINTR (a signal), HD_EIO (a read or write failed) or HD_ENOMEM. */
int hd_db_merge(const char *out, const char *const *in, int n_in, int64_t *runs, hd_error *err);

/* Whether a process holds a write lock in path.lock, the lock file of the runs writing to the
 * database path (run/hd_run.c run_lock): on byte `run` (run run's lock) when run >= 0,
 * on any byte (some run writing) when run < 0.  0 when there is no lock file. */
int hd_merge_lock_held(const char *path, long long run);

#endif
