/* hd_walck: a thread that checkpoints a database's write-ahead log from a connection of its own,
 * so that the connection that writes never stops to copy the log back into the database file
 * and wait for its fsync (SQLite's automatic checkpoint runs inside the COMMIT that crosses
 * the threshold).  The checkpoints are PASSIVE: they copy what no reader still needs and never
 * block the writer.  Internal to db/: hd_db starts one with its writer thread. */
#ifndef HD_WALCK_H
#define HD_WALCK_H

#include <sqlite3.h>

#include "hd_error.h"

/* Frames in the log after a commit from which the thread is woken (SQLite's default
 * automatic checkpoint threshold). */
#define HD_WALCK_FRAMES 1000
/* Frames in the log past which the committing thread finishes the checkpoint itself, so that
 * the log restarts from its beginning: the log stays below about this size (16 MB). */
#define HD_WALCK_RESTART 4000

typedef struct hd_walck hd_walck;

/* Starts checkpointing the file `path` for the writing connection `w` (in WAL mode): turns
 * w's automatic checkpoints off and wakes the thread after each commit of w that leaves at
 * least HD_WALCK_FRAMES frames in the log (HD_WALCK_RESTART: see hd_walck.c).  On failure (*out =
 * NULL, HD_ENOMEM or HD_EIO) w is left as it was, with its automatic checkpoints. */
int hd_walck_start(hd_walck **out, sqlite3 *w, const char *path, hd_error *err);

/* Stops the thread (after the checkpoint under way, if any), closes its connection and gives
 * w its automatic checkpoints back.  Must not run while another thread uses w.  NULL is a
 * no-op. */
void hd_walck_stop(hd_walck *c);

#endif
