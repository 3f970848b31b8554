/* hd_epsdb: the store of the eps tables (engine/rods/eps.h): tables eps_tables and
 * eps_table_points of db/schema.sql.  `haff mc eps --tabulate` writes them. */
#ifndef HD_EPSDB_H
#define HD_EPSDB_H

#include <sqlite3.h>
#include <stdint.h>

#include "eps.h"
#include "hd_error.h"

/* Writes the table to db (tables eps_tables and eps_table_points of db/schema.sql, created if
 * missing) in one transaction; *id (if not NULL) gets its eps_tables.id.  HD_OK or HD_EIO. */
int hd_eps_table_save(const hd_eps_table *t, sqlite3 *db, unsigned long seed, int64_t *id,
                      hd_error *err);

#endif
