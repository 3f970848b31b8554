/* hd_path: whether writing one file would destroy another (the same file by any link, or the
 * log SQLite keeps beside a database): the check of every output against the inputs, by the
 * option parser (hd_opt_check_outputs), haff export and haff merge; and the checks of an output
 * before it is opened (its folder exists; a text output is not a database). */
#ifndef HD_PATH_H
#define HD_PATH_H

#include <stddef.h>

/* Whether writing the file out would destroy the file in: 1 when they are the same file (by
 * device and inode when both exist, whatever symbolic or hard link leads there; else the same
 * path once the folder is resolved by realpath), or when out is one of the files SQLite keeps
 * beside a database in (in-wal, in-shm, in-journal), which hold its newest rows; else 0. */
int hd_path_overwrites(const char *out, const char *in);

/* Whether the folder that would hold the file path is missing: 0 when it exists (or path names
 * no folder: the current one, or /); 1 when it does not exist, 2 when it is not a folder (a
 * file), either with its name (path up to its last '/') into dir (size bytes, truncated). */
int hd_path_folder_missing(const char *path, char *dir, size_t size);

/* Whether path is an existing regular file that begins with SQLite's header ("SQLite format 3"
 * and a NUL): 1 yes (a database, haff's or another's), 0 not (missing, unreadable, another
 * file, a folder). */
int hd_path_is_sqlite(const char *path);

#endif
