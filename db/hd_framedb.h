/* hd_framedb: reading a run's frames back (`haff movie`): the run and its scene text, its
 * bodies' kinds from the 'initial' states, then the rows of table frames one by one.  Every
 * function works on a connection of hd_db_open_read (hd_db.h) and reports an SQLite failure as
 * HD_EIO with SQLite's message alone in err (the caller says what it was reading). */
#ifndef HD_FRAMEDB_H
#define HD_FRAMEDB_H

#include <sqlite3.h>
#include <stdint.h>

#include "hd_error.h"

/* A run as a reader of its frames needs it. */
typedef struct hd_framedb_run {
  int64_t id;   /* runs.id */
  char *scene;  /* runs.scene, malloc'd (free()); NULL when the row has none */
  double box_x; /* runs.box_x, box_y (NULL reads as 0) */
  double box_y;
} hd_framedb_run;

/* Reads run `want` (> 0), or the newest run when want <= 0, into *r.  HD_OK; HD_EINPUT with
 * "there is no such run" or "the database holds no run" (also when reading the row fails);
 * HD_EIO when the query cannot be prepared; HD_ENOMEM. */
int hd_framedb_run_read(sqlite3 *h, int64_t want, hd_framedb_run *r, hd_error *err);

/* For every body b < n of the run's earliest 'initial' states: kinds[b] = dimer_kind when its
 * kind is 'dimer', else disk_kind (bodies without a row keep their value).  HD_OK or HD_EIO. */
int hd_framedb_kinds(sqlite3 *h, int64_t run, int *kinds, long n, int dimer_kind, int disk_kind,
                     hd_error *err);

/* One row of table frames: its time, cpd, body count and packed data (bytes long, the layout
 * of db/schema.sql), valid until the next hd_framedb_next or hd_framedb_close. */
typedef struct hd_framedb_frame {
  double t, cpd;
  long n;
  const unsigned char *data;
  long bytes;
} hd_framedb_frame;

typedef struct hd_framedb hd_framedb; /* the frames of one run, in time order */

/* Starts reading the frames of run.  HD_OK; HD_EINPUT when the file has no frames table (a
 * database from before it) with err naming the run; HD_EIO or HD_ENOMEM. */
int hd_framedb_open(sqlite3 *h, int64_t run, hd_framedb **out, hd_error *err);

/* The next frame into *f: 1, 0 after the last, or -1 with HD_EIO in err. */
int hd_framedb_next(hd_framedb *fr, hd_framedb_frame *f, hd_error *err);

/* Ends the reading (NULL allowed). */
void hd_framedb_close(hd_framedb *fr);

#endif
